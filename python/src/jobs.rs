//! The CLI's jobs from Python: each function runs the library's job
//! (`photosolid::jobs`) with the CLI's options under the CLI's names, and
//! returns the document the command prints with `--json`, as a dict (a list
//! of dicts for `validate`, one per line). Where an option's CLI name is a
//! Python keyword, it ends in `_` (`--class` is `class_`).

use std::path::PathBuf;

use photosolid::jobs::{self, Named};
use photosolid::scene::road::RoadError;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

use crate::errors::{arg, int_in, located, pct_arg, py_err, to_py, Located};
use crate::{read_options, Luminaire};

/// A road's error as a Python exception: a `PhotosolidValueError` (every
/// road error is a value the user gave: an option, a `[road]` key, a table)
/// with the road's code, and the scene file, line and column where the error
/// has them.
fn road_err(e: RoadError) -> PyErr {
    let (path, line, column) = match &e {
        RoadError::AtKey { path, line, column, .. } => (Some(path.display().to_string()), Some(*line), Some(*column)),
        RoadError::File { path, .. } => (Some(path.display().to_string()), None, None),
        _ => (None, None, None),
    };
    located(Located {
        class: Some("PhotosolidValueError"),
        message: e.to_string(),
        code: e.code(),
        path,
        line,
        column,
    })
}

fn job_err(e: jobs::JobError) -> PyErr {
    match e {
        jobs::JobError::Library(e) => py_err(e),
        jobs::JobError::Road(e) => road_err(e),
    }
}

/// `--range`: `"A:B[:STEP]"` or a tuple `(A, B)` / `(A, B, STEP)`.
fn range_arg(range: &Bound<'_, PyAny>) -> PyResult<jobs::Range> {
    if let Ok(s) = range.extract::<String>() {
        return jobs::parse_range(&s).map_err(road_err);
    }
    let parts: Vec<f64> = range
        .extract()
        .map_err(|_| PyValueError::new_err("range: expected \"A:B[:STEP]\" or a tuple (A, B[, STEP])"))?;
    let text = parts.iter().map(f64::to_string).collect::<Vec<_>>().join(":");
    jobs::parse_range(&text).map_err(road_err)
}

/// `photosolid road SCENE --json` (`class_` is `--class`, `range` and `grid`
/// as the CLI writes them: `"30:40:0.5"`, `"mounting_height_m=8:12:1"`).
#[pyfunction]
#[pyo3(signature = (scene, *, class_ = None, maximize = None, range = None, grid = None))]
pub(crate) fn road<'py>(
    py: Python<'py>,
    scene: PathBuf,
    class_: Option<&str>,
    maximize: Option<&str>,
    range: Option<Bound<'py, PyAny>>,
    grid: Option<&str>,
) -> PyResult<Bound<'py, PyAny>> {
    let settings = jobs::RoadSettings {
        class: class_.map(jobs::parse_class).transpose().map_err(road_err)?,
        maximize: maximize.map(jobs::parse_key).transpose().map_err(road_err)?,
        range: range.as_ref().map(range_arg).transpose()?,
        grid: grid.map(jobs::parse_grid).transpose().map_err(road_err)?,
    };
    let answer = crate::interrupt::detached(py, move || jobs::road(&scene, &settings, None))?.map_err(road_err)?;
    to_py(py, &answer)
}

/// `photosolid scene SCENE --json`.
#[pyfunction]
pub(crate) fn scene<'py>(py: Python<'py>, scene: PathBuf) -> PyResult<Bound<'py, PyAny>> {
    let result = crate::interrupt::detached(py, move || jobs::scene(&scene, None))?.map_err(py_err)?;
    to_py(py, &result)
}

/// `photosolid plan SCENE --json` (`tolerance` as `--tolerance`, `"1%"`; `class_` as `--class`).
#[pyfunction]
#[pyo3(signature = (scene, *, tolerance = "1%", class_ = None))]
pub(crate) fn plan<'py>(
    py: Python<'py>,
    scene: PathBuf,
    tolerance: &str,
    class_: Option<&str>,
) -> PyResult<Bound<'py, PyAny>> {
    let tolerance = photosolid::numfmt::PctOfPeak::parse(tolerance, true)
        .map_err(|e| PyValueError::new_err(format!("tolerance = {tolerance:?}: {e}")))?;
    let settings = jobs::PlanSettings {
        tolerance,
        class: class_.map(jobs::parse_class).transpose().map_err(road_err)?,
        ..Default::default()
    };
    let answer = crate::interrupt::detached(py, move || jobs::plan(&scene, &settings, None))?.map_err(job_err)?;
    to_py(py, &answer)
}

/// `photosolid validate PATHS --json`: one dict per file, in the CLI's order
/// (`derived` as `--derived`; the reader options as `load`'s).
#[pyfunction]
#[pyo3(signature = (paths, *, derived = false, repair = false, handedness = "ccw", lamp_sets = "first", front = None))]
pub(crate) fn validate<'py>(
    py: Python<'py>,
    paths: Vec<PathBuf>,
    derived: bool,
    repair: bool,
    handedness: &str,
    lamp_sets: &str,
    front: Option<f64>,
) -> PyResult<Bound<'py, PyAny>> {
    let read = read_options(repair, handedness, lamp_sets, front)?;
    let validated = py
        .detach(|| jobs::validate(&paths, derived, &read, &jobs::no_progress))
        .map_err(py_err)?;
    to_py(py, &validated.lines)
}

/// `photosolid synth KIND -o OUTPUT --json`.
#[pyfunction]
#[pyo3(signature = (kind, output, *, p = 1.0, cutoff = 90.0, intensity = 1000.0, c_step = 15.0, gamma_step = 5.0, c_list = None, gamma_list = None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn synth<'py>(
    py: Python<'py>,
    kind: &str,
    output: PathBuf,
    p: f64,
    cutoff: f64,
    intensity: f64,
    c_step: f64,
    gamma_step: f64,
    c_list: Option<Vec<f64>>,
    gamma_list: Option<Vec<f64>>,
) -> PyResult<Bound<'py, PyAny>> {
    let Some(kind) = photosolid::synth::Synth::named(kind, p, cutoff) else {
        return Err(PyValueError::new_err(format!(
            "kind = {kind:?}: expected one of {}",
            photosolid::synth::Synth::NAMES.join(", ")
        )));
    };
    let mut grid = photosolid::synth::GridSpec::uniform(c_step, gamma_step).map_err(crate::errors::model_err)?;
    if let Some(c) = c_list {
        grid.c = c;
    }
    if let Some(g) = gamma_list {
        grid.gamma = g;
    }
    let settings = jobs::SynthSettings {
        kind,
        intensity_cd: intensity,
        grid,
    };
    let written = py.detach(|| jobs::synth(&output, &settings)).map_err(py_err)?;
    to_py(py, &written)
}

impl Luminaire {
    /// The document as a job running on a thread of its own owns it.
    pub(crate) fn loaded(&self) -> jobs::Loaded {
        jobs::Loaded {
            name: self.path.clone(),
            document: self.lum.clone(),
            read: self.options.clone(),
        }
    }

    /// The document as the library's jobs take it.
    pub(crate) fn named(&self) -> Named<'_> {
        Named {
            name: &self.path,
            document: &self.lum,
            handedness: self.options.handedness,
        }
    }
}

/// `photosolid tradeoff FILE --json` on a loaded luminaire (`photosolid.tradeoff`).
#[pyfunction]
#[pyo3(signature = (lum, vs = None, *, against = None, factors = None, factor = None, repeats = 5, gpu = false))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn _tradeoff<'py>(
    py: Python<'py>,
    lum: PyRef<'py, Luminaire>,
    vs: Option<PyRef<'py, Luminaire>>,
    against: Option<&str>,
    factors: Option<Vec<i64>>,
    factor: Option<i64>,
    repeats: i64,
    gpu: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let defaults = jobs::TradeoffSettings::default();
    let factors = match factors {
        Some(f) => f
            .into_iter()
            .map(|k| int_in("factors", k, 1, 64).map(|k| k as u32))
            .collect::<PyResult<_>>()?,
        None => defaults.factors,
    };
    let settings = jobs::TradeoffSettings {
        against: against.map(|a| arg("against", a)).transpose()?,
        factors,
        factor: factor
            .map(|f| int_in("factor", f, 1, i64::MAX).map(|f| f as usize))
            .transpose()?,
        repeats: int_in("repeats", repeats, 1, i64::MAX)? as usize,
        gpu,
        plots: false,
        ..defaults
    };
    let (file, other) = (lum.loaded(), vs.as_ref().map(|v| v.loaded()));
    let table = crate::interrupt::detached(py, move || {
        jobs::tradeoff(
            file.named(),
            other.as_ref().map(jobs::Loaded::named),
            &settings,
            &jobs::no_progress,
        )
    })?
    .map_err(py_err)?;
    to_py(py, &table)
}

/// `--resolution` of the engines where it is a choice: 1 to 65,536.
fn resolution_arg(resolution: Option<i64>) -> PyResult<Option<usize>> {
    resolution
        .map(|r| int_in("resolution", r, 1, 1 << 16).map(|r| r as usize))
        .transpose()
}

/// `photosolid engines FILE --json` on a loaded luminaire (`photosolid.engines`).
#[pyfunction]
#[pyo3(signature = (lum, *, engines = None, against = None, tolerance = None, resolution = None, filter = "catmull-rom", factor = 3))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn _engines<'py>(
    py: Python<'py>,
    lum: PyRef<'py, Luminaire>,
    engines: Option<Bound<'py, PyAny>>,
    against: Option<&str>,
    tolerance: Option<&str>,
    resolution: Option<i64>,
    filter: &str,
    factor: i64,
) -> PyResult<Bound<'py, PyAny>> {
    let engines = engines
        .map(|e| -> PyResult<Vec<photosolid::engines::Engine>> {
            crate::errors::recon_names(&e)?
                .iter()
                .map(|name| arg("engines", name))
                .collect()
        })
        .transpose()?;
    let settings = jobs::EnginesSettings {
        engines,
        against: against.map(|a| arg("against", a)).transpose()?,
        tolerance: tolerance.map(|t| pct_arg("tolerance", t)).transpose()?,
        resolution: resolution_arg(resolution)?,
        filter: arg("filter", filter)?,
        factor: int_in("factor", factor, 1, i64::MAX)? as usize,
        plots: false,
    };
    let file = lum.loaded();
    let report = crate::interrupt::detached(py, move || jobs::engines(file.named(), &settings))?.map_err(py_err)?;
    to_py(py, &report)
}

/// `photosolid export FILE --engine E -o OUTPUT --json` on a loaded luminaire (`photosolid.export`).
#[pyfunction]
#[pyo3(signature = (lum, output, *, engine, resolution = None, filter = "catmull-rom"))]
pub(crate) fn _export<'py>(
    py: Python<'py>,
    lum: PyRef<'py, Luminaire>,
    output: PathBuf,
    engine: &str,
    resolution: Option<i64>,
    filter: &str,
) -> PyResult<Bound<'py, PyAny>> {
    let settings = jobs::ExportSettings {
        engine: arg("engine", engine)?,
        resolution: resolution_arg(resolution)?,
        filter: arg("filter", filter)?,
    };
    let file = lum.named();
    let written = py.detach(|| jobs::export(file, &output, &settings)).map_err(py_err)?;
    to_py(py, &written)
}

/// `photosolid convert IN OUT --json` on a loaded luminaire (`photosolid.convert`).
#[pyfunction]
#[pyo3(signature = (lum, output, *, ies_version = "2002", rotate_c = 0.0, mirror = false))]
pub(crate) fn _convert<'py>(
    py: Python<'py>,
    lum: PyRef<'py, Luminaire>,
    output: PathBuf,
    ies_version: &str,
    rotate_c: f64,
    mirror: bool,
) -> PyResult<Bound<'py, PyAny>> {
    if !rotate_c.is_finite() {
        return Err(PyValueError::new_err(format!(
            "rotate_c = {rotate_c}: expected a finite angle in degrees"
        )));
    }
    let settings = jobs::ConvertSettings {
        write: photosolid::formats::WriteOptions {
            ies_version: arg("ies_version", ies_version)?,
        },
        rotate_c_deg: rotate_c,
        mirror,
    };
    let file = lum.named();
    let written = py.detach(|| jobs::convert(file, &output, &settings)).map_err(py_err)?;
    to_py(py, &written)
}

/// Register the job functions on the module.
pub(crate) fn add(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(road, m)?)?;
    m.add_function(wrap_pyfunction!(scene, m)?)?;
    m.add_function(wrap_pyfunction!(plan, m)?)?;
    m.add_function(wrap_pyfunction!(validate, m)?)?;
    m.add_function(wrap_pyfunction!(synth, m)?)?;
    m.add_function(wrap_pyfunction!(_tradeoff, m)?)?;
    m.add_function(wrap_pyfunction!(_engines, m)?)?;
    m.add_function(wrap_pyfunction!(_export, m)?)?;
    m.add_function(wrap_pyfunction!(_convert, m)?)?;
    Ok(())
}
