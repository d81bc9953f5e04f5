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
//! - UE4 (4.19.2, mirror Kryptexas/UE4-GameWorks-4.19.2, commit 324683ce,
//!   `Engine/Source/Editor/UnrealEd/Private/Factories/IESLoader.cpp`,
//!   `FIESLoadHelper`): `GetWidth` 256, `GetHeight` 1; `ExtractInRGBA16F`
//!   writes `Interpolate1D(180·x/256) / ComputeMax()` (the same
//!   `ComputeFilterPos`, `InterpolateBilinear` and `Interpolate1D` as UE5;
//!   UE4's `Interpolate2D` folds no symmetry) and returns the texture
//!   multiplier `ComputeMax() / ComputeFullIntegral()`, which
//!   `ULightComponent::ComputeLightBrightness` (`LightComponent.cpp`)
//!   multiplies into the light's brightness. `ComputeFullIntegral` is a
//!   Monte Carlo mean over 1 000 000 `FRandomStream(0x1234).GetUnitVector()`
//!   directions of `Interpolate2D(acos(z)·180/π, atan2(y, x)·180/π + 180)`:
//!   the polar angle goes in as the *horizontal* angle and the azimuth as
//!   the vertical one (UE5's `FIESLoader::ComputeFullIntegral` passes them
//!   the right way round, and UE5's multiplier is 1). [`ue4_integral`]
//!   replays that stream (`Engine/Source/Runtime/Core/Public/Math/RandomStream.h`:
//!   `MutateSeed` `seed·196314165 + 907633515`, `GetFraction` from the low
//!   23 bits, `GetUnitVector` by rejection in the cube); the error the
//!   swapped angles cause is a defect row ([`crate::engines::defects`]).
//!   The layout row takes the light's intensity as UE's integral without
//!   the swap, so it shows the strip's own error (the C-average).

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

/// `FIESLoader::InterpolateBilinear` at fractional indices (h, v) of the
/// table (cd): indices wrap modulo the angle counts. Unity's
/// `IESReader.InterpolateBilinear` is the same function.
pub fn bilinear_index(t: &IesTable, fh: f64, fv: f64) -> f64 {
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

/// The mean of the table over the sphere as UE computes it
/// (`ComputeFullIntegral`: 1 000 000 directions of `FRandomStream(0x1234)`),
/// cd. `swapped`: UE4's call, the polar angle as the horizontal angle and
/// the azimuth as the vertical one, through UE4's `Interpolate2D` (no
/// symmetry folding); otherwise UE5's call, through [`interpolate_2d`].
pub fn ue4_integral(t: &IesTable, swapped: bool) -> f64 {
    const SAMPLES: usize = 1_000_000;
    let mut stream = RandomStream(0x1234);
    let mut sum = 0.0;
    for _ in 0..SAMPLES {
        let [x, y, z] = stream.unit_vector();
        let polar = f64::from(z).clamp(-1.0, 1.0).acos().to_degrees();
        let azimuth = f64::from(y).atan2(f64::from(x)).to_degrees() + 180.0;
        sum += if swapped {
            bilinear_index(t, filter_pos(polar, &t.h), filter_pos(azimuth, &t.v))
        } else {
            interpolate_2d(t, azimuth, polar)
        };
    }
    sum / SAMPLES as f64
}

/// UE's `FRandomStream` (an LCG on an `int32` seed).
struct RandomStream(i32);

impl RandomStream {
    /// `GetFraction`: the low 23 bits of the next seed as the mantissa of a float in [1, 2), minus 1.
    fn fraction(&mut self) -> f32 {
        self.0 = self.0.wrapping_mul(196_314_165).wrapping_add(907_633_515);
        f32::from_bits(0x3f80_0000 | (self.0 as u32 & 0x007f_ffff)) - 1.0
    }
    /// `GetUnitVector`: rejection sampling in the cube [−1, 1]³, then normalised.
    fn unit_vector(&mut self) -> [f32; 3] {
        loop {
            let v = [
                self.fraction() * 2.0 - 1.0,
                self.fraction() * 2.0 - 1.0,
                self.fraction() * 2.0 - 1.0,
            ];
            let l = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
            // KINDA_SMALL_NUMBER = 1e-4.
            if (1e-4..=1.0).contains(&l) {
                let inv = 1.0 / l.sqrt();
                return [v[0] * inv, v[1] * inv, v[2] * inv];
            }
        }
    }
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

    #[test]
    fn integrals_meet_their_closed_forms_on_a_single_plane_table() {
        // cos⁵ on the lower hemisphere, 2.5° vertical steps, one plane.
        let v: Vec<f64> = (0..=72).map(|i| f64::from(i) * 2.5).collect();
        let cd: Vec<f64> = v
            .iter()
            .map(|&g: &f64| {
                if g < 90.0 {
                    1000.0 * g.to_radians().cos().powi(5)
                } else {
                    0.0
                }
            })
            .collect();
        let t = IesTable { h: vec![0.0], v, cd };
        // Right: the mean over the sphere, 1000 / (2 (p + 1)).
        let right = ue4_integral(&t, false);
        assert!((right / (1000.0 / 12.0) - 1.0).abs() < 5e-3, "{right}");
        // Swapped: the azimuth (uniform on 0..360) is the vertical angle, clamped
        // at 180: the table's mean over 0..360 degrees of vertical angle.
        let linear: f64 =
            t.v.windows(2)
                .enumerate()
                .map(|(i, w)| 0.5 * (t.cd[i] + t.cd[i + 1]) * (w[1] - w[0]))
                .sum::<f64>()
                / 360.0;
        let swapped = ue4_integral(&t, true);
        // UE's LCG stream leaves its Monte Carlo mean about 0.5 % from the exact one here.
        assert!((swapped / linear - 1.0).abs() < 1e-2, "{swapped} vs {linear}");
        // An isotropic table: both are the constant, exactly.
        let iso = IesTable {
            h: vec![0.0],
            v: vec![0.0, 180.0],
            cd: vec![5.0, 5.0],
        };
        assert_eq!((ue4_integral(&iso, false), ue4_integral(&iso, true)), (5.0, 5.0));
    }

    #[test]
    fn random_stream_is_uniform_on_the_sphere() {
        let mut s = RandomStream(0x1234);
        let n = 20_000;
        let (mut mean_z, mut mean_z2) = (0.0, 0.0);
        for _ in 0..n {
            let [x, y, z] = s.unit_vector();
            assert!((x * x + y * y + z * z - 1.0).abs() < 1e-5);
            mean_z += f64::from(z) / n as f64;
            mean_z2 += f64::from(z * z) / n as f64;
        }
        // Uniform on the sphere: E[z] = 0, E[z²] = 1/3.
        assert!(
            mean_z.abs() < 0.02 && (mean_z2 - 1.0 / 3.0).abs() < 0.01,
            "{mean_z} {mean_z2}"
        );
    }
}
