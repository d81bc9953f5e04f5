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
use std::sync::{Arc, Mutex};

use numpy::ndarray::Array2;
use numpy::{AllowTypeChange, IntoPyArray, PyArray1, PyArray2, PyArrayDyn, PyArrayLikeDyn};
use photosolid::compare::{Against, Directions, Normalize};
use photosolid::error::WarningCode;
use photosolid::fit::{fit, ErrorMetric, FitOptions, FitReport};
use photosolid::reconstruct::{Backend, Filter, LightTexture, RenderOptions};
use photosolid::registry::render_on;
use photosolid::registry::Recon;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyBytes;

mod batch;
mod errors;
mod interrupt;
mod jobs;
mod sampling;

use errors::{arg, int_in, model_err, pct_arg, py_err, recon_names, to_py, PhotosolidError};
use sampling::{sample_angles, sample_directions, Field, Prepared};

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
pub(crate) fn read_options(
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

/// A [`Luminaire`] from its name, source bytes and reader options: what
/// `Luminaire.__reduce__` returns to rebuild a pickled one, and what
/// `photosolid.load` calls on bytes and file objects; not for direct use.
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

    /// The photometric summary as a dict: exactly `photosolid info FILE --json`
    /// (the library's info job). `tilt` (`--tilt`): the installed tilt angle,
    /// degrees, through the file's tilt table; `ugr_spacing` (`--ugr-spacing`):
    /// the UGR table's spacing in H (0.25, the catalogue spacing; any 1/n of H
    /// from 0.1 to 1).
    #[pyo3(signature = (*, tilt = None, ugr_spacing = 0.25))]
    fn photometry<'py>(&self, py: Python<'py>, tilt: Option<f64>, ugr_spacing: f64) -> PyResult<Bound<'py, PyAny>> {
        if let Some(t) = tilt.filter(|t| !t.is_finite()) {
            return Err(PyValueError::new_err(format!(
                "tilt = {t}: expected a finite angle in degrees"
            )));
        }
        let settings = photosolid::jobs::InfoSettings {
            tilt_deg: tilt,
            ugr_spacing_h: ugr_spacing,
        };
        let file = self.named();
        let report = py.detach(|| photosolid::jobs::info(file, &settings)).map_err(py_err)?;
        to_py(py, &report)
    }

    /// What the file says of itself, without computing anything: `metadata`
    /// (manufacturer, luminaire and lamp names, catalogue number, ...),
    /// `declared` (lamp flux, luminaire flux, LOR, watts as the file declares
    /// them; None where it does not) and `format` (`Ies`, `Ldt` or `Tm33`),
    /// the library's `Metadata` and `Declared` as dicts.
    #[getter]
    fn metadata<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_py(
            py,
            &serde_json::json!({
                "metadata": self.lum.metadata(),
                "declared": self.lum.declared(),
                "format": self.lum.format(),
            }),
        )
    }

    /// The reader's warnings (`{line, code, message}` each, as `info --json`'s
    /// `warnings`); `warnings.warn` is not called, so a batch stays quiet.
    #[getter]
    fn warnings<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_py(py, &self.lum.warnings())
    }

    /// The UGR table of `photometry()` (CIE 117/190, as `info --json` gives it) with numpy arrays:
    /// `rooms_h` (19, 2) room X, Y in H, `reflectances` (5, 3) ceiling, walls, floor, `crosswise` and
    /// `endwise` (19, 5) UGR, and the scalars `spacing_h`, `flux_lm`, `max`. A `ValueError` naming the
    /// reason where the table is undefined (a point source: no luminous area). `tilt` and
    /// `ugr_spacing` as `photometry`'s.
    #[pyo3(signature = (*, tilt = None, ugr_spacing = 0.25))]
    fn ugr_table<'py>(
        &self,
        py: Python<'py>,
        tilt: Option<f64>,
        ugr_spacing: f64,
    ) -> PyResult<Bound<'py, pyo3::types::PyDict>> {
        let table = self.photometry(py, tilt, ugr_spacing)?.get_item("ugr_table")?;
        let table = table.cast_into::<pyo3::types::PyDict>()?;
        if let Some(reason) = table.get_item("undefined")? {
            return Err(PyValueError::new_err(format!("{}: {reason}", self.path)));
        }
        let asarray = py.import("numpy")?.getattr("asarray")?;
        for key in ["rooms_h", "reflectances", "crosswise", "endwise"] {
            if let Some(v) = table.get_item(key)? {
                table.set_item(key, asarray.call1((v, "float64"))?)?;
            }
        }
        Ok(table)
    }

    /// The measured grid as a pandas DataFrame: one row per γ (index `gamma_deg`), one column per
    /// C-plane the file holds (columns `c_deg`), candela. Needs pandas.
    fn grid_frame<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let pandas = py.import("pandas")?;
        let index = |values: Bound<'py, PyArray1<f64>>, name: &str| -> PyResult<Bound<'py, PyAny>> {
            let kwargs = pyo3::types::PyDict::new(py);
            kwargs.set_item("name", name)?;
            pandas.getattr("Index")?.call((values,), Some(&kwargs))
        };
        let kwargs = pyo3::types::PyDict::new(py);
        kwargs.set_item("index", index(self.gamma_deg(py)?, "gamma_deg")?)?;
        kwargs.set_item("columns", index(self.c_deg(py)?, "c_deg")?)?;
        let values = self.candela(py)?.getattr("T")?.call_method0("copy")?;
        pandas.getattr("DataFrame")?.call((values,), Some(&kwargs))
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
    /// `photometry()["max_cd"]` for cd). `backend` is `--backend`: `auto` (a
    /// GPU adapter when one exists, else the CPU, with a Python warning saying
    /// why), `gpu` (an error without an adapter; `WGPU_BACKEND` picks the
    /// drivers) or `cpu`; every backend renders from the same tap tables.
    #[pyo3(signature = (filter = "catmull-rom", factor = 5, *, backend = "auto"))]
    fn texture<'py>(
        &self,
        py: Python<'py>,
        filter: &str,
        factor: i64,
        backend: &str,
    ) -> PyResult<Bound<'py, PyArray2<f32>>> {
        let filter: Filter = arg("filter", filter)?;
        let factor = int_in("factor", factor, 1, 32)? as u32;
        let backend: Backend = arg("backend", backend)?;
        let on = py
            .detach(|| -> photosolid::Result<_> {
                let tex = LightTexture::new(self.lum.distribution())?;
                let options = RenderOptions {
                    filter,
                    factor,
                    ..Default::default()
                };
                render_on(backend, &tex, &options)
            })
            .map_err(py_err)?;
        if let Some(notice) = &on.notice {
            py.import("warnings")?.getattr("warn")?.call1((*notice,))?;
        }
        let r = on.rendered;
        let a = Array2::from_shape_vec((r.mapping.height, r.mapping.width), r.data)
            .map_err(|e| PyValueError::new_err(e.to_string()))?;
        Ok(a.into_pyarray(py))
    }

    /// The photometric solid of reconstruction `filter` (as `photosolid mesh
    /// FILE --filter F`, the library's mesh job): `(vertices, faces)`, float64
    /// (V, 3) in `units` (cd, peak, klm or flux, as `--units`) and int64 (F, 3)
    /// vertex indices, counter-clockwise seen from outside:
    /// `trimesh.Trimesh(vertices, faces)` takes them as they are. `filter`: a
    /// filter, `fitted-gl`, or `measured` (`--measured`). As the CLI: the
    /// adaptive grid within `tolerance` (a percent of I_max, default `"0.1%"`)
    /// unless `factor` names a fixed grid; `texture=True` (`--texture`) builds
    /// it from the filter's rendered texture (render factor `factor`, default 5).
    #[pyo3(signature = (filter = "catmull-rom", factor = None, *, tolerance = None, units = "cd", texture = false))]
    fn mesh<'py>(
        &self,
        py: Python<'py>,
        filter: &str,
        factor: Option<i64>,
        tolerance: Option<&str>,
        units: &str,
        texture: bool,
    ) -> PyResult<MeshArrays<'py>> {
        let settings = photosolid::jobs::MeshSettings {
            recon: arg("filter", filter)?,
            texture,
            factor: factor
                .map(|f| int_in("factor", f, 1, if texture { 32 } else { i64::MAX }).map(|f| f as usize))
                .transpose()?,
            tolerance: tolerance.map(|t| pct_arg("tolerance", t)).transpose()?,
            units: arg("units", units)?,
            color: false,
        };
        let file = self.loaded();
        let (v, f) = interrupt::detached(py, move || -> Result<_, photosolid::Error> {
            let built = photosolid::jobs::mesh(file.named(), &settings, &photosolid::jobs::no_progress)?;
            let v: Vec<f64> = built.mesh.positions().iter().flatten().map(|&x| f64::from(x)).collect();
            let f: Vec<i64> = built.mesh.triangles().iter().flatten().map(|&i| i64::from(i)).collect();
            Ok((v, f))
        })?
        .map_err(py_err)?;
        let (nv, nf) = (v.len() / 3, f.len() / 3);
        let bad = |e: numpy::ndarray::ShapeError| PyValueError::new_err(e.to_string());
        Ok((
            Array2::from_shape_vec((nv, 3), v).map_err(bad)?.into_pyarray(py),
            Array2::from_shape_vec((nf, 3), f).map_err(bad)?.into_pyarray(py),
        ))
    }

    /// Compare reconstructions (as `photosolid compare FILE --json`, the
    /// library's compare job): the comparison as a dict. `recons`: names
    /// (default: the CLI's); `against`: `truth`, `withheld` or a
    /// reconstruction (default as the CLI: truth when the file records one,
    /// else withheld; with `vs`, catmull-rom of `vs`). `units` (`--units`;
    /// `normalize` is its older name): cd, peak, klm or flux. `align`
    /// (`--align`, with `vs`): the best C rotation and mirror first.
    /// Its `smallest_within_1pct` names the reconstruction with the fewest
    /// bytes whose radial max error is within 1 % of I_max (or None).
    /// `tolerance` (Hausdorff) and `solid_tolerance` (adaptive solids; default
    /// 0.05%, excluded by `factor`) are percents of I_max as the CLI writes them
    /// (`"0.1%"`); a bare number is refused with the CLI's hint. `directions`
    /// (`--directions`, default `dense:20000`) given under the withheld
    /// reference has no effect: an `ignored-option` warning, in the dict and
    /// as a Python `UserWarning`.
    #[pyo3(signature = (recons = None, against = None, vs = None, folds = None, normalize = "cd", directions = None, tolerance = "0.1%", factor = None, solid_tolerance = None, *, units = None, align = false))]
    #[allow(clippy::too_many_arguments)]
    fn compare<'py>(
        &self,
        py: Python<'py>,
        recons: Option<Bound<'py, PyAny>>,
        against: Option<&str>,
        vs: Option<PyRef<'py, Luminaire>>,
        folds: Option<i64>,
        normalize: &str,
        directions: Option<&str>,
        tolerance: &str,
        factor: Option<i64>,
        solid_tolerance: Option<&str>,
        units: Option<&str>,
        align: bool,
    ) -> PyResult<Bound<'py, PyAny>> {
        let recons = recons
            .map(|rs| -> PyResult<Vec<Recon>> { recon_names(&rs)?.iter().map(|r| arg::<Recon>("recons", r)).collect() })
            .transpose()?;
        let units = match (units, normalize) {
            (Some(u), "cd") => u,
            (Some(u), n) if u != n => {
                return Err(PyValueError::new_err(format!(
                    "units = {u:?} and normalize = {n:?}: normalize is the older name of units; give one"
                )))
            }
            (_, n) => n,
        };
        if factor.is_some() && solid_tolerance.is_some() {
            return Err(PyValueError::new_err(
                "factor and solid_tolerance exclude each other (as --factor and --solid-tolerance)",
            ));
        }
        if align && vs.is_none() {
            return Err(PyValueError::new_err("align needs vs (as --align needs --vs OTHER)"));
        }
        let settings = photosolid::jobs::CompareSettings {
            recons,
            against: against.map(|a| arg::<Against>("against", a)).transpose()?,
            // The library checks k >= 2, as for the CLI.
            folds: folds
                .map(|k| int_in("folds", k, 0, i64::MAX).map(|k| k as usize))
                .transpose()?,
            units: arg::<Normalize>("units", units)?,
            align,
            directions: directions.map(|d| arg::<Directions>("directions", d)).transpose()?,
            tolerance: pct_arg("tolerance", tolerance)?,
            factor: factor
                .map(|f| int_in("factor", f, 1, i64::MAX).map(|f| f as usize))
                .transpose()?,
            solid_tolerance: solid_tolerance.map(|t| pct_arg("solid_tolerance", t)).transpose()?,
            plots: false,
            ..Default::default()
        };
        let (file, other) = (self.loaded(), vs.as_ref().map(|o| o.loaded()));
        let c = interrupt::detached(py, move || {
            use photosolid::jobs::{compare, no_progress, Loaded};
            compare(file.named(), other.as_ref().map(Loaded::named), &settings, &no_progress)
        })?
        .map_err(py_err)?;
        // An option that had no effect is also a Python warning, where a notebook shows it.
        let warn = py.import("warnings")?.getattr("warn")?;
        for w in c.warnings.iter().filter(|w| w.code == WarningCode::IgnoredOption) {
            warn.call1((w.message.clone(),))?;
        }
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

/// The native module.
#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    // The GPU is plugged in at import, as the CLI's main does at start-up: `tradeoff(gpu=True)`
    // and the `+gpu` representations then run on the adapter (WGPU_BACKEND chooses it).
    photosolid::gpu::install();
    m.add("PhotosolidError", m.py().get_type::<PhotosolidError>())?;
    errors::add_error_subclasses(m)?;
    m.add_class::<Luminaire>()?;
    m.add_class::<Field>()?;
    m.add_function(wrap_pyfunction!(load, m)?)?;
    m.add_function(wrap_pyfunction!(load_all, m)?)?;
    m.add_function(wrap_pyfunction!(batch::batch_parquet, m)?)?;
    m.add_function(wrap_pyfunction!(batch::list_inputs, m)?)?;
    jobs::add(m)?;
    m.add_function(wrap_pyfunction!(_luminaire_from_source, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
