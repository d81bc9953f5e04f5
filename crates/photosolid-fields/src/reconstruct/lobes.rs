//! Mixtures of cosine-power lobes `I(d) = Σ_k w_k · max(0, d · a_k)^{p_k}`
//! (`lobes:K`), the representation; [`crate::fit::lobes`] fits them to
//! measured data.
//!
//! LED and reflector distributions are described well by a few such lobes
//! (Moreno and Sun 2008, Opt. Express 16(3)); Zotti, Neumann and
//! Purgathofer's OpenGL model (2005) is two. A lobe is 5 f32 (axis x, y, z,
//! exponent, weight): [`LOBE_BYTES`]; the parameters are rounded to f32 as a
//! shader's uniforms hold them.
//!
//! A rotationally symmetric mixture ([`Lobes::rings`]) sweeps each lobe
//! about the vertical axis: in direction `u` the lobe's axis is turned into
//! `u`'s own C-plane, so the cosine is `u_z a_z + |u_xy| |a_xy|`
//! ([`ring_cosine`]), `cos(γ − γ_a)` for polar angles γ and γ_a. A lobe
//! tilted by γ_a is then a ring of light at γ_a, the batwing of a
//! rotationally symmetric luminaire, which no sum of vertical lobes makes;
//! a vertical axis gives the plain lobe.

use glam::DVec3;

use crate::model::{IntensityField, Rim};

/// Largest exponent of a lobe (a beam of about 3° half width at half maximum).
pub const MAX_LOBE_EXPONENT: f64 = 1024.0;
/// Bytes a lobe holds: axis (3), exponent, weight, each an f32.
pub const LOBE_BYTES: usize = 20;

/// One cosine-power lobe.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Lobe {
    /// Unit axis in the luminaire frame ([`crate::model::frame`]).
    pub axis: DVec3,
    /// Exponent p (dimensionless), in [0, [`MAX_LOBE_EXPONENT`]].
    pub exponent: f64,
    /// On-axis intensity, cd.
    pub weight_cd: f64,
}

impl Lobe {
    /// Intensity (cd) in unit direction `u`.
    #[inline]
    pub fn intensity_unit(&self, u: DVec3) -> f64 {
        lobe_factor(u.dot(self.axis), self.exponent) * self.weight_cd
    }
    /// Intensity (cd) in unit direction `u` of the lobe swept about the
    /// vertical axis (a ring, see the module docs).
    #[inline]
    pub fn ring_intensity_unit(&self, u: DVec3) -> f64 {
        lobe_factor(ring_cosine(u, self.axis), self.exponent) * self.weight_cd
    }
}

/// The cosine between unit direction `u` and unit `axis` turned about the
/// vertical axis into `u`'s C-plane: `u_z a_z + |u_xy| |a_xy|` (= `u · a`
/// for a vertical axis).
#[inline]
pub fn ring_cosine(u: DVec3, axis: DVec3) -> f64 {
    u.z * axis.z + u.truncate().length() * axis.truncate().length()
}

/// `max(0, t)^p` (t a cosine, p ≥ 0), 1 at t > 0 for p = 0, finite for every input.
#[inline]
pub(crate) fn lobe_factor(t: f64, p: f64) -> f64 {
    if t > 0.0 {
        let v = t.min(1.0).powf(p);
        if v.is_finite() {
            v
        } else {
            0.0
        }
    } else {
        0.0
    }
}

/// A mixture of lobes, an [`IntensityField`] named `lobes:K`.
#[derive(Debug, Clone, PartialEq)]
pub struct Lobes {
    /// The lobes, parameters rounded to f32.
    pub lobes: Vec<Lobe>,
    /// Whether each lobe is swept about the vertical axis into a ring
    /// (rotationally symmetric data, [`Lobes::rings`]).
    pub rings: bool,
}

impl Lobes {
    /// The mixture of `lobes`, parameters rounded to f32 (axes renormalised,
    /// exponents and weights clamped to their ranges, non-finite ones 0).
    pub fn new(lobes: Vec<Lobe>) -> Self {
        Self::stored(lobes, false)
    }

    /// The rotationally symmetric mixture of `lobes`, each swept about the
    /// vertical axis into a ring (module docs); rounded as [`Lobes::new`].
    pub fn rings(lobes: Vec<Lobe>) -> Self {
        Self::stored(lobes, true)
    }

    fn stored(lobes: Vec<Lobe>, rings: bool) -> Self {
        let f = |x: f64| if x.is_finite() { x as f32 as f64 } else { 0.0 };
        let lobes = lobes
            .into_iter()
            .map(|l| {
                let a = l.axis.try_normalize().unwrap_or(DVec3::NEG_Z);
                Lobe {
                    axis: DVec3::new(f(a.x), f(a.y), f(a.z)),
                    exponent: f(l.exponent).clamp(0.0, MAX_LOBE_EXPONENT),
                    weight_cd: f(l.weight_cd).max(0.0),
                }
            })
            .collect();
        Self { lobes, rings }
    }

    /// Intensity (cd) in unit direction `u`.
    #[inline]
    pub fn intensity_unit(&self, u: DVec3) -> f64 {
        if self.rings {
            self.lobes.iter().map(|l| l.ring_intensity_unit(u)).sum()
        } else {
            self.lobes.iter().map(|l| l.intensity_unit(u)).sum()
        }
    }
}

impl IntensityField for Lobes {
    fn intensity_cd(&self, c_deg: f64, gamma_deg: f64) -> f64 {
        if !(c_deg.is_finite() && gamma_deg.is_finite()) {
            return 0.0;
        }
        self.intensity_unit(crate::model::frame::direction(c_deg, gamma_deg))
    }
    fn intensity_dir_cd(&self, d: DVec3) -> f64 {
        d.try_normalize().map_or(0.0, |u| self.intensity_unit(u))
    }
    fn name(&self) -> String {
        format!("lobes:{}", self.lobes.len())
    }
    /// `rings` when every lobe is swept about the vertical axis ([`Lobes::rings`]).
    fn form(&self) -> Option<String> {
        self.rings.then(|| "rings".to_string())
    }
    /// [`LOBE_BYTES`] per lobe.
    fn bytes(&self) -> usize {
        self.lobes.len() * LOBE_BYTES
    }
    /// `max(0, t)^p` is continuous for p > 0; p = 0 is a hemisphere's step.
    fn is_continuous(&self) -> bool {
        self.lobes.iter().all(|l| l.exponent > 0.0 || l.weight_cd == 0.0)
    }
    /// A lobe of exponent 0 steps by its weight across the great circle
    /// perpendicular to its axis; the field is continuous elsewhere. A
    /// ring of exponent 0 steps across a cone about the vertical (`None`:
    /// such a mixture is meshed; rotationally symmetric data is measured
    /// on profiles anyway).
    fn rims(&self) -> Option<Vec<Rim>> {
        let steps = || {
            self.lobes
                .iter()
                .enumerate()
                .filter(|(_, l)| l.exponent == 0.0 && l.weight_cd > 0.0)
        };
        if self.rings && steps().next().is_some() {
            return None;
        }
        Some(
            steps()
                .map(|(k, l)| Rim {
                    axis: l.axis,
                    cos_angle: 0.0,
                    jump_cd: l.weight_cd,
                    source: k,
                })
                .collect(),
        )
    }
    /// The mixture without lobe `source`.
    fn intensity_outside_rim_cd(&self, source: usize, u: DVec3) -> f64 {
        let u = u.try_normalize().unwrap_or(DVec3::NEG_Z);
        let others = self.lobes.iter().enumerate().filter(|&(k, _)| k != source);
        if self.rings {
            others.map(|(_, l)| l.ring_intensity_unit(u)).sum()
        } else {
            others.map(|(_, l)| l.intensity_unit(u)).sum()
        }
    }
}
