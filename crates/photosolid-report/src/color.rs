//! Lamp colour: the correlated colour temperature a file states, and the
//! display colour the plots use for it.
//!
//! CCT → chromaticity by the cubic approximation of the Planckian locus of
//! Kang et al. (2002) (colour-science: `CCT_to_xy_Kang2002`), valid 1667 K to
//! 25000 K (clamped outside); xy → XYZ with Y = 1 → linear sRGB (IEC
//! 61966-2-1 matrix, D65 white), negative components clipped, scaled so the
//! largest is 1, then the sRGB transfer function. The notebook
//! `cross_check_textures.ipynb` checks these numbers against colour-science.

use serde::Serialize;

pub use crate::solid::colormap::srgb_encode;

/// Chromaticity (x, y) of a blackbody at `cct_k` kelvin (Kang et al. 2002).
pub fn cct_to_xy(cct_k: f64) -> (f64, f64) {
    let t = cct_k.clamp(1667.0, 25000.0);
    let (t2, t3) = (t * t, t * t * t);
    let x = if t <= 4000.0 {
        -0.2661239e9 / t3 - 0.2343589e6 / t2 + 0.8776956e3 / t + 0.179910
    } else {
        -3.0258469e9 / t3 + 2.1070379e6 / t2 + 0.2226347e3 / t + 0.240390
    };
    let (x2, x3) = (x * x, x * x * x);
    let y = if t <= 2222.0 {
        -1.1063814 * x3 - 1.34811020 * x2 + 2.18555832 * x - 0.20219683
    } else if t <= 4000.0 {
        -0.9549476 * x3 - 1.37418593 * x2 + 2.09137015 * x - 0.16748867
    } else {
        3.0817580 * x3 - 5.87338670 * x2 + 3.75112997 * x - 0.37001483
    };
    (x, y)
}

/// Linear sRGB of chromaticity (x, y) at Y = 1.
pub fn xy_to_linear_srgb(x: f64, y: f64) -> [f64; 3] {
    let (cx, cy, cz) = (x / y, 1.0, (1.0 - x - y) / y);
    [
        3.2404542 * cx - 1.5371385 * cy - 0.4985314 * cz,
        -0.9692660 * cx + 1.8760108 * cy + 0.0415560 * cz,
        0.0556434 * cx - 0.2040259 * cy + 1.0572252 * cz,
    ]
}

/// A display colour for a lamp: 8-bit sRGB, brightest channel at full scale.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct LampColor {
    /// Correlated colour temperature, K.
    pub cct_k: f64,
    /// Chromaticity x, y.
    pub xy: (f64, f64),
    /// Encoded sRGB in [0, 1], brightest channel 1.
    pub srgb: [f64; 3],
    /// The same as 8-bit values.
    pub srgb8: [u8; 3],
}

/// The display colour of a blackbody at `cct_k`.
pub fn lamp_color(cct_k: f64) -> LampColor {
    let xy = cct_to_xy(cct_k);
    let lin = xy_to_linear_srgb(xy.0, xy.1).map(|c| c.max(0.0));
    let m = lin.iter().copied().fold(0.0, f64::max).max(1e-12);
    let srgb = lin.map(|c| srgb_encode(c / m));
    LampColor {
        cct_k,
        xy,
        srgb,
        srgb8: srgb.map(|c| (c * 255.0).round() as u8),
    }
}

/// The CCT (K) a lamp colour field states: "3000K", "3000 K", "4000",
/// "ww3000k", or a CIE code like "830" (CRI 8x, 3000 K) / "940". `None`
/// when the text names no temperature.
pub fn parse_cct(text: &str) -> Option<f64> {
    let mut best = None;
    let b = text.as_bytes();
    let mut i = 0;
    while i < b.len() {
        if b[i].is_ascii_digit() {
            let j = (i..b.len()).find(|&k| !b[k].is_ascii_digit()).unwrap_or(b.len());
            let n: f64 = text[i..j].parse().ok()?;
            let kelvin_suffix = b.get(j).is_some_and(|c| c.eq_ignore_ascii_case(&b'k'))
                || (b.get(j) == Some(&b' ') && b.get(j + 1).is_some_and(|c| c.eq_ignore_ascii_case(&b'k')));
            if (1000.0..=25000.0).contains(&n) && (kelvin_suffix || j - i == 4 || j - i == 5) {
                return Some(n);
            }
            if j - i == 3 && best.is_none() && (7.0..=9.0).contains(&(n / 100.0).floor()) {
                let t = (n % 100.0) * 100.0;
                if (1700.0..=9900.0).contains(&t) {
                    best = Some(t);
                }
            }
            i = j;
        } else {
            i += 1;
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_common_spellings() {
        assert_eq!(parse_cct("3000K"), Some(3000.0));
        assert_eq!(parse_cct("4000 K"), Some(4000.0));
        assert_eq!(parse_cct("ww3000k"), Some(3000.0));
        assert_eq!(parse_cct("830"), Some(3000.0));
        assert_eq!(parse_cct("LED 940"), Some(4000.0));
        assert_eq!(parse_cct("5000"), Some(5000.0));
        assert_eq!(parse_cct("warm white"), None);
        assert_eq!(parse_cct("80"), None);
    }

    #[test]
    fn planckian_reference_points() {
        // Kang et al. give x, y within 1e-3 of the Planckian locus; at 6504 K
        // the locus passes near D65 (0.3127, 0.3290): within 0.01.
        let (x, y) = cct_to_xy(6504.0);
        assert!((x - 0.3135).abs() < 2e-3 && (y - 0.3237).abs() < 2e-3, "{x} {y}");
        let warm = lamp_color(2700.0);
        assert!(warm.srgb8[0] == 255 && warm.srgb8[2] < warm.srgb8[1]);
        let cool = lamp_color(10000.0);
        assert!(cool.srgb8[2] == 255 && cool.srgb8[0] < 255);
    }
}
