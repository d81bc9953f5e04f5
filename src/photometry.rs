//! Photometric quantities of a [`Distribution`]: flux, output ratios, beam and field angles.
//!
//! # Flux
//! Φ = ∫₀^{2π} ∫₀^{π} I(C, γ) sin γ dγ dC, computed as the **exact integral of
//! the piecewise-linear interpolant in γ** (DOMAIN §5: on [a, b],
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

use crate::error::{Warning, WarningCode};
use crate::model::{periodic_widths, Distribution, Luminaire, ANGLE_EPS};

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

/// ∫ I(γ) sin γ dγ (sr·cd per radian of C) of one plane's linear interpolant,
/// split at γ = 90°: (downward, upward).
fn plane_integral(gamma_rad: &[f64], values: &[f64]) -> (f64, f64) {
    let half = std::f64::consts::FRAC_PI_2;
    let (mut down, mut up) = (0.0, 0.0);
    for i in 0..gamma_rad.len().saturating_sub(1) {
        let (a, b) = (gamma_rad[i], gamma_rad[i + 1]);
        let (ia, ib) = (values[i], values[i + 1]);
        if b <= half + 1e-15 {
            let (wa, wb) = segment_weights(a, b);
            down += wa * ia + wb * ib;
        } else if a >= half - 1e-15 {
            let (wa, wb) = segment_weights(a, b);
            up += wa * ia + wb * ib;
        } else {
            let im = ia + (ib - ia) * (half - a) / (b - a);
            let (wa, wm) = segment_weights(a, half);
            down += wa * ia + wm * im;
            let (wm2, wb) = segment_weights(half, b);
            up += wm2 * im + wb * ib;
        }
    }
    (down, up)
}

/// Flux of `d` (see the module docs for the rule).
pub fn flux(d: &Distribution) -> Flux {
    let g: Vec<f64> = d.gamma_angles().iter().map(|x| x.to_radians()).collect();
    let planes = d.full_planes();
    let angles: Vec<f64> = planes.iter().map(|p| p.0).collect();
    let widths = periodic_widths(&angles);
    let (mut down, mut up) = (0.0, 0.0);
    for (&(_, ic), w) in planes.iter().zip(&widths) {
        let (pd, pu) = plane_integral(&g, d.plane(ic));
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

/// Intensities (cd) at every γ of the grid in the half-plane C (degrees,
/// any value): the stored plane when C is a grid plane, otherwise linear
/// interpolation between the two neighbouring full-circle planes.
pub fn plane_profile(d: &Distribution, c: f64) -> Vec<f64> {
    let c = crate::model::wrap360(c);
    let planes = d.full_planes();
    let n = planes.len();
    if n == 1 {
        return d.plane(planes[0].1).to_vec();
    }
    let i = planes.partition_point(|p| p.0 < c - ANGLE_EPS);
    if i < n && (planes[i].0 - c).abs() <= ANGLE_EPS {
        return d.plane(planes[i].1).to_vec();
    }
    // Neighbours on the periodic circle.
    let (lo, hi) = if i == 0 || i == n {
        (planes[n - 1], planes[0])
    } else {
        (planes[i - 1], planes[i])
    };
    let span = (hi.0 - lo.0).rem_euclid(360.0);
    let t = if span > 0.0 {
        (c - lo.0).rem_euclid(360.0) / span
    } else {
        0.0
    };
    d.plane(lo.1)
        .iter()
        .zip(d.plane(hi.1))
        .map(|(a, b)| a + t * (b - a))
        .collect()
}

/// Full beam or field angle (degrees) in the plane pair (C, C + 180): the
/// angle between the two outermost-connected points around the reference
/// direction where the intensity falls to `fraction` of the reference.
///
/// The two half-planes form one profile over a signed angle θ ∈ [−180, 180]
/// (θ = −γ on the C + 180 side). With `of_max` the walk starts at the
/// profile's maximum and the reference is that maximum (IES definition);
/// otherwise it starts at θ = 0 and the reference is the centre-beam value
/// I(γ = 0) (CIE definition). Crossings are linearly interpolated; beyond
/// the measured γ range the intensity is zero, so a profile still above the
/// threshold at its last measured γ crosses there. `None` when the reference
/// is not positive, when no crossing exists on a side (e.g. isotropic
/// full-sphere data), or when γ = 0 is not measured (CIE).
pub fn spread_angle(d: &Distribution, c: f64, fraction: f64, of_max: bool) -> Option<f64> {
    let g = d.gamma_angles();
    let a = plane_profile(d, c);
    let b = plane_profile(d, c + 180.0);
    // Signed profile: the C+180 side reversed with negated angles, then the C side.
    let mut theta = Vec::with_capacity(2 * g.len());
    let mut val = Vec::with_capacity(2 * g.len());
    for i in (0..g.len()).rev() {
        if g[i] > ANGLE_EPS {
            theta.push(-g[i]);
            val.push(b[i]);
        }
    }
    let has_zero = g[0] <= ANGLE_EPS;
    for i in 0..g.len() {
        theta.push(g[i]);
        // At γ = 0 both half-planes meet: use their mean (they differ only in files with mismatched nadirs).
        val.push(if i == 0 && has_zero { 0.5 * (a[0] + b[0]) } else { a[i] });
    }
    let (start, reference) = if of_max {
        let (k, &m) = val.iter().enumerate().max_by(|x, y| x.1.total_cmp(y.1))?;
        (k, m)
    } else {
        if !has_zero {
            return None;
        }
        let k = theta.iter().position(|&t| t == g[0])?;
        (k, val[k])
    };
    if reference <= 0.0 || !reference.is_finite() {
        return None;
    }
    let thr = fraction * reference;
    let walk = |dir: isize| -> Option<f64> {
        let mut k = start as isize;
        loop {
            let next = k + dir;
            if next < 0 || next >= val.len() as isize {
                // Ran off the measured range: the intensity is zero beyond it,
                // unless the profile closes the circle (full 0..180 data),
                // where no crossing exists.
                let end_angle = theta[k as usize].abs();
                return if (end_angle - 180.0).abs() <= ANGLE_EPS {
                    None
                } else {
                    Some(theta[k as usize])
                };
            }
            let (v0, v1) = (val[k as usize], val[next as usize]);
            if v1 < thr {
                let (t0, t1) = (theta[k as usize], theta[next as usize]);
                let f = (v0 - thr) / (v0 - v1);
                return Some(t0 + f * (t1 - t0));
            }
            k = next;
        }
    };
    let left = walk(-1)?;
    let right = walk(1)?;
    Some(right - left)
}

/// Beam (50 %) and field (10 %) angles in the C0-C180 and C90-C270 planes, degrees.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct BeamAngles {
    /// IES beam angle (50 % of the maximum) in C0-C180 / C90-C270.
    pub ies_beam_deg: [Option<f64>; 2],
    /// IES field angle (10 % of the maximum) in C0-C180 / C90-C270.
    pub ies_field_deg: [Option<f64>; 2],
    /// CIE beam angle (50 % of the centre-beam intensity) in C0-C180 / C90-C270.
    pub cie_beam_deg: [Option<f64>; 2],
    /// CIE field angle (10 % of the centre-beam intensity) in C0-C180 / C90-C270.
    pub cie_field_deg: [Option<f64>; 2],
}

/// Beam and field angles of `d`.
pub fn beam_angles(d: &Distribution) -> BeamAngles {
    let both = |f: f64, of_max: bool| [spread_angle(d, 0.0, f, of_max), spread_angle(d, 90.0, f, of_max)];
    BeamAngles {
        ies_beam_deg: both(0.5, true),
        ies_field_deg: both(0.1, true),
        cie_beam_deg: both(0.5, false),
        cie_field_deg: both(0.1, false),
    }
}

/// The photometric summary of a luminaire that `info` prints.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Summary {
    /// Largest intensity, cd.
    pub max_cd: f64,
    /// Direction of the largest intensity: (C, γ) in degrees.
    pub max_direction_deg: (f64, f64),
    /// Computed flux.
    pub flux: Flux,
    /// Declared luminaire flux, lm (lamp flux × LOR, or the absolute flux).
    pub declared_flux_lm: Option<f64>,
    /// Computed flux / declared flux.
    pub flux_ratio: Option<f64>,
    /// Light output ratio: computed flux / lamp flux (None for absolute photometry).
    pub lor: Option<f64>,
    /// Downward light output ratio.
    pub dlor: Option<f64>,
    /// Upward light output ratio.
    pub ulor: Option<f64>,
    /// Downward flux fraction: downward / total flux.
    pub dff: Option<f64>,
    /// Beam and field angles.
    pub beams: BeamAngles,
    /// Consistency warnings (declared vs computed).
    pub warnings: Vec<Warning>,
}

/// Relative difference past which declared and computed flux disagree.
pub const FLUX_MISMATCH: f64 = 0.05;

/// Difference (fraction, i.e. 0.01 = 1 percentage point) past which computed and declared LOR disagree.
pub const LOR_MISMATCH: f64 = 0.01;

/// Compute the summary of `lum` (untilted).
pub fn summary(lum: &Luminaire) -> Summary {
    let d = &lum.distribution;
    let (max_cd, mc, mg) = d.max();
    let flux = flux(d);
    let lamp = if lum.declared.absolute {
        None
    } else {
        lum.declared.lamp_flux_lm.filter(|&v| v > 0.0)
    };
    // A ratio to a declared flux is reported only when it is a number: a
    // file may declare a flux so small (1e-320 lm) that the ratio overflows.
    let ratio = |x: f64| lamp.map(|l| x / l).filter(|r| r.is_finite());
    let declared = lum.declared.luminaire_flux_lm.filter(|&v| v > 0.0);
    let flux_ratio = declared.map(|dcl| flux.total_lm / dcl).filter(|r| r.is_finite());
    let mut warnings = Vec::new();
    if let (Some(r), Some(dcl)) = (flux_ratio, declared) {
        if (r - 1.0).abs() > FLUX_MISMATCH {
            warnings.push(Warning::new(
                WarningCode::FluxMismatch,
                format!(
                    "integrated flux {:.1} lm is {:.1} % of the declared {:.1} lm (more than {:.0} % off)",
                    flux.total_lm,
                    100.0 * r,
                    dcl,
                    100.0 * FLUX_MISMATCH
                ),
            ));
        }
    }
    if let (Some(decl), Some(l)) = (lum.declared.lor, lamp) {
        let lor = flux.total_lm / l;
        if (lor - decl).abs() > LOR_MISMATCH {
            warnings.push(Warning::new(
                WarningCode::LorMismatch,
                format!(
                    "integrated LOR {:.2} % differs from the declared {:.2} % by {:+.2} percentage points",
                    100.0 * lor,
                    100.0 * decl,
                    100.0 * (lor - decl)
                ),
            ));
        }
    }
    if let (Some(decl_dff), true) = (lum.declared.dff, flux.total_lm > 0.0) {
        let dff = flux.downward_lm / flux.total_lm;
        if (dff - decl_dff).abs() > 0.05 {
            warnings.push(Warning::new(
                WarningCode::DffMismatch,
                format!(
                    "computed downward flux fraction {:.1} % differs from the declared {:.1} %",
                    100.0 * dff,
                    100.0 * decl_dff
                ),
            ));
        }
    }
    Summary {
        max_cd,
        max_direction_deg: (mc, mg),
        flux,
        declared_flux_lm: declared,
        flux_ratio,
        lor: ratio(flux.total_lm),
        dlor: ratio(flux.downward_lm),
        ulor: ratio(flux.upward_lm),
        dff: (flux.total_lm > 0.0).then(|| flux.downward_lm / flux.total_lm),
        beams: beam_angles(d),
        warnings,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Symmetry;
    use std::f64::consts::PI;

    fn rot(gamma: Vec<f64>, f: impl Fn(f64) -> f64) -> Distribution {
        let cd = gamma.iter().map(|&g| f(g.to_radians())).collect();
        Distribution::new(vec![0.0], gamma, cd, Symmetry::Rotational).unwrap()
    }

    fn uniform(n: usize, to: f64) -> Vec<f64> {
        (0..n).map(|i| to * i as f64 / (n - 1) as f64).collect()
    }

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
    fn beam_angles_of_closed_forms() {
        let g = uniform(1801, 180.0);
        let lam = rot(g.clone(), |x| if x <= PI / 2.0 { x.cos() } else { 0.0 });
        let b = beam_angles(&lam);
        assert!((b.ies_beam_deg[0].unwrap() - 120.0).abs() < 0.01);
        assert!((b.cie_beam_deg[1].unwrap() - 120.0).abs() < 0.01);
        let field = 2.0 * 0.1f64.acos().to_degrees();
        assert!((b.ies_field_deg[0].unwrap() - field).abs() < 0.01);
        let p = 10.0;
        let lobe = rot(g.clone(), |x| if x <= PI / 2.0 { x.cos().powf(p) } else { 0.0 });
        let exact = 2.0 * 0.5f64.powf(1.0 / p).acos().to_degrees();
        assert!((beam_angles(&lobe).ies_beam_deg[0].unwrap() - exact).abs() < 0.01);
        // Isotropic: no crossing anywhere.
        assert_eq!(beam_angles(&rot(g, |_| 1.0)).ies_beam_deg[0], None);
    }
}
