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
//! - three.js 0.187.0 (npm package `three@0.187.0`, read from the published
//!   tarball): `IESLamp` scales candela linearly (PR #34554), shifts the
//!   horizontal angles to start at 0 and closes a range ending between 180°
//!   and 360° with the first plane at 360°; `_getIESValues` samples row φ at
//!   γ = φ·180/179 and folds θ only beyond the last horizontal angle; `parse`
//!   uploads every plane (`DataTexture(data, 180, data.length / 180)`,
//!   `RepeatWrapping` in θ); `IESSpotLightNode` reads it at
//!   (γ/180 inset by half a texel, the twist angle + half a texel) with
//!   linear filtering ([`bake_grid_three`], [`WebLookup::Three`]).
//!
//! The layout rows emulate the current releases: three.js 0.187.0 as just
//! said, Babylon's 1° grid with every plane, bilinear on the knots; the
//! loaders' old behaviours (three.js up to 0.186.1: squared candela, the
//! 180 x 1 texture, the half-degree γ offset) are separate rows
//! ([`crate::engines::defects`]).

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

/// three.js 0.187.0's grid (`IESLoader._getIESValues` and `IESLamp` as
/// published in the npm package `three@0.187.0`,
/// `examples/jsm/loaders/IESLoader.js`): the horizontal angles shifted to
/// start at 0; a range ending between 180° and 360° closed with a copy of
/// the first plane at 360° (as Blender's Cycles does); θ = 0..359 folded
/// (mirrored) only beyond the last horizontal angle; row φ = 0..179 sampled
/// at γ = φ · 180/179, so the 180 texels span 0-180° inclusive. Half floats,
/// I/I_max, `data[phi + theta * 180]`.
pub fn bake_grid_three(t: &IesTable) -> Vec<f32> {
    let base = t.h[0];
    let mut table = IesTable {
        h: t.h.iter().map(|h| h - base).collect(),
        v: t.v.clone(),
        cd: t.cd.clone(),
    };
    let end = table.h[table.h.len() - 1];
    if end > 180.0 && end < 360.0 {
        table.h.push(360.0);
        let first: Vec<f64> = table.cd[..table.v.len()].to_vec();
        table.cd.extend(first);
    }
    let end = table.h[table.h.len() - 1];
    let max = t.max_cd();
    let inv = if max > 0.0 { 1.0 / max } else { 0.0 };
    let mut data = vec![0.0f32; THETA * PHI];
    for i in 0..THETA * PHI {
        let theta = (i % THETA) as f64;
        let phi = (i / THETA) as f64;
        let mut sample = theta;
        if end != 0.0 && sample > end {
            sample %= end * 2.0;
            if sample > end {
                sample = end * 2.0 - sample;
            }
        }
        let v = inv * interpolate(&table, phi * 180.0 / (PHI - 1) as f64, sample);
        data[phi as usize + theta as usize * PHI] = to_half(v);
    }
    data
}

/// How a web engine reads its 1° grid.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum WebLookup {
    /// three.js 0.187.0 (`IESSpotLightNode.getSpotAttenuation` in the npm
    /// package): the 180 x 360 texture of every plane, bilinear, C wrapping
    /// (texel θ centred at C = θ), γ inset by half a texel at both ends so
    /// texel φ sits at γ = φ · 180/179 ([`bake_grid_three`]).
    Three,
    /// Every plane, bilinear in C (wrapping) and γ, γ read ½° early (three.js's texel centres).
    ThreeAllPlanes,
    /// Only θ = 0, as three.js's 180 x 1 texture (γ read ½° early).
    ThreeSinglePlane,
    /// Babylon.js 9.23.0 … 9.35.0 (npm): `LoadIESData` returns `{ width: 180,
    /// height: 1, data }`, the first 180 values of the grid (the θ = 0 plane,
    /// float32), and `getIESAttenuation` samples it at u = γ/180 (texel
    /// centres: γ read half a degree early), the same for every C.
    Babylon,
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
            WebLookup::Three => self.across(c_deg, g * (PHI - 1) as f64 / 180.0),
            WebLookup::ThreeAllPlanes => self.across(c_deg, g - 0.5),
            WebLookup::ThreeSinglePlane | WebLookup::Babylon => self.along(0, g - 0.5),
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
            WebLookup::Babylon => PHI * 4,
            WebLookup::ThreeAllPlanes | WebLookup::Three => THETA * PHI * 2,
            _ => THETA * PHI * 4,
        }
    }
}

/// The grid as an image in the loader's own memory order: three.js's array
/// read as 180 columns (φ) by 360 rows (θ), the texture 0.187.0 uploads;
/// Babylon's 180 x 1 texture (the first 180 values: the θ = 0 plane).
pub fn grid_image(data: &[f32], babylon: bool) -> Result<Image, crate::error::ModelError> {
    if babylon {
        Image::new(PHI, 1, data[..PHI.min(data.len())].to_vec())
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
        // three.js 0.187.0: knots at φ · 180/179, read where they are: a
        // profile linear in γ comes back exact (to half-float rounding).
        let now = WebField {
            data: bake_grid_three(&t),
            lookup: WebLookup::Three,
            i_max_cd: 100.0,
        };
        for g in [0.0, 45.0, 90.0, 137.3, 180.0] {
            let want = (100.0 - 50.0 * g / 90.0f64).max(0.0);
            assert!(
                (now.intensity_cd(77.0, g) - want).abs() < 0.05,
                "{g}: {}",
                now.intensity_cd(77.0, g)
            );
        }
    }

    /// three.js 0.187.0 closes a 0-270° range with the first plane at 360°
    /// (the old loaders extrapolated the last interval) and mirrors a
    /// quadrant only beyond its last angle.
    #[test]
    fn three_r187_wraps_and_mirrors_the_horizontal_range() {
        let v = vec![0.0, 90.0, 180.0];
        let open = IesTable {
            h: vec![0.0, 90.0, 180.0, 270.0],
            v: v.clone(),
            cd: vec![100.0, 0.0, 0.0, 50.0, 0.0, 0.0, 100.0, 0.0, 0.0, 50.0, 0.0, 0.0],
        };
        let f = WebField {
            data: bake_grid_three(&open),
            lookup: WebLookup::Three,
            i_max_cd: 100.0,
        };
        // Halfway from C270 (50) to the copied C0 (100) at C315: 75, not the extrapolated 25.
        assert!(
            (f.intensity_cd(315.0, 0.0) - 75.0).abs() < 0.1,
            "{}",
            f.intensity_cd(315.0, 0.0)
        );
        let quadrant = IesTable {
            h: vec![0.0, 90.0],
            v,
            cd: vec![100.0, 0.0, 0.0, 40.0, 0.0, 0.0],
        };
        let q = WebField {
            data: bake_grid_three(&quadrant),
            lookup: WebLookup::Three,
            i_max_cd: 100.0,
        };
        for (c, want) in [(30.0, 80.0), (150.0, 80.0), (210.0, 80.0), (330.0, 80.0), (90.0, 40.0)] {
            assert!(
                (q.intensity_cd(c, 0.0) - want).abs() < 0.1,
                "C{c}: {}",
                q.intensity_cd(c, 0.0)
            );
        }
    }
}
