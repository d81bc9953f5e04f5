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

mod layer;
mod roundtrip;
mod warning;

pub use layer::{LayerError, Layered};
pub use roundtrip::Difference;
pub use warning::{Warning, WarningCode, WarningRecord};

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
    /// `:line` or `:line:column` for a location with a line (to follow a path), else nothing.
    pub fn suffix(self) -> String {
        match (self.line, self.column) {
            (0, _) => String::new(),
            (line, Some(column)) => format!(":{line}:{column}"),
            (line, None) => format!(":{line}"),
        }
    }

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
        crate::numfmt::write_shortest(f, self.0)
    }
}

/// `n` and the noun, singular for exactly one: `count(1, "file", "files")`
/// is `1 file`, `count(3, ...)` is `3 files`.
pub fn count(n: usize, one: &str, many: &str) -> String {
    format!("{n} {}", if n == 1 { one } else { many })
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
        /// "C" or "gamma" (or "horizontal"/"vertical" for a Type A/B source grid).
        axis: &'static str,
        /// What is wrong, with the offending values.
        reason: String,
    },
    /// The intensity table does not match the grid, or holds NaN/infinity.
    #[error("intensities: {0}")]
    Intensities(String),
    /// A mesh's parts do not make a mesh: an index past the vertices, an
    /// origin vertex that is not at the origin (a reader's file, or a bug).
    #[error("mesh: {0}")]
    Mesh(String),
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
    /// A derived quantity (UGR, luminance) is not defined for this
    /// luminaire; the text is what `info --json` writes as `{"undefined": ...}`.
    #[error("{}", undefined_text(.quantity, *.why))]
    Undefined {
        /// The quantity, as the sentence names it: "UGR", "luminance".
        quantity: &'static str,
        /// Why it is undefined.
        why: Undefined,
    },
    /// The luminous opening the luminaire declares is not one this crate
    /// models (a sign combination no LM-63 version defines, a non-finite
    /// size), the reason naming the values (`model::opening`).
    #[error("{0}")]
    Opening(String),
    /// A GPU representation was asked for and the GPU path failed: the GPU
    /// error (`photosolid_fields::error::GpuError`) is kept as the source
    /// ([`ModelError::code`] stays `model`).
    #[error("recon = {recon}: the GPU lookup is not available: {source}")]
    Gpu {
        /// The representation, as the CLI spells it (`catmull-rom@x5+gpu`).
        recon: String,
        /// What the GPU path reported ([`Layered::downcast_ref`] gives its type back).
        source: Layered,
    },
}

/// Why a derived quantity is undefined ([`ModelError::Undefined`]).
#[non_exhaustive]
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Undefined {
    /// The file declares no luminous area (a point source).
    NoLuminousArea,
    /// The luminaire sends no light downward (no glare).
    NoDownwardLight,
    /// No luminaire of a standard room sends light toward the observer.
    NoLightTowardObserver {
        /// The room, X × Y in H.
        room_h: (f64, f64),
    },
}

/// The sentence of [`ModelError::Undefined`] (the texts `info --json` has
/// written since the tables exist: a JSON contract).
fn undefined_text(quantity: &str, why: Undefined) -> String {
    match why {
        Undefined::NoLuminousArea => {
            format!("the file declares no luminous area (point source): {quantity} undefined")
        }
        Undefined::NoDownwardLight => {
            format!("no downward light: {quantity} undefined (no glare from the luminaires)")
        }
        Undefined::NoLightTowardObserver { room_h: (x, y) } => {
            format!("no light toward the observer in the {x}H x {y}H room: {quantity} undefined")
        }
    }
}

impl ModelError {
    /// A GPU representation `recon` (as the CLI spells it) that the GPU path failed to give,
    /// `source` the GPU's own error (kept, [`ModelError::Gpu`]).
    pub fn gpu(recon: impl Into<String>, source: impl LayerError) -> Self {
        ModelError::Gpu {
            recon: recon.into(),
            source: Layered::new(source),
        }
    }

    /// The stable code of this error in [`ErrorRecord::code`]: `model` for
    /// every invariant and parameter error (and a GPU representation that
    /// failed, as before), `undefined` and `opening` for the two kinds a
    /// caller may want to tell apart.
    pub fn code(&self) -> &'static str {
        match self {
            ModelError::Angles { .. }
            | ModelError::Intensities(_)
            | ModelError::Mesh(_)
            | ModelError::AllZero(_)
            | ModelError::Internal(_)
            | ModelError::Parameter { .. }
            | ModelError::Gpu { .. } => "model",
            ModelError::Undefined { .. } => "undefined",
            ModelError::Opening(_) => "opening",
        }
    }
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
    /// An error of a layer above this crate, of the type that layer defines: the GPU's
    /// (`GpuError`), a mesh file's (`MeshError`), a scene's (`SceneError`). Each converts
    /// into [`Error`] with `From`; [`Error::downcast_ref`] gives the type back.
    #[error(transparent)]
    Layer(Layered),
    /// A job's option that cannot be used as given (a range outside its key's values, an
    /// option that needs another): the option as the command line spells it and why.
    #[error("{option}: {message}")]
    Option {
        /// The option, as the command line spells it (`--range`, `--align`).
        option: String,
        /// What is wrong and what was expected.
        message: String,
    },
    /// A luminaire written in a format did not read back as it was (the
    /// writers' round-trip property, [`crate::formats::roundtrip`]).
    #[error("{format}: {difference}")]
    RoundTrip {
        /// The format written, e.g. "IES LM-63-2002".
        format: &'static str,
        /// The first difference.
        difference: Difference,
    },
    /// A luminaire written in a format gave text that does not read back.
    #[error("{format}: the written text does not read back: {source}")]
    RoundTripRead {
        /// The format written, e.g. "EULUMDAT".
        format: &'static str,
        /// The reader's error.
        source: Box<Error>,
    },
}

/// `a`, `a or b`, `a, b or c`.
fn join_or(items: &[&str]) -> String {
    match items {
        [] => String::new(),
        [one] => (*one).to_string(),
        [init @ .., last] => format!("{} or {last}", init.join(", ")),
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

    /// The stable code of this error ([`ErrorRecord::code`]; every code is in [`ERROR_CODES`]).
    pub fn code(&self) -> &'static str {
        match self {
            Error::Parse(p) => match p.kind {
                ErrorKind::Invalid => "invalid",
                ErrorKind::Unsupported => "unsupported",
            },
            Error::Io { .. } => "io",
            // Every model error was `model` before ModelError had codes; the
            // new kinds have their own.
            Error::Model(m) => m.code(),
            Error::Encode { .. } => "encode",
            Error::UnknownExtension { .. } => "unknown-extension",
            Error::NothingChecked(_) => "nothing-checked",
            Error::Option { .. } => "option",
            Error::Layer(l) => l.code(),
            Error::RoundTrip { .. } | Error::RoundTripRead { .. } => "round-trip",
        }
    }

    /// Where in its file the error is, when it has a line.
    pub fn location(&self) -> Option<Location> {
        let l = match self {
            Error::Parse(p) => p.location,
            Error::Layer(l) => l.location()?,
            _ => return None,
        };
        (l.line > 0).then_some(l)
    }

    /// The error of a layer above this crate as its own type `T`, when it is one.
    pub fn downcast_ref<T: LayerError>(&self) -> Option<&T> {
        match self {
            Error::Layer(l) => l.downcast_ref(),
            _ => None,
        }
    }
}

/// Every stable code an [`ErrorRecord`] (and the CLI's JSON, and the Python
/// exception's `code`) can carry, with its meaning: this crate's errors' and
/// those of the layers above ([`LayerError::code`]), one table. The documentation of
/// [`ErrorRecord::code`] lists the same codes; a unit test checks that the two
/// lists agree and that this crate's codes are here, an integration test
/// (`tests/it/typed_errors.rs`) that every code is produced by some error of some crate.
pub const ERROR_CODES: &[(&str, &str)] = &[
    (
        "invalid",
        "a file's content is malformed (ParseError, ErrorKind::Invalid)",
    ),
    (
        "unsupported",
        "a file uses a feature this crate does not read (ErrorKind::Unsupported)",
    ),
    ("io", "reading or writing a file failed (Error::Io)"),
    (
        "model",
        "a model invariant or parameter domain was violated (ModelError)",
    ),
    (
        "undefined",
        "a derived quantity is undefined for the luminaire (ModelError::Undefined)",
    ),
    (
        "opening",
        "the declared luminous opening is not one this crate models (ModelError::Opening)",
    ),
    (
        "mesh-file",
        "a mesh file is not a mesh the mesh readers read (MeshError::File)",
    ),
    (
        "empty-mesh",
        "a mesh without triangles where one is needed (MeshError::Empty)",
    ),
    ("encode", "an output could not be encoded (Error::Encode)"),
    (
        "unknown-extension",
        "a path whose extension names no format (Error::UnknownExtension)",
    ),
    (
        "nothing-checked",
        "a check that found nothing to check (Error::NothingChecked)",
    ),
    ("option", "a job's option that cannot be used as given (Error::Option)"),
    (
        "scene-invalid",
        "a value of a scene file is malformed (SceneError::Invalid)",
    ),
    (
        "inside-opening",
        "a receiver point inside a luminous opening (SceneError::InsideOpening)",
    ),
    (
        "round-trip",
        "a written luminaire does not read back as it was (Error::RoundTrip, Error::RoundTripRead)",
    ),
    ("gpu-no-adapter", "no GPU adapter (GpuError::NoAdapter)"),
    ("gpu-device", "GPU device, submission or wait failed (GpuError::Device)"),
    (
        "gpu-pipeline",
        "a GPU shader or pipeline could not be created (GpuError::Pipeline)",
    ),
    ("gpu-buffer-map", "a GPU read-back failed (GpuError::BufferMap)"),
    ("gpu-invalid-job", "a malformed GPU render job (GpuError::InvalidJob)"),
    (
        "gpu-too-large",
        "a GPU render job past the device's limits (GpuError::TooLarge)",
    ),
    ("gpu-not-built", "GPU asked of a build without it (GpuError::NotBuilt)"),
];

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
    /// Stable code ([`ERROR_CODES`]):
    /// file content: `invalid`, `unsupported`;
    /// files: `io`, `mesh-file`, `empty-mesh`, `encode`, `unknown-extension`, `round-trip`;
    /// models: `model`, `undefined`, `opening`;
    /// checks: `nothing-checked`;
    /// options of a job: `option`;
    /// scenes: `scene-invalid`, `inside-opening`;
    /// GPU (`GpuError::code`): `gpu-no-adapter`, `gpu-device`, `gpu-pipeline`,
    /// `gpu-buffer-map`, `gpu-invalid-job`, `gpu-too-large`, `gpu-not-built`.
    pub code: &'static str,
    /// The full message (as [`std::fmt::Display`] prints it).
    pub message: String,
}

impl From<&Error> for ErrorRecord {
    fn from(e: &Error) -> Self {
        let location = e.location();
        Self {
            line: location.map(|l| l.line),
            column: location.and_then(|l| l.column),
            code: e.code(),
            message: e.to_string(),
        }
    }
}

#[cfg(test)]
mod tests;
