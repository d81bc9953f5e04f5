//! `photosolid._native`: the Rust side of the Python package `photosolid`.
//!
//! A thin layer over the photosolid library: every number comes from the
//! same functions as the CLI (`info --json`, `fit --json`, `compare --json`,
//! `photosolid batch`), so the values are equal. The GIL is released
//! (`Python::detach`) around all Rust work. Errors raise
//! `photosolid.PhotosolidError` with `path`, `line`, `column`, `code` and
//! `message` attributes. Angles are degrees in the library's frame (C0 = +x,
//! C90 = +y, γ = 0 at nadir, -z); intensities are candela.

use std::collections::HashMap;
use std::path::PathBuf;
use std::sync::atomic::Ordering;
use std::sync::{Arc, Mutex};

use glam::DVec3;
use numpy::ndarray::{Array2, ArrayD};
use numpy::{AllowTypeChange, IntoPyArray, PyArray1, PyArray2, PyArrayDyn, PyArrayLikeDyn};
use photosolid::compare::{compare, Against, CompareOptions, Directions, Normalize};
use photosolid::error::{Error, ErrorRecord};
use photosolid::fit::{fit, ErrorMetric, FitOptions, FitReport};
use photosolid::model::IntensityField;
use photosolid::reconstruct::{render_with, Filter, LightTexture, RenderOptions};
use photosolid::registry::{Recon, Reconstructions};
use photosolid::report::InfoReport;
use photosolid::solid::Units;
use pyo3::exceptions::{PyException, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyBytes;

pyo3::create_exception!(
    photosolid,
    PhotosolidError,
    PyException,
    "A photosolid error: `path`, `line` and `column` (None when unknown), `code` (`invalid`, `unsupported`, \
     `io`, `model`, ...: the stable codes of `photosolid::error::ERROR_CODES`) and `message` (the full text)."
);

/// The Python exception of a library error, with its location as attributes.
fn py_err(e: Error) -> PyErr {
    let rec = ErrorRecord::from(&e);
    let path: Option<String> = match &e {
        Error::Parse(p) => Some(p.path.display().to_string()),
        Error::Io { path, .. } | Error::MeshFile { path, .. } | Error::EmptyMesh { path } => {
            Some(path.display().to_string())
        }
        _ => None,
    };
    // The subclass a Python user catches by the builtin it also derives from.
    let class = match &e {
        Error::Io { source, .. } if source.kind() == std::io::ErrorKind::NotFound => {
            Some("PhotosolidFileNotFoundError")
        }
        Error::Io { .. } => Some("PhotosolidOSError"),
        Error::Parse(p) if p.kind == photosolid::ErrorKind::Unsupported => Some("PhotosolidUnsupportedError"),
        Error::Parse(_) | Error::Model(_) | Error::UnknownExtension { .. } => Some("PhotosolidValueError"),
        _ => None,
    };
    Python::attach(|py| {
        let subclass = || -> PyResult<PyErr> {
            let cls = py
                .import("photosolid._native")?
                .getattr(class.unwrap_or("PhotosolidError"))?;
            Ok(PyErr::from_value(cls.call1((rec.message.clone(),))?))
        };
        let err = match class {
            Some(_) => subclass().unwrap_or_else(|_| PhotosolidError::new_err(rec.message.clone())),
            None => PhotosolidError::new_err(rec.message.clone()),
        };
        let v = err.value(py);
        let set = || -> PyResult<()> {
            v.setattr("path", path)?;
            v.setattr("line", rec.line)?;
            v.setattr("column", rec.column)?;
            v.setattr("code", rec.code)?;
            v.setattr("message", rec.message.clone())?;
            Ok(())
        };
        match set() {
            Ok(()) => err,
            Err(e) => e,
        }
    })
}

fn model_err(e: photosolid::ModelError) -> PyErr {
    py_err(Error::Model(e))
}

/// A `ValueError` for an argument that does not parse.
fn arg<T: std::str::FromStr>(name: &str, s: &str) -> PyResult<T>
where
    T::Err: std::fmt::Display,
{
    s.parse()
        .map_err(|e| PyValueError::new_err(format!("{name} = {s:?}: {e}")))
}

/// Argument `name`, a percent of I_max as the CLI spells it (`"0.1%"`); a
/// bare number is refused with the CLI's hint.
fn pct_arg(name: &str, value: &str) -> PyResult<photosolid::numfmt::PctOfPeak> {
    photosolid::numfmt::PctOfPeak::parse(value, false)
        .map_err(|e| PyValueError::new_err(format!("{name} = {value:?}: {e}")))
}

/// `value` of argument `name` when it lies in `lo..=hi`; a `ValueError`
/// naming the argument and its range otherwise (a negative count is a
/// value error, not an `OverflowError` of a conversion).
fn int_in(name: &str, value: i64, lo: i64, hi: i64) -> PyResult<i64> {
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
fn recon_names(recons: &Bound<'_, PyAny>) -> PyResult<Vec<String>> {
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
fn to_py<'py>(py: Python<'py>, v: &impl serde::Serialize) -> PyResult<Bound<'py, PyAny>> {
    let text = serde_json::to_string(v).map_err(|e| PyValueError::new_err(e.to_string()))?;
    py.import("json")?.call_method1("loads", (text,))
}

/// `(vertices (V, 3) f64 cd, faces (F, 3) i64)` of a solid.
type MeshArrays<'py> = (Bound<'py, PyArray2<f64>>, Bound<'py, PyArray2<i64>>);

/// A loaded photometric file (IES LM-63, EULUMDAT, TM-33 or a GLDF photometry).
#[pyclass(frozen, module = "photosolid")]
struct Luminaire {
    path: String,
    lum: photosolid::formats::Document,
    /// The bytes the document was parsed from (the file's, or its
    /// container's): a pickle carries them and parses them again, so a
    /// luminaire travels to a process or machine that has no such file.
    source: Arc<Vec<u8>>,
    /// The reader options it was read with (a pickle reads it again with them).
    options: photosolid::ReadOptions,
    /// The reconstructions built so far, by name (`Luminaire.prepared`).
    built: Mutex<HashMap<String, Arc<Prepared>>>,
}

/// The luminaire `path` names, parsed from `source` (its bytes, as
/// `document_source_bytes` reads them) with `options`.
fn luminaire_from_source(
    py: Python<'_>,
    path: PathBuf,
    source: Vec<u8>,
    options: photosolid::ReadOptions,
) -> PyResult<Luminaire> {
    let source = Arc::new(source);
    let lum = py
        .detach(|| photosolid::formats::load_document_from_bytes(&path, source.to_vec(), &options))
        .map_err(py_err)?;
    Ok(Luminaire {
        path: path.display().to_string(),
        lum,
        source,
        options,
        built: Mutex::default(),
    })
}

/// The reader options of `load`, `load_all` and `batch`, in the CLI's words
/// (`--repair`, `--handedness ccw|cw`, `--lamp-sets first|sum`, `--front DEG`).
fn read_options(
    repair: bool,
    handedness: &str,
    lamp_sets: &str,
    front: Option<f64>,
) -> PyResult<photosolid::ReadOptions> {
    if let Some(f) = front.filter(|f| !f.is_finite()) {
        return Err(PyValueError::new_err(format!(
            "front = {f}: expected a finite angle in degrees"
        )));
    }
    Ok(photosolid::ReadOptions {
        repair,
        handedness: arg("handedness", handedness)?,
        lamp_set_flux: arg("lamp_sets", lamp_sets)?,
        front_c_deg: front,
    })
}

/// The bytes `path` names and the luminaire read from them with `options`.
fn load_with(py: Python<'_>, path: PathBuf, options: photosolid::ReadOptions) -> PyResult<Luminaire> {
    let source = py
        .detach(|| photosolid::formats::document_source_bytes(&path))
        .map_err(py_err)?;
    luminaire_from_source(py, path, source, options)
}

/// `array` with numpy's write flag cleared: a property that hands out the
/// luminaire's data cannot be written through (`lum.candela[0, 0] = 1`
/// raises instead of changing a copy nobody sees).
fn read_only<'py, T>(array: Bound<'py, T>) -> PyResult<Bound<'py, T>> {
    let kwargs = pyo3::types::PyDict::new(array.py());
    kwargs.set_item("write", false)?;
    array.as_any().call_method("setflags", (), Some(&kwargs))?;
    Ok(array)
}

/// What `Luminaire.__reduce__` returns: the function that rebuilds a
/// luminaire, and its arguments (the path, the source bytes, the reader options).
type Reduced<'py> = (
    Bound<'py, PyAny>,
    (
        String,
        Bound<'py, PyBytes>,
        bool,
        &'static str,
        &'static str,
        Option<f64>,
    ),
);

/// Rebuild a pickled [`Luminaire`] from its path, source bytes and reader
/// options (what `Luminaire.__reduce__` returns); not for direct use.
#[pyfunction]
fn _luminaire_from_source(
    py: Python<'_>,
    path: PathBuf,
    source: Vec<u8>,
    repair: bool,
    handedness: &str,
    lamp_sets: &str,
    front: Option<f64>,
) -> PyResult<Luminaire> {
    let options = read_options(repair, handedness, lamp_sets, front)?;
    luminaire_from_source(py, path, source, options)
}

/// Load an .ies, .ldt, TM-33 .xml or GLDF file (`FILE.gldf#ID` for one
/// photometry of a container, `FILE.xml#ID` for one emitter of a TM-33
/// document), with the CLI's reader options: `repair` (sort unsorted and drop
/// duplicated angles, with a warning, instead of failing), `handedness` (`ccw`
/// or `cw`: the rotation sense of Type A/B horizontal angles), `lamp_sets`
/// (`first` or `sum`: which flux EULUMDAT cd/klm refer to), `front` (the
/// luminaire's front, C degrees in the file's frame, instead of its format's
/// convention). Raises a `PhotosolidError` naming the file and line when it is bad.
#[pyfunction]
#[pyo3(signature = (path, *, repair = false, handedness = "ccw", lamp_sets = "first", front = None))]
fn load(
    py: Python<'_>,
    path: PathBuf,
    repair: bool,
    handedness: &str,
    lamp_sets: &str,
    front: Option<f64>,
) -> PyResult<Luminaire> {
    load_with(py, path, read_options(repair, handedness, lamp_sets, front)?)
}

/// Every photometry `path` holds, each a `Luminaire` with its `id`: the
/// photometries of a GLDF container, the emitters of a TM-33 document, or the
/// one luminaire of any other file (options as `load`).
#[pyfunction]
#[pyo3(signature = (path, *, repair = false, handedness = "ccw", lamp_sets = "first", front = None))]
fn load_all(
    py: Python<'_>,
    path: PathBuf,
    repair: bool,
    handedness: &str,
    lamp_sets: &str,
    front: Option<f64>,
) -> PyResult<Vec<Luminaire>> {
    let options = read_options(repair, handedness, lamp_sets, front)?;
    let paths = py.detach(|| photosolid::formats::photometries_in(&path));
    paths.into_iter().map(|p| load_with(py, p, options.clone())).collect()
}

impl Luminaire {
    /// The reconstructions of the measured grid that `recon` names.
    fn field_of(&self, recon: Recon) -> Result<Reconstructions, photosolid::ModelError> {
        Reconstructions::new(self.lum.distribution().clone(), &[recon])
    }

    /// Reconstruction `name` (the `filter`/`recon` argument), built at its
    /// first use on this luminaire and kept: a later call looks it up.
    fn prepared(&self, py: Python<'_>, name: &str) -> PyResult<Arc<Prepared>> {
        let recon: Recon = arg("filter", name)?;
        let key = recon.to_string();
        py.detach(|| {
            // A poisoned lock only means another thread panicked while
            // building: the map itself is still whole.
            let mut built = self.built.lock().unwrap_or_else(|e| e.into_inner());
            if let Some(p) = built.get(&key) {
                return Ok(Arc::clone(p));
            }
            let p = Arc::new(Prepared::new(self.lum.distribution(), recon)?);
            built.insert(key, Arc::clone(&p));
            Ok(p)
        })
        .map_err(model_err)
    }
}

/// One reconstruction of a luminaire, built once: a field that owns what it
/// samples, or the built reconstructions a cheap field borrows from (a
/// filter over the light texture, the measured solid, the fitted lights).
enum Prepared {
    Owned(Box<dyn IntensityField + Send>),
    Shared(Box<Reconstructions>, Recon),
}

impl Prepared {
    fn new(dist: &photosolid::Distribution, recon: Recon) -> Result<Self, photosolid::ModelError> {
        let recs = Reconstructions::new(dist.clone(), &[recon])?;
        Ok(match recs.owned_field(recon)? {
            Some(field) => Prepared::Owned(field),
            None => Prepared::Shared(Box::new(recs), recon),
        })
    }

    /// `f` of the field.
    fn with<T>(&self, f: impl FnOnce(&dyn IntensityField) -> T) -> Result<T, photosolid::ModelError> {
        match self {
            Prepared::Owned(field) => Ok(f(&**field)),
            Prepared::Shared(recs, recon) => Ok(f(&*recs.field(*recon)?)),
        }
    }
}

/// `prepared` at each (C, γ) pair (degrees) of two arrays of one shape.
fn sample_angles<'py>(
    py: Python<'py>,
    prepared: &Prepared,
    c_deg: PyArrayLikeDyn<'py, f64, AllowTypeChange>,
    gamma_deg: PyArrayLikeDyn<'py, f64, AllowTypeChange>,
) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
    let (shape, c, g) = broadcast_angles(c_deg.as_array(), gamma_deg.as_array())?;
    let out = py
        .detach(|| prepared.with(|field| c.iter().zip(&g).map(|(&c, &g)| field.intensity_cd(c, g)).collect()))
        .map_err(model_err)?;
    let a = ArrayD::from_shape_vec(shape, out).map_err(|e| PyValueError::new_err(e.to_string()))?;
    Ok(a.into_pyarray(py))
}

/// `c_deg` and `gamma_deg` broadcast against each other as numpy does (a
/// scalar against an array, a row against a column): the common shape and
/// both flattened in its order; a `ValueError` for shapes that do not
/// broadcast or a value that is not finite.
fn broadcast_angles(
    c: numpy::ndarray::ArrayViewD<'_, f64>,
    g: numpy::ndarray::ArrayViewD<'_, f64>,
) -> PyResult<(Vec<usize>, Vec<f64>, Vec<f64>)> {
    let n = c.ndim().max(g.ndim());
    let dim = |a: &[usize], i: usize| if i + a.len() >= n { a[i + a.len() - n] } else { 1 };
    let mut shape = Vec::with_capacity(n);
    for i in 0..n {
        let (a, b) = (dim(c.shape(), i), dim(g.shape(), i));
        if a != b && a != 1 && b != 1 {
            return Err(PyValueError::new_err(format!(
                "c_deg has shape {:?} and gamma_deg {:?}: they do not broadcast to one shape",
                c.shape(),
                g.shape()
            )));
        }
        shape.push(if a == 1 { b } else { a });
    }
    let target = numpy::ndarray::IxDyn(&shape);
    let flat = |a: &numpy::ndarray::ArrayViewD<'_, f64>, name: &str| -> PyResult<Vec<f64>> {
        let v: Vec<f64> = a
            .broadcast(target.clone())
            .map(|b| b.iter().copied().collect())
            .ok_or_else(|| PyValueError::new_err(format!("{name} does not broadcast to {shape:?}")))?;
        match v.iter().position(|x| !x.is_finite()) {
            Some(i) => Err(PyValueError::new_err(format!(
                "{name} holds {} (at flat index {i} of the broadcast shape {shape:?}): angles must be finite",
                v[i]
            ))),
            None => Ok(v),
        }
    };
    Ok((shape.clone(), flat(&c, "c_deg")?, flat(&g, "gamma_deg")?))
}

/// `prepared` along each direction of `dirs`, shape (..., 3) (a single
/// direction (3,) gives a 0-d array, (N, 3) gives (N,)); none zero or not finite.
fn sample_directions<'py>(
    py: Python<'py>,
    prepared: &Prepared,
    dirs: PyArrayLikeDyn<'py, f64, AllowTypeChange>,
) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
    let d = dirs.as_array();
    if d.ndim() == 0 || d.shape()[d.ndim() - 1] != 3 {
        return Err(PyValueError::new_err(format!(
            "dirs has shape {:?}: expected (N, 3), or (3,) for one direction",
            d.shape()
        )));
    }
    let shape = d.shape()[..d.ndim() - 1].to_vec();
    let flat: Vec<f64> = d.iter().copied().collect();
    let v: Vec<DVec3> = flat.chunks_exact(3).map(|r| DVec3::new(r[0], r[1], r[2])).collect();
    if let Some(i) = v.iter().position(|x| !(x.length() > 0.0 && x.is_finite())) {
        return Err(PyValueError::new_err(format!(
            "direction {i} (in flat order) is {:?}: expected a finite, non-zero vector",
            v[i].to_array()
        )));
    }
    let out = py
        .detach(|| prepared.with(|field| v.iter().map(|&x| field.intensity_dir_cd(x.normalize())).collect()))
        .map_err(model_err)?;
    let a = ArrayD::from_shape_vec(shape, out).map_err(|e| PyValueError::new_err(e.to_string()))?;
    Ok(a.into_pyarray(py))
}

/// One reconstruction of a luminaire, built once (`Luminaire.field(recon)`):
/// sampling it builds nothing.
#[pyclass(frozen, module = "photosolid")]
struct Field {
    name: String,
    prepared: Arc<Prepared>,
}

#[pymethods]
impl Field {
    /// The reconstruction's name, as given.
    #[getter]
    fn name(&self) -> &str {
        &self.name
    }

    /// Intensity (cd) at each (C, γ) pair in degrees, as `Luminaire.sample`.
    fn sample<'py>(
        &self,
        py: Python<'py>,
        c_deg: PyArrayLikeDyn<'py, f64, AllowTypeChange>,
        gamma_deg: PyArrayLikeDyn<'py, f64, AllowTypeChange>,
    ) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
        sample_angles(py, &self.prepared, c_deg, gamma_deg)
    }

    /// Intensity (cd) along each row of `dirs`, shape (N, 3), as `Luminaire.sample_dirs`.
    fn sample_dirs<'py>(
        &self,
        py: Python<'py>,
        dirs: PyArrayLikeDyn<'py, f64, AllowTypeChange>,
    ) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
        sample_directions(py, &self.prepared, dirs)
    }

    fn __repr__(&self) -> String {
        format!("photosolid.Field({:?})", self.name)
    }
}

#[pymethods]
impl Luminaire {
    /// The file, as given to `load`.
    #[getter]
    fn path(&self) -> &str {
        &self.path
    }

    /// The photometry's id within its GLDF container or TM-33 document
    /// (`FILE.gldf#ID`, `FILE.xml#ID`), or None for a file of one photometry.
    #[getter]
    fn id(&self) -> Option<String> {
        let p = std::path::Path::new(&self.path);
        photosolid::formats::gldf::split_reference(p)
            .and_then(|(_, id)| id)
            .or_else(|| photosolid::formats::tm33::split_reference(p).map(|(_, id)| id))
    }

    /// Pickling: the path and the bytes the luminaire was parsed from, parsed
    /// again on unpickling (no file needed there); equal data, the same numbers.
    fn __reduce__<'py>(&self, py: Python<'py>) -> PyResult<Reduced<'py>> {
        let rebuild = py.import("photosolid._native")?.getattr("_luminaire_from_source")?;
        let o = &self.options;
        Ok((
            rebuild,
            (
                self.path.clone(),
                PyBytes::new(py, &self.source),
                o.repair,
                o.handedness.as_str(),
                o.lamp_set_flux.as_str(),
                o.front_c_deg,
            ),
        ))
    }

    /// A luminaire is immutable: its copy is itself.
    fn __copy__(slf: Py<Self>) -> Py<Self> {
        slf
    }

    /// A luminaire is immutable: a deep copy shares nothing mutable and may be itself.
    fn __deepcopy__(slf: Py<Self>, _memo: Bound<'_, PyAny>) -> Py<Self> {
        slf
    }

    /// The hash of the path (equal luminaires have equal paths).
    fn __hash__(&self) -> u64 {
        use std::hash::{Hash, Hasher};
        let mut h = std::collections::hash_map::DefaultHasher::new();
        self.path.hash(&mut h);
        h.finish()
    }

    /// Whether `other` is a luminaire of the same path and the same parsed data.
    fn __eq__(&self, other: &Bound<'_, PyAny>) -> bool {
        other
            .cast::<Luminaire>()
            .is_ok_and(|o| o.get().path == self.path && o.get().lum == self.lum)
    }

    /// Stored C-planes, degrees, shape (n_c,); read-only.
    #[getter]
    fn c_deg<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        read_only(PyArray1::from_slice(py, self.lum.distribution().c_angles_deg()))
    }

    /// γ angles, degrees (0 = nadir), shape (n_gamma,); read-only.
    #[getter]
    fn gamma_deg<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        read_only(PyArray1::from_slice(py, self.lum.distribution().gamma_angles_deg()))
    }

    /// Measured intensities, cd, shape (n_c, n_gamma): `candela[i, j]` at `c_deg[i]`, `gamma_deg[j]`;
    /// read-only (`.copy()` for an array to change).
    #[getter]
    fn candela<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let d = self.lum.distribution();
        let a = Array2::from_shape_vec((d.n_c(), d.n_gamma()), d.intensities_cd().to_vec())
            .map_err(|e| PyValueError::new_err(e.to_string()))?;
        read_only(a.into_pyarray(py))
    }

    /// The grid on the full circle of planes (symmetry expanded), as `photosolid grid FILE --full`:
    /// `(c_deg (n,), gamma_deg (n_gamma,), candela (n, n_gamma))`, degrees and cd.
    #[allow(clippy::type_complexity)]
    fn full_grid<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(
        Bound<'py, PyArray1<f64>>,
        Bound<'py, PyArray1<f64>>,
        Bound<'py, PyArray2<f64>>,
    )> {
        let d = self.lum.distribution().expand(1);
        let c = d.c_angles_deg().to_vec();
        let a = Array2::from_shape_vec((d.n_c(), d.n_gamma()), d.intensities_cd().to_vec())
            .map_err(|e| PyValueError::new_err(e.to_string()))?;
        Ok((
            PyArray1::from_vec(py, c),
            PyArray1::from_slice(py, d.gamma_angles_deg()),
            a.into_pyarray(py),
        ))
    }

    /// Symmetry of the stored planes: `none`, `rotational`, `c0-c180`, `c90-c270`, `quadrant`.
    #[getter]
    fn symmetry(&self) -> String {
        serde_json::to_value(self.lum.distribution().symmetry())
            .ok()
            .and_then(|v| v.as_str().map(str::to_string))
            .unwrap_or_default()
    }

    /// The photometric summary as a dict: exactly `photosolid info FILE --json`.
    fn photometry<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let report = py.detach(|| InfoReport::of_document(&self.lum));
        to_py(py, &report)
    }

    /// Intensity (cd) of reconstruction `filter` (a filter such as `bilinear`,
    /// `catmull-rom`, `pchip`; or `measured`, `fitted-gl`, a texture spec,
    /// `sh:L`, `lobes:K`) at each (C, γ) pair in degrees; `c_deg` and
    /// `gamma_deg` have one shape, the result has it too (float64). The
    /// reconstruction is built at the first call for `filter` and kept (see
    /// `field`).
    fn sample<'py>(
        &self,
        py: Python<'py>,
        filter: &str,
        c_deg: PyArrayLikeDyn<'py, f64, AllowTypeChange>,
        gamma_deg: PyArrayLikeDyn<'py, f64, AllowTypeChange>,
    ) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
        let prepared = self.prepared(py, filter)?;
        sample_angles(py, &prepared, c_deg, gamma_deg)
    }

    /// Intensity (cd) of reconstruction `filter` along each row of `dirs`, shape
    /// (N, 3) (any length, not zero; luminaire frame: +x = C0, +y = C90, -z =
    /// nadir); returns shape (N,). Built once per `filter`, as `sample`.
    fn sample_dirs<'py>(
        &self,
        py: Python<'py>,
        filter: &str,
        dirs: PyArrayLikeDyn<'py, f64, AllowTypeChange>,
    ) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
        let prepared = self.prepared(py, filter)?;
        sample_directions(py, &prepared, dirs)
    }

    /// Reconstruction `recon` (the names of `sample`) as a `Field`, built now
    /// and shared with `sample`: its `sample` and `sample_dirs` look it up
    /// without building anything again.
    fn field(&self, py: Python<'_>, recon: &str) -> PyResult<Field> {
        let prepared = self.prepared(py, recon)?;
        Ok(Field {
            name: recon.trim().to_string(),
            prepared,
        })
    }

    /// The light texture `photosolid texture FILE --filter F --factor K` writes
    /// (its EXR channel `Y`): float32, shape (height, width) = (K·R, K·P) with R
    /// the number of the file's mean measured γ steps in 180° (at least 1) and P
    /// the number of planes on the full circle (so it depends on the file: a
    /// 5° grid of 72 planes gives (36·K, 72·K)); γ rows from nadir, C columns from C0; texel centres at (i + 0.5)·180/height
    /// and (j + 0.5)·360/width degrees), values I / I_max (multiply by
    /// `photometry()["max_cd"]` for cd).
    #[pyo3(signature = (filter = "catmull-rom", factor = 5))]
    fn texture<'py>(&self, py: Python<'py>, filter: &str, factor: i64) -> PyResult<Bound<'py, PyArray2<f32>>> {
        let filter: Filter = arg("filter", filter)?;
        let factor = int_in("factor", factor, 1, 32)? as u32;
        let r = py
            .detach(|| -> Result<_, photosolid::ModelError> {
                let tex = LightTexture::new(self.lum.distribution())?;
                render_with(
                    &tex,
                    &RenderOptions {
                        filter,
                        factor,
                        ..Default::default()
                    },
                )
            })
            .map_err(model_err)?;
        let a = Array2::from_shape_vec((r.mapping.height, r.mapping.width), r.data)
            .map_err(|e| PyValueError::new_err(e.to_string()))?;
        Ok(a.into_pyarray(py))
    }

    /// The photometric solid of reconstruction `filter` (as `photosolid mesh
    /// FILE --filter F --factor K`): `(vertices, faces)`, float64 (V, 3) in cd
    /// and int64 (F, 3) vertex indices, counter-clockwise seen from outside:
    /// `trimesh.Trimesh(vertices, faces)` takes them as they are.
    #[pyo3(signature = (filter = "catmull-rom", factor = 5))]
    fn mesh<'py>(&self, py: Python<'py>, filter: &str, factor: i64) -> PyResult<MeshArrays<'py>> {
        let recon: Recon = arg("filter", filter)?;
        let factor = int_in("factor", factor, 1, i64::MAX)? as usize;
        let (v, f) = py
            .detach(|| -> Result<_, photosolid::ModelError> {
                let mesh = self.field_of(recon)?.solid_in(recon, factor, Units::Candela)?;
                let v: Vec<f64> = mesh.positions().iter().flatten().map(|&x| f64::from(x)).collect();
                let f: Vec<i64> = mesh.triangles().iter().flatten().map(|&i| i64::from(i)).collect();
                Ok((v, f))
            })
            .map_err(model_err)?;
        let (nv, nf) = (v.len() / 3, f.len() / 3);
        let bad = |e: numpy::ndarray::ShapeError| PyValueError::new_err(e.to_string());
        Ok((
            Array2::from_shape_vec((nv, 3), v).map_err(bad)?.into_pyarray(py),
            Array2::from_shape_vec((nf, 3), f).map_err(bad)?.into_pyarray(py),
        ))
    }

    /// Compare reconstructions (as `photosolid compare FILE --json`): the
    /// comparison as a dict. `recons`: names (default: the CLI's); `against`:
    /// `truth`, `withheld` or a reconstruction (default as the CLI: truth when
    /// the file records one, else withheld; with `vs`, catmull-rom of `vs`).
    /// Its `smallest_within_1pct` names the reconstruction with the fewest
    /// bytes whose radial max error is within 1 % of I_max (or None).
    /// `tolerance` (Hausdorff) and `solid_tolerance` (adaptive solids; default
    /// 0.05%, excluded by `factor`) are percents of I_max as the CLI writes them
    /// (`"0.1%"`); a bare number is refused with the CLI's hint.
    #[pyo3(signature = (recons = None, against = None, vs = None, folds = 2, normalize = "cd", directions = "dense:20000", tolerance = "0.1%", factor = None, solid_tolerance = None))]
    #[allow(clippy::too_many_arguments)]
    fn compare<'py>(
        &self,
        py: Python<'py>,
        recons: Option<Bound<'py, PyAny>>,
        against: Option<&str>,
        vs: Option<PyRef<'py, Luminaire>>,
        folds: i64,
        normalize: &str,
        directions: &str,
        tolerance: &str,
        factor: Option<i64>,
        solid_tolerance: Option<&str>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let defaults = CompareOptions::default();
        let recons = match recons {
            Some(rs) => recon_names(&rs)?
                .iter()
                .map(|r| arg::<Recon>("recons", r))
                .collect::<PyResult<_>>()?,
            None => defaults.recons.clone(),
        };
        let folds = int_in("folds", folds, 0, i64::MAX)? as usize; // the library checks k >= 2, as for the CLI
        let factor = factor
            .map(|f| int_in("factor", f, 1, i64::MAX).map(|f| f as usize))
            .transpose()?;
        let opts = CompareOptions {
            recons,
            against: against.map(|a| arg::<Against>("against", a)).transpose()?,
            truth: photosolid::synth::Truth::of_luminaire(&self.lum),
            folds,
            normalize: arg::<Normalize>("normalize", normalize)?,
            lamp_flux_lm: [
                self.lum.declared().lamp_flux_lm,
                vs.as_ref().and_then(|o| o.lum.declared().lamp_flux_lm),
            ],
            directions: arg::<Directions>("directions", directions)?,
            tolerance: pct_arg("tolerance", tolerance)?.fraction(),
            // As the CLI: adaptive grid solids unless `factor` names a fixed grid.
            factor: factor.unwrap_or(defaults.factor),
            solid_tolerance: match (factor, solid_tolerance) {
                (Some(_), Some(_)) => {
                    return Err(PyValueError::new_err(
                        "factor and solid_tolerance exclude each other (as --factor and --solid-tolerance)",
                    ))
                }
                (Some(_), None) => None,
                (None, Some(t)) => Some(pct_arg("solid_tolerance", t)?.fraction()),
                (None, None) => defaults.solid_tolerance,
            },
            // As the CLI: a Type A/B file's withheld reference withholds its own readings
            // (read with the default handedness, as `load` reads).
            source: self
                .lum
                .source_grid()
                .map(|grid| photosolid::compare::SourceMeasurements {
                    grid: grid.clone(),
                    handedness: self.options.handedness,
                }),
            ..defaults
        };
        let other = vs.as_ref().map(|o| o.lum.distribution());
        let mut c = py
            .detach(|| compare(self.lum.distribution(), other, &opts))
            .map_err(model_err)?;
        c.file = self.path.clone();
        c.vs = vs.as_ref().map(|o| o.path.clone());
        c.warnings = photosolid::compare::file_warnings(
            &self.lum.luminaire,
            vs.as_ref().map(|o| (o.path.as_str(), &o.lum.luminaire)),
        );
        to_py(py, &c)
    }

    /// Fit at most `max_lights` OpenGL lights (as `photosolid fit FILE --json`): the fit report as a dict.
    /// `tolerance` is in percentage points of the fit's error (`"1%"`), `guard` a percent of I_max
    /// (`"2%"`), written as the CLI's `--tolerance` and `--guard`; a bare number is refused.
    #[pyo3(signature = (max_lights = 2, error = "relative", tolerance = "1%", guard = "2%"))]
    fn fit<'py>(
        &self,
        py: Python<'py>,
        max_lights: i64,
        error: &str,
        tolerance: &str,
        guard: &str,
    ) -> PyResult<Bound<'py, PyAny>> {
        let metric = match error {
            "relative" => ErrorMetric::Relative,
            "solid-angle" => ErrorMetric::SolidAngle,
            e => return Err(PyValueError::new_err(format!("error = {e:?}: relative or solid-angle"))),
        };
        let options = FitOptions {
            max_lights: int_in("max_lights", max_lights, 1, 2)? as usize,
            metric,
            guard: pct_arg("guard", guard)?.fraction(),
            tolerance: photosolid::numfmt::parse_percentage_points(tolerance)
                .map_err(|e| PyValueError::new_err(format!("tolerance = {tolerance:?}: {e}")))?
                / 100.0,
            ..Default::default()
        };
        let report = py
            .detach(|| fit(self.lum.distribution(), &options).map(|f| FitReport::of(&f)))
            .map_err(model_err)?;
        to_py(py, &report)
    }

    fn __repr__(&self) -> String {
        let d = self.lum.distribution();
        format!(
            "<photosolid.Luminaire {:?}: {} C-planes x {} gamma angles>",
            self.path,
            d.n_c(),
            d.n_gamma()
        )
    }
}

/// The batch table of every input under `paths` (.ies, .ldt, TM-33 .xml,
/// .gldf, files read by content) (as `photosolid
/// batch PATHS -o OUT.parquet`, with `compact` as `--compact`) as Parquet
/// bytes; `photosolid.batch` reads them into a `pyarrow.Table`.
#[pyfunction]
#[pyo3(signature = (paths, compact = false, *, repair = false, handedness = "ccw", lamp_sets = "first", front = None, progress = None))]
#[allow(clippy::too_many_arguments)]
fn batch_parquet<'py>(
    py: Python<'py>,
    paths: Vec<PathBuf>,
    compact: bool,
    repair: bool,
    handedness: &str,
    lamp_sets: &str,
    front: Option<f64>,
    progress: Option<Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyBytes>> {
    let read = read_options(repair, handedness, lamp_sets, front)?;
    let files = py.detach(|| photosolid::batch::collect(&paths)).map_err(py_err)?;
    let options = photosolid::batch::BatchOptions { compact, read };
    let done = std::sync::atomic::AtomicUsize::new(0);
    let stop = std::sync::atomic::AtomicBool::new(false);
    let report = |n: usize| -> PyResult<()> {
        match &progress {
            Some(callback) => callback.call1((n, files.len())).map(drop),
            None => Ok(()),
        }
    };
    let rows = interruptible(
        py,
        || photosolid::batch::run_until(&files, &options, &|d, _, _| done.store(d, Ordering::Relaxed), &stop),
        &stop,
        || report(done.load(Ordering::Relaxed)),
    )?;
    let Some(rows) = rows else {
        return Err(pyo3::exceptions::PyKeyboardInterrupt::new_err("batch stopped"));
    };
    report(files.len())?;
    let bytes = py
        .detach(|| photosolid::batch::table::parquet_bytes(&rows))
        .map_err(py_err)?;
    Ok(PyBytes::new(py, &bytes))
}

/// Run `work` on a thread of its own while this one, every 0.1 s, lets
/// Python handle its signals (a Ctrl-C raises `KeyboardInterrupt` here) and
/// calls `tick` (progress). On an exception `stop` is set, so `work` stops
/// starting new items, and the exception is raised once `work` returns
/// (within the items already started: a file of a batch, not the batch).
fn interruptible<T: Send>(
    py: Python<'_>,
    work: impl FnOnce() -> T + Send,
    stop: &std::sync::atomic::AtomicBool,
    mut tick: impl FnMut() -> PyResult<()>,
) -> PyResult<T> {
    std::thread::scope(|s| {
        let handle = s.spawn(work);
        let mut failure: Option<PyErr> = None;
        while !handle.is_finished() {
            py.detach(|| {
                for _ in 0..20 {
                    if handle.is_finished() {
                        break;
                    }
                    std::thread::sleep(std::time::Duration::from_millis(5));
                }
            });
            if failure.is_none() {
                if let Err(e) = py.check_signals().and_then(|()| tick()) {
                    stop.store(true, Ordering::Relaxed);
                    failure = Some(e);
                }
            }
        }
        let out = py
            .detach(|| handle.join())
            .map_err(|_| pyo3::exceptions::PyRuntimeError::new_err("a photosolid worker thread panicked (a bug)"))?;
        match failure {
            Some(e) => Err(e),
            None => Ok(out),
        }
    })
}

/// Every photometry `photosolid batch PATHS` reads, in its order: files named
/// explicitly whatever their extension, and below each directory the .ies,
/// .ldt, TM-33 .xml and .gldf files and the extension-less files read by
/// content; a GLDF container or a TM-33 document with several photometries as
/// one `FILE#ID` path each. The one list of `batch` (the library's
/// `batch::collect`), for recipes that shard it.
#[pyfunction]
fn list_inputs(py: Python<'_>, paths: Vec<PathBuf>) -> PyResult<Vec<String>> {
    let files = py.detach(|| photosolid::batch::collect(&paths)).map_err(py_err)?;
    Ok(files.iter().map(|p| p.display().to_string()).collect())
}

/// The subclasses of `PhotosolidError` that also derive from the builtin a
/// Python user catches: a missing file is a `FileNotFoundError`, another
/// I/O failure an `OSError`, a malformed file or a value outside its domain a
/// `ValueError`, a feature the readers do not support a `NotImplementedError`.
/// Each keeps `path`, `line`, `column`, `code` and `message`.
fn add_error_subclasses(m: &Bound<'_, PyModule>) -> PyResult<()> {
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

/// The native module.
#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("PhotosolidError", m.py().get_type::<PhotosolidError>())?;
    add_error_subclasses(m)?;
    m.add_class::<Luminaire>()?;
    m.add_class::<Field>()?;
    m.add_function(wrap_pyfunction!(load, m)?)?;
    m.add_function(wrap_pyfunction!(load_all, m)?)?;
    m.add_function(wrap_pyfunction!(batch_parquet, m)?)?;
    m.add_function(wrap_pyfunction!(list_inputs, m)?)?;
    m.add_function(wrap_pyfunction!(_luminaire_from_source, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
