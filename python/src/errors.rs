//! Errors and arguments: a library error as the Python exception a user
//! catches, and the checks of arguments written as the CLI writes them.

use photosolid::error::{Error, ErrorRecord};
use pyo3::exceptions::{PyException, PyValueError};
use pyo3::prelude::*;

pyo3::create_exception!(
    photosolid,
    PhotosolidError,
    PyException,
    "A photosolid error: `path`, `line` and `column` (None when unknown), `code` (`invalid`, `unsupported`, \
     `io`, `model`, ...: the stable codes of `photosolid::error::ERROR_CODES`) and `message` (the full text)."
);

/// The Python exception of a library error, with its location as attributes.
pub(crate) fn py_err(e: Error) -> PyErr {
    let rec = ErrorRecord::from(&e);
    let path: Option<String> = match &e {
        Error::Parse(p) => Some(p.path.display().to_string()),
        Error::Layer(l) => l.path().map(|p| p.display().to_string()),
        Error::Io { path, .. } => Some(path.display().to_string()),
        _ => None,
    };
    // The subclass a Python user catches by the builtin it also derives from.
    let class = match &e {
        Error::Io { source, .. } if source.kind() == std::io::ErrorKind::NotFound => {
            Some("PhotosolidFileNotFoundError")
        }
        Error::Io { .. } => Some("PhotosolidOSError"),
        Error::Parse(p) if p.kind == photosolid::ErrorKind::Unsupported => Some("PhotosolidUnsupportedError"),
        Error::Parse(_) | Error::Model(_) | Error::UnknownExtension { .. } | Error::Option { .. } => {
            Some("PhotosolidValueError")
        }
        _ => None,
    };
    located(Located {
        class,
        message: rec.message,
        code: rec.code,
        path,
        line: rec.line,
        column: rec.column,
    })
}

/// What a raised photosolid exception carries.
pub(crate) struct Located {
    /// The `PhotosolidError` subclass of `photosolid._native` (None: `PhotosolidError` itself).
    pub(crate) class: Option<&'static str>,
    /// The full message.
    pub(crate) message: String,
    /// The stable code.
    pub(crate) code: &'static str,
    /// The file, when the error concerns one.
    pub(crate) path: Option<String>,
    /// 1-based line, when known.
    pub(crate) line: Option<usize>,
    /// 1-based column, when known.
    pub(crate) column: Option<usize>,
}

/// The exception `e` describes, its location and code as attributes: the one
/// place a photosolid error (the library's, a road's) becomes a Python exception.
pub(crate) fn located(e: Located) -> PyErr {
    Python::attach(|py| {
        let subclass = |name: &str| -> PyResult<PyErr> {
            let cls = py.import("photosolid._native")?.getattr(name)?;
            Ok(PyErr::from_value(cls.call1((e.message.clone(),))?))
        };
        let err = match e.class {
            Some(name) => subclass(name).unwrap_or_else(|_| PhotosolidError::new_err(e.message.clone())),
            None => PhotosolidError::new_err(e.message.clone()),
        };
        let v = err.value(py);
        let set = || -> PyResult<()> {
            v.setattr("path", e.path)?;
            v.setattr("line", e.line)?;
            v.setattr("column", e.column)?;
            v.setattr("code", e.code)?;
            v.setattr("message", e.message.clone())?;
            Ok(())
        };
        match set() {
            Ok(()) => err,
            Err(failed) => failed,
        }
    })
}

pub(crate) fn model_err(e: photosolid::ModelError) -> PyErr {
    py_err(Error::Model(e))
}

/// A `ValueError` for an argument that does not parse.
pub(crate) fn arg<T: std::str::FromStr>(name: &str, s: &str) -> PyResult<T>
where
    T::Err: std::fmt::Display,
{
    s.parse()
        .map_err(|e| PyValueError::new_err(format!("{name} = {s:?}: {e}")))
}

/// Argument `name`, a percent of I_max as the CLI spells it (`"0.1%"`); a
/// bare number is refused with the CLI's hint.
pub(crate) fn pct_arg(name: &str, value: &str) -> PyResult<photosolid::numfmt::PctOfPeak> {
    photosolid::numfmt::PctOfPeak::parse(value, false)
        .map_err(|e| PyValueError::new_err(format!("{name} = {value:?}: {e}")))
}

/// `value` of argument `name` when it lies in `lo..=hi`; a `ValueError`
/// naming the argument and its range otherwise (a negative count is a
/// value error, not an `OverflowError` of a conversion).
pub(crate) fn int_in(name: &str, value: i64, lo: i64, hi: i64) -> PyResult<i64> {
    if (lo..=hi).contains(&value) {
        Ok(value)
    } else {
        Err(PyValueError::new_err(format!(
            "{name} = {value}: expected {lo} to {hi}"
        )))
    }
}

/// The reconstruction names of `recons`: one string (comma-separated, as
/// the CLI's `--recon`) or a sequence of strings.
pub(crate) fn recon_names(recons: &Bound<'_, PyAny>) -> PyResult<Vec<String>> {
    if let Ok(s) = recons.extract::<String>() {
        return Ok(s
            .split(',')
            .map(|r| r.trim().to_string())
            .filter(|r| !r.is_empty())
            .collect());
    }
    recons.extract::<Vec<String>>().map_err(|_| {
        pyo3::exceptions::PyTypeError::new_err(format!(
            "recons = {}: expected a string (\"bilinear\" or \"bilinear,pchip\") or a list of strings",
            recons.repr().map(|r| r.to_string()).unwrap_or_default()
        ))
    })
}

/// A serde value as a Python object (through `json.loads`, so it equals the CLI's JSON).
pub(crate) fn to_py<'py>(py: Python<'py>, v: &impl serde::Serialize) -> PyResult<Bound<'py, PyAny>> {
    let text = serde_json::to_string(v).map_err(|e| PyValueError::new_err(e.to_string()))?;
    py.import("json")?.call_method1("loads", (text,))
}

/// The subclasses of `PhotosolidError` that also derive from the builtin a
/// Python user catches: a missing file is a `FileNotFoundError`, another
/// I/O failure an `OSError`, a malformed file or a value outside its domain a
/// `ValueError`, a feature the readers do not support a `NotImplementedError`.
/// Each keeps `path`, `line`, `column`, `code` and `message`.
pub(crate) fn add_error_subclasses(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    let builtins = py.import("builtins")?;
    let base = py.get_type::<PhotosolidError>();
    for (name, builtin, doc) in [
        (
            "PhotosolidFileNotFoundError",
            "FileNotFoundError",
            "A file that does not exist.",
        ),
        ("PhotosolidOSError", "OSError", "A file that cannot be read or written."),
        (
            "PhotosolidValueError",
            "ValueError",
            "A malformed file, or a value outside its domain.",
        ),
        (
            "PhotosolidUnsupportedError",
            "NotImplementedError",
            "A file that uses a feature photosolid does not read.",
        ),
    ] {
        let namespace = pyo3::types::PyDict::new(py);
        namespace.set_item("__module__", "photosolid")?;
        namespace.set_item("__doc__", doc)?;
        let bases = pyo3::types::PyTuple::new(py, [base.as_any(), &builtins.getattr(builtin)?])?;
        let class = builtins.getattr("type")?.call1((name, bases, namespace))?;
        m.add(name, class)?;
    }
    Ok(())
}
