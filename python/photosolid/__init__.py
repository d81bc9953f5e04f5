"""photosolid: read, analyse, reconstruct and compare the photometric solids of luminaires.

Python bindings over the photosolid Rust library (the same numbers as the ``photosolid`` CLI).

- ``load(path, *, repair, handedness, lamp_sets, front)`` -> ``Luminaire`` (the CLI's reader options;
  ``load_all(path)`` gives every photometry of a GLDF container or TM-33 document, each with its ``id``) with numpy arrays ``c_deg``, ``gamma_deg`` (degrees) and ``candela``
  (cd, shape (n_c, n_gamma); read-only), ``photometry()`` (the dict of ``photosolid info --json``), ``sample``
  and ``sample_dirs`` (each reconstruction built at its first use and kept; ``field(recon)`` returns it),
  ``texture``, ``mesh``, ``compare``, ``fit``; it pickles and copies;
- the CLI's jobs, each returning the dict its ``--json`` prints: ``road``, ``scene``, ``plan`` (scene files),
  ``validate`` (a list of dicts, one per file), ``synth`` and ``convert`` and ``export`` (what was written),
  ``engines`` and ``tradeoff`` (a Luminaire or a path); ``Luminaire.ugr_table()`` (numpy arrays) and
  ``Luminaire.grid_frame()`` (a pandas DataFrame);
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
from typing import BinaryIO, Callable, Iterable, Optional, Union

from ._native import load as _load_path
from ._native import (
    Field,
    Luminaire,
    PhotosolidError,
    PhotosolidFileNotFoundError,
    PhotosolidOSError,
    PhotosolidUnsupportedError,
    PhotosolidValueError,
    __version__,
    _convert,
    _engines,
    _export,
    _tradeoff,
    batch_parquet,
    _luminaire_from_source,
    list_inputs,
    load_all,
    plan,
    road,
    scene,
    synth,
    validate,
)

__all__ = [
    "Field",
    "Luminaire",
    "PhotosolidError",
    "PhotosolidFileNotFoundError",
    "PhotosolidOSError",
    "PhotosolidUnsupportedError",
    "PhotosolidValueError",
    "__version__", "batch", "convert", "engines", "export", "list_files", "list_inputs", "load", "load_all",
    "plan", "road", "scene", "synth", "tradeoff", "validate"]

PathLike = Union[str, os.PathLike]


def load(
    source: Union[PathLike, bytes, bytearray, memoryview, BinaryIO],
    *,
    name: Optional[str] = None,
    repair: bool = False,
    handedness: str = "ccw",
    lamp_sets: str = "first",
    front: Optional[float] = None,
) -> Luminaire:
    """Load an .ies, .ldt, TM-33 .xml or GLDF file (``FILE.gldf#ID`` for one photometry of a container,
    ``FILE.xml#ID`` for one emitter of a TM-33 document), from a path, from bytes, or from a binary file object
    (its ``read()``), with the CLI's reader options: ``repair`` (sort unsorted and drop duplicated angles, with a
    warning, instead of failing), ``handedness`` (``ccw`` or ``cw``: the rotation sense of Type A/B horizontal
    angles), ``lamp_sets`` (``first`` or ``sum``: which flux EULUMDAT cd/klm refer to), ``front`` (the
    luminaire's front, C degrees in the file's frame, instead of its format's convention).

    Bytes and file objects are read by the same readers: ``name`` (default: the file object's ``name``, else
    ``"<bytes>"``) names the luminaire in messages and outputs, and its extension picks the format (``.gldf``
    for a container, ``NAME.gldf#ID`` for one of its photometries); without one the content decides, as for
    ``batch``'s extension-less files. Raises a ``PhotosolidError`` naming the file and line when it is bad."""
    if isinstance(source, (bytes, bytearray, memoryview)) or hasattr(source, "read"):
        data = source.read() if hasattr(source, "read") else source
        if isinstance(data, str):
            raise TypeError("load: the file object gives text; open it in binary mode ('rb')")
        label = name if name is not None else getattr(source, "name", None)
        label = os.fspath(label) if isinstance(label, (str, os.PathLike)) else "<bytes>"
        return _luminaire_from_source(label, bytes(data), repair, handedness, lamp_sets, front)
    if name is not None:
        raise TypeError("load: name is for bytes and file objects; a path names itself")
    return _load_path(source, repair=repair, handedness=handedness, lamp_sets=lamp_sets, front=front)


def _luminaire(file: Union[Luminaire, PathLike], read: dict) -> Luminaire:
    """``file`` itself when it is a Luminaire (its reader options kept), else ``load(file, **read)``."""
    if isinstance(file, Luminaire):
        return file
    return load(file, **read)


def tradeoff(
    file: Union[Luminaire, PathLike],
    vs: Union[None, Luminaire, PathLike] = None,
    *,
    against: Optional[str] = None,
    factors: Optional[Iterable[int]] = None,
    factor: Optional[int] = None,
    repeats: int = 5,
    gpu: bool = False,
    repair: bool = False,
    handedness: str = "ccw",
    lamp_sets: str = "first",
    front: Optional[float] = None,
) -> dict:
    """``photosolid tradeoff FILE --json`` as a dict: every representation a renderer could hold, its bytes, time
    per lookup and error against the reference (``against``: truth, withheld or a reconstruction; default as the
    CLI). ``factors`` as ``--factors`` (default 1, 2, 5, 10), ``factor`` as ``--factor``, ``repeats`` as
    ``--repeats``, ``gpu`` as ``--gpu``. ``file`` and ``vs``: a Luminaire or a path loaded with the reader options."""
    read = dict(repair=repair, handedness=handedness, lamp_sets=lamp_sets, front=front)
    other = None if vs is None else _luminaire(vs, read)
    return _tradeoff(
        _luminaire(file, read),
        other,
        against=against,
        factors=None if factors is None else list(factors),
        factor=factor,
        repeats=repeats,
        gpu=gpu,
    )


def engines(
    file: Union[Luminaire, PathLike],
    *,
    engines: Union[None, str, Iterable[str]] = None,
    against: Optional[str] = None,
    tolerance: Optional[str] = None,
    resolution: Optional[int] = None,
    filter: str = "catmull-rom",
    factor: int = 3,
    repair: bool = False,
    handedness: str = "ccw",
    lamp_sets: str = "first",
    front: Optional[float] = None,
) -> dict:
    """``photosolid engines FILE --json`` as a dict: each engine's emulated lookup against the reference.
    ``engines`` (names, or one comma-separated string; default all), ``against`` (truth or a reconstruction;
    default catmull-rom), ``tolerance`` (``"1%"``: the resolution search), ``resolution``, ``filter``, ``factor``
    as the CLI's flags."""
    read = dict(repair=repair, handedness=handedness, lamp_sets=lamp_sets, front=front)
    if engines is not None and not isinstance(engines, str):
        engines = list(engines)
    return _engines(
        _luminaire(file, read),
        engines=engines,
        against=against,
        tolerance=tolerance,
        resolution=resolution,
        filter=filter,
        factor=factor,
    )


def export(
    file: Union[Luminaire, PathLike],
    output: PathLike,
    *,
    engine: str,
    resolution: Optional[int] = None,
    filter: str = "catmull-rom",
    repair: bool = False,
    handedness: str = "ccw",
    lamp_sets: str = "first",
    front: Optional[float] = None,
) -> dict:
    """``photosolid export FILE --engine ENGINE -o OUTPUT --json``: writes the engine's light-profile layout
    (atomically) and returns what was written: ``output``, ``engine``, ``layout``, ``size``, ``pbrt_flux_lm``,
    ``warnings`` (``layout-limit`` above 5 % radial max)."""
    read = dict(repair=repair, handedness=handedness, lamp_sets=lamp_sets, front=front)
    return _export(_luminaire(file, read), os.fspath(output), engine=engine, resolution=resolution, filter=filter)


def convert(
    file: Union[Luminaire, PathLike],
    output: PathLike,
    *,
    ies_version: str = "2002",
    rotate_c: float = 0.0,
    mirror: bool = False,
    repair: bool = False,
    handedness: str = "ccw",
    lamp_sets: str = "first",
    front: Optional[float] = None,
) -> dict:
    """``photosolid convert IN OUT --json``: writes the luminaire in the format of ``output``'s extension
    (.ies, .ldt, .xml TM-33-23; ``ies_version`` "2002" or "2019"), turned by ``rotate_c`` degrees after an optional
    ``mirror``, and returns ``output`` and ``warnings`` (what the target format does not keep)."""
    read = dict(repair=repair, handedness=handedness, lamp_sets=lamp_sets, front=front)
    return _convert(_luminaire(file, read), os.fspath(output), ies_version=ies_version, rotate_c=rotate_c, mirror=mirror)

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
