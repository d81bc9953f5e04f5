//! Point lookups (f64 reference) of a [`LightTexture`] by angle or direction.
//!
//! # Frame
//! The luminaire frame of [`crate::model`]: C0 = +x, C90 = +y, γ = 0 = −z:
//! `d = (sin γ cos C, sin γ sin C, −cos γ)`, and back
//! `γ = acos(−d_z)`, `C = atan2(d_y, d_x) mod 360` (degrees). At a pole C is
//! whatever `atan2` gives (0 at the exact pole); the value there does not
//! depend on it for interpolating filters (pole values are averaged).

use glam::DVec3;
use rayon::prelude::*;

use super::filter::Filter;
use super::texture::LightTexture;

/// The unit direction of (C, γ) in degrees.
pub fn direction(c_deg: f64, gamma_deg: f64) -> DVec3 {
    let (sg, cg) = gamma_deg.to_radians().sin_cos();
    let (sc, cc) = c_deg.to_radians().sin_cos();
    DVec3::new(sg * cc, sg * sc, -cg)
}

/// (C, γ) in degrees of a direction (any length; it is normalised), C in
/// [0, 360), γ in [0, 180]. `None` for a zero or non-finite vector.
pub fn angles(d: DVec3) -> Option<(f64, f64)> {
    let u = d.try_normalize()?;
    let gamma = (-u.z).clamp(-1.0, 1.0).acos().to_degrees();
    let c = crate::model::wrap360(u.y.atan2(u.x).to_degrees());
    Some((c, gamma))
}

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
