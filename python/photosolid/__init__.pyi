"""Type stubs of the photosolid package."""

import os
from typing import Any, BinaryIO, Callable, Iterable, Optional, Union

import pyarrow

from ._native import Field as Field
from ._native import Luminaire as Luminaire
from ._native import PhotosolidError as PhotosolidError
from ._native import PhotosolidFileNotFoundError as PhotosolidFileNotFoundError
from ._native import PhotosolidOSError as PhotosolidOSError
from ._native import PhotosolidUnsupportedError as PhotosolidUnsupportedError
from ._native import PhotosolidValueError as PhotosolidValueError
from ._native import __version__ as __version__
from ._native import batch_parquet as batch_parquet
from ._native import list_inputs as list_inputs
from ._native import load_all as load_all
from ._native import plan as plan
from ._native import road as road
from ._native import scene as scene
from ._native import synth as synth
from ._native import validate as validate

__all__ = [
    "Field",
    "Luminaire",
    "PhotosolidError",
    "PhotosolidFileNotFoundError",
    "PhotosolidOSError",
    "PhotosolidUnsupportedError",
    "PhotosolidValueError",
    "__version__",
    "batch",
    "convert",
    "engines",
    "export",
    "list_files",
    "list_inputs",
    "load",
    "load_all",
    "plan",
    "road",
    "scene",
    "synth",
    "tradeoff",
    "validate",
]

list_files = list_inputs

def batch(
    paths: Union[str, os.PathLike[str], Iterable[Union[str, os.PathLike[str]]]],
    compact: bool = False,
    *,
    repair: bool = False,
    handedness: str = "ccw",
    lamp_sets: str = "first",
    front: Optional[float] = None,
    progress: Union[None, bool, Callable[[int, int], object]] = None,
) -> pyarrow.Table:
    """The batch table (columns of ``photosolid batch``, docs/batch.md) of every input under ``paths`` (.ies, .ldt, TM-33 .xml, .gldf, files read by content);
    ``compact=True`` as ``batch --compact`` (fills ``smallest_within_1pct``)."""

PathLike = Union[str, os.PathLike[str]]

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
) -> dict[str, Any]:
    """``photosolid tradeoff FILE --json`` as a dict."""

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
) -> dict[str, Any]:
    """``photosolid engines FILE --json`` as a dict."""

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
) -> dict[str, Any]:
    """``photosolid export FILE --engine ENGINE -o OUTPUT --json``: what was written."""

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
) -> dict[str, Any]:
    """``photosolid convert IN OUT --json``: what was written."""

def load(
    source: Union[PathLike, bytes, bytearray, memoryview, BinaryIO],
    *,
    name: Optional[str] = None,
    repair: bool = False,
    handedness: str = "ccw",
    lamp_sets: str = "first",
    front: Optional[float] = None,
) -> Luminaire:
    """Load a photometric file from a path, bytes or a binary file object (``name`` names bytes: its
    extension picks the format, else the content), with the CLI's reader options."""
