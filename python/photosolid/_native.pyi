"""Type stubs of the native module photosolid._native (python/src/lib.rs)."""

import os
from typing import Any, Callable, Optional, Sequence, Tuple, Union, final

import numpy as np
import numpy.typing as npt

__all__ = [
    "PhotosolidError",
    "PhotosolidFileNotFoundError",
    "PhotosolidOSError",
    "PhotosolidValueError",
    "PhotosolidUnsupportedError",
    "Luminaire",
    "Field",
    "load",
    "load_all",
    "batch_parquet",
    "list_inputs",
    "road",
    "scene",
    "plan",
    "validate",
    "synth",
    "_tradeoff",
    "_engines",
    "_export",
    "_convert",
    "_luminaire_from_source",
    "__version__",
]

__version__: str

class PhotosolidError(Exception):
    """A photosolid error with its location."""

    path: Optional[str]
    """The file, when the error concerns one."""
    line: Optional[int]
    """1-based line in the file, when known."""
    column: Optional[int]
    """1-based column, when known."""
    code: str
    """A stable code: ``invalid``, ``unsupported``, ``io``, ``model``, ... (``photosolid::error::ERROR_CODES``)."""
    message: str
    """The full message (also ``str(error)``)."""

class PhotosolidFileNotFoundError(PhotosolidError, FileNotFoundError):
    """A file that does not exist (code ``io``)."""

class PhotosolidOSError(PhotosolidError, OSError):
    """A file that cannot be read or written (code ``io``)."""

class PhotosolidValueError(PhotosolidError, ValueError):
    """A malformed file or a value outside its domain (codes ``invalid``, ``model``, ...)."""

class PhotosolidUnsupportedError(PhotosolidError, NotImplementedError):
    """A file that uses a feature photosolid does not read (code ``unsupported``)."""

@final
class Field:
    """One reconstruction of a luminaire, built once (``Luminaire.field``)."""

    @property
    def name(self) -> str:
        """The reconstruction's name, as given."""
    def sample(self, c_deg: npt.ArrayLike, gamma_deg: npt.ArrayLike) -> npt.NDArray[np.float64]:
        """Intensity (cd) at each (C, gamma) pair in degrees; the shape of ``c_deg``."""
    def sample_dirs(self, dirs: npt.ArrayLike) -> npt.NDArray[np.float64]:
        """Intensity (cd) along each row of ``dirs`` (N, 3); shape (N,)."""

@final
class Luminaire:
    """A loaded photometric file (IES LM-63, EULUMDAT, TM-33 or a GLDF photometry). Immutable; pickles (with the
    bytes it was read from, parsed again on unpickling) and copies; its array properties are read-only."""

    def __eq__(self, value: object, /) -> bool: ...
    def __hash__(self) -> int: ...
    def __copy__(self) -> "Luminaire": ...
    def __deepcopy__(self, _memo: Any) -> "Luminaire": ...

    @property
    def path(self) -> str:
        """The file, as given to ``load``."""
    @property
    def id(self) -> Optional[str]:
        """The photometry's id in its GLDF container or TM-33 document, or None."""
    @property
    def c_deg(self) -> npt.NDArray[np.float64]:
        """Stored C-planes, degrees, shape (n_c,)."""
    @property
    def gamma_deg(self) -> npt.NDArray[np.float64]:
        """Gamma angles, degrees (0 = nadir), shape (n_gamma,)."""
    @property
    def candela(self) -> npt.NDArray[np.float64]:
        """Measured intensities, cd, shape (n_c, n_gamma)."""
    def full_grid(
        self,
    ) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.float64], npt.NDArray[np.float64]]:
        """The grid on the full circle of planes (``grid --full``): c_deg (n,), gamma_deg (n_gamma,), cd (n, n_gamma)."""
    @property
    def symmetry(self) -> str:
        """``none``, ``rotational``, ``c0-c180``, ``c90-c270`` or ``quadrant``."""
    def photometry(self, *, tilt: Optional[float] = None, ugr_spacing: float = 0.25) -> dict[str, Any]:
        """The photometric summary: exactly ``photosolid info FILE --json`` (``tilt``: ``--tilt``, degrees;
        ``ugr_spacing``: ``--ugr-spacing``, in H)."""
    def sample(
        self, filter: str, c_deg: npt.ArrayLike, gamma_deg: npt.ArrayLike
    ) -> npt.NDArray[np.float64]:
        """Intensity (cd) of reconstruction ``filter`` at each (C, gamma) pair (degrees); same shape as the inputs."""
    def sample_dirs(self, filter: str, dirs: npt.ArrayLike) -> npt.NDArray[np.float64]:
        """Intensity (cd) along each row of ``dirs`` (N, 3), luminaire frame (+x = C0, +y = C90, -z = nadir); shape (N,)."""
    def field(self, recon: str) -> Field:
        """Reconstruction ``recon`` built now and kept: its ``sample``/``sample_dirs`` build nothing again."""
    def texture(
        self, filter: str = "catmull-rom", factor: int = 5, *, backend: str = "auto"
    ) -> npt.NDArray[np.float32]:
        """The light texture (EXR channel Y of ``photosolid texture``): I / I_max, shape (factor R, factor P), R the
        file's mean measured gamma steps in 180 degrees, P its planes on the full circle (it depends on the file).
        ``backend`` is ``--backend``: ``auto`` (a GPU adapter when one exists, else the CPU with a warning), ``gpu``
        (an error without an adapter) or ``cpu``."""
    def mesh(
        self,
        filter: str = "catmull-rom",
        factor: Optional[int] = None,
        *,
        tolerance: Optional[str] = None,
        units: str = "cd",
        texture: bool = False,
    ) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.int64]]:
        """The photometric solid (``photosolid mesh FILE --filter F``): vertices (V, 3) in ``units`` and faces
        (F, 3), for ``trimesh.Trimesh(vertices, faces)``. As the CLI: the adaptive grid within ``tolerance`` (default
        ``"0.1%"`` of I_max) unless ``factor`` names a fixed grid; ``filter`` may be ``measured``."""
    def compare(
        self,
        recons: Optional[Union[str, Sequence[str]]] = None,
        against: Optional[str] = None,
        vs: Optional["Luminaire"] = None,
        folds: Optional[int] = None,
        normalize: str = "cd",
        directions: Optional[str] = None,
        tolerance: str = "0.1%",
        factor: int | None = None,
        solid_tolerance: Optional[str] = None,
        *,
        units: Optional[str] = None,
        align: bool = False,
    ) -> dict[str, Any]:
        """The comparison of ``photosolid compare FILE --json`` as a dict (adaptive solids within ``solid_tolerance``,
        default 0.05%, unless ``factor`` names a fixed grid). ``tolerance`` and ``solid_tolerance`` are percents of
        I_max written as the CLI's flags are (``"0.1%"``; a bare number is refused with the CLI's hint). Its
        ``smallest_within_1pct`` names the reconstruction with the fewest bytes whose radial max error is within
        1 % of I_max, or is None. ``units`` (``--units``; ``normalize`` is its older name): cd, peak, klm or flux;
        ``align`` (``--align``, with ``vs``)."""
    @property
    def metadata(self) -> dict[str, Any]:
        """``metadata`` (names, catalogue number, ...), ``declared`` (fluxes, LOR, watts as the file declares them)
        and ``format``, without computing anything."""
    @property
    def warnings(self) -> list[dict[str, Any]]:
        """The reader's warnings, ``{line, code, message}`` each."""
    def ugr_table(self, *, tilt: Optional[float] = None, ugr_spacing: float = 0.25) -> dict[str, Any]:
        """The UGR table of ``photometry()`` with numpy arrays: ``rooms_h`` (19, 2), ``reflectances`` (5, 3),
        ``crosswise`` and ``endwise`` (19, 5); a ValueError where it is undefined."""
    def grid_frame(self) -> Any:
        """The measured grid as a pandas DataFrame: index ``gamma_deg``, columns ``c_deg``, candela. Needs pandas."""
    def fit(
        self, max_lights: int = 2, error: str = "relative", tolerance: str = "1%", guard: str = "2%"
    ) -> dict[str, Any]:
        """The fit report of ``photosolid fit FILE --json`` as a dict: ``tolerance`` in percentage points of the
        fit's error, ``guard`` a percent of I_max, both written with their sign as the CLI's flags."""

def load(
    path: Union[str, os.PathLike[str]],
    *,
    repair: bool = False,
    handedness: str = "ccw",
    lamp_sets: str = "first",
    front: Optional[float] = None,
) -> Luminaire:
    """Load an .ies, .ldt, TM-33 .xml or GLDF (``FILE.gldf#ID``) file with the CLI's reader options (``--repair``,
    ``--handedness ccw|cw``, ``--lamp-sets first|sum``, ``--front DEG``); raises PhotosolidError naming the file
    and line when it is bad."""

def load_all(
    path: Union[str, os.PathLike[str]],
    *,
    repair: bool = False,
    handedness: str = "ccw",
    lamp_sets: str = "first",
    front: Optional[float] = None,
) -> list[Luminaire]:
    """Every photometry of a GLDF container or TM-33 document (the one of any other file), each with its ``id``."""

def batch_parquet(
    paths: Sequence[Union[str, os.PathLike[str]]],
    compact: bool = False,
    *,
    repair: bool = False,
    handedness: str = "ccw",
    lamp_sets: str = "first",
    front: Optional[float] = None,
    progress: Optional[Callable[[int, int], object]] = None,
) -> bytes:
    """The batch table of every input under ``paths`` (.ies, .ldt, TM-33 .xml, .gldf, files read by content) as Parquet bytes (``compact``: ``batch --compact``)."""

def list_inputs(paths: Sequence[Union[str, os.PathLike[str]]]) -> list[str]:
    """Every photometry ``photosolid batch PATHS`` reads, in its order (``FILE#ID`` per photometry of a GLDF
    container or TM-33 document)."""

def road(
    scene: Union[str, os.PathLike[str]],
    *,
    class_: Optional[str] = None,
    maximize: Optional[str] = None,
    range: Union[None, str, Tuple[float, float], Tuple[float, float, float]] = None,
    grid: Optional[str] = None,
) -> dict[str, Any]:
    """``photosolid road SCENE --json`` (``class_`` is ``--class``)."""

def scene(scene: Union[str, os.PathLike[str]]) -> dict[str, Any]:
    """``photosolid scene SCENE --json``."""

def plan(
    scene: Union[str, os.PathLike[str]], *, tolerance: str = "1%", class_: Optional[str] = None
) -> dict[str, Any]:
    """``photosolid plan SCENE --json``."""

def validate(
    paths: Sequence[Union[str, os.PathLike[str]]],
    *,
    derived: bool = False,
    repair: bool = False,
    handedness: str = "ccw",
    lamp_sets: str = "first",
    front: Optional[float] = None,
) -> list[dict[str, Any]]:
    """``photosolid validate PATHS --json``: one dict per file."""

def synth(
    kind: str,
    output: Union[str, os.PathLike[str]],
    *,
    p: float = 1.0,
    cutoff: float = 90.0,
    intensity: float = 1000.0,
    c_step: float = 15.0,
    gamma_step: float = 5.0,
    c_list: Optional[Sequence[float]] = None,
    gamma_list: Optional[Sequence[float]] = None,
) -> dict[str, Any]:
    """``photosolid synth KIND -o OUTPUT --json``: writes the file, returns what was written."""

def _tradeoff(
    lum: Luminaire,
    vs: Optional[Luminaire] = None,
    *,
    against: Optional[str] = None,
    factors: Optional[Sequence[int]] = None,
    factor: Optional[int] = None,
    repeats: int = 5,
    gpu: bool = False,
) -> dict[str, Any]: ...
def _engines(
    lum: Luminaire,
    *,
    engines: Union[None, str, Sequence[str]] = None,
    against: Optional[str] = None,
    tolerance: Optional[str] = None,
    resolution: Optional[int] = None,
    filter: str = "catmull-rom",
    factor: int = 3,
) -> dict[str, Any]: ...
def _export(
    lum: Luminaire,
    output: Union[str, os.PathLike[str]],
    *,
    engine: str,
    resolution: Optional[int] = None,
    filter: str = "catmull-rom",
) -> dict[str, Any]: ...
def _convert(
    lum: Luminaire,
    output: Union[str, os.PathLike[str]],
    *,
    ies_version: str = "2002",
    rotate_c: float = 0.0,
    mirror: bool = False,
) -> dict[str, Any]: ...
def _luminaire_from_source(
    path: Union[str, os.PathLike[str]],
    source: bytes,
    repair: bool,
    handedness: str,
    lamp_sets: str,
    front: Optional[float],
) -> Luminaire: ...
