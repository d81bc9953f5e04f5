//! Point lookups (f64 reference) of a [`LightTexture`] by angle or direction.
//!
//! Directions are in the luminaire frame of [`crate::model::frame`]. At a
//! pole C is 0; the value there does not depend on it for interpolating
//! filters (pole values are averaged).

use glam::DVec3;
use rayon::prelude::*;

use crate::model::frame::angles;
use crate::model::IntensityField;

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
}
