//! The OpenGL light model: up to two fixed-function lights (spot or point)
//! and its evaluation in any direction.
//!
//! # Semantics (OpenGL 1.x fixed function, `glLight`)
//! A spot with axis `a` (unit), exponent `p` ∈ [0, 128] and cut-off `c` ∈
//! [0, 90] degrees gives, for a unit direction `d`,
//! `w · max(d·a, 0)^p` when `d·a ≥ cos c` (inside the cut-off), `0` outside
//! (OpenGL spec §2.14.1: the spotlight factor). A point light (GL cut-off
//! 180) gives `w` everywhere. Zotti et al. 2005 (§3) add at most two
//! of: a spot into the lower hemisphere, a spot into the upper hemisphere, a
//! point light.
//!
//! # Attenuation
//! Only quadratic attenuation is used (`GL_CONSTANT_ATTENUATION` = 0,
//! `GL_LINEAR_ATTENUATION` = 0, `GL_QUADRATIC_ATTENUATION` = 1): with the
//! diffuse scale `w` in cd, the illuminance at distance `r` metres is
//! `I/r²` lux, the inverse-square law of far-field photometry (Zotti et al. 2005, §3). What
//! is fitted, and what [`FittedLights::intensity`] returns, is the far-field
//! intensity `I(d)` in cd.
//!
//! # Frames
//! Directions are in the luminaire frame of [`crate::model`]: z up, C0 = +x,
//! C90 = +y, nadir = −z, `d = (sinγ cosC, sinγ sinC, −cosγ)`. OpenGL scenes
//! (and Zotti et al. 2005) are y-up; [`to_gl`] maps a luminaire-frame vector into the
//! y-up frame `(x, z, −y)` (a proper rotation of −90° about x: C0 stays +x,
//! zenith becomes +y, C90 becomes −z).

use glam::DVec3;
use serde::Serialize;

use crate::error::ModelError;
use crate::model::frame::{direction, to_gl};
use crate::model::{Distribution, Symmetry};

/// The name of this reconstruction among the filters (`--filter fitted-gl`).
pub const RECONSTRUCTION_NAME: &str = "fitted-gl";
/// Largest spot exponent OpenGL accepts (`GL_SPOT_EXPONENT` ∈ [0, 128]).
pub const MAX_EXPONENT: f64 = 128.0;
/// Largest spot cut-off OpenGL accepts besides the point-light value 180 (degrees).
pub const MAX_CUTOFF_DEG: f64 = 90.0;

/// cos of the cut-off (degrees), with exact values at 0 and 90 so that the
/// inclusion test `d·a ≥ cos c` matches the geometry at the extremes.
#[inline]
pub(crate) fn cos_cutoff(cutoff_deg: f64) -> f64 {
    if cutoff_deg >= MAX_CUTOFF_DEG {
        0.0
    } else if cutoff_deg <= 0.0 {
        1.0
    } else {
        cutoff_deg.to_radians().cos()
    }
}

/// The unit-weight spot factor for `t = d·a`: `max(t, 0)^p` inside the cut-off
/// (`t ≥ cos_cut`), 0 outside. Never NaN: `0^0` is 1 (GL evaluates
/// `max(t, 0)^0` as 1 inside the cone), and `t` is clamped to 1.
#[inline]
pub(crate) fn spot_factor(t: f64, p: f64, cos_cut: f64) -> f64 {
    if t < cos_cut {
        0.0
    } else if t <= 0.0 {
        if p == 0.0 {
            1.0
        } else {
            0.0
        }
    } else {
        t.min(1.0).powf(p)
    }
}

/// Which hemisphere a spot points into.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Hemisphere {
    /// Into the lower hemisphere (γ < 90°); tilt is measured from the nadir.
    Down,
    /// Into the upper hemisphere (γ > 90°); tilt is measured from the zenith.
    Up,
}

impl Hemisphere {
    /// γ (degrees) of the direction at `tilt_deg` from this hemisphere's pole.
    #[inline]
    pub fn gamma_of_tilt(self, tilt_deg: f64) -> f64 {
        match self {
            Hemisphere::Down => tilt_deg,
            Hemisphere::Up => 180.0 - tilt_deg,
        }
    }
    /// Name used in reports.
    pub fn name(self) -> &'static str {
        match self {
            Hemisphere::Down => "down",
            Hemisphere::Up => "up",
        }
    }
}

/// An OpenGL spot light of the fitted model.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Spot {
    /// Which hemisphere the axis points into.
    pub hemisphere: Hemisphere,
    /// Diffuse scale `w`: the intensity on the axis, cd (≥ 0).
    pub weight_cd: f64,
    /// Cosine exponent `GL_SPOT_EXPONENT`, in [0, 128].
    pub exponent: f64,
    /// `GL_SPOT_CUTOFF`, degrees in [0, 90].
    pub cutoff_deg: f64,
    /// Angle of the axis from the hemisphere's pole (nadir for `Down`,
    /// zenith for `Up`), degrees in [0, 90].
    pub tilt_deg: f64,
    /// C angle (azimuth) of the axis, degrees in [0, 360); 0 when the tilt is 0.
    pub azimuth_deg: f64,
}

impl Spot {
    /// A spot on the vertical axis of `hemisphere`.
    pub fn vertical(hemisphere: Hemisphere, weight_cd: f64, exponent: f64, cutoff_deg: f64) -> Self {
        Self {
            hemisphere,
            weight_cd,
            exponent,
            cutoff_deg,
            tilt_deg: 0.0,
            azimuth_deg: 0.0,
        }
    }

    /// The unit axis (`GL_SPOT_DIRECTION`) in the luminaire frame (z up).
    pub fn axis(&self) -> DVec3 {
        direction(self.azimuth_deg, self.hemisphere.gamma_of_tilt(self.tilt_deg))
    }

    /// The unit axis in the y-up OpenGL frame of Zotti et al. 2005 (see [`to_gl`]).
    pub fn axis_gl(&self) -> DVec3 {
        to_gl(self.axis())
    }

    /// Intensity (cd) in the unit direction `d` (luminaire frame).
    #[inline]
    pub fn intensity_dir(&self, d: DVec3) -> f64 {
        let t = d.dot(self.axis());
        self.weight_cd * spot_factor(t, self.exponent, cos_cutoff(self.cutoff_deg))
    }

    /// Check the OpenGL parameter domains.
    pub fn validate(&self) -> Result<(), ModelError> {
        let bad = |name, value: f64, reason: &str| {
            Err(ModelError::Parameter {
                name,
                value: value.to_string(),
                reason: reason.into(),
            })
        };
        if !(self.weight_cd.is_finite() && self.weight_cd >= 0.0) {
            return bad("weight", self.weight_cd, "must be a finite number of cd >= 0");
        }
        if !(0.0..=MAX_EXPONENT).contains(&self.exponent) {
            return bad("exponent", self.exponent, "must be in [0, 128] (OpenGL)");
        }
        if !(0.0..=MAX_CUTOFF_DEG).contains(&self.cutoff_deg) {
            return bad("cutoff", self.cutoff_deg, "must be in [0, 90] degrees (OpenGL)");
        }
        if !(0.0..=90.0).contains(&self.tilt_deg) {
            return bad("tilt", self.tilt_deg, "must be in [0, 90] degrees");
        }
        if !self.azimuth_deg.is_finite() {
            return bad("azimuth", self.azimuth_deg, "must be finite degrees");
        }
        Ok(())
    }
}

/// One OpenGL light of the fitted model.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "lowercase")]
pub enum Light {
    /// A spot light.
    Spot(Spot),
    /// A point light (GL cut-off 180): `weight_cd` in every direction.
    Point {
        /// Diffuse scale: the intensity in every direction, cd (≥ 0).
        weight_cd: f64,
    },
}

impl Light {
    /// Intensity (cd) in the unit direction `d` (luminaire frame).
    #[inline]
    pub fn intensity_dir(&self, d: DVec3) -> f64 {
        match self {
            Light::Spot(s) => s.intensity_dir(d),
            Light::Point { weight_cd } => *weight_cd,
        }
    }
    /// The diffuse scale (cd).
    pub fn weight_cd(&self) -> f64 {
        match self {
            Light::Spot(s) => s.weight_cd,
            Light::Point { weight_cd } => *weight_cd,
        }
    }
}

/// A luminaire approximated by OpenGL lights: the `fitted-gl` reconstruction.
///
/// Like every reconstruction it answers the intensity (cd) in any direction,
/// so it can be sampled onto a grid ([`FittedLights::sample`]), a texture or a
/// mesh, and compared with the measured data by any metric.
#[derive(Debug, Clone, PartialEq, Serialize, Default)]
pub struct FittedLights {
    /// The lights, summed (at most two in a fit, any number here).
    pub lights: Vec<Light>,
}

impl FittedLights {
    /// A model from its lights.
    pub fn new(lights: Vec<Light>) -> Self {
        Self { lights }
    }

    /// Intensity (cd) in direction `d` (luminaire frame, z up; need not be
    /// unit length). The zero vector and non-finite vectors give 0.
    pub fn intensity_dir(&self, d: DVec3) -> f64 {
        let Some(u) = d.try_normalize() else {
            return 0.0;
        };
        self.lights.iter().map(|l| l.intensity_dir(u)).sum()
    }

    /// Intensity (cd) at C, γ (degrees, the frame of [`crate::model`]).
    pub fn intensity(&self, c_deg: f64, gamma_deg: f64) -> f64 {
        let d = direction(c_deg, gamma_deg);
        self.lights.iter().map(|l| l.intensity_dir(d)).sum()
    }

    /// Whether the model is rotationally symmetric about the vertical axis
    /// (every spot has tilt 0).
    pub fn is_rotational(&self) -> bool {
        self.lights.iter().all(|l| match l {
            Light::Spot(s) => s.tilt_deg == 0.0,
            Light::Point { .. } => true,
        })
    }

    /// Sample the model onto a Type C grid (degrees). `c` are full-circle
    /// planes in [0, 360) stored with [`Symmetry::None`]; when the model is
    /// rotational a single plane C = 0 with [`Symmetry::Rotational`] is stored
    /// instead, whatever `c` holds.
    pub fn sample(&self, c: &[f64], gamma: &[f64]) -> Result<Distribution, ModelError> {
        let (c, sym) = if self.is_rotational() {
            (vec![0.0], Symmetry::Rotational)
        } else {
            (c.to_vec(), Symmetry::None)
        };
        let prepared = self.prepare();
        let cd = crate::model::frame::grid_directions(&c, gamma)
            .into_iter()
            .map(|d| prepared.intensity_unit(d))
            .collect();
        Distribution::new(c, gamma.to_vec(), cd, sym)
    }

    /// Sample the model on the grid of `d`: its γ angles and its full circle
    /// of planes (see [`FittedLights::sample`]).
    pub fn sample_like(&self, d: &Distribution) -> Result<Distribution, ModelError> {
        let c: Vec<f64> = d.full_planes().iter().map(|p| p.0).collect();
        self.sample(&c, d.gamma_angles_deg())
    }
}

/// The fitted lights are an intensity field, evaluated from their GL
/// parameters on every call (see [`PreparedLights`] for a renderer's cost).
impl crate::model::IntensityField for FittedLights {
    fn intensity_cd(&self, c_deg: f64, gamma_deg: f64) -> f64 {
        if !(c_deg.is_finite() && gamma_deg.is_finite()) {
            return 0.0;
        }
        self.intensity(c_deg, gamma_deg).max(0.0)
    }
    fn intensity_dir_cd(&self, d: DVec3) -> f64 {
        self.intensity_dir(d).max(0.0)
    }
    fn name(&self) -> String {
        RECONSTRUCTION_NAME.into()
    }
    fn bytes(&self) -> usize {
        std::mem::size_of::<Self>() + self.lights.len() * std::mem::size_of::<Light>()
    }
}

/// One spot with what a shader holds in its uniforms: the unit axis, the
/// exponent, the cosine of the cut-off and the weight.
#[derive(Debug, Clone, Copy, PartialEq)]
struct PreparedSpot {
    axis: DVec3,
    exponent: f64,
    cos_cutoff: f64,
    weight_cd: f64,
}

/// The fitted lights as a renderer evaluates them: axes and cut-off cosines
/// computed once ([`FittedLights::prepare`]), point lights summed into one
/// constant. Gives exactly [`FittedLights::intensity_dir`] for unit vectors.
#[derive(Debug, Clone, PartialEq)]
pub struct PreparedLights {
    spots: Vec<PreparedSpot>,
    point_cd: f64,
}

impl FittedLights {
    /// Precompute what every evaluation needs (a renderer's uniforms).
    pub fn prepare(&self) -> PreparedLights {
        let mut spots = Vec::new();
        let mut point_cd = 0.0;
        for l in &self.lights {
            match l {
                Light::Spot(s) => spots.push(PreparedSpot {
                    axis: s.axis(),
                    exponent: s.exponent,
                    cos_cutoff: cos_cutoff(s.cutoff_deg),
                    weight_cd: s.weight_cd,
                }),
                Light::Point { weight_cd } => point_cd += weight_cd,
            }
        }
        PreparedLights { spots, point_cd }
    }
}

impl PreparedLights {
    /// Intensity (cd, ≥ 0) in the unit direction `u` (luminaire frame; not normalised here).
    #[inline]
    pub fn intensity_unit(&self, u: DVec3) -> f64 {
        let mut v = self.point_cd;
        for s in &self.spots {
            v += s.weight_cd * spot_factor(u.dot(s.axis), s.exponent, s.cos_cutoff);
        }
        v.max(0.0)
    }
}

impl crate::model::IntensityField for PreparedLights {
    fn intensity_cd(&self, c_deg: f64, gamma_deg: f64) -> f64 {
        if !(c_deg.is_finite() && gamma_deg.is_finite()) {
            return 0.0;
        }
        self.intensity_unit(direction(c_deg, gamma_deg))
    }
    fn intensity_dir_cd(&self, d: DVec3) -> f64 {
        d.try_normalize().map_or(0.0, |u| self.intensity_unit(u))
    }
    fn name(&self) -> String {
        RECONSTRUCTION_NAME.into()
    }
    fn bytes(&self) -> usize {
        std::mem::size_of::<Self>() + self.spots.len() * std::mem::size_of::<PreparedSpot>()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn directions_are_exact_at_the_axes() {
        assert_eq!(direction(0.0, 0.0), DVec3::new(0.0, 0.0, -1.0));
        assert_eq!(direction(0.0, 180.0), DVec3::new(0.0, 0.0, 1.0));
        assert_eq!(direction(90.0, 90.0), DVec3::new(0.0, 1.0, 0.0));
        assert_eq!(to_gl(DVec3::Z), DVec3::Y);
        assert_eq!(
            crate::model::frame::from_gl(to_gl(DVec3::new(1.0, 2.0, 3.0))),
            DVec3::new(1.0, 2.0, 3.0)
        );
    }

    #[test]
    fn spot_follows_gl_semantics_at_the_extremes() {
        // p = 0, cut-off 90: a hemisphere of constant intensity, horizon included.
        let s = Spot::vertical(Hemisphere::Down, 2.0, 0.0, 90.0);
        assert_eq!(s.intensity_dir(direction(0.0, 90.0)), 2.0);
        assert_eq!(s.intensity_dir(direction(0.0, 91.0)), 0.0);
        let u = Spot::vertical(Hemisphere::Up, 2.0, 0.0, 90.0);
        assert_eq!(u.intensity_dir(direction(0.0, 90.0)), 2.0);
        // cut-off 0: only the axis itself.
        let s = Spot::vertical(Hemisphere::Down, 1.0, 128.0, 0.0);
        assert_eq!(s.intensity_dir(DVec3::NEG_Z), 1.0);
        assert_eq!(s.intensity_dir(direction(0.0, 0.01)), 0.0);
        // p = 128 far off-axis underflows to 0, never NaN.
        let s = Spot::vertical(Hemisphere::Down, 1.0, 128.0, 90.0);
        let v = s.intensity_dir(direction(0.0, 89.9999));
        assert!((0.0..1e-300).contains(&v));
    }

    #[test]
    fn tilted_axis_points_where_asked() {
        let s = Spot {
            hemisphere: Hemisphere::Up,
            weight_cd: 1.0,
            exponent: 10.0,
            cutoff_deg: 30.0,
            tilt_deg: 20.0,
            azimuth_deg: 90.0,
        };
        let a = s.axis();
        let want = direction(90.0, 160.0);
        assert!((a - want).abs().max_element() < 1e-15);
        assert!((s.intensity(90.0, 160.0) - 1.0).abs() < 1e-12);
        assert_eq!(FittedLights::new(vec![Light::Spot(s)]).intensity_dir(DVec3::ZERO), 0.0);
    }

    #[test]
    fn prepared_lights_agree_with_the_parameters() {
        use crate::model::IntensityField;
        let m = FittedLights::new(vec![
            Light::Spot(Spot {
                hemisphere: Hemisphere::Down,
                weight_cd: 100.0,
                exponent: 12.0,
                cutoff_deg: 50.0,
                tilt_deg: 25.0,
                azimuth_deg: 30.0,
            }),
            Light::Point { weight_cd: 3.0 },
        ]);
        let p = m.prepare();
        for ic in 0..24 {
            for ig in 0..=36 {
                let (c, g) = (ic as f64 * 15.0, ig as f64 * 5.0);
                assert_eq!(p.intensity_cd(c, g), m.intensity_cd(c, g), "({c}, {g})");
            }
        }
        assert_eq!(p.intensity_dir_cd(DVec3::ZERO), 0.0);
        assert!(p.bytes() < m.bytes() + 100);
    }

    impl Spot {
        fn intensity(&self, c: f64, g: f64) -> f64 {
            self.intensity_dir(direction(c, g))
        }
    }
}
