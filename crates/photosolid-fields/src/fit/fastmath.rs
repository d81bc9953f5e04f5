//! `exp` and `ln` on the fit's ranges, without branches, so a loop over a
//! slice of them compiles to vector instructions (the C library's functions
//! are calls the compiler cannot vectorise, and they were a third of the fit's
//! time: docs/history/benchmarks-to-2026-12-07.md, "The profile's t^p in vector lanes").
//!
//! Both follow the classic reductions (Cody and Waite 1980; the argument
//! reductions of Sun's fdlibm, 1993): exp(x) = 2^n exp(r) with |r| ≤ ln 2 / 2,
//! ln(x) = k ln 2 + ln(m) with m in [√½, √2). The polynomials are the Taylor
//! series, long enough that the truncation is below an f64's resolution; the
//! unit tests hold both within a few ulp of the standard library's.

/// ln 2 split so that n · LN2_HI is exact for |n| < 2^11 (fdlibm's constants).
const LN2_HI: f64 = 6.931_471_803_691_238e-1;
const LN2_LO: f64 = 1.908_214_929_270_587_7e-10;
/// 1.5 · 2^52: adding it rounds an f64 of magnitude below 2^51 to an integer
/// held in the low bits of the sum.
const ROUND_SHIFT: f64 = 6_755_399_441_055_744.0;
/// From this down [`exp_nonpositive`] returns 0 (e^x ≤ 3.3e-308).
const EXP_MIN_ARG: f64 = -708.0;
/// The bits of √½.
const SQRT_HALF_BITS: u64 = 0x3fe6_a09e_667f_3bcd;
/// The mantissa bits of an f64.
const MANTISSA: u64 = 0x000f_ffff_ffff_ffff;

/// 1 / k! for k = 0, 1, …, N − 1: the Taylor coefficients of e^r.
const fn inverse_factorials<const N: usize>() -> [f64; N] {
    let mut c = [1.0; N];
    let mut k = 1;
    while k < N {
        c[k] = c[k - 1] / k as f64;
        k += 1;
    }
    c
}

/// 1 / (2k + 1) for k = 0, 1, …, N − 1: the coefficients of atanh(s) / s in s².
const fn inverse_odd_numbers<const N: usize>() -> [f64; N] {
    let mut c = [1.0; N];
    let mut k = 1;
    while k < N {
        c[k] = 1.0 / (2 * k + 1) as f64;
        k += 1;
    }
    c
}

/// e^x for x ≤ 0 (−∞ gives 0), within a few ulp of [`f64::exp`]; 0 from −708
/// down, where e^x ≤ 3.3e-308 is at the edge of the subnormals. Branch-free.
#[inline(always)]
pub(crate) fn exp_nonpositive(x: f64) -> f64 {
    let xc = if x > EXP_MIN_ARG { x } else { EXP_MIN_ARG };
    let shifted = xc * std::f64::consts::LOG2_E + ROUND_SHIFT;
    let n = shifted - ROUND_SHIFT;
    let r = (xc - n * LN2_HI) - n * LN2_LO;
    // e^r, |r| ≤ 0.347: the Taylor series to r^12 (remainder below 2e-16 relative).
    const C: [f64; 13] = inverse_factorials();
    // Estrin's scheme in r² and r⁴: a shorter dependency chain than Horner's.
    let r2 = r * r;
    let r4 = r2 * r2;
    let r8 = r4 * r4;
    let p01 = C[0] + C[1] * r;
    let p23 = C[2] + C[3] * r;
    let p45 = C[4] + C[5] * r;
    let p67 = C[6] + C[7] * r;
    let p89 = C[8] + C[9] * r;
    let p1011 = C[10] + C[11] * r;
    let lo = (p01 + p23 * r2) + (p45 + p67 * r2) * r4;
    let hi = (p89 + p1011 * r2) + C[12] * r4;
    let poly = lo + hi * r8;
    // 2^n from n's integer bits in `shifted`; n ≥ −1022 since xc ≥ −708.
    let n_bits = shifted.to_bits().wrapping_sub(ROUND_SHIFT.to_bits());
    let scale = f64::from_bits(n_bits.wrapping_add(1023) << 52);
    let v = poly * scale;
    if x > EXP_MIN_ARG {
        v
    } else {
        0.0
    }
}

/// ln x for x in [0, 1] (0 gives −∞), within a few ulp of [`f64::ln`] for normal
/// x; a subnormal x (below 2.2e-308) also gives −∞. Branch-free.
#[inline(always)]
pub(crate) fn ln_unit(x: f64) -> f64 {
    // x = 2^k m, m in [√½, √2) (musl's reduction, on the whole 64 bits).
    let shifted = x.to_bits().wrapping_add(0x3ff0_0000_0000_0000 - SQRT_HALF_BITS);
    let k_biased = shifted >> 52;
    let k = (f64::from_bits(0x4330_0000_0000_0000 | k_biased) - 4_503_599_627_370_496.0) - 1023.0;
    let m = f64::from_bits((shifted & MANTISSA).wrapping_add(SQRT_HALF_BITS));
    // ln m = 2 atanh(s), s = (m − 1)/(m + 1), |s| ≤ 0.1716: the series to s^19
    // (remainder below 3e-17 relative).
    let f = m - 1.0;
    let s = f / (2.0 + f);
    let z = s * s;
    const C: [f64; 10] = inverse_odd_numbers();
    let z2 = z * z;
    let z4 = z2 * z2;
    let z8 = z4 * z4;
    let lo = (C[0] + C[1] * z) + (C[2] + C[3] * z) * z2 + ((C[4] + C[5] * z) + (C[6] + C[7] * z) * z2) * z4;
    let series = lo + (C[8] + C[9] * z) * z8;
    let ln_m = 2.0 * s * series;
    let v = k * LN2_HI + (ln_m + k * LN2_LO);
    if x >= f64::MIN_POSITIVE {
        v
    } else {
        f64::NEG_INFINITY
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// |a − b| in units of b's last place.
    fn ulps(a: f64, b: f64) -> f64 {
        if a == b {
            return 0.0;
        }
        let ulp = f64::from_bits(b.abs().to_bits() + 1) - b.abs();
        (a - b).abs() / ulp
    }

    #[test]
    fn exp_matches_the_standard_library() {
        let mut worst: f64 = 0.0;
        for i in 0..=200_000 {
            let x = -707.99 * (i as f64 / 200_000.0).powi(2);
            worst = worst.max(ulps(exp_nonpositive(x), x.exp()));
        }
        for x in [
            0.0,
            -0.0,
            -1e-300,
            -1e-17,
            -0.5 * std::f64::consts::LN_2,
            -1.0,
            -707.999,
        ] {
            worst = worst.max(ulps(exp_nonpositive(x), x.exp()));
        }
        assert!(worst <= 4.0, "largest error {worst} ulp");
        assert_eq!(exp_nonpositive(0.0), 1.0);
        assert_eq!(exp_nonpositive(-708.5), 0.0);
        assert_eq!(exp_nonpositive(-1e300), 0.0);
        assert_eq!(exp_nonpositive(f64::NEG_INFINITY), 0.0);
    }

    #[test]
    fn ln_matches_the_standard_library() {
        let mut worst: f64 = 0.0;
        for i in 1..=200_000 {
            let u = i as f64 / 200_000.0;
            for x in [u, u.powi(8), (-700.0 * u).exp(), 1.0 - u * 1e-9] {
                // Relative to |ln x| where it is large, absolute near x = 1 (ln x → 0).
                let (a, b) = (ln_unit(x), x.ln());
                let err = if b.abs() > 1e-3 {
                    ulps(a, b)
                } else {
                    (a - b).abs() / f64::EPSILON
                };
                worst = worst.max(err);
            }
        }
        assert!(worst <= 4.0, "largest error {worst} ulp");
        assert_eq!(ln_unit(1.0), 0.0);
        assert_eq!(ln_unit(0.0), f64::NEG_INFINITY);
        assert_eq!(ln_unit(1e-310), f64::NEG_INFINITY);
        assert!((ln_unit(f64::MIN_POSITIVE) - f64::MIN_POSITIVE.ln()).abs() < 1e-12);
    }
}
