"""photosolid: read, analyse, reconstruct and compare the photometric solids of luminaires.

Python bindings over the photosolid Rust library (the same numbers as the ``photosolid`` CLI).

- ``load(path, *, repair, handedness, lamp_sets, front)`` -> ``Luminaire`` (the CLI's reader options;
  ``load_all(path)`` gives every photometry of a GLDF container or TM-33 document, each with its ``id``) with numpy arrays ``c_deg``, ``gamma_deg`` (degrees) and ``candela``
  (cd, shape (n_c, n_gamma); read-only), ``photometry()`` (the dict of ``photosolid info --json``), ``sample``
  and ``sample_dirs`` (each reconstruction built at its first use and kept; ``field(recon)`` returns it),
  ``texture``, ``mesh``, ``compare``, ``fit``; it pickles and copies;
- ``batch(paths)`` -> ``pyarrow.Table`` with the columns of ``photosolid batch`` (docs/batch.md);
- ``list_inputs(paths)`` -> the paths ``batch`` reads, in its order (every format, files read by content,
  one ``FILE#ID`` per photometry of a GLDF container or TM-33 document), for recipes that shard them
  (``list_files`` is the same function under its earlier name);
- errors raise ``PhotosolidError`` with ``path``, ``line``, ``column``, ``code`` and ``message``; a missing
  file is also a ``FileNotFoundError``, another I/O failure an ``OSError``, a malformed file or a value out of
  its domain a ``ValueError``, an unsupported feature a ``NotImplementedError`` (the ``Photosolid*Error``
  subclasses); a bad argument is a ``ValueError`` or ``TypeError`` naming it.

The GIL is released while Rust works, so threads (e.g. Dask's) run files in parallel.
"""

from __future__ import annotations

import os
from typing import Callable, Iterable, Optional, Union

from ._native import (
    Field,
    Luminaire,
    PhotosolidError,
    PhotosolidFileNotFoundError,
    PhotosolidOSError,
    PhotosolidUnsupportedError,
    PhotosolidValueError,
    __version__,
    batch_parquet,
    list_inputs,
    load,
    load_all,
)

__all__ = [
    "Field",
    "Luminaire",
    "PhotosolidError",
    "PhotosolidFileNotFoundError",
    "PhotosolidOSError",
    "PhotosolidUnsupportedError",
    "PhotosolidValueError",
    "__version__", "batch", "list_files", "list_inputs", "load"]

list_files = list_inputs  # the earlier name of list_inputs, kept for the recipes that use it


def batch(
    paths: Union[str, os.PathLike, Iterable[Union[str, os.PathLike]]],
    compact: bool = False,
    *,
    repair: bool = False,
    handedness: str = "ccw",
    lamp_sets: str = "first",
    front: Optional[float] = None,
    progress: Union[None, bool, Callable[[int, int], object]] = None,
) -> "pyarrow.Table":  # noqa: F821
    """The batch table of every photometry under ``paths`` (directories recursively: .ies, .ldt, TM-33 .xml,
    .gldf and files read by content; ``list_inputs(paths)`` lists them), one row per photometry.

    Equal to ``photosolid batch PATHS -o OUT.parquet`` read with ``pyarrow.parquet.read_table``; with
    ``compact=True`` to ``batch --compact``, which fills ``smallest_within_1pct``. A file that does not load is
    a row with ``ok`` False and its error, not an exception. The reader options are ``load``'s (the CLI's
    ``--repair``, ``--handedness``, ``--lamp-sets``, ``--front``). ``progress``: a callable
    ``progress(done, total)`` called about ten times a second and once at the end, or True for a tqdm bar (when
    tqdm is installed). Ctrl-C raises KeyboardInterrupt within about a tenth of a second plus the files already
    started. Needs pyarrow.
    """
    import pyarrow as pa
    import pyarrow.parquet as pq

    if isinstance(paths, (str, os.PathLike)):
        paths = [paths]
    bar = None
    if progress is True:
        try:
            from tqdm import tqdm
        except ImportError:
            progress = None
        else:
            bar = tqdm(unit="file")

            def progress(done: int, total: int) -> None:
                bar.total = total
                bar.n = done
                bar.refresh()

    elif progress is False:
        progress = None
    try:
        data = batch_parquet(
            [os.fspath(p) for p in paths],
            compact,
            repair=repair,
            handedness=handedness,
            lamp_sets=lamp_sets,
            front=front,
            progress=progress,
        )
    finally:
        if bar is not None:
            bar.close()
    return pq.read_table(pa.BufferReader(data))
