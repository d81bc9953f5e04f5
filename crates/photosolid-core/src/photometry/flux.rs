//! Photometric quantities of a [`Distribution`]: flux, output ratios, beam and field angles.
//!
//! # Flux
//! Φ = ∫₀^{2π} ∫₀^{π} I(C, γ) sin γ dγ dC, computed as the **exact integral of
//! the piecewise-linear interpolant in γ** (docs/domain.md §5: on [a, b],
//! `∫ I sinγ = I_a (cos a − cos b) + (I_b − I_a)[sin b − sin a − (b − a) cos b]/(b − a)`),
//! with **trapezoid weights in C** over the full, periodic circle of planes
//! (symmetry expanded, C = 0 and C = 360 the same plane). This is the integral
//! of the bilinear reconstruction, so it matches what the `bilinear` filter
//! renders; it is exact for data linear in γ (isotropic), and converges as h²
//! otherwise. Outside the measured γ range the intensity is zero.
//! A single γ sample spans no solid angle, so it carries no flux.
//!
//! Downward flux is the part with γ < 90°, upward γ > 90°; an interval that
//! straddles 90° is split at 90° on the linear interpolant (exact).

use serde::Serialize;

use crate::model::{periodic_widths, Distribution};

/// Luminous flux of a distribution, lm.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Flux {
    /// Total flux, lm.
    pub total_lm: f64,
    /// Flux below the horizontal (γ < 90°), lm.
    pub downward_lm: f64,
    /// Flux above the horizontal (γ > 90°), lm.
    pub upward_lm: f64,
}

/// Weights (sr per cd) of the linear interpolant on [a, b] (radians):
/// `∫_a^b I(γ) sin γ dγ = w_a I_a + w_b I_b`.
#[inline]
fn segment_weights(a: f64, b: f64) -> (f64, f64) {
    let h = b - a;
    if h <= 0.0 {
        return (0.0, 0.0);
    }
    let (sa, ca) = a.sin_cos();
    let (sb, cb) = b.sin_cos();
    let wb = (sb - sa - h * cb) / h;
    let wa = (ca - cb) - wb;
    (wa, wb)
}

/// Shortest γ interval (radians) integrated: a bound that falls this close to
/// a knot would leave a sliver whose weights are all rounding error.
const SLIVER_RAD: f64 = 1e-9;

/// One γ segment of a band: knots `i`, `i + 1` (radians `a`, `b`), the part
/// `[x0, x1]` inside the band and its weights (see [`segment_weights`]).
#[derive(Debug, Clone, Copy)]
pub(crate) struct BandSegment {
    i: usize,
    a: f64,
    b: f64,
    x0: f64,
    x1: f64,
    w0: f64,
    w1: f64,
}

/// The segments of γ ∈ [lo, hi] (radians) on the knots `gamma_rad`, with
/// their weights: these depend on the grid only, so they are computed once
/// per band and applied to every plane ([`band_integral_with`]), not once per
/// plane (two `sin_cos` per segment were most of a `validate`, issue 26).
pub(crate) fn band_segments(gamma_rad: &[f64], lo: f64, hi: f64) -> Vec<BandSegment> {
    let mut out = Vec::new();
    for i in 0..gamma_rad.len().saturating_sub(1) {
        let (a, b) = (gamma_rad[i], gamma_rad[i + 1]);
        let (x0, x1) = (a.max(lo), b.min(hi));
        if x1 - x0 <= SLIVER_RAD {
            continue;
        }
        let (w0, w1) = segment_weights(x0, x1);
        out.push(BandSegment {
            i,
            a,
            b,
            x0,
            x1,
            w0,
            w1,
        });
    }
    out
}

/// ∫_lo^hi I(γ) sin γ dγ (sr·cd per radian of C) of one plane's linear
/// interpolant over the band's `segments`, exact; zero outside the measured γ
/// range. A segment cut by a bound is integrated from the interpolated value there.
#[inline]
pub(crate) fn band_integral_with(segments: &[BandSegment], values: &[f64]) -> f64 {
    let mut sum = 0.0;
    for s in segments {
        let (ia, ib) = (values[s.i], values[s.i + 1]);
        let at = |x: f64| ia + (ib - ia) * (x - s.a) / (s.b - s.a);
        sum += s.w0 * at(s.x0) + s.w1 * at(s.x1);
    }
    sum
}

/// Weights (radians) of the full-circle planes `angles` (degrees, ascending in
/// [0, 360)) for ∫ over C ∈ [c_lo, c_hi] (degrees, c_hi − c_lo ≤ 360) of the
/// interpolant that is linear in C between neighbouring planes (periodic).
/// Over the full circle these are the trapezoid widths of [`periodic_widths`].
pub(crate) fn c_weights(angles: &[f64], c_lo: f64, c_hi: f64) -> Vec<f64> {
    let n = angles.len();
    let span = (c_hi - c_lo).clamp(0.0, 360.0);
    if n <= 1 {
        return vec![span.to_radians(); n];
    }
    let mut w = vec![0.0; n];
    // Intervals [p_k, p_k+1] over three periods, so a range anywhere in
    // [-360, 720] meets every copy it overlaps.
    for period in [-360.0, 0.0, 360.0] {
        for k in 0..n {
            let p0 = angles[k] + period;
            let p1 = if k + 1 < n { angles[k + 1] } else { angles[0] + 360.0 } + period;
            let len = p1 - p0;
            let (u0, u1) = (p0.max(c_lo), p1.min(c_lo + span));
            if len <= 0.0 || u1 <= u0 {
                continue;
            }
            // ∫ (p1 − u)/len du and ∫ (u − p0)/len du over [u0, u1].
            let to_k = ((p1 - u0).powi(2) - (p1 - u1).powi(2)) / (2.0 * len);
            let to_next = ((u1 - p0).powi(2) - (u0 - p0).powi(2)) / (2.0 * len);
            w[k] += to_k.to_radians();
            w[(k + 1) % n] += to_next.to_radians();
        }
    }
    w
}

/// Flux (lm) in γ zones over the whole circle of C ([`zone_flux`] with C ∈
/// [0, 360]), for many zones of one distribution: the radian γ knots, the
/// full-circle planes and their C weights are found once, not once per zone
/// (the same numbers, bit for bit).
pub(crate) struct Rings<'d> {
    d: &'d Distribution,
    g: Vec<f64>,
    planes: Vec<(f64, usize)>,
    weights: Vec<f64>,
}

impl<'d> Rings<'d> {
    pub(crate) fn new(d: &'d Distribution) -> Self {
        let g: Vec<f64> = d.gamma_angles_deg().iter().map(|x| x.to_radians()).collect();
        let planes = d.full_planes();
        let angles: Vec<f64> = planes.iter().map(|p| p.0).collect();
        let weights = c_weights(&angles, 0.0, 360.0);
        Rings { d, g, planes, weights }
    }

    /// Flux (lm) in γ ∈ [γ_lo, γ_hi] (degrees) over the whole circle.
    pub(crate) fn flux(&self, gamma_deg: (f64, f64)) -> f64 {
        let (lo, hi) = (gamma_deg.0.to_radians(), gamma_deg.1.to_radians());
        let band = band_segments(&self.g, lo, hi);
        self.planes
            .iter()
            .zip(&self.weights)
            .filter(|(_, &w)| w > 0.0)
            .map(|(&(_, ic), w)| w * band_integral_with(&band, self.d.plane_cd(ic)))
            .sum()
    }
}

/// Flux (lm) in the zone γ ∈ [γ_lo, γ_hi], C ∈ [c_lo, c_hi] (degrees; the C
/// range may start below 0 and spans at most 360), by the same rule as
/// [`flux`]: exact in γ on the linear interpolant, linear in C between planes.
/// Zones that tile the sphere add up to [`flux`]'s total.
pub fn zone_flux(d: &Distribution, gamma_deg: (f64, f64), c_deg: (f64, f64)) -> f64 {
    let g: Vec<f64> = d.gamma_angles_deg().iter().map(|x| x.to_radians()).collect();
    let planes = d.full_planes();
    let angles: Vec<f64> = planes.iter().map(|p| p.0).collect();
    let weights = c_weights(&angles, c_deg.0, c_deg.1);
    let (lo, hi) = (gamma_deg.0.to_radians(), gamma_deg.1.to_radians());
    let band = band_segments(&g, lo, hi);
    planes
        .iter()
        .zip(&weights)
        .filter(|(_, &w)| w > 0.0)
        .map(|(&(_, ic), w)| w * band_integral_with(&band, d.plane_cd(ic)))
        .sum()
}

/// Flux of `d` (see the module docs for the rule).
pub fn flux(d: &Distribution) -> Flux {
    let g: Vec<f64> = d.gamma_angles_deg().iter().map(|x| x.to_radians()).collect();
    let planes = d.full_planes();
    let angles: Vec<f64> = planes.iter().map(|p| p.0).collect();
    let widths = periodic_widths(&angles);
    // ∫ I(γ) sin γ dγ of each plane's linear interpolant, split at γ = 90°.
    let half = std::f64::consts::FRAC_PI_2;
    let (lower, upper) = (
        band_segments(&g, 0.0, half),
        band_segments(&g, half, std::f64::consts::PI),
    );
    let (mut down, mut up) = (0.0, 0.0);
    for (&(_, ic), w) in planes.iter().zip(&widths) {
        let values = d.plane_cd(ic);
        let (pd, pu) = (band_integral_with(&lower, values), band_integral_with(&upper, values));
        let w = w.to_radians();
        down += w * pd;
        up += w * pu;
    }
    Flux {
        total_lm: down + up,
        downward_lm: down,
        upward_lm: up,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Symmetry;
    use crate::photometry::test_support::{rot, uniform};
    use std::f64::consts::PI;

    #[test]
    fn isotropic_is_exact_on_every_grid() {
        for n in 2..=181 {
            let f = flux(&rot(uniform(n, 180.0), |_| 1.0));
            assert!((f.total_lm - 4.0 * PI).abs() < 1e-12, "n={n}: {}", f.total_lm);
            assert!((f.downward_lm - 2.0 * PI).abs() < 1e-12);
        }
        // Non-uniform grid, and a grid with a gap.
        let g = vec![0.0, 0.5, 3.0, 10.0, 45.0, 89.0, 130.5, 180.0];
        assert!((flux(&rot(g, |_| 1.0)).total_lm - 4.0 * PI).abs() < 1e-12);
        // One sample spans no solid angle.
        assert_eq!(flux(&rot(vec![0.0], |_| 1.0)).total_lm, 0.0);
    }

    /// The piecewise-linear interpolant's error is at most h²/8 · max|f''|
    /// pointwise, so the flux error is at most 2π · (h²/8) · max|f''| · ∫ sinγ dγ.
    #[test]
    fn cos_power_lobes_converge_within_the_interpolation_bound() {
        for p in [1.0, 2.0, 5.0, 20.0, 128.0] {
            let exact = 2.0 * PI / (p + 1.0);
            let lobe = |g: f64| if g <= PI / 2.0 { g.cos().powf(p) } else { 0.0 };
            // max |d²/dγ² cos^p γ| <= p² + p
            let f2 = p * p + p;
            let mut prev = f64::NAN;
            for n in [19usize, 37, 73, 181, 721] {
                let gam = uniform(n, 90.0);
                let h = (90.0f64 / (n - 1) as f64).to_radians();
                let err = (flux(&rot(gam, lobe)).total_lm - exact).abs();
                let bound = 2.0 * PI * h * h / 8.0 * f2;
                assert!(err <= bound, "p={p} n={n}: err {err} > bound {bound}");
                if prev.is_finite() && err > 1e-9 {
                    assert!(err < prev, "p={p}: error must shrink with the grid");
                }
                prev = err;
            }
        }
    }

    #[test]
    fn lambertian_second_order_convergence() {
        let lam = |g: f64| if g <= PI / 2.0 { 100.0 * g.cos() } else { 0.0 };
        let e1 = (flux(&rot(uniform(19, 90.0), lam)).total_lm - 100.0 * PI).abs();
        let e2 = (flux(&rot(uniform(37, 90.0), lam)).total_lm - 100.0 * PI).abs();
        let ratio = e1 / e2;
        assert!((3.8..4.2).contains(&ratio), "h² convergence expected, ratio {ratio}");
        // Full-sphere grid with zeros above: the kink at 90 is a knot, same answer.
        let e3 = (flux(&rot(uniform(37, 180.0), lam)).total_lm - 100.0 * PI).abs();
        assert!((e3 - e1).abs() < 1e-9 || e3 < e1 * 1.01);
    }

    #[test]
    fn straddling_segment_splits_exactly() {
        // Two samples 0 and 180 with linear data: down+up = total and both exact.
        let d = rot(vec![0.0, 180.0], |g| 1.0 + g);
        let f = flux(&d);
        assert!((f.downward_lm + f.upward_lm - f.total_lm).abs() < 1e-12);
        // exact: 2π ∫_0^{π/2} (1+γ) sinγ dγ = 2π (1 + 1)
        assert!((f.downward_lm - 2.0 * PI * 2.0).abs() < 1e-12);
    }

    #[test]
    fn trapezoid_in_c_on_nonuniform_planes() {
        // I = 1 + cos C (asymmetric), planes at non-uniform angles: ∫(1 + cos C) dC over
        // the circle by trapezoids equals 2π for the constant part; the cos part is
        // approximated. With 72 planes of 5° the error is tiny.
        let c: Vec<f64> = (0..72).map(|k| k as f64 * 5.0).collect();
        let g = uniform(2, 180.0);
        let cd: Vec<f64> = c
            .iter()
            .flat_map(|&cc: &f64| [1.0 + cc.to_radians().cos(); 2])
            .collect();
        let d = Distribution::new(c, g, cd, Symmetry::None).unwrap();
        assert!((flux(&d).total_lm - 4.0 * PI).abs() < 1e-9);
    }

    #[test]
    fn zones_tile_the_total_and_match_closed_forms() {
        // Isotropic 1 cd: a zone [a, b] x [c0, c1] holds (c1 - c0)(cos a - cos b) lm exactly.
        let iso = rot(uniform(19, 180.0), |_| 1.0);
        let z = zone_flux(&iso, (41.0, 77.3), (10.0, 100.0));
        let exact = 90f64.to_radians() * (41f64.to_radians().cos() - 77.3f64.to_radians().cos());
        assert!((z - exact).abs() < 1e-12, "{z} vs {exact}");
        // Asymmetric planes: the four quadrants and two hemispheres add up to the total.
        let c: Vec<f64> = (0..24).map(|k| k as f64 * 15.0).collect();
        let g = uniform(37, 180.0);
        let cd: Vec<f64> = c
            .iter()
            .flat_map(|&cc| g.iter().map(move |&gg| 1.0 + (cc.to_radians()).cos() * (gg / 180.0)))
            .collect();
        let d = Distribution::new(c, g, cd, Symmetry::None).unwrap();
        let total = flux(&d).total_lm;
        let mut sum = 0.0;
        for (c0, c1) in [(0.0, 90.0), (90.0, 180.0), (180.0, 270.0), (270.0, 360.0)] {
            sum += zone_flux(&d, (0.0, 90.0), (c0, c1)) + zone_flux(&d, (90.0, 180.0), (c0, c1));
        }
        assert!((sum - total).abs() < 1e-9 * total, "{sum} vs {total}");
        // A range starting below 0 is the same as its wrapped copy.
        let a = zone_flux(&d, (0.0, 180.0), (-90.0, 90.0));
        let b = zone_flux(&d, (0.0, 180.0), (270.0, 360.0)) + zone_flux(&d, (0.0, 180.0), (0.0, 90.0));
        assert!((a - b).abs() < 1e-9 * total);
    }
}
