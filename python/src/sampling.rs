//! Sampling a reconstruction: built once per luminaire (`Prepared`), at
//! angles broadcast as numpy does or along directions.

use std::sync::Arc;

use glam::DVec3;
use numpy::ndarray::ArrayD;
use numpy::{AllowTypeChange, IntoPyArray, PyArrayDyn, PyArrayLikeDyn};
use photosolid::model::IntensityField;
use photosolid::registry::{Recon, Reconstructions};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

use crate::errors::model_err;

/// One reconstruction of a luminaire, built once: a field that owns what it
/// samples, or the built reconstructions a cheap field borrows from (a
/// filter over the light texture, the measured solid, the fitted lights).
pub(crate) enum Prepared {
    Owned(Box<dyn IntensityField + Send>),
    Shared(Box<Reconstructions>, Recon),
}

impl Prepared {
    pub(crate) fn new(dist: &photosolid::Distribution, recon: Recon) -> Result<Self, photosolid::ModelError> {
        let recs = Reconstructions::new(dist.clone(), &[recon])?;
        Ok(match recs.owned_field(recon)? {
            Some(field) => Prepared::Owned(field),
            None => Prepared::Shared(Box::new(recs), recon),
        })
    }

    /// `f` of the field.
    pub(crate) fn with<T>(&self, f: impl FnOnce(&dyn IntensityField) -> T) -> Result<T, photosolid::ModelError> {
        match self {
            Prepared::Owned(field) => Ok(f(&**field)),
            Prepared::Shared(recs, recon) => Ok(f(&*recs.field(*recon)?)),
        }
    }
}

/// Points sampled between two looks at Python's signals: about 10 ms of work.
const CHUNK: usize = 1 << 16;

/// `sample` of `prepared`'s field at each of `points`, with the GIL released,
/// [`CHUNK`] points at a time: a Ctrl-C between two chunks raises
/// `KeyboardInterrupt` (millions of points stop within a few milliseconds).
fn in_chunks<P: Sync>(
    py: Python<'_>,
    prepared: &Prepared,
    points: &[P],
    sample: impl Fn(&dyn IntensityField, &P) -> f64 + Sync,
) -> PyResult<Vec<f64>> {
    let mut out = Vec::with_capacity(points.len());
    for chunk in points.chunks(CHUNK) {
        let values: Vec<f64> = py
            .detach(|| prepared.with(|field| chunk.iter().map(|p| sample(field, p)).collect()))
            .map_err(model_err)?;
        out.extend(values);
        py.check_signals()?;
    }
    Ok(out)
}

/// `prepared` at each (C, γ) pair (degrees) of two arrays of one shape.
pub(crate) fn sample_angles<'py>(
    py: Python<'py>,
    prepared: &Prepared,
    c_deg: PyArrayLikeDyn<'py, f64, AllowTypeChange>,
    gamma_deg: PyArrayLikeDyn<'py, f64, AllowTypeChange>,
) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
    let (shape, c, g) = broadcast_angles(c_deg.as_array(), gamma_deg.as_array())?;
    let pairs: Vec<(f64, f64)> = c.into_iter().zip(g).collect();
    let out = in_chunks(py, prepared, &pairs, |field, &(c, g)| field.intensity_cd(c, g))?;
    let a = ArrayD::from_shape_vec(shape, out).map_err(|e| PyValueError::new_err(e.to_string()))?;
    Ok(a.into_pyarray(py))
}

/// `c_deg` and `gamma_deg` broadcast against each other as numpy does (a
/// scalar against an array, a row against a column): the common shape and
/// both flattened in its order; a `ValueError` for shapes that do not
/// broadcast or a value that is not finite.
pub(crate) fn broadcast_angles(
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
pub(crate) fn sample_directions<'py>(
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
    let out = in_chunks(py, prepared, &v, |field, &x| field.intensity_dir_cd(x.normalize()))?;
    let a = ArrayD::from_shape_vec(shape, out).map_err(|e| PyValueError::new_err(e.to_string()))?;
    Ok(a.into_pyarray(py))
}

/// One reconstruction of a luminaire, built once (`Luminaire.field(recon)`):
/// sampling it builds nothing.
#[pyclass(frozen, module = "photosolid")]
pub(crate) struct Field {
    pub(crate) name: String,
    pub(crate) prepared: Arc<Prepared>,
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
