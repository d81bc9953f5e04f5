//! The one reconstruction [`Filter`] type and its 1-D kernels.
//!
//! Every filter is evaluated on four consecutive knots `t_{i-1} < t_i <
//! t_{i+1} < t_{i+2}` around a query `x` in `[t_i, t_{i+1}]`, with the local
//! fraction `s = (x - t_i) / (t_{i+1} - t_i)`. The same code serves the point
//! sampler (f64) and the texture render (f32, the GPU's precision), so the
//! kernels are generic over [`Real`].
//!
//! Sources:
//! - Catmull–Rom on non-uniform knots: cubic Hermite with
//!   `m_i = (p_{i+1} − p_{i−1}) / (t_{i+1} − t_{i−1})` (docs/domain.md §4; on uniform
//!   knots this is the classic Catmull–Rom, Mitchell–Netravali B = 0, C = ½).
//! - Mitchell–Netravali (B, C): D. Mitchell, A. Netravali, "Reconstruction
//!   filters in computer graphics", SIGGRAPH 1988; the cubic B-spline is B = 1, C = 0.
//! - PCHIP: F. N. Fritsch, J. Butland, "A method for constructing local
//!   monotone piecewise cubic interpolants", SIAM J. Sci. Stat. Comput. 5
//!   (1984), with the weighted harmonic mean of SciPy's `PchipInterpolator`.

use std::fmt;
use std::ops::{Add, Div, Mul, Sub};
use std::str::FromStr;

use serde::{Serialize, Serializer};

use crate::error::ModelError;

/// A reconstruction filter on the (C, γ) sphere grid.
///
/// Spelled on the command line (and by [`Display`](fmt::Display) /
/// [`FromStr`]) as `nearest`, `bilinear`, `catmull-rom`, `mitchell`
/// (B = C = 1/3), `mitchell:B:C`, `bspline`, `pchip`. `mitchell:B,C` is still
/// read, but written `mitchell:B:C` so that a comma-separated list
/// (`--recon bilinear,mitchell:0:0.5`) keeps it whole.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Filter {
    /// Nearest knot (ties go to the upper knot). Interpolating, piecewise constant.
    Nearest,
    /// Linear in each axis between the two neighbouring knots. Interpolating, no overshoot.
    Bilinear,
    /// Non-uniform Catmull–Rom (cubic Hermite, centred-difference slopes). Interpolating, C¹, may overshoot.
    CatmullRom,
    /// Mitchell–Netravali cubic with parameters B and C (dimensionless).
    /// Approximating unless B = 0. `mitchell` alone means B = C = 1/3.
    Mitchell {
        /// The B parameter (B = 1, C = 0 is the cubic B-spline).
        b: f64,
        /// The C parameter (B = 0, C = ½ is Catmull–Rom).
        c: f64,
    },
    /// Uniform cubic B-spline (Mitchell–Netravali B = 1, C = 0). Approximating, C², never overshoots.
    BSpline,
    /// Monotone piecewise cubic Hermite (Fritsch–Butland slopes as SciPy's
    /// `PchipInterpolator`). Interpolating, C¹, never overshoots the data.
    Pchip,
}

/// The spellings [`Filter::from_str`] accepts, for error messages and help.
pub const FILTER_NAMES: &str = "nearest, bilinear, catmull-rom, mitchell, mitchell:B:C, bspline, pchip";

const THIRD: f64 = 1.0 / 3.0;

impl Filter {
    /// Every filter with its default parameters, in order of increasing support.
    pub const ALL: [Filter; 6] = [
        Filter::Nearest,
        Filter::Bilinear,
        Filter::CatmullRom,
        Filter::Mitchell { b: THIRD, c: THIRD },
        Filter::BSpline,
        Filter::Pchip,
    ];

    /// The default Mitchell–Netravali filter, B = C = 1/3.
    pub const MITCHELL: Filter = Filter::Mitchell { b: THIRD, c: THIRD };

    /// True when the filter returns every knot value exactly at its knot.
    pub fn is_interpolating(self) -> bool {
        match self {
            Filter::Nearest | Filter::Bilinear | Filter::CatmullRom | Filter::Pchip => true,
            Filter::Mitchell { b, .. } => b == 0.0,
            Filter::BSpline => false,
        }
    }

    /// True for the cubic filters (4 taps per axis); their result may dip below zero
    /// (except PCHIP and the B-spline), which the samplers clamp by default.
    pub fn is_cubic(self) -> bool {
        !matches!(self, Filter::Nearest | Filter::Bilinear)
    }

    /// True for PCHIP, whose tap rows hold knot spacings instead of weights
    /// (its weights depend on the data; see [`crate::reconstruct::AxisTaps`]).
    pub fn is_data_dependent(self) -> bool {
        matches!(self, Filter::Pchip)
    }

    /// The four linear weights of taps `i-1, i, i+1, i+2` for a query at fraction `s`
    /// in `[t_i, t_{i+1}]` on the knots `t = [t_{i-1}, t_i, t_{i+1}, t_{i+2}]` (degrees).
    /// `None` for PCHIP (data dependent).
    ///
    /// Interpolating filters use the knot positions (exact at every knot on any
    /// grid); approximating ones (Mitchell, B-spline) use the fraction `s` alone,
    /// i.e. treat the four knots as if they were evenly spaced.
    pub(crate) fn linear_weights(self, t: [f64; 4], s: f64) -> Option<[f64; 4]> {
        Some(match self {
            Filter::Nearest => {
                if s < 0.5 {
                    [0.0, 1.0, 0.0, 0.0]
                } else {
                    [0.0, 0.0, 1.0, 0.0]
                }
            }
            Filter::Bilinear => [0.0, 1.0 - s, s, 0.0],
            Filter::CatmullRom => {
                let h = t[2] - t[1];
                let (h00, h10, h01, h11) = hermite_basis(s);
                // m_i = (p_{i+1} − p_{i−1}) / (t_{i+1} − t_{i−1}); m_{i+1} likewise:
                // the Hermite form is linear in p, so fold the slopes into weights.
                let a = h10 * h / (t[2] - t[0]);
                let b = h11 * h / (t[3] - t[1]);
                [-a, h00 - b, h01 + a, b]
            }
            Filter::Mitchell { .. } | Filter::BSpline => {
                let (b, c) = match self {
                    Filter::Mitchell { b, c } => (b, c),
                    _ => (1.0, 0.0), // the B-spline is Mitchell-Netravali (1, 0)
                };
                [
                    mitchell_kernel(b, c, s + 1.0),
                    mitchell_kernel(b, c, s),
                    mitchell_kernel(b, c, 1.0 - s),
                    mitchell_kernel(b, c, 2.0 - s),
                ]
            }
            Filter::Pchip => return None,
        })
    }
}

/// Cubic Hermite basis (h00, h10, h01, h11) at `s` in [0, 1].
#[inline]
fn hermite_basis<T: Real>(s: T) -> (T, T, T, T) {
    let one = T::ONE;
    let two = T::from_f64(2.0);
    let three = T::from_f64(3.0);
    let s2 = s * s;
    let s3 = s2 * s;
    (
        two * s3 - three * s2 + one,
        s3 - two * s2 + s,
        three * s2 - two * s3,
        s3 - s2,
    )
}

/// Mitchell–Netravali kernel k(x) (Mitchell & Netravali 1988, eq. 8).
fn mitchell_kernel(b: f64, c: f64, x: f64) -> f64 {
    let x = x.abs();
    if x < 1.0 {
        ((12.0 - 9.0 * b - 6.0 * c) * x * x * x + (-18.0 + 12.0 * b + 6.0 * c) * x * x + (6.0 - 2.0 * b)) / 6.0
    } else if x < 2.0 {
        ((-b - 6.0 * c) * x * x * x + (6.0 * b + 30.0 * c) * x * x + (-12.0 * b - 48.0 * c) * x + (8.0 * b + 24.0 * c))
            / 6.0
    } else {
        0.0
    }
}

/// The float types the kernels run in: f64 for the reference sampler, f32 for
/// the texture render (the precision of the GPU path).
pub trait Real:
    Copy + PartialOrd + Add<Output = Self> + Sub<Output = Self> + Mul<Output = Self> + Div<Output = Self>
{
    /// 0.
    const ZERO: Self;
    /// 1.
    const ONE: Self;
    /// Conversion (rounding) from f64.
    fn from_f64(v: f64) -> Self;
}

impl Real for f64 {
    const ZERO: Self = 0.0;
    const ONE: Self = 1.0;
    #[inline]
    fn from_f64(v: f64) -> Self {
        v
    }
}

impl Real for f32 {
    const ZERO: Self = 0.0;
    const ONE: Self = 1.0;
    #[inline]
    fn from_f64(v: f64) -> Self {
        v as f32
    }
}

/// Combine four tap values with one tap row.
///
/// For every filter but PCHIP, `w` holds the four linear weights. For PCHIP,
/// `w = [s, h_prev, h, h_next]`: the fraction in the interval and the knot
/// spacings `t_i − t_{i−1}`, `t_{i+1} − t_i`, `t_{i+2} − t_{i+1}` (degrees);
/// `h = 0` marks a query outside the band (result 0).
#[inline]
pub fn combine<T: Real>(pchip: bool, v: [T; 4], w: [T; 4]) -> T {
    if pchip {
        pchip_eval(v, w)
    } else {
        w[0] * v[0] + w[1] * v[1] + w[2] * v[2] + w[3] * v[3]
    }
}

/// Fritsch–Butland slope at a knot between secants `d0` (left, spacing `h0`)
/// and `d1` (right, spacing `h1`): zero at a local extremum, otherwise the
/// weighted harmonic mean `(w1 + w2) / (w1/d0 + w2/d1)` with
/// `w1 = 2h1 + h0`, `w2 = h1 + 2h0` (SciPy `_find_derivatives`).
#[inline]
fn fritsch_butland<T: Real>(d0: T, d1: T, h0: T, h1: T) -> T {
    if d0 * d1 <= T::ZERO {
        return T::ZERO;
    }
    let two = T::from_f64(2.0);
    let w1 = two * h1 + h0;
    let w2 = h1 + two * h0;
    (w1 + w2) / (w1 / d0 + w2 / d1)
}

#[inline]
fn pchip_eval<T: Real>(v: [T; 4], w: [T; 4]) -> T {
    let [s, h_prev, h, h_next] = w;
    if h <= T::ZERO {
        return T::ZERO;
    }
    let d_prev = (v[1] - v[0]) / h_prev;
    let d = (v[2] - v[1]) / h;
    let d_next = (v[3] - v[2]) / h_next;
    let m0 = fritsch_butland(d_prev, d, h_prev, h);
    let m1 = fritsch_butland(d, d_next, h, h_next);
    let (h00, h10, h01, h11) = hermite_basis(s);
    h00 * v[1] + h10 * h * m0 + h01 * v[2] + h11 * h * m1
}

impl fmt::Display for Filter {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Filter::Nearest => f.write_str("nearest"),
            Filter::Bilinear => f.write_str("bilinear"),
            Filter::CatmullRom => f.write_str("catmull-rom"),
            Filter::Mitchell { b, c } if b == THIRD && c == THIRD => f.write_str("mitchell"),
            // `{}` of an f64 is the shortest text that parses back to the same value.
            Filter::Mitchell { b, c } => write!(f, "mitchell:{b}:{c}"),
            Filter::BSpline => f.write_str("bspline"),
            Filter::Pchip => f.write_str("pchip"),
        }
    }
}

impl FromStr for Filter {
    type Err = ModelError;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let bad = |reason: String| ModelError::Parameter {
            name: "filter",
            value: s.to_string(),
            reason,
        };
        let t = s.trim().to_ascii_lowercase();
        Ok(match t.as_str() {
            "nearest" => Filter::Nearest,
            "bilinear" => Filter::Bilinear,
            "catmull-rom" => Filter::CatmullRom,
            "mitchell" => Filter::MITCHELL,
            "bspline" => Filter::BSpline,
            "pchip" => Filter::Pchip,
            _ => {
                let Some(params) = t.strip_prefix("mitchell:") else {
                    return Err(bad(format!("unknown filter; valid: {FILTER_NAMES}")));
                };
                let parts: Vec<&str> = params.split([':', ',']).map(str::trim).collect();
                let nums: Vec<Option<f64>> = parts.iter().map(|p| p.parse::<f64>().ok()).collect();
                match nums.as_slice() {
                    [Some(b), Some(c)] if b.is_finite() && c.is_finite() => Filter::Mitchell { b: *b, c: *c },
                    _ => {
                        return Err(bad(
                            "expected mitchell:B:C with two finite numbers, e.g. mitchell:0.333:0.333".into(),
                        ))
                    }
                }
            }
        })
    }
}

impl Serialize for Filter {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.collect_str(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spellings_round_trip() {
        for f in Filter::ALL.into_iter().chain([
            Filter::Mitchell { b: 0.0, c: 0.5 },
            Filter::Mitchell { b: 0.1, c: -2.5e-3 },
        ]) {
            let s = f.to_string();
            assert_eq!(s.parse::<Filter>().unwrap(), f, "{s}");
        }
        // the old spelling is read; the written one has no comma
        assert_eq!("mitchell:1,0".parse::<Filter>().unwrap().to_string(), "mitchell:1:0");
        assert_eq!(
            "mitchell:1:0".parse::<Filter>().unwrap(),
            Filter::Mitchell { b: 1.0, c: 0.0 }
        );
        // a comma-separated list (`--recon`, `--filters`) keeps a written Mitchell whole
        let list = format!("bilinear,{},pchip", Filter::Mitchell { b: 0.0, c: 0.75 });
        let parsed: Vec<Filter> = list.split(',').map(|t| t.parse().unwrap()).collect();
        assert_eq!(parsed[1], Filter::Mitchell { b: 0.0, c: 0.75 });
        let e = "lanczos".parse::<Filter>().unwrap_err().to_string();
        assert!(e.contains("catmull-rom") && e.contains("pchip"), "{e}");
        assert!("mitchell:1".parse::<Filter>().is_err());
        assert!("mitchell:nan,0".parse::<Filter>().is_err());
    }

    #[test]
    fn mitchell_weights_match_published_values() {
        let w = Filter::MITCHELL.linear_weights([-1.0, 0.0, 1.0, 2.0], 0.0).unwrap();
        assert!((w[1] - 8.0 / 9.0).abs() < 1e-15 && (w[0] - 1.0 / 18.0).abs() < 1e-15);
        // B = 0, C = 1/2 is Catmull–Rom on uniform knots.
        for s in [0.0, 0.25, 0.5, 0.9] {
            let a = Filter::Mitchell { b: 0.0, c: 0.5 }
                .linear_weights([-1.0, 0.0, 1.0, 2.0], s)
                .unwrap();
            let b = Filter::CatmullRom.linear_weights([-1.0, 0.0, 1.0, 2.0], s).unwrap();
            for k in 0..4 {
                assert!((a[k] - b[k]).abs() < 1e-14);
            }
            let bs = Filter::BSpline.linear_weights([0.0; 4], s).unwrap();
            let expect = [
                (1.0 - s).powi(3) / 6.0,
                (3.0 * s * s * s - 6.0 * s * s + 4.0) / 6.0,
                (-3.0 * s * s * s + 3.0 * s * s + 3.0 * s + 1.0) / 6.0,
                s * s * s / 6.0,
            ];
            for k in 0..4 {
                assert!((bs[k] - expect[k]).abs() < 1e-14);
            }
        }
    }

    #[test]
    fn pchip_matches_scipy_interior_and_is_monotone() {
        // scipy.interpolate.PchipInterpolator([0,1,3,4],[0,1,1.5,4])(2.0) interior interval [1,3]:
        // d_prev = 1, d = 0.25, d_next = 2.5; m1 = (w1+w2)/(w1/1 + w2/0.25) with h0=1,h1=2: w1=5,w2=4 → 9/21.
        let v = [0.0, 1.0, 1.5, 4.0];
        let w = [0.5, 1.0, 2.0, 1.0];
        let m0 = 9.0 / 21.0;
        // m at knot 3: h0 = 2, h1 = 1: w1 = 4, w2 = 5, d0 = 0.25, d1 = 2.5 → 9 / (16 + 2) = 0.5
        let m1 = 0.5;
        let (h00, h10, h01, h11) = hermite_basis(0.5f64);
        let expect = h00 * 1.0 + h10 * 2.0 * m0 + h01 * 1.5 + h11 * 2.0 * m1;
        assert!((combine(true, v, w) - expect).abs() < 1e-15);
        assert_eq!(combine(true, v, [0.0, 1.0, 0.0, 1.0]), 0.0, "h = 0 means outside");
    }
}
