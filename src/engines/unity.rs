//! Unity HDRP IES import: point lights through an equirectangular buffer, spot
//! lights as a gnomonic cookie.
//!
//! Source (Unity-Technologies/Graphics, commit 0328a1b1):
//! `com.unity.render-pipelines.core/Editor/Lighting/IESEngine.cs`:
//! - `GenerateCubeCookie`: a `2N x 2N` buffer from `BuildTypeCCylindricalTexture`
//!   (texel (x, y): u = π − x·2π/(W−1), v = y·π/(H−1) − π/2; C = atan2(sin u cos v,
//!   sin v) mod 360°, γ = asin(−cos u cos v) + 90°: the nadir is +Z at the
//!   centre, C0 is +Y, C90 is +X), converted by Unity's importer with
//!   `generateCubemap = Cylindrical`;
//! - `BuildTypeCGnomonicTexture`: an `N x N` cookie, limit = tan(cone/2),
//!   step = 2·limit/(N − 3), texels 1..N−2 at u, v = (i − 1)·step − limit,
//!   C = atan2(v, u) − 90° mod 360°, γ = atan(√(u² + v²)), divided by
//!   (1 + u² + v²) when attenuation is on, a 1-texel black border;
//! - every texel is `(byte)(I / MaxCandelas · 255)` in a `Color32` (8 bits,
//!   truncated); bilinear filtering, clamp, no mipmaps, at most 2048 texels a side.
//!
//! The emulation looks the buffers up bilinearly between the texels' own
//! directions (the cube-map conversion of the point buffer and BC7
//! compression are not modelled), with the light's intensity set to the
//! maximum candela. The table is interpolated with photosolid's bilinear
//! filter: Unity's `IESReader.InterpolateBilinear` was not read.

use std::f64::consts::{FRAC_PI_2, PI, TAU};

use super::table::{to_byte, Image};
use crate::model::IntensityField;

/// Unity's default cookie size N.
pub const DEFAULT_SIZE: usize = 128;
/// Unity's largest texture side.
pub const MAX_SIDE: usize = 2048;
/// Unity's default spot cone, degrees.
pub const DEFAULT_CONE_DEG: f64 = 120.0;

/// (C, γ) in degrees of texel (x, y) of the `w` x `h` cylindrical buffer.
pub fn cylindrical_angles(x: usize, y: usize, w: usize, h: usize) -> (f64, f64) {
    let u = PI - x as f64 * TAU / (w - 1) as f64;
    let v = y as f64 * PI / (h - 1) as f64 - FRAC_PI_2;
    let c = ((u.sin() * v.cos()).atan2(v.sin()) + TAU) % TAU;
    let g = (-u.cos() * v.cos()).clamp(-1.0, 1.0).asin() + FRAC_PI_2;
    (c.to_degrees(), g.to_degrees())
}

/// Continuous texel coordinates (x, y) of direction (C, γ) in the cylindrical buffer.
pub fn cylindrical_coords(c_deg: f64, gamma_deg: f64, w: usize, h: usize) -> (f64, f64) {
    let (sg, cg) = crate::model::frame::sin_cos_deg(gamma_deg);
    let (sc, cc) = crate::model::frame::sin_cos_deg(c_deg);
    // Components: +X = C90, +Y = C0, +Z = nadir.
    let (dx, dy, dz) = (sg * sc, sg * cc, cg);
    let v = dy.clamp(-1.0, 1.0).asin();
    let u = dx.atan2(dz);
    ((PI - u) / TAU * (w - 1) as f64, (v + FRAC_PI_2) / PI * (h - 1) as f64)
}

/// The point-light buffer: `2n x 2n` bytes of I / I_max (`field` in cd, `i_max` its peak).
pub fn bake_point(field: &dyn IntensityField, i_max: f64, n: usize) -> Result<Image, crate::error::ModelError> {
    let side = 2 * n;
    let inv = if i_max > 0.0 { 1.0 / i_max } else { 0.0 };
    Image::from_fn(side, side, |x, y| {
        let (c, g) = cylindrical_angles(x, y, side, side);
        to_byte(inv * field.intensity_cd(c, g))
    })
}

/// The spot cookie's texel spacing in the gnomonic plane and its limit tan(cone/2).
pub fn gnomonic_step(n: usize, cone_deg: f64) -> (f64, f64) {
    let limit = (0.5 * cone_deg).to_radians().tan();
    (2.0 * limit / (n - 3) as f64, limit)
}

/// The spot cookie: `n x n` bytes, 1-texel black border, attenuation on.
pub fn bake_spot(
    field: &dyn IntensityField,
    i_max: f64,
    n: usize,
    cone_deg: f64,
) -> Result<Image, crate::error::ModelError> {
    let (step, limit) = gnomonic_step(n, cone_deg);
    let inv = if i_max > 0.0 { 1.0 / i_max } else { 0.0 };
    Image::from_fn(n, n, |x, y| {
        if x == 0 || y == 0 || x + 1 == n || y + 1 == n {
            return 0.0;
        }
        let u = (x - 1) as f64 * step - limit;
        let v = (y - 1) as f64 * step - limit;
        let len = (u * u + v * v).sqrt();
        let c = ((v.atan2(u) - FRAC_PI_2 + TAU) % TAU).to_degrees();
        let g = len.atan().to_degrees();
        to_byte(inv * field.intensity_cd(c, g) / (1.0 + len * len))
    })
}

/// Unity's lookup of a baked buffer, times I_max.
#[derive(Debug, Clone)]
pub struct UnityField {
    /// The buffer (I / I_max, 8-bit steps).
    pub image: Image,
    /// The light's intensity: the file's maximum candela.
    pub i_max_cd: f64,
    /// `Some(cone)` for the spot cookie, `None` for the point buffer.
    pub spot_cone_deg: Option<f64>,
}

impl IntensityField for UnityField {
    fn intensity_cd(&self, c_deg: f64, gamma_deg: f64) -> f64 {
        if !(c_deg.is_finite() && gamma_deg.is_finite()) {
            return 0.0;
        }
        let im = &self.image;
        let v = match self.spot_cone_deg {
            None => {
                let (x, y) = cylindrical_coords(c_deg, gamma_deg, im.width, im.height);
                im.bilinear_clamped(x, y)
            }
            Some(cone) => {
                if gamma_deg >= 90.0 {
                    return 0.0;
                }
                let (step, limit) = gnomonic_step(im.width, cone);
                let r = gamma_deg.to_radians().tan();
                let (s, c) = crate::model::frame::sin_cos_deg(c_deg + 90.0);
                let x = (r * c + limit) / step + 1.0;
                let y = (r * s + limit) / step + 1.0;
                let last = (im.width - 1) as f64;
                if !(0.0..=last).contains(&x) || !(0.0..=last).contains(&y) {
                    return 0.0;
                }
                im.bilinear_clamped(x, y)
            }
        };
        self.i_max_cd * v
    }
    fn name(&self) -> String {
        match self.spot_cone_deg {
            None => format!("unity point {}x{} cylindrical", self.image.width, self.image.height),
            Some(c) => format!(
                "unity spot {}x{} gnomonic cone {c}",
                self.image.width, self.image.height
            ),
        }
    }
    fn bytes(&self) -> usize {
        // One byte per texel and channel (Color32: 4 channels).
        self.image.data.len() * 4
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cylindrical_round_trip() {
        let (w, h) = (64, 64);
        for &(x, y) in &[(5usize, 7usize), (31, 40), (50, 20)] {
            let (c, g) = cylindrical_angles(x, y, w, h);
            let (x2, y2) = cylindrical_coords(c, g, w, h);
            assert!(
                (x as f64 - x2).abs() < 1e-9 && (y as f64 - y2).abs() < 1e-9,
                "{x} {y} -> {x2} {y2}"
            );
        }
        // The centre of the buffer is the nadir.
        let (_, g) = cylindrical_angles(0, 0, 3, 3);
        assert!((g - 90.0).abs() < 1e-9);
        let (_, g) = cylindrical_angles(1, 1, 3, 3);
        assert!(g.abs() < 1e-9);
    }
}
