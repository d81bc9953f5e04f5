//! Unreal Engine IES light profiles: UE5's 256 x 256 texture and UE4's 256 x 1 strip.
//!
//! Source (Epic's UnrealEngine, mirror chenyong2github/UnrealEngine):
//! - `Engine/Source/Runtime/IESFile/Private/IESLoader.cpp`: `GetWidth`/`GetHeight`
//!   return 256; `ExtractInRGBA16F` writes texel (x, y) =
//!   `Interpolate2D(360·y/256, 180·x/256) / ComputeMax()` into all four
//!   half-float channels; `Interpolate2D` folds the horizontal angle through
//!   the file's symmetry (last angle 90, 180 or 360; first angle 90 for
//!   90-270 files), `ComputeFilterPos` turns an angle into a fractional
//!   index (binary search, linear fraction) and `InterpolateBilinear` lerps
//!   the four table values around it (indices wrap modulo the angle counts);
//!   `Interpolate1D` averages `InterpolateBilinear(i, v)` over every
//!   horizontal index i (what a 1D strip holds). A `TILT=` other than NONE
//!   fails the import; the brightness is the maximum candela.
//! - `Engine/Source/Editor/ComponentVisualizers/Private/PointLightComponentVisualizer.cpp`,
//!   `FilterLightProfile` (the CPU copy of the shader's lookup): texture
//!   coordinate X = γ/180 (`asin(dot(ToLight, LightDirection))/π + 0.5`) and
//!   Y = C/360, each scaled by the size and clamped to [0, size − 1], bilinear
//!   between the two texels around it (no half-texel offset).
//!
//! UE4's strip is emulated with UE5's `Interpolate1D` and the same
//! normalisation (256 x 1, x → γ = 180·x/256); UE4's own `FIESLoadHelper`
//! was not read.

use super::table::{lerp, to_half, IesTable, Image};
use crate::model::IntensityField;

/// Texture side of UE's light profile (`FIESLoader::GetWidth`, `GetHeight`).
pub const SIZE: usize = 256;

/// `FIESLoader::ComputeFilterPos`: the fractional index of `value` in `sorted`.
pub fn filter_pos(value: f64, sorted: &[f64]) -> f64 {
    let n = sorted.len();
    if n == 0 || value < sorted[0] {
        return 0.0;
    }
    if value > sorted[n - 1] {
        return (n - 1) as f64;
    }
    let (mut start, mut end) = (0usize, n - 1);
    while start < end {
        let test = (start + end).div_ceil(2);
        if value >= sorted[test] {
            start = test;
        } else {
            end = test - 1;
        }
    }
    let mut fraction = 0.0;
    if start + 1 < n {
        let delta = sorted[start + 1] - sorted[start];
        if delta > 0.0001 {
            fraction = (value - sorted[start]) / delta;
        }
    }
    start as f64 + fraction
}

/// `FIESLoader::InterpolateBilinear` at fractional indices (h, v) of the table.
fn bilinear_index(t: &IesTable, fh: f64, fv: f64) -> f64 {
    let (x, y) = (fh as usize, fv as usize);
    let (fx, fy) = (fh - x as f64, fv - y as f64);
    let (nh, nv) = (t.h.len(), t.v.len());
    let p = |x: usize, y: usize| t.at(x % nh, y % nv);
    let p0 = lerp(p(x, y), p(x, y + 1), fy);
    let p1 = lerp(p(x + 1, y), p(x + 1, y + 1), fy);
    lerp(p0, p1, fx)
}

/// `FIESLoader::Interpolate2D` (Type C): candela at horizontal angle `h` and
/// vertical angle `v` (degrees), folding `h` through the file's symmetry.
pub fn interpolate_2d(t: &IesTable, mut h: f64, v: f64) -> f64 {
    let (first, last) = (t.h[0], t.h[t.h.len() - 1]);
    if last > 0.0 && h > last {
        let quadrant = (h / last) as i64;
        h = if quadrant == 1 || quadrant == 3 {
            last - h % last
        } else {
            h % last
        };
    } else if first > 0.0 && h < first {
        h = last - first - h;
    }
    bilinear_index(t, filter_pos(h, &t.h), filter_pos(v, &t.v))
}

/// `FIESLoader::Interpolate1D`: the mean over every horizontal index of the
/// table at vertical angle `v` (each stored plane counts once, whatever its width).
pub fn interpolate_1d(t: &IesTable, v: f64) -> f64 {
    let fv = filter_pos(v, &t.v);
    (0..t.h.len()).map(|i| bilinear_index(t, i as f64, fv)).sum::<f64>() / t.h.len() as f64
}

/// UE5's texture: 256 x 256 half floats, x → γ = 180·x/256, y → C = 360·y/256, I / I_max.
pub fn bake_ue5(t: &IesTable) -> Result<Image, crate::error::ModelError> {
    let max = t.max_cd();
    let inv = if max > 0.0 { 1.0 / max } else { 0.0 };
    Image::from_fn(SIZE, SIZE, |x, y| {
        let c = 360.0 * y as f64 / SIZE as f64;
        let g = 180.0 * x as f64 / SIZE as f64;
        to_half(inv * interpolate_2d(t, c, g))
    })
}

/// UE4's strip: 256 x 1 half floats, x → γ = 180·x/256, the C-average over I_max.
pub fn bake_ue4(t: &IesTable) -> Result<Image, crate::error::ModelError> {
    let max = t.max_cd();
    let inv = if max > 0.0 { 1.0 / max } else { 0.0 };
    Image::from_fn(SIZE, 1, |x, _| {
        to_half(inv * interpolate_1d(t, 180.0 * x as f64 / SIZE as f64))
    })
}

/// The texel (x, y) UE5's texture stores nearest to (C, γ) (degrees).
pub fn texel_of(c_deg: f64, gamma_deg: f64) -> (usize, usize) {
    let x = (gamma_deg / 180.0 * SIZE as f64).round().clamp(0.0, (SIZE - 1) as f64) as usize;
    let y = (crate::model::wrap360(c_deg) / 360.0 * SIZE as f64).round() as usize % SIZE;
    (x, y)
}

/// UE's lookup of its texture (`FilterLightProfile`), times the brightness (I_max, cd).
#[derive(Debug, Clone)]
pub struct UeField {
    /// 256 x 256 (UE5) or 256 x 1 (UE4), I / I_max.
    pub image: Image,
    /// The brightness: the file's maximum candela.
    pub i_max_cd: f64,
}

impl IntensityField for UeField {
    fn intensity_cd(&self, c_deg: f64, gamma_deg: f64) -> f64 {
        if !(c_deg.is_finite() && gamma_deg.is_finite()) {
            return 0.0;
        }
        let x = gamma_deg.clamp(0.0, 180.0) / 180.0 * self.image.width as f64;
        let y = crate::model::wrap360(c_deg) / 360.0 * self.image.height as f64;
        self.i_max_cd
            * self
                .image
                .bilinear_clamped(x, if self.image.height == 1 { 0.0 } else { y })
    }
    fn name(&self) -> String {
        format!("ue {}x{} bilinear", self.image.width, self.image.height)
    }
    fn bytes(&self) -> usize {
        // RGBA16F on the GPU: 8 bytes per texel.
        self.image.data.len() * 8
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn filter_pos_is_fractional_index() {
        let a = [0.0, 10.0, 30.0];
        assert_eq!(filter_pos(-1.0, &a), 0.0);
        assert_eq!(filter_pos(0.0, &a), 0.0);
        assert_eq!(filter_pos(5.0, &a), 0.5);
        assert_eq!(filter_pos(20.0, &a), 1.5);
        assert_eq!(filter_pos(30.0, &a), 2.0);
        assert_eq!(filter_pos(99.0, &a), 2.0);
    }

    #[test]
    fn symmetry_folds() {
        // Quadrant table: plane 0 = 1 cd, plane 90 = 2 cd.
        let t = IesTable {
            h: vec![0.0, 90.0],
            v: vec![0.0, 90.0],
            cd: vec![1.0, 1.0, 2.0, 2.0],
        };
        assert_eq!(interpolate_2d(&t, 180.0, 10.0), 1.0);
        assert_eq!(interpolate_2d(&t, 270.0, 10.0), 2.0);
        assert_eq!(interpolate_2d(&t, 135.0, 10.0), 1.5);
        assert_eq!(interpolate_1d(&t, 10.0), 1.5);
    }
}
