"""Type stubs of the photosolid package."""

import os
from typing import Callable, Iterable, Optional, Union

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
from ._native import load as load
from ._native import load_all as load_all

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
