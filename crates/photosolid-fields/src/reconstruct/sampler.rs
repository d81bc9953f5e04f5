//! Point lookups (f64 reference) of a [`LightTexture`] by angle or direction.
//!
//! Directions are in the luminaire frame of [`crate::model::frame`]. At a
//! pole C is 0; the value there does not depend on it for interpolating
//! filters (pole values are averaged).

use glam::DVec3;
use rayon::prelude::*;

use crate::model::frame::angles;
use crate::model::{ConstantCells, IntensityField, ANGLE_EPS};

use super::filter::Filter;
use super::texture::LightTexture;

/// Samples one texture with one filter, in f64: the reference the f32 render
/// and the GPU path are checked against.
#[derive(Debug, Clone, Copy)]
pub struct Sampler<'t> {
    texture: &'t LightTexture,
    filter: Filter,
    clamp: bool,
}

impl LightTexture {
    /// A sampler with `filter`, clamping negative overshoot to 0.
    pub fn sampler(&self, filter: Filter) -> Sampler<'_> {
        Sampler {
            texture: self,
            filter,
            clamp: true,
        }
    }
}

impl<'t> Sampler<'t> {
    /// The same sampler without clamping: cubic overshoot below 0 is returned as is.
    #[must_use]
    pub fn unclamped(self) -> Self {
        Sampler { clamp: false, ..self }
    }
    /// The filter.
    pub fn filter(&self) -> Filter {
        self.filter
    }
    /// The texture.
    pub fn texture(&self) -> &'t LightTexture {
        self.texture
    }

    /// Intensity (cd) at C, γ (degrees; C any real, wrapped), and whether it was clamped.
    #[inline]
    fn eval(&self, c_deg: f64, gamma_deg: f64) -> (f64, bool) {
        let v = self.texture.eval_cd(self.filter, c_deg, gamma_deg);
        if self.clamp && v < 0.0 {
            (0.0, true)
        } else {
            (v, false)
        }
    }

    /// Intensity (cd) at C, γ (degrees). 0 outside the measured γ band and for non-finite angles.
    pub fn cd(&self, c_deg: f64, gamma_deg: f64) -> f64 {
        if !(c_deg.is_finite() && gamma_deg.is_finite()) {
            return 0.0;
        }
        self.eval(c_deg, gamma_deg).0
    }

    /// Intensity normalised by I_max (dimensionless) at C, γ (degrees).
    pub fn normalized(&self, c_deg: f64, gamma_deg: f64) -> f64 {
        self.cd(c_deg, gamma_deg) / self.texture.i_max_cd()
    }

    /// Intensity (cd) in direction `d` (luminaire frame; normalised here). 0 for a zero or non-finite vector.
    pub fn cd_dir(&self, d: DVec3) -> f64 {
        angles(d).map_or(0.0, |(c, g)| self.cd(c, g))
    }

    /// Intensities (cd) for many directions, in parallel; returns how many were clamped.
    ///
    /// # Panics
    /// If `out` and `dirs` differ in length.
    pub fn cd_dirs(&self, dirs: &[DVec3], out: &mut [f64]) -> usize {
        assert_eq!(dirs.len(), out.len(), "one output per direction");
        out.par_iter_mut()
            .zip(dirs.par_iter())
            .map(|(o, &d)| {
                let (v, clamped) = angles(d).map_or((0.0, false), |(c, g)| self.eval(c, g));
                *o = v;
                usize::from(clamped)
            })
            .sum()
    }
}

/// A filter on the measured data is an intensity field (the reference f64
/// sampler, clamped at 0 unless [`Sampler::unclamped`]). Its bytes are the
/// texture's: the normalised grid and its axis tables.
impl IntensityField for Sampler<'_> {
    fn intensity_cd(&self, c_deg: f64, gamma_deg: f64) -> f64 {
        self.cd(c_deg, gamma_deg)
    }
    fn intensity_dir_cd(&self, d: DVec3) -> f64 {
        self.cd_dir(d)
    }
    fn name(&self) -> String {
        self.filter.to_string()
    }
    fn bytes(&self) -> usize {
        self.texture.bytes()
    }
    fn is_continuous(&self) -> bool {
        !matches!(self.filter, Filter::Nearest)
    }
    fn knot_spacing_deg(&self) -> Option<f64> {
        self.texture.knot_spacing_deg()
    }
    /// A nearest filter is constant between the midpoints of its knots
    /// (`nearest_cells`); `None` for every other filter, and where a value
    /// is negative (unclamped data below 0, which cells do not hold).
    fn constant_cells(&self) -> Option<ConstantCells> {
        if self.filter != Filter::Nearest {
            return None;
        }
        let cells = nearest_cells(self);
        cells.values_cd.iter().all(|&v| v >= 0.0).then_some(cells)
    }
}

/// The cells of a nearest filter on its texture: C edges at the midpoints
/// between neighbouring full-circle planes (the seam's included) and γ
/// edges at the midpoints between stored rows, and where the stored band
/// ends (ANGLE_EPS beyond its first and last row, where every lookup
/// becomes 0), each cell valued by the sampler at its centre. The tap picks
/// the nearer knot of the interval a query falls in, so the lookup is
/// constant on each cell; which side a midpoint itself takes does not
/// matter to a distance, since the wall between the two values is part of
/// the solid either way.
fn nearest_cells(sampler: &Sampler<'_>) -> ConstantCells {
    let g = sampler.texture.gamma_rows();
    let mut gamma_edges = vec![0.0];
    if let (Some(&a), Some(&b)) = (g.first(), g.last()) {
        gamma_edges.push(a - ANGLE_EPS);
        gamma_edges.extend(g.windows(2).map(|w| 0.5 * (w[0] + w[1])));
        gamma_edges.push(b + ANGLE_EPS);
    }
    gamma_edges.push(180.0);
    let c: Vec<f64> = sampler.texture.full_circle().map(|(c, _)| c).collect();
    let mut c_edges = vec![0.0, 360.0];
    if c.len() >= 2 {
        c_edges.extend(c.windows(2).map(|w| 0.5 * (w[0] + w[1])));
        c_edges.push(crate::model::wrap360(0.5 * (c[c.len() - 1] + c[0] + 360.0)));
    }
    let edges = |mut e: Vec<f64>, hi: f64| {
        e.retain(|x| (0.0..=hi).contains(x));
        e.sort_by(f64::total_cmp);
        e.dedup();
        e
    };
    let (gamma_edges, c_edges) = (edges(gamma_edges, 180.0), edges(c_edges, 360.0));
    let values_cd = gamma_edges
        .windows(2)
        .flat_map(|gw| {
            let g = 0.5 * (gw[0] + gw[1]);
            c_edges.windows(2).map(move |cw| (0.5 * (cw[0] + cw[1]), g))
        })
        .map(|(c, g)| sampler.cd(c, g))
        .collect();
    ConstantCells {
        gamma_edges_deg: gamma_edges,
        c_edges_deg: c_edges,
        values_cd,
    }
}
