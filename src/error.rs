//! Typed errors and warnings of the library.
//!
//! Two classes matter to a caller (after the `exr` crate): the file is bad
//! ([`ErrorKind::Invalid`]: truncation counts as bad data, not as an I/O
//! failure), or the file is valid but uses something this crate does not do
//! ([`ErrorKind::Unsupported`]). Every parse error names the file, the line
//! (and column where it helps), what was expected and what was found.
//! Recoverable oddities are not errors: they become [`Warning`]s kept on the
//! loaded luminaire, so a report can show them.

use std::fmt;
use std::path::{Path, PathBuf};

use serde::Serialize;

/// Result alias of the library.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// What kind of failure a [`ParseError`] is.
#[non_exhaustive]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ErrorKind {
    /// The data is malformed: truncated, out of range, not a number, ...
    Invalid,
    /// The data is well formed but uses a feature this crate does not support.
    Unsupported,
}

/// A position in a source file: 1-based line and optional 1-based column.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
pub struct Location {
    /// 1-based line number; 0 when the error concerns the file as a whole.
    pub line: usize,
    /// 1-based column (in bytes), when it helps.
    pub column: Option<usize>,
}

impl Location {
    /// A location on a line, without column.
    pub fn line(line: usize) -> Self {
        Self { line, column: None }
    }
    /// A location on a line and column.
    pub fn at(line: usize, column: usize) -> Self {
        Self {
            line,
            column: Some(column),
        }
    }
}

/// A number as error and warning messages print it: the shortest text that
/// reads back to the same `f64`, in scientific notation below 1e-4 and from
/// 1e16 on in magnitude (`1e-200`, not two hundred digits). Units are the
/// caller's; `NaN` and `inf` print as such.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Num(pub f64);

impl fmt::Display for Num {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let x = self.0;
        if x == 0.0 || !x.is_finite() || (1e-4..1e16).contains(&x.abs()) {
            write!(f, "{x}")
        } else {
            write!(f, "{x:e}")
        }
    }
}

/// `n` and the noun, singular for exactly one: `count(1, "file", "files")`
/// is `1 file`, `count(3, ...)` is `3 files`.
pub fn count(n: usize, one: &str, many: &str) -> String {
    format!("{n} {}", if n == 1 { one } else { many })
}

/// `x` with `n` significant digits as a reader expects it: plain decimals
/// without trailing zeros from 1e-4 to below 1e9 (`3153`, `0.316992`,
/// `-12.5`), scientific outside (`1.5e-7`); `NaN` and `inf` as such.
pub fn sig(x: f64, n: usize) -> String {
    let n = n.max(1);
    if x == 0.0 {
        return "0".into();
    }
    if !x.is_finite() {
        return x.to_string();
    }
    let a = x.abs();
    if !(1e-4..1e9).contains(&a) {
        let s = format!("{:.*e}", n - 1, x);
        // 1.500e-7 -> 1.5e-7
        return match s.split_once('e') {
            Some((m, e)) if m.contains('.') => format!("{}e{e}", m.trim_end_matches('0').trim_end_matches('.')),
            _ => s,
        };
    }
    let decimals = (n as i32 - 1 - a.log10().floor() as i32).max(0) as usize;
    let s = format!("{x:.decimals$}");
    let s = if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    };
    if s == "-0" {
        "0".into()
    } else {
        s
    }
}

/// `fraction` in percent, rounded to 12 significant digits so that a
/// percent typed by a user reads back as typed (`0.001` is `0.1`, not
/// `0.10000000000000002`).
pub fn percent_of(fraction: f64) -> f64 {
    let p = 100.0 * fraction;
    if p == 0.0 || !p.is_finite() {
        return p;
    }
    let digits = 12 - p.abs().log10().ceil() as i32;
    if !(-300..=300).contains(&digits) {
        return p;
    }
    let k = 10f64.powi(digits);
    (p * k).round() / k
}

/// Several numbers as messages print them ([`Num`]), comma-separated in brackets.
#[derive(Debug, Clone, Copy)]
pub struct Nums<'a>(pub &'a [f64]);

impl fmt::Display for Nums<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("[")?;
        for (i, &x) in self.0.iter().enumerate() {
            if i > 0 {
                f.write_str(", ")?;
            }
            write!(f, "{}", Num(x))?;
        }
        f.write_str("]")
    }
}

/// A photometric file could not be read: where, what was expected, what was found.
#[derive(Debug, Clone, PartialEq)]
pub struct ParseError {
    /// The file (`<memory>` for in-memory input).
    pub path: PathBuf,
    /// Where in the file.
    pub location: Location,
    /// Invalid or unsupported.
    pub kind: ErrorKind,
    /// What the reader expected, e.g. "number of vertical angles (integer >= 1)".
    pub expected: String,
    /// What it found, e.g. "`abc`" or "end of file".
    pub found: String,
}

impl fmt::Display for ParseError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.path.display())?;
        if self.location.line > 0 {
            write!(f, ":{}", self.location.line)?;
            if let Some(c) = self.location.column {
                write!(f, ":{c}")?;
            }
        }
        let what = match self.kind {
            ErrorKind::Unsupported => "unsupported: ",
            _ => "",
        };
        write!(f, ": {what}expected {}, found {}", self.expected, self.found)
    }
}

impl std::error::Error for ParseError {}

/// An invariant of the canonical model was violated while building it.
#[non_exhaustive]
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ModelError {
    /// An angle list is empty, unsorted, has duplicates, or leaves its range.
    #[error("{axis} angles: {reason}")]
    Angles {
        /// "C" or "gamma".
        axis: &'static str,
        /// What is wrong, with the offending values.
        reason: String,
    },
    /// The intensity table does not match the grid, or holds NaN/infinity.
    #[error("intensities: {0}")]
    Intensities(String),
    /// A computation needs a non-zero distribution (normalisation, fitting).
    #[error("the distribution is zero everywhere: {0}")]
    AllZero(&'static str),
    /// An internal invariant does not hold: a bug in photosolid, reported
    /// instead of a panic.
    #[error("internal error (a bug in photosolid, please report it): {0}")]
    Internal(String),
    /// A parameter is outside its documented domain.
    #[error("{name} = {value}: {reason}")]
    Parameter {
        /// Parameter name as the CLI spells it.
        name: &'static str,
        /// The value given.
        value: String,
        /// Allowed domain.
        reason: String,
    },
}

/// Every error of the library.
#[non_exhaustive]
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A file's content is bad or unsupported.
    #[error(transparent)]
    Parse(#[from] ParseError),
    /// Reading or writing a file failed.
    #[error("{path}: {source}", path = .path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// A model invariant or parameter domain was violated.
    #[error(transparent)]
    Model(#[from] ModelError),
    /// A mesh file (OBJ, PLY, STL or GLB) whose content is not a mesh this
    /// crate reads.
    #[error("{path}: cannot read the mesh: {source}", path = .path.display())]
    MeshFile {
        /// The file.
        path: PathBuf,
        /// What the mesh reader found wrong.
        source: ModelError,
    },
    /// A mesh with no triangles where one with triangles is needed (a solid
    /// is never empty, and glTF cannot hold an empty mesh).
    #[error("{path}: the mesh has no triangles; expected at least one", path = .path.display())]
    EmptyMesh {
        /// The file that was to be written.
        path: PathBuf,
    },
    /// The GPU path failed: no adapter, the device, a pipeline, a read-back.
    #[error(transparent)]
    Gpu(#[from] GpuError),
    /// An output could not be encoded (PNG, EXR, JSON, Arrow, Parquet).
    #[error("cannot encode {format}: {message}")]
    Encode {
        /// The format being written, e.g. "PNG".
        format: &'static str,
        /// The encoder's message.
        message: String,
    },
    /// An output (or mesh input) path whose extension names no format this
    /// crate writes (or reads) there.
    #[error(
        "{path}: cannot tell the {what} from the extension; expected {accepted}",
        path = .path.display(),
        accepted = join_or(.accepted)
    )]
    UnknownExtension {
        /// The path given.
        path: PathBuf,
        /// What the extension selects, e.g. "mesh format".
        what: &'static str,
        /// The extensions accepted there, with their dot: `[".obj", ".ply"]`.
        accepted: &'static [&'static str],
    },
    /// A check found nothing to check (no file loaded, no render compared):
    /// a check that checked nothing fails.
    #[error("checked nothing: {0}")]
    NothingChecked(String),
}

/// `a`, `a or b`, `a, b or c`.
fn join_or(items: &[&str]) -> String {
    match items {
        [] => String::new(),
        [one] => (*one).to_string(),
        [init @ .., last] => format!("{} or {last}", init.join(", ")),
    }
}

/// Errors of the GPU path (feature `gpu`). The type exists without the
/// feature so that [`Error`] has one shape; [`GpuError::NotBuilt`] is then
/// what asking for the GPU gives.
#[non_exhaustive]
#[derive(Clone, Debug, thiserror::Error)]
pub enum GpuError {
    /// No adapter on any of the tried backends.
    #[error(
        "no GPU adapter found (backends tried: {tried}; {detail}); install a Vulkan or GL driver, e.g. Mesa's \
         software drivers (`apt-get install mesa-vulkan-drivers libvulkan1 libegl-mesa0`, see \
         scripts/install-gpu-drivers.sh), or use --backend cpu"
    )]
    NoAdapter {
        /// Backends that were tried.
        tried: String,
        /// wgpu's last message.
        detail: String,
    },
    /// Device creation, a submission or a wait failed.
    #[error("GPU device error: {0}")]
    Device(String),
    /// A shader or pipeline could not be created (a driver that cannot compile it).
    #[error("GPU pipeline error: {0}")]
    Pipeline(String),
    /// A read-back buffer could not be mapped or read.
    #[error("GPU read-back error: {0}")]
    BufferMap(String),
    /// A job is malformed.
    #[error("render job {index}: {reason}")]
    InvalidJob {
        /// Index of the job in the batch.
        index: usize,
        /// What is wrong.
        reason: String,
    },
    /// A single job does not fit the device's limits.
    #[error("render job {index} is too large for this device: {reason}")]
    TooLarge {
        /// Index of the job in the batch.
        index: usize,
        /// Which limit.
        reason: String,
    },
    /// This build has no GPU support (cargo feature `gpu` off).
    #[error("this photosolid binary was built without GPU support (cargo feature `gpu`)")]
    NotBuilt,
}

impl GpuError {
    /// The stable code of this error in [`ErrorRecord::code`] (`gpu-no-adapter`, ...).
    pub fn code(&self) -> &'static str {
        match self {
            GpuError::NoAdapter { .. } => "gpu-no-adapter",
            GpuError::Device(_) => "gpu-device",
            GpuError::Pipeline(_) => "gpu-pipeline",
            GpuError::BufferMap(_) => "gpu-buffer-map",
            GpuError::InvalidJob { .. } => "gpu-invalid-job",
            GpuError::TooLarge { .. } => "gpu-too-large",
            GpuError::NotBuilt => "gpu-not-built",
        }
    }
}

impl Error {
    /// An I/O error on `path`.
    pub fn io(path: impl AsRef<Path>, source: std::io::Error) -> Self {
        Error::Io {
            path: path.as_ref().to_path_buf(),
            source,
        }
    }
}

/// An error as a machine-readable record, the shape of a [`Warning`]:
/// serialised as `{"line": 12, "column": 5, "code": "invalid", "message": "..."}`
/// (`line` and `column` are `null` when the error has none; `message` is the
/// error's full text).
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct ErrorRecord {
    /// 1-based line in the file, when the error has one.
    pub line: Option<usize>,
    /// 1-based column, when the error has one.
    pub column: Option<usize>,
    /// Stable code: `invalid` or `unsupported` (file content), `io`, `model`,
    /// `unsupported-operation`, `encode`, `unknown-extension`, `nothing-checked`,
    /// or a GPU code ([`GpuError::code`]: `gpu-no-adapter`, `gpu-device`, ...).
    pub code: &'static str,
    /// The full message (as [`std::fmt::Display`] prints it).
    pub message: String,
}

impl From<&Error> for ErrorRecord {
    fn from(e: &Error) -> Self {
        let (line, column, code) = match e {
            Error::Parse(p) => (
                (p.location.line > 0).then_some(p.location.line),
                p.location.column,
                match p.kind {
                    ErrorKind::Invalid => "invalid",
                    ErrorKind::Unsupported => "unsupported",
                },
            ),
            Error::Io { .. } => (None, None, "io"),
            Error::Model(_) => (None, None, "model"),
            Error::MeshFile { .. } => (None, None, "mesh-file"),
            Error::EmptyMesh { .. } => (None, None, "empty-mesh"),
            Error::Gpu(g) => (None, None, g.code()),
            Error::Encode { .. } => (None, None, "encode"),
            Error::UnknownExtension { .. } => (None, None, "unknown-extension"),
            Error::NothingChecked(_) => (None, None, "nothing-checked"),
        };
        Self {
            line,
            column,
            code,
            message: e.to_string(),
        }
    }
}

/// The stable code of a [`Warning`], serialised as its kebab-case string
/// (`extra-values`, `lor-mismatch`, ...), the codes files and tools rely on.
#[non_exhaustive]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum WarningCode {
    /// `angles-repaired`.
    AnglesRepaired,
    /// `blank-number`.
    BlankNumber,
    /// `c360-plane`.
    C360Plane,
    /// `cfli`.
    Cfli,
    /// `dc-mismatch`.
    DcMismatch,
    /// `dff-mismatch`.
    DffMismatch,
    /// `dg-mismatch`.
    DgMismatch,
    /// `extra-values`.
    ExtraValues,
    /// `flux-above-lamp`: a declared luminaire flux above the lamp flux (declared separately).
    FluxAboveLamp,
    /// `flux-mismatch`.
    FluxMismatch,
    /// `header-junk`.
    HeaderJunk,
    /// `invalid-ballast-factor`.
    InvalidBallastFactor,
    /// `invalid-blpf`.
    InvalidBlpf,
    /// `invalid-lumens`.
    InvalidLumens,
    /// `ityp`.
    Ityp,
    /// `lamp-set-layout`.
    LampSetLayout,
    /// `lor-above-100`: a declared or computed light output ratio above 100.5 % (relative photometry).
    #[serde(rename = "lor-above-100")]
    LorAbove100,
    /// `lor-mismatch`.
    LorMismatch,
    /// `luminous-area-larger-than-luminaire`: the luminous area exceeds the luminaire's own dimensions.
    LuminousAreaLargerThanLuminaire,
    /// `mc-divisibility`.
    McDivisibility,
    /// `missing-ballast-line`.
    MissingBallastLine,
    /// `negative-intensity`.
    NegativeIntensity,
    /// `not-a-number`.
    NotANumber,
    /// `plane-count`.
    PlaneCount,
    /// `pole-mismatch`.
    PoleMismatch,
    /// `range-snapped`.
    RangeSnapped,
    /// `seam-mismatch`.
    SeamMismatch,
    /// `single-plane`.
    SinglePlane,
    /// `tilt-extra-values`.
    TiltExtraValues,
    /// `tilt-file-keyword`.
    TiltFileKeyword,
    /// `unknown-version`.
    UnknownVersion,
    /// `unsorted-angles`.
    UnsortedAngles,
    /// `zero-lamp-flux`.
    ZeroLampFlux,
}

impl WarningCode {
    /// The code as written in JSON and text (kebab-case).
    pub fn as_str(self) -> &'static str {
        match self {
            WarningCode::AnglesRepaired => "angles-repaired",
            WarningCode::BlankNumber => "blank-number",
            WarningCode::C360Plane => "c360-plane",
            WarningCode::Cfli => "cfli",
            WarningCode::DcMismatch => "dc-mismatch",
            WarningCode::DffMismatch => "dff-mismatch",
            WarningCode::DgMismatch => "dg-mismatch",
            WarningCode::ExtraValues => "extra-values",
            WarningCode::FluxAboveLamp => "flux-above-lamp",
            WarningCode::FluxMismatch => "flux-mismatch",
            WarningCode::HeaderJunk => "header-junk",
            WarningCode::InvalidBallastFactor => "invalid-ballast-factor",
            WarningCode::InvalidBlpf => "invalid-blpf",
            WarningCode::InvalidLumens => "invalid-lumens",
            WarningCode::Ityp => "ityp",
            WarningCode::LampSetLayout => "lamp-set-layout",
            WarningCode::LorAbove100 => "lor-above-100",
            WarningCode::LorMismatch => "lor-mismatch",
            WarningCode::LuminousAreaLargerThanLuminaire => "luminous-area-larger-than-luminaire",
            WarningCode::McDivisibility => "mc-divisibility",
            WarningCode::MissingBallastLine => "missing-ballast-line",
            WarningCode::NegativeIntensity => "negative-intensity",
            WarningCode::NotANumber => "not-a-number",
            WarningCode::PlaneCount => "plane-count",
            WarningCode::PoleMismatch => "pole-mismatch",
            WarningCode::RangeSnapped => "range-snapped",
            WarningCode::SeamMismatch => "seam-mismatch",
            WarningCode::SinglePlane => "single-plane",
            WarningCode::TiltExtraValues => "tilt-extra-values",
            WarningCode::TiltFileKeyword => "tilt-file-keyword",
            WarningCode::UnknownVersion => "unknown-version",
            WarningCode::UnsortedAngles => "unsorted-angles",
            WarningCode::ZeroLampFlux => "zero-lamp-flux",
        }
    }
}

impl fmt::Display for WarningCode {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

impl PartialEq<&str> for WarningCode {
    fn eq(&self, other: &&str) -> bool {
        self.as_str() == *other
    }
}

/// A recoverable oddity found while reading or checking a file.
///
/// Serialised as `{"line": 12, "code": "nadir-mismatch", "message": "..."}`
/// (`line` is `null` when the warning concerns the whole file).
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct Warning {
    /// 1-based line number, when the warning has one.
    pub line: Option<usize>,
    /// Stable machine-readable code, kebab-case (e.g. `extra-values`).
    pub code: WarningCode,
    /// Human explanation with the numbers involved.
    pub message: String,
}

/// A warning as `validate --json` writes it, in the shape of an
/// [`ErrorRecord`]: `{line, column, code, message}` (`line` and `column`
/// `null` when the warning has none; warnings carry no column today).
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct WarningRecord {
    /// 1-based line in the file, when the warning has one.
    pub line: Option<usize>,
    /// 1-based column, when the warning has one.
    pub column: Option<usize>,
    /// Stable machine-readable code, kebab-case.
    pub code: WarningCode,
    /// Human explanation with the numbers involved.
    pub message: String,
}

impl From<&Warning> for WarningRecord {
    fn from(w: &Warning) -> Self {
        Self {
            line: w.line,
            column: None,
            code: w.code,
            message: w.message.clone(),
        }
    }
}

impl Warning {
    /// A warning about the file as a whole.
    pub fn new(code: WarningCode, message: impl Into<String>) -> Self {
        Self {
            line: None,
            code,
            message: message.into(),
        }
    }
    /// A warning about one line.
    pub fn at(line: usize, code: WarningCode, message: impl Into<String>) -> Self {
        Self {
            line: Some(line),
            code,
            message: message.into(),
        }
    }
}

impl fmt::Display for WarningRecord {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.line {
            Some(l) => write!(f, "line {l}: [{}] {}", self.code, self.message),
            None => write!(f, "[{}] {}", self.code, self.message),
        }
    }
}

impl fmt::Display for Warning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.line {
            Some(l) => write!(f, "line {l}: [{}] {}", self.code, self.message),
            None => write!(f, "[{}] {}", self.code, self.message),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{Num, Nums};

    #[test]
    fn numbers_print_short_and_read_back() {
        let cases = [
            (1e-200, "1e-200"),
            (-1e-200, "-1e-200"),
            (1e300, "1e300"),
            (4e-320, "4e-320"),
            (1.2345678901234568e29, "1.2345678901234568e29"),
            (0.0001, "0.0001"),
            (0.00009, "9e-5"),
            (123.25, "123.25"),
            (1e15, "1000000000000000"),
            (1e16, "1e16"),
            (0.0, "0"),
            (f64::NAN, "NaN"),
            (f64::NEG_INFINITY, "-inf"),
        ];
        for (x, want) in cases {
            let s = Num(x).to_string();
            assert_eq!(s, want);
            if x.is_finite() {
                assert_eq!(s.parse::<f64>().unwrap(), x, "{s} reads back");
            }
        }
        assert_eq!(Nums(&[0.0, 1e-300, 90.0]).to_string(), "[0, 1e-300, 90]");
    }
}
