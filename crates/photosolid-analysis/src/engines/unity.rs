//! Unity HDRP IES import: point lights through an equirectangular buffer and
//! a cube map, spot lights as a gnomonic cookie.
//!
//! Sources (Unity-Technologies/Graphics):
//! - `com.unity.render-pipelines.core/Editor/Lighting/IESReader.cs` (commit
//!   20072799): the table interpolation. `ComputeTypeCHorizontalAnglePosition`
//!   folds C by the last horizontal angle (0: C = 0; 90: C = 90 − ||C − 180| − 90|;
//!   180: C = 180 − |C − 180|; otherwise, 360 or a 90-270 file, unchanged);
//!   `ComputeAnglePosition` turns an angle into a fractional index (binary
//!   search, clamped to the first and last angle, linear fraction when the
//!   step exceeds 0.0001); `InterpolateBilinear`/`InterpolatePoint` lerp the
//!   four values around it, indices modulo the counts: the same functions as
//!   UE's `ComputeFilterPos`/`InterpolateBilinear` ([`super::ue::filter_pos`],
//!   [`super::ue::bilinear_index`]). `MaxCandelas` is the largest value
//!   (times multiplier and ballast). A `TILT=` other than NONE is refused.
//!   A 90-270 file is not folded: C below 90 and above 270 clamp to the
//!   first and last plane (a defect row, [`super::defects`]).
//! - `IESEngine.cs` (commit 0328a1b1): `GenerateCubeCookie`, a `2N x 2N`
//!   buffer from `BuildTypeCCylindricalTexture` (texel (x, y): u = π −
//!   x·2π/(W−1), v = y·π/(H−1) − π/2; C = atan2(sin u cos v, sin v) mod 360°,
//!   γ = asin(−cos u cos v) + 90°: the nadir is +Z at the centre, C0 is +Y,
//!   C90 is +X), made a cube map by Unity's importer ([`super::unity_cube`]);
//!   `BuildTypeCGnomonicTexture`, an `N x N` cookie, limit = tan(cone/2),
//!   step = 2·limit/(N − 3), texels 1..N−2 at u, v = (i − 1)·step − limit,
//!   C = atan2(v, u) − 90° mod 360°, γ = atan(√(u² + v²)), divided by
//!   (1 + u² + v²) when attenuation is on, a 1-texel black border; every
//!   texel `(byte)(I / MaxCandelas · 255)` (truncated); `GenerateTexture`:
//!   bilinear, clamp, no mipmaps, at most 2048 texels a side.
//! - `IESObject.cs`: defaults `iesSize` 128, `SpotAngle` 120, `ApplyLightAttenuation` true.
//! - HDRP (2020.1 and later) copies both cookies into its `R11G11B10` cookie
//!   atlas and samples it bilinearly (`LightCookieManager.cs`,
//!   `CookieSampling.hlsl`); the point light's cube map goes in as an
//!   octahedral map ([`super::unity_cube`]).
//!
//! Not modelled: the importer's default BC7 compression, the atlas padding,
//! and Unity's native cylindrical-to-cube conversion, for which
//! [`super::unity_cube`] has a stand-in ([`POINT_STAND_INS`]).

use std::f64::consts::{FRAC_PI_2, PI, TAU};

use super::table::{to_byte, to_f11, IesTable, Image};
use super::ue::{bilinear_index, filter_pos};
pub use super::unity_cube::cylindrical_coords;
use super::unity_cube::{self, CubeMap};
use crate::model::IntensityField;

/// Unity's default cookie size N.
pub const DEFAULT_SIZE: usize = 128;
/// Unity's largest texture side.
pub const MAX_SIDE: usize = 2048;
/// Unity's default spot cone, degrees.
pub const DEFAULT_CONE_DEG: f64 = 120.0;

/// The steps of the point-light emulation that follow no source the
/// project could read.
pub const POINT_STAND_INS: &[&str] = &[
    "cube-map conversion (Unity's native TextureImporter, not public): face side N per the HDRP manual, \
     each face texel = bilinear value of the 2N x 2N buffer at its centre direction, 8-bit, BC7 not modelled",
];
/// The steps of the spot-light emulation that follow no source.
pub const SPOT_STAND_INS: &[&str] = &["BC7 compression (the importer's default) not modelled"];

/// `IESReader.ComputeTypeCHorizontalAnglePosition`: the fractional plane
/// index of horizontal angle `c_deg` (in [0, 360]). `fold_90_270`: mirror a
/// 90-270 file about its plane of symmetry (what Unity does not do).
pub fn horizontal_position(t: &IesTable, c_deg: f64, fold_90_270: bool) -> f64 {
    let (first, last) = (t.h[0], t.h[t.h.len() - 1]);
    let c = if last == 0.0 {
        0.0
    } else if last == 90.0 {
        90.0 - ((c_deg - 180.0).abs() - 90.0).abs()
    } else if last == 180.0 {
        180.0 - (c_deg - 180.0).abs()
    } else if fold_90_270 && first == 90.0 && last == 270.0 {
        if c_deg < 90.0 {
            180.0 - c_deg
        } else if c_deg > 270.0 {
            540.0 - c_deg
        } else {
            c_deg
        }
    } else {
        c_deg
    };
    filter_pos(c, &t.h)
}

/// Unity's `InterpolateBilinear` of the table at (C, γ) (degrees), cd.
pub fn candela(t: &IesTable, c_deg: f64, gamma_deg: f64, fold_90_270: bool) -> f64 {
    bilinear_index(
        t,
        horizontal_position(t, c_deg, fold_90_270),
        filter_pos(gamma_deg, &t.v),
    )
}

/// (C, γ) in degrees of texel (x, y) of the `w` x `h` cylindrical buffer.
pub fn cylindrical_angles(x: usize, y: usize, w: usize, h: usize) -> (f64, f64) {
    let u = PI - x as f64 * TAU / (w - 1) as f64;
    let v = y as f64 * PI / (h - 1) as f64 - FRAC_PI_2;
    let c = ((u.sin() * v.cos()).atan2(v.sin()) + TAU) % TAU;
    let g = (-u.cos() * v.cos()).clamp(-1.0, 1.0).asin() + FRAC_PI_2;
    (c.to_degrees(), g.to_degrees())
}

/// The point-light buffer (`BuildTypeCCylindricalTexture`): `2n x 2n` bytes of I / MaxCandelas.
pub fn bake_point(t: &IesTable, n: usize, fold_90_270: bool) -> Result<Image, crate::error::ModelError> {
    let side = 2 * n;
    let max = t.max_cd();
    let inv = if max > 0.0 { 1.0 / max } else { 0.0 };
    Image::from_fn(side, side, |x, y| {
        let (c, g) = cylindrical_angles(x, y, side, side);
        to_byte(inv * candela(t, c, g, fold_90_270))
    })
}

/// The spot cookie's texel spacing in the gnomonic plane and its limit tan(cone/2).
pub fn gnomonic_step(n: usize, cone_deg: f64) -> (f64, f64) {
    let limit = (0.5 * cone_deg).to_radians().tan();
    (2.0 * limit / (n - 3) as f64, limit)
}

/// The spot cookie (`BuildTypeCGnomonicTexture`): `n x n` bytes, 1-texel black border, attenuation on.
pub fn bake_spot(t: &IesTable, n: usize, cone_deg: f64, fold_90_270: bool) -> Result<Image, crate::error::ModelError> {
    let (step, limit) = gnomonic_step(n, cone_deg);
    let max = t.max_cd();
    let inv = if max > 0.0 { 1.0 / max } else { 0.0 };
    Image::from_fn(n, n, |x, y| {
        if x == 0 || y == 0 || x + 1 == n || y + 1 == n {
            return 0.0;
        }
        let u = (x - 1) as f64 * step - limit;
        let v = (y - 1) as f64 * step - limit;
        let len = (u * u + v * v).sqrt();
        let c = ((v.atan2(u) - FRAC_PI_2 + TAU) % TAU).to_degrees();
        let g = len.atan().to_degrees();
        to_byte(inv * candela(t, c, g, fold_90_270) / (1.0 + len * len))
    })
}

/// What HDRP samples for a point light: the octahedral atlas copy of the
/// cube map of the buffer ([`unity_cube`] steps 1 to 3).
pub fn point_atlas(buffer: &Image, n: usize) -> Result<Image, crate::error::ModelError> {
    unity_cube::octahedral(&CubeMap::from_cylindrical(buffer, n))
}

/// What HDRP samples for a spot light: the cookie in `R11G11B10` precision.
pub fn spot_atlas(cookie: &Image) -> Image {
    Image {
        data: cookie.data.iter().map(|&v| to_f11(f64::from(v))).collect(),
        ..cookie.clone()
    }
}

/// HDRP's lookup of a Unity IES cookie in its atlas, times I_max.
#[derive(Debug, Clone)]
pub struct UnityField {
    /// The atlas entry: the octahedral map (point) or the gnomonic cookie (spot), I / I_max.
    pub image: Image,
    /// The light's intensity: the file's maximum candela.
    pub i_max_cd: f64,
    /// `Some(cone)` for the spot cookie, `None` for the point light's octahedral map.
    pub spot_cone_deg: Option<f64>,
}

impl UnityField {
    /// The point light's lookup of `buffer` (the `2n x 2n` cylindrical buffer).
    pub fn point(buffer: &Image, n: usize, i_max_cd: f64) -> Result<Self, crate::error::ModelError> {
        Ok(Self {
            image: point_atlas(buffer, n)?,
            i_max_cd,
            spot_cone_deg: None,
        })
    }

    /// The spot light's lookup of `cookie` (cone in degrees).
    pub fn spot(cookie: &Image, cone_deg: f64, i_max_cd: f64) -> Self {
        Self {
            image: spot_atlas(cookie),
            i_max_cd,
            spot_cone_deg: Some(cone_deg),
        }
    }
}

impl IntensityField for UnityField {
    fn intensity_cd(&self, c_deg: f64, gamma_deg: f64) -> f64 {
        if !(c_deg.is_finite() && gamma_deg.is_finite()) {
            return 0.0;
        }
        let im = &self.image;
        let v = match self.spot_cone_deg {
            None => {
                let d = unity_cube::frame_to_cube(crate::model::frame::direction(c_deg, gamma_deg));
                unity_cube::sample_octahedral(im, d)
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
            None => format!(
                "unity point {}x{} octahedral atlas",
                self.image.width, self.image.height
            ),
            Some(c) => format!(
                "unity spot {}x{} gnomonic cone {c}",
                self.image.width, self.image.height
            ),
        }
    }
    fn bytes(&self) -> usize {
        // R11G11B10 in the atlas: 4 bytes per texel.
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

    #[test]
    fn horizontal_folds_follow_the_last_angle() {
        let t = |h: Vec<f64>| IesTable {
            v: vec![0.0, 90.0],
            cd: vec![1.0; 2 * h.len()],
            h,
        };
        let quad = t(vec![0.0, 45.0, 90.0]);
        assert_eq!(horizontal_position(&quad, 135.0, false), 1.0);
        // 300 mirrors to 60 = 45 + 15: index 1 + 1/3.
        assert!((horizontal_position(&quad, 300.0, false) - 4.0 / 3.0).abs() < 1e-12);
        let half = t(vec![0.0, 90.0, 180.0]);
        assert_eq!(horizontal_position(&half, 270.0, false), 1.0);
        let side = t(vec![90.0, 180.0, 270.0]);
        // Unity clamps a 90-270 file's C outside 90..270; the fold mirrors it.
        assert_eq!(horizontal_position(&side, 0.0, false), 0.0);
        assert_eq!(horizontal_position(&side, 350.0, false), 2.0);
        assert_eq!(horizontal_position(&side, 0.0, true), 1.0);
        assert_eq!(horizontal_position(&side, 315.0, true), 1.5);
    }
}
