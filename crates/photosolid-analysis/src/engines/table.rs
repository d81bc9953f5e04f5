//! The photometric table as the engines' own IES readers see it, and a
//! single-channel image with the lookups the engines use.

use crate::error::ModelError;
use crate::model::{Distribution, Luminaire};

/// The Type C table of an IES file, as written by photosolid's IES writer
/// ([`crate::formats::ies::type_c_planes`]): the stored horizontal angles
/// (with a closing 360° plane when there is no symmetry) and the vertical
/// angles, in degrees, and the candela values plane by plane.
#[derive(Debug, Clone, PartialEq)]
pub struct IesTable {
    /// Horizontal angles (C), degrees, ascending.
    pub h: Vec<f64>,
    /// Vertical angles (γ), degrees, ascending.
    pub v: Vec<f64>,
    /// Candela, `cd[ih * v.len() + iv]`.
    pub cd: Vec<f64>,
}

impl IesTable {
    /// The table of `d` as an IES file holds it.
    pub fn of(d: &Distribution) -> Self {
        let (h, cd) = crate::formats::ies::type_c_planes(d);
        Self {
            h,
            v: d.gamma_angles_deg().to_vec(),
            cd,
        }
    }

    /// The table of the luminaire's distribution (absolute candela, untilted).
    pub fn of_luminaire(lum: &Luminaire) -> Self {
        Self::of(lum.distribution())
    }

    /// Value at plane `ih`, vertical index `iv` (cd).
    #[inline]
    pub fn at(&self, ih: usize, iv: usize) -> f64 {
        self.cd[ih * self.v.len() + iv]
    }

    /// The largest value (cd); at least 0.
    pub fn max_cd(&self) -> f64 {
        self.cd.iter().copied().fold(0.0, f64::max)
    }

    /// Every value squared (the defect of the three.js and Babylon.js loaders).
    pub fn squared(&self) -> Self {
        Self {
            cd: self.cd.iter().map(|v| v * v).collect(),
            ..self.clone()
        }
    }
}

/// A single-channel image, row-major: `data[y * width + x]`.
#[derive(Debug, Clone, PartialEq)]
pub struct Image {
    /// Columns.
    pub width: usize,
    /// Rows.
    pub height: usize,
    /// Texel values (the unit is the layout's: cd or I/I_max).
    pub data: Vec<f32>,
}

impl Image {
    /// An image from its texels.
    ///
    /// # Errors
    /// [`ModelError::Internal`] when `data.len() != width * height` or the image is empty.
    pub fn new(width: usize, height: usize, data: Vec<f32>) -> Result<Self, ModelError> {
        if width == 0 || height == 0 || data.len() != width * height {
            return Err(ModelError::Internal(format!(
                "an image of {width} x {height} texels with {} values",
                data.len()
            )));
        }
        Ok(Self { width, height, data })
    }

    /// Fill a `width` x `height` image with `f(x, y)`, rows in parallel.
    pub fn from_fn(width: usize, height: usize, f: impl Fn(usize, usize) -> f32 + Sync) -> Result<Self, ModelError> {
        use rayon::prelude::*;
        let mut data = vec![0.0f32; width * height];
        data.par_chunks_mut(width.max(1)).enumerate().for_each(|(y, row)| {
            for (x, v) in row.iter_mut().enumerate() {
                *v = f(x, y);
            }
        });
        Self::new(width, height, data)
    }

    /// Texel (x, y).
    #[inline]
    pub fn texel(&self, x: usize, y: usize) -> f32 {
        self.data[y * self.width + x]
    }

    /// Bilinear lookup at continuous texel coordinates (texel i's centre at
    /// coordinate i), both clamped to the image (clamp-to-edge addressing).
    /// Non-finite coordinates give 0.
    pub fn bilinear_clamped(&self, x: f64, y: f64) -> f64 {
        if !(x.is_finite() && y.is_finite()) {
            return 0.0;
        }
        let x = x.clamp(0.0, (self.width - 1) as f64);
        let y = y.clamp(0.0, (self.height - 1) as f64);
        let (x0, y0) = (x.floor() as usize, y.floor() as usize);
        let (x1, y1) = ((x0 + 1).min(self.width - 1), (y0 + 1).min(self.height - 1));
        let (fx, fy) = (x - x0 as f64, y - y0 as f64);
        let t = |x, y| f64::from(self.texel(x, y));
        let a = t(x0, y0) + (t(x1, y0) - t(x0, y0)) * fx;
        let b = t(x0, y1) + (t(x1, y1) - t(x0, y1)) * fx;
        a + (b - a) * fy
    }

    /// The texel with the largest value, (x, y); ties go to the first in row-major order.
    pub fn argmax(&self) -> (usize, usize) {
        let mut best = (0, f32::NEG_INFINITY);
        for (i, &v) in self.data.iter().enumerate() {
            if v > best.1 {
                best = (i, v);
            }
        }
        (best.0 % self.width, best.0 / self.width)
    }

    /// Mean texel value.
    pub fn mean(&self) -> f64 {
        self.data.iter().map(|&v| f64::from(v)).sum::<f64>() / self.data.len() as f64
    }

    /// Bytes of the texels as stored here (4 per texel).
    pub fn bytes(&self) -> usize {
        self.data.len() * std::mem::size_of::<f32>()
    }
}

/// Round to the nearest IEEE half float and back (the precision of an
/// R16F / RGBA16F texture).
#[inline]
pub fn to_half(v: f64) -> f32 {
    exr::prelude::f16::from_f64(v).to_f32()
}

/// Round a non-negative value to the nearest unsigned 11-bit float (5-bit
/// exponent, bias 15, 6-bit mantissa: the R and G channels of an
/// `R11G11B10` texture, HDRP's default cookie-atlas format) and back.
/// Negative and non-finite values give 0; values above the largest finite
/// 11-bit float (65024) give it.
#[inline]
pub fn to_f11(v: f64) -> f32 {
    if !(v > 0.0 && v.is_finite()) {
        return 0.0;
    }
    const MAX: f64 = 65024.0;
    // Below 2^-14 the format is denormal: a fixed step of 2^-20.
    let e = v.log2().floor().max(-14.0);
    let step = (e - 6.0).exp2();
    ((v / step).round_ties_even() * step).min(MAX) as f32
}

/// Quantise a value in [0, 1] to an 8-bit channel the way a C# `(byte)` cast
/// of `v * 255` does (truncation toward zero, wrap-free because clamped).
#[inline]
pub fn to_byte(v: f64) -> f32 {
    ((v * 255.0).clamp(0.0, 255.0).trunc() / 255.0) as f32
}

/// Linear interpolation.
#[inline]
pub fn lerp(a: f64, b: f64, t: f64) -> f64 {
    a + (b - a) * t
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bilinear_hits_texels_and_clamps() {
        let im = Image::new(2, 2, vec![0.0, 1.0, 2.0, 3.0]).unwrap();
        assert_eq!(im.bilinear_clamped(0.0, 0.0), 0.0);
        assert_eq!(im.bilinear_clamped(1.0, 1.0), 3.0);
        assert_eq!(im.bilinear_clamped(0.5, 0.5), 1.5);
        assert_eq!(im.bilinear_clamped(-4.0, 9.0), 2.0);
        assert_eq!(im.bilinear_clamped(f64::NAN, 0.0), 0.0);
        assert_eq!(im.argmax(), (1, 1));
        assert!(Image::new(2, 2, vec![0.0; 3]).is_err());
    }

    #[test]
    fn quantisers() {
        assert_eq!(to_byte(1.0), 1.0);
        assert_eq!(to_byte(0.999), 254.0 / 255.0);
        assert_eq!(to_half(1.0), 1.0);
        assert!((to_half(0.1) - 0.1).abs() < 1e-4);
        // 6-bit mantissa: 1 + 1/64 is exact, 1 + 1/128 ties to even (1).
        assert_eq!(to_f11(1.0 + 1.0 / 64.0), 1.0 + 1.0 / 64.0);
        assert_eq!(to_f11(1.0 + 1.0 / 128.0), 1.0);
        assert_eq!(to_f11(0.75), 0.75);
        assert_eq!(to_f11(-1.0), 0.0);
        assert_eq!(to_f11(1e9), 65024.0);
        // Relative error at most half a mantissa step.
        for v in [0.013, 0.37, 0.999, 3.3] {
            assert!((f64::from(to_f11(v)) - v).abs() <= v / 128.0, "{v}");
        }
    }
}
