//! pbrt-v4 goniometric light: a square, single-channel (`Y`) image in
//! Clarberg's equal-area octahedral mapping, looked up at the nearest texel.
//!
//! Source (mmp/pbrt-v4): `src/pbrt/lights.cpp`, `GoniometricLight::Create`
//! (square image with a `Y` channel or averaged RGB; NaN/Inf refused;
//! `power` rescales by `k_e = 4π·mean(Y)`; the light frame is
//! `renderFromLight * swapYZ`) and `GoniometricLight::I` in `lights.h`
//! (`image.LookupNearestChannel(EqualAreaSphereToSquare(w), 0)`);
//! `src/pbrt/util/math.cpp`, `EqualAreaSquareToSphere` / `EqualAreaSphereToSquare`.
//!
//! Frame: the pbrt light's own frame is the luminaire frame
//! ([`crate::model::frame`]: x = C0, y = C90, z up, nadir −z). The image
//! direction `w` is the light-frame direction `(w.x, w.z, w.y)` (swapYZ), so
//! the square's centre (w.z = +1) is C90 at the horizon (+y) and its corners
//! are C270 (−y). Texel values are candela: with `scale 1` (and the spectrum
//! `I` normalised to 1 nit by pbrt) the light emits the file's intensities;
//! 4π × the image mean is the flux (the map is equal-area).

use glam::DVec3;

use super::table::Image;
use crate::model::{frame, IntensityField};

/// The unit direction of the point `(u, v)` of the unit square (Clarberg's
/// equal-area octahedral mapping as pbrt-v4 implements it).
pub fn square_to_sphere(u: f64, v: f64) -> DVec3 {
    let (su, sv) = (2.0 * u - 1.0, 2.0 * v - 1.0);
    let (up, vp) = (su.abs(), sv.abs());
    let signed_distance = 1.0 - (up + vp);
    let r = 1.0 - signed_distance.abs();
    let phi = if r == 0.0 { 1.0 } else { (vp - up) / r + 1.0 } * std::f64::consts::FRAC_PI_4;
    let z = (1.0 - r * r).copysign(signed_distance);
    let s = r * (2.0 - r * r).max(0.0).sqrt();
    DVec3::new(phi.cos().copysign(su) * s, phi.sin().copysign(sv) * s, z)
}

/// The point of the unit square of the unit direction `d` (inverse of
/// [`square_to_sphere`]); exact arctangent where pbrt uses a polynomial
/// (its error, below 1e-6 rad, moves no texel boundary that matters here).
pub fn sphere_to_square(d: DVec3) -> (f64, f64) {
    let (x, y, z) = (d.x.abs(), d.y.abs(), d.z.abs());
    let r = (1.0 - z).max(0.0).sqrt();
    let a = x.max(y);
    let b = if a == 0.0 { 0.0 } else { x.min(y) / a };
    let mut phi = b.atan() * std::f64::consts::FRAC_2_PI;
    if x < y {
        phi = 1.0 - phi;
    }
    let mut v = phi * r;
    let mut u = r - v;
    if d.z < 0.0 {
        std::mem::swap(&mut u, &mut v);
        u = 1.0 - u;
        v = 1.0 - v;
    }
    (0.5 * (u.copysign(d.x) + 1.0), 0.5 * (v.copysign(d.y) + 1.0))
}

/// The image direction (pbrt's `wLight`) of a luminaire-frame direction: swapYZ.
#[inline]
pub fn image_direction(d: DVec3) -> DVec3 {
    DVec3::new(d.x, d.z, d.y)
}

/// The texel (x, y) pbrt reads for the luminaire-frame direction `d` in an
/// `n` x `n` image: `LookupNearest` truncates `uv · n` (clamped to the image).
pub fn texel_of(d: DVec3, n: usize) -> (usize, usize) {
    let (u, v) = sphere_to_square(image_direction(d.normalize_or_zero()));
    let idx = |t: f64| ((t * n as f64) as usize).min(n - 1);
    (idx(u), idx(v))
}

/// The luminaire-frame direction of texel (x, y)'s centre in an `n` x `n` image.
pub fn texel_direction(x: usize, y: usize, n: usize) -> DVec3 {
    let w = square_to_sphere((x as f64 + 0.5) / n as f64, (y as f64 + 0.5) / n as f64);
    image_direction(w)
}

/// pbrt's layout of `field`: an `n` x `n` image of candela, each texel the
/// field at its centre's direction (point sampling, no prefilter).
pub fn bake(field: &dyn IntensityField, n: usize) -> Result<Image, crate::error::ModelError> {
    Image::from_fn(n, n, |x, y| field.intensity_dir_cd(texel_direction(x, y, n)) as f32)
}

/// pbrt's lookup of a baked image: the nearest texel, in candela.
#[derive(Debug, Clone)]
pub struct PbrtField {
    /// The image (cd).
    pub image: Image,
}

impl IntensityField for PbrtField {
    fn intensity_cd(&self, c_deg: f64, gamma_deg: f64) -> f64 {
        if !(c_deg.is_finite() && gamma_deg.is_finite()) {
            return 0.0;
        }
        self.intensity_dir_cd(frame::direction(c_deg, gamma_deg))
    }
    fn intensity_dir_cd(&self, d: DVec3) -> f64 {
        if !d.is_finite() || d == DVec3::ZERO {
            return 0.0;
        }
        let (x, y) = texel_of(d, self.image.width);
        f64::from(self.image.texel(x, y))
    }
    fn name(&self) -> String {
        format!("pbrt {}x{} nearest", self.image.width, self.image.height)
    }
    fn bytes(&self) -> usize {
        self.image.bytes()
    }
}

/// The flux pbrt computes from an image of candela: 4π × mean (lm).
pub fn flux_lm(image: &Image) -> f64 {
    4.0 * std::f64::consts::PI * image.mean()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mapping_round_trips_and_centre_is_plus_y() {
        for i in 0..40 {
            for j in 0..40 {
                let (u, v) = ((i as f64 + 0.5) / 40.0, (j as f64 + 0.5) / 40.0);
                let d = square_to_sphere(u, v);
                assert!((d.length() - 1.0).abs() < 1e-12);
                let (u2, v2) = sphere_to_square(d);
                assert!((u - u2).abs() < 1e-9 && (v - v2).abs() < 1e-9, "{u} {v} -> {u2} {v2}");
            }
        }
        // Centre of the square: image +z = luminaire +y (C90 on the horizon).
        let c = texel_direction(50, 50, 101);
        assert!((c - DVec3::Y).length() < 1e-12);
        // A corner: luminaire −y.
        assert!((image_direction(square_to_sphere(0.0, 0.0)) - DVec3::NEG_Y).length() < 1e-12);
    }

    #[test]
    fn equal_area_mean_is_flux() {
        // Isotropic 1 cd: 4π lm whatever n.
        let f = |_c: f64, _g: f64| 1.0;
        let im = bake(&f, 8).unwrap();
        assert!((flux_lm(&im) - 4.0 * std::f64::consts::PI).abs() < 1e-5);
    }
}
