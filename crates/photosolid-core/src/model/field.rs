//! The seam of the pipeline: anything that answers an intensity in a direction.
//!
//! A filter on the measured grid, a rendered texture and its lookup, the
//! fitted OpenGL lights, the measured solid's radial function, an analytic
//! distribution and a scene's source are all [`IntensityField`]s. Solids,
//! metrics, the trade table, scenes and engine emulations take a field, so a
//! new reconstruction plugs in once: implement this trait.

use glam::DVec3;
use rayon::prelude::*;

use super::frame;

/// Intensities below this fraction of the peak are zero in a solid (round-off
/// of a zero: I0 cos 90° = 6e-17 I0), in the grid solids and the profiles alike.
pub const ZERO_FRACTION: f64 = 1e-9;

/// A circle on the sphere across which a field jumps (the great circle
/// bounding a lobe of exponent 0, a hemisphere's step): the directions at
/// angle acos(`cos_angle`) from `axis`. Inside
/// it the field is `jump_cd` more than the field without the part that
/// jumps ([`IntensityField::intensity_outside_rim_cd`]), so the solid has a
/// wall along it: in each rim direction u, the points t · u for t from the
/// value outside to that plus `jump_cd`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rim {
    /// The circle's centre, a unit direction of the luminaire frame.
    pub axis: DVec3,
    /// The cosine of its angular radius, in [0, 1] (1: the axis alone).
    pub cos_angle: f64,
    /// The jump (cd, > 0) from just outside the rim (and on it) to just inside.
    pub jump_cd: f64,
    /// Which part of the field jumps here, passed back to
    /// [`IntensityField::intensity_outside_rim_cd`] (a lobe mixture: the lobe).
    pub source: usize,
}

/// An intensity distribution on the whole sphere, in candela.
///
/// Implemented by every reconstruction in the crate and by every
/// `Fn(c_deg, gamma_deg) -> cd` closure that is `Sync` (named `function`,
/// holding no bytes of its own).
pub trait IntensityField: Sync {
    /// Intensity (cd) in the direction (C, γ), degrees; C any real (periodic),
    /// γ in [0, 180]. Zero where nothing is emitted; never NaN for finite
    /// angles (non-finite angles give 0).
    fn intensity_cd(&self, c_deg: f64, gamma_deg: f64) -> f64;

    /// Intensity (cd) in direction `d` of the luminaire frame
    /// ([`crate::model::frame`]); `d` need not be unit length. The zero and
    /// non-finite vectors give 0. The default converts to angles; a field
    /// that works on vectors (the fitted lights) overrides it.
    fn intensity_dir_cd(&self, d: DVec3) -> f64 {
        frame::angles(d).map_or(0.0, |(c, g)| self.intensity_cd(c, g))
    }

    /// Fill `out` (C-major, γ fastest: `out[ic * gamma.len() + ig]`) with the
    /// intensity (cd) at every grid direction. The default evaluates
    /// [`IntensityField::intensity_cd`] per point, C-planes in parallel.
    ///
    /// # Panics
    /// If `out.len() != c_deg.len() * gamma_deg.len()`.
    fn sample_grid(&self, c_deg: &[f64], gamma_deg: &[f64], out: &mut [f64]) {
        assert_eq!(
            out.len(),
            c_deg.len() * gamma_deg.len(),
            "one output per grid direction"
        );
        let ng = gamma_deg.len();
        if ng == 0 {
            return;
        }
        out.par_chunks_mut(ng).zip(c_deg.par_iter()).for_each(|(row, &c)| {
            for (o, &g) in row.iter_mut().zip(gamma_deg) {
                *o = self.intensity_cd(c, g);
            }
        });
    }

    /// The intensity (cd) at every (C, γ) of `dirs` (degrees), in order.
    /// The default evaluates [`IntensityField::intensity_cd`] per direction
    /// in parallel; a field that answers batches at once (a GPU lookup,
    /// `gpu::realtime`) overrides it. `reconstruct::eval_all` calls it.
    fn intensity_batch_cd(&self, dirs: &[(f64, f64)]) -> Vec<f64> {
        dirs.par_iter().map(|&(c, g)| self.intensity_cd(c, g)).collect()
    }

    /// For a field that answers batches ([`IntensityField::intensity_batch_cd`]
    /// overridden): the median over `repeats` runs of the wall time (ns) per
    /// direction of evaluating all of `dirs` as one batch, from the caller's
    /// side (a GPU lookup: upload, dispatch, read-back). `None` (the
    /// default): the field is timed one lookup at a time
    /// (`metrics::time_per_sample_ns`).
    fn batch_time_per_sample_ns(&self, dirs: &[DVec3], repeats: usize) -> Option<f64> {
        let _ = (dirs, repeats);
        None
    }

    /// A short name for reports and metadata (e.g. `catmull-rom`,
    /// `texture catmull-rom x5 / bilinear`, `fitted-gl`, `truth cosine p=5`).
    fn name(&self) -> String;

    /// How the representation was built, when the data chose it and its name in
    /// the registry does not say it: `rings` (a lobe mixture swept about the
    /// vertical axis, for rotationally symmetric data), `zonal` (a spherical-harmonic
    /// series with only its m = 0 terms). `None` (the default) for every other field.
    fn form(&self) -> Option<String> {
        None
    }

    /// Bytes this representation holds to answer lookups (tables, texels,
    /// light parameters), not counting what it borrows from its source data
    /// when that data is needed anyway (documented per implementation).
    fn bytes(&self) -> usize;

    /// Whether the field is known to be continuous on the sphere. A field
    /// that may jump (a nearest lookup, a spot's cut-off, a crop's edge: the
    /// default, `false`) has a solid with walls at its jumps, which a search
    /// on the surface (`photosolid::metrics::nearest`) does not see: distances
    /// to it are measured on a mesh of the solid instead.
    fn is_continuous(&self) -> bool {
        false
    }

    /// The rims across which the field jumps, when it is continuous
    /// everywhere else: `Some` of an empty list for a continuous field (the
    /// default answers [`IntensityField::is_continuous`] so), the edges of
    /// its exponent-0 lobes for a lobe mixture, `None` for a field that may
    /// jump elsewhere. The solid then has a wall along each rim, which
    /// `photosolid::metrics::nearest` measures in closed form beside its search
    /// on the surface.
    fn rims(&self) -> Option<Vec<Rim>> {
        self.is_continuous().then(Vec::new)
    }

    /// The field (cd) in unit direction `u` without the part that jumps at
    /// rim `source` ([`Rim::source`]): the outer end of the rim's wall
    /// where `u` lies on the rim. The default is the field itself (no rims).
    fn intensity_outside_rim_cd(&self, source: usize, u: DVec3) -> f64 {
        let _ = source;
        self.intensity_dir_cd(u)
    }

    /// Whether evaluating one direction is a round trip (a GPU dispatch,
    /// upload and read-back each): algorithms that ask one direction at a
    /// time (the surface search of `photosolid::metrics::nearest`) then use a
    /// batched alternative (an adaptive mesh, built from batches). `false`
    /// (the default) for every field evaluated in place.
    fn prefers_batches(&self) -> bool {
        false
    }

    /// The smallest spacing (degrees) between the grid knots the field
    /// interpolates, when it interpolates measured values on a C × γ grid:
    /// its solid can have a basin (a local minimum of the distance to a
    /// point) about that narrow, between two knots of a noisy plane, so the
    /// surface search of `photosolid::metrics::nearest` samples no coarser.
    /// `None` (the default) for a field with no such grid.
    fn knot_spacing_deg(&self) -> Option<f64> {
        None
    }

    /// The field as constant cells, when it is exactly that (a nearest
    /// lookup of a texture or of the data): its solid is then spherical patches joined by
    /// radial walls, and `photosolid::metrics::cells` measures distances to it
    /// exactly instead of on a mesh. `None` (the default) for every other field.
    fn constant_cells(&self) -> Option<ConstantCells> {
        None
    }
}

/// A field that is constant on the cells of a C × γ grid: `values_cd[i *
/// n_c + j]` on γ ∈ [`gamma_edges_deg[i]`, `gamma_edges_deg[i + 1]`) and C ∈
/// [`c_edges_deg[j]`, `c_edges_deg[j + 1]`), n_c = `c_edges_deg.len() − 1`.
/// The γ edges run from 0 to 180 and the C edges from 0 to 360 (the last
/// column meets the first at the seam), both increasing; values are cd, ≥ 0.
#[derive(Debug, Clone, PartialEq)]
pub struct ConstantCells {
    /// Row edges, degrees, 0 to 180, increasing.
    pub gamma_edges_deg: Vec<f64>,
    /// Column edges, degrees, 0 to 360, increasing.
    pub c_edges_deg: Vec<f64>,
    /// Each cell's intensity, cd, row-major (γ rows of `c_edges_deg.len() − 1` columns).
    pub values_cd: Vec<f64>,
}

impl ConstantCells {
    /// Rows (γ) and columns (C).
    pub fn shape(&self) -> (usize, usize) {
        (
            self.gamma_edges_deg.len().saturating_sub(1),
            self.c_edges_deg.len().saturating_sub(1),
        )
    }
    /// Intensity (cd) of cell (row `i`, column `j`).
    pub fn value(&self, i: usize, j: usize) -> f64 {
        self.values_cd[i * self.shape().1 + j]
    }
}

impl<F: Fn(f64, f64) -> f64 + Sync> IntensityField for F {
    fn intensity_cd(&self, c_deg: f64, gamma_deg: f64) -> f64 {
        self(c_deg, gamma_deg)
    }
    fn name(&self) -> String {
        "function".into()
    }
    fn bytes(&self) -> usize {
        std::mem::size_of_val(self)
    }
}

/// A borrowed field as an owned value (for `Box<dyn IntensityField + 'a>`
/// holding either an owned or a borrowed field). A blanket impl for `&T`
/// would overlap the closure impl, hence this newtype.
#[derive(Clone, Copy)]
pub struct Borrowed<'a>(pub &'a dyn IntensityField);

impl IntensityField for Borrowed<'_> {
    fn intensity_cd(&self, c_deg: f64, gamma_deg: f64) -> f64 {
        self.0.intensity_cd(c_deg, gamma_deg)
    }
    fn intensity_dir_cd(&self, d: DVec3) -> f64 {
        self.0.intensity_dir_cd(d)
    }
    fn sample_grid(&self, c_deg: &[f64], gamma_deg: &[f64], out: &mut [f64]) {
        self.0.sample_grid(c_deg, gamma_deg, out)
    }
    fn intensity_batch_cd(&self, dirs: &[(f64, f64)]) -> Vec<f64> {
        self.0.intensity_batch_cd(dirs)
    }
    fn batch_time_per_sample_ns(&self, dirs: &[DVec3], repeats: usize) -> Option<f64> {
        self.0.batch_time_per_sample_ns(dirs, repeats)
    }
    fn name(&self) -> String {
        self.0.name()
    }
    fn bytes(&self) -> usize {
        self.0.bytes()
    }
    fn is_continuous(&self) -> bool {
        self.0.is_continuous()
    }
    fn rims(&self) -> Option<Vec<Rim>> {
        self.0.rims()
    }
    fn intensity_outside_rim_cd(&self, source: usize, u: DVec3) -> f64 {
        self.0.intensity_outside_rim_cd(source, u)
    }
    fn prefers_batches(&self) -> bool {
        self.0.prefers_batches()
    }
    fn constant_cells(&self) -> Option<ConstantCells> {
        self.0.constant_cells()
    }
    fn knot_spacing_deg(&self) -> Option<f64> {
        self.0.knot_spacing_deg()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn closures_are_fields() {
        let f = |_c: f64, g: f64| frame::cos_deg(g).max(0.0) * 10.0;
        assert_eq!(f.intensity_cd(0.0, 0.0), 10.0);
        assert_eq!(f.intensity_dir_cd(DVec3::new(0.0, 0.0, -5.0)), 10.0);
        assert_eq!(f.intensity_dir_cd(DVec3::ZERO), 0.0);
        let mut out = vec![0.0; 6];
        f.sample_grid(&[0.0, 90.0], &[0.0, 90.0, 180.0], &mut out);
        assert_eq!(out, vec![10.0, 0.0, 0.0, 10.0, 0.0, 0.0]);
        let boxed: Box<dyn IntensityField> = Box::new(f);
        assert_eq!(boxed.intensity_cd(0.0, 0.0), 10.0);
        assert_eq!(boxed.name(), "function");
    }
}
