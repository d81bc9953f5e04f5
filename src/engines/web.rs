//! three.js and Babylon.js: the IES file resampled on a 1° grid.
//!
//! Sources:
//! - three.js (mrdoob/three.js, commit 0a5a85c7) `examples/jsm/loaders/IESLoader.js`:
//!   `_getIESValues` fills `data[phi + theta * height]` (width 360 = θ, the
//!   horizontal angle; height 180 = φ, the vertical angle, whole degrees)
//!   with `interpolateCandelaValues(phi, theta)`, linear in both angles
//!   between the file's angles (the last interval is extrapolated beyond the
//!   last angle), after folding θ through the file's last horizontal angle;
//!   `parse` makes `new DataTexture(data, 180, 1, RedFormat, HalfFloatType)`
//!   with linear filtering, so only θ = 0 (the first 180 values) reaches the
//!   GPU. `IESLamp` multiplies each candela value by itself
//!   (`candelaValues[i][j] *= candelaValues[i][j] * multiplier * ballFactor * blpFactor`)
//!   and divides by the maximum; the TILT block is read and not applied.
//!   The shader (`IESSpotLightNode.getSpotAttenuation`) samples
//!   `texture(iesMap, vec2(acos(cosθ)/π, 0))`: texel φ (value at φ degrees)
//!   is centred at u = (φ + ½)/180, so γ reads the profile at γ − ½°.
//! - Babylon.js (BabylonJS/Babylon.js, commit 0571ea8c)
//!   `packages/dev/core/src/Lights/IES/iesLoader.ts`, `LoadIESData`: the same
//!   interpolation and the same squaring
//!   (`candelaValues[index][subIndex] *= candelaValues[index][subIndex] * ...`),
//!   into `RawTexture.CreateRTexture(arrayBuffer, 360, 180)` (R32F) filled
//!   at `arrayBuffer[phi + theta * height]`; TILT is skipped. The shader
//!   (`lightsFragmentFunctions`, `getIESAttenuation`) samples
//!   `texture(iesLightSampler, vec2(acos(cosAngle)/PI, 0.))`: row 0 of a
//!   360-wide texture, whose texels 0..179 are θ = 0 and 180..359 are θ = 1.
//!
//! The layout rows emulate the 1° grid with every plane kept, bilinear in
//! C and γ (three.js with its half-degree γ offset); the loaders' defects
//! are separate rows ([`crate::engines::defects`]).

use super::table::{lerp, to_half, IesTable, Image};
use crate::model::IntensityField;

/// Grid width (θ, horizontal angles, whole degrees 0..359).
pub const THETA: usize = 360;
/// Grid height (φ, vertical angles, whole degrees 0..179).
pub const PHI: usize = 180;

/// `interpolateCandelaValues(phi, theta)` of both loaders: linear in θ
/// between the file's horizontal angles and in φ between its vertical ones,
/// the last interval extended beyond the last angle; 0 when the vertical
/// interval is empty (one vertical angle).
pub fn interpolate(t: &IesTable, phi: f64, theta: f64) -> f64 {
    let bracket = |a: &[f64], x: f64| -> (usize, f64, f64) {
        let n = a.len();
        if n < 2 {
            return (0, a[0], a[0]);
        }
        let i = (0..n - 1).find(|&i| x < a[i + 1] || i == n - 2).unwrap_or(0);
        (i, a[i], a[i + 1])
    };
    let (ti, t0, t1) = bracket(&t.h, theta);
    let (pi, p0, p1) = bracket(&t.v, phi);
    let (dt, dp) = (t1 - t0, p1 - p0);
    if dp == 0.0 {
        return 0.0;
    }
    let ft = if dt == 0.0 { 0.0 } else { (theta - t0) / dt };
    let fp = (phi - p0) / dp;
    let tn = if dt == 0.0 { ti } else { ti + 1 };
    let v1 = lerp(t.at(ti, pi), t.at(tn, pi), ft);
    let v2 = lerp(t.at(ti, pi + 1), t.at(tn, pi + 1), ft);
    lerp(v1, v2, fp)
}

/// The loaders' grid: `data[phi + theta * 180]`, θ folded through the last
/// horizontal angle as the loaders do, normalised by the table's maximum
/// (the table already squared for the defect rows). `half`: round to half
/// floats (three.js's `HalfFloatType`); Babylon keeps float32.
pub fn bake_grid(t: &IesTable, half: bool) -> Vec<f32> {
    let max = t.max_cd();
    let inv = if max > 0.0 { 1.0 / max } else { 0.0 };
    let (start, end) = (t.h[0], t.h[t.h.len() - 1]);
    let mut data = vec![0.0f32; THETA * PHI];
    for i in 0..THETA * PHI {
        let mut theta = (i % THETA) as f64;
        let phi = (i / THETA) as f64;
        if end - start != 0.0 && (theta < start || theta >= end) {
            theta %= end * 2.0;
            if theta > end {
                theta = end * 2.0 - theta;
            }
        }
        let v = inv * interpolate(t, phi, theta);
        data[phi as usize + theta as usize * PHI] = if half { to_half(v) } else { v as f32 };
    }
    data
}

/// How a web engine reads its 1° grid.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum WebLookup {
    /// Every plane, bilinear in C (wrapping) and γ, γ read ½° early (three.js's texel centres).
    ThreeAllPlanes,
    /// Only θ = 0, as three.js's 180 x 1 texture (γ read ½° early).
    ThreeSinglePlane,
    /// Every plane, bilinear in C and γ on the whole-degree knots (Babylon's grid read as intended).
    BabylonAllPlanes,
    /// Babylon's shader: row 0 of the 360-wide texture at u = γ/180.
    BabylonRowZero,
}

/// A web engine's lookup of its grid, times I_max (the light's intensity).
#[derive(Debug, Clone)]
pub struct WebField {
    /// `data[phi + theta * 180]`, I / I_max.
    pub data: Vec<f32>,
    /// The lookup.
    pub lookup: WebLookup,
    /// cd per unit texel.
    pub i_max_cd: f64,
}

impl WebField {
    #[inline]
    fn at(&self, theta: usize, phi: usize) -> f64 {
        f64::from(self.data[phi + (theta % THETA) * PHI])
    }
    /// Linear in γ along plane θ at texel coordinate `t` (clamped to 0..179).
    fn along(&self, theta: usize, t: f64) -> f64 {
        let t = t.clamp(0.0, (PHI - 1) as f64);
        let p0 = t.floor() as usize;
        let p1 = (p0 + 1).min(PHI - 1);
        lerp(self.at(theta, p0), self.at(theta, p1), t - p0 as f64)
    }
    fn across(&self, c_deg: f64, t: f64) -> f64 {
        let c = crate::model::wrap360(c_deg);
        let c0 = c.floor() as usize;
        lerp(self.along(c0, t), self.along(c0 + 1, t), c - c0 as f64)
    }
}

impl IntensityField for WebField {
    fn intensity_cd(&self, c_deg: f64, gamma_deg: f64) -> f64 {
        if !(c_deg.is_finite() && gamma_deg.is_finite()) {
            return 0.0;
        }
        let g = gamma_deg.clamp(0.0, 180.0);
        let v = match self.lookup {
            WebLookup::ThreeAllPlanes => self.across(c_deg, g - 0.5),
            WebLookup::ThreeSinglePlane => self.along(0, g - 0.5),
            WebLookup::BabylonAllPlanes => self.across(c_deg, g),
            WebLookup::BabylonRowZero => {
                let t = (2.0 * g - 0.5).clamp(0.0, (THETA - 1) as f64);
                let k0 = t.floor() as usize;
                let k1 = (k0 + 1).min(THETA - 1);
                lerp(f64::from(self.data[k0]), f64::from(self.data[k1]), t - k0 as f64)
            }
        };
        // The loaders extrapolate the last interval beyond the file's angles; a
        // negative texel emits nothing.
        self.i_max_cd * v.max(0.0)
    }
    fn name(&self) -> String {
        format!("{:?} 1-degree grid", self.lookup)
    }
    fn bytes(&self) -> usize {
        match self.lookup {
            WebLookup::ThreeSinglePlane => PHI * 2,
            WebLookup::ThreeAllPlanes => THETA * PHI * 2,
            _ => THETA * PHI * 4,
        }
    }
}

/// The grid as an image in the loader's own memory order: three.js's array
/// read as 180 columns (φ) by 360 rows (θ), whose first row is the 180 x 1
/// texture it uploads; Babylon's as the 360 x 180 texture it declares.
pub fn grid_image(data: &[f32], babylon: bool) -> Result<Image, crate::error::ModelError> {
    if babylon {
        Image::new(THETA, PHI, data.to_vec())
    } else {
        Image::new(PHI, THETA, data.to_vec())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grid_of_a_rotational_table() {
        let t = IesTable {
            h: vec![0.0],
            v: vec![0.0, 90.0, 180.0],
            cd: vec![100.0, 50.0, 0.0],
        };
        assert_eq!(interpolate(&t, 45.0, 0.0), 75.0);
        let data = bake_grid(&t, false);
        assert_eq!(data[0], 1.0);
        assert_eq!(data[45 + 200 * PHI], 0.75);
        let f = WebField {
            data,
            lookup: WebLookup::BabylonAllPlanes,
            i_max_cd: 100.0,
        };
        assert!((f.intensity_cd(123.4, 45.0) - 75.0).abs() < 1e-4);
        let three = WebField {
            lookup: WebLookup::ThreeAllPlanes,
            ..f.clone()
        };
        // Half a degree early: at γ = 45 it reads 44.5°.
        assert!((three.intensity_cd(0.0, 45.0) - (100.0 - 50.0 * 44.5 / 90.0)).abs() < 1e-4);
    }
}
