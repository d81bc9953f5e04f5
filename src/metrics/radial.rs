//! Radial (per-direction) errors between two intensity distributions.
//!
//! All metrics are computed over a stated [`DirectionSet`] with solid-angle
//! weights ΔΩ_k (sr): the measured directions of a reference grid (cells
//! bounded by the γ midpoints and the periodic C midpoints, docs/domain.md §5), or a
//! dense, nearly uniform spherical Fibonacci sampling (equal weights 4π/N).
//! With `m` the reference and `a` the approximation, in cd:
//!
//! | field | formula |
//! |---|---|
//! | `max_abs_cd` | max_k abs(a_k − m_k) (an upper bound of the Hausdorff distance of the solids) |
//! | `max_pct` | 100 · max_abs_cd / I_max(m) |
//! | `rms_cd` | sqrt(Σ ΔΩ_k (a_k − m_k)² / Σ ΔΩ_k) |
//! | `rms_pct` | 100 · rms_cd / I_max(m) |
//! | `zotti_err` | sqrt(Σ w_k ((a_k − m_k)/(m_k + C))² / Σ w_k) on data scaled to I_max(m) = 1, C = `zotti_c` (default 0.02); w_k = 1 (Zotti et al. 2005) |
//! | `zotti_err_solid_angle` | the same with w_k = ΔΩ_k (no over-weighting of the poles) |
//! | `flux_error_pct` | 100 · (Σ a_k ΔΩ_k − Σ m_k ΔΩ_k) / Σ m_k ΔΩ_k |
//! | `misplaced_flux` | Σ abs(a_k − m_k) ΔΩ_k / Σ m_k ΔΩ_k, in [0, 2] |

use serde::Serialize;

use crate::model::{periodic_widths, Distribution, ANGLE_EPS};

/// Directions (C, γ in degrees) with solid-angle weights (sr).
#[derive(Debug, Clone, PartialEq)]
pub struct DirectionSet {
    /// What the set is, for reports (`measured 72x37`, `fibonacci 20000`).
    pub label: String,
    /// (C, γ) in degrees.
    pub directions: Vec<(f64, f64)>,
    /// Solid angle of each direction's cell, sr.
    pub weights: Vec<f64>,
}

impl DirectionSet {
    /// The measured directions of `d` on the full circle of planes; each
    /// direction's cell spans half-way to its neighbours (clamped to the
    /// measured γ range, periodic in C). A pole (γ = 0 or 180) is one
    /// direction whose cell is the polar cap, not one per plane.
    pub fn measured(d: &Distribution) -> Self {
        Self::measured_where(d, "measured", |_, _| true)
    }

    /// The measured directions of `d` whose stored sample `(ic, ig)` passes
    /// `keep`, with the weights of [`DirectionSet::measured`]; `label` names
    /// the subset (e.g. `withheld`). A pole direction is kept when any
    /// plane's sample there is.
    pub fn measured_where(d: &Distribution, label: &str, keep: impl Fn(usize, usize) -> bool) -> Self {
        let planes = d.full_planes();
        let c: Vec<f64> = planes.iter().map(|p| p.0).collect();
        let wc = periodic_widths(&c);
        let g = d.gamma_angles_deg();
        let n = g.len();
        let mut directions = Vec::with_capacity(c.len() * n);
        let mut weights = Vec::with_capacity(c.len() * n);
        for i in 0..n {
            let lo = if i == 0 { g[0] } else { 0.5 * (g[i - 1] + g[i]) };
            let hi = if i + 1 == n { g[n - 1] } else { 0.5 * (g[i] + g[i + 1]) };
            let band = lo.to_radians().cos() - hi.to_radians().cos();
            let pole = g[i] <= ANGLE_EPS || g[i] >= 180.0 - ANGLE_EPS;
            if pole {
                if (0..d.n_c()).any(|ic| keep(ic, i)) {
                    directions.push((0.0, g[i]));
                    weights.push(2.0 * std::f64::consts::PI * band);
                }
                continue;
            }
            for (k, &(cc, ic)) in planes.iter().enumerate() {
                if keep(ic, i) {
                    directions.push((cc, g[i]));
                    weights.push(wc[k].to_radians() * band);
                }
            }
        }
        Self {
            label: format!("{label} {}x{}", c.len(), n),
            directions,
            weights,
        }
    }

    /// `n` directions of a spherical Fibonacci lattice (nearly uniform), each of weight 4π/n.
    pub fn fibonacci(n: usize) -> Self {
        let n = n.max(1);
        let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
        let directions = (0..n)
            .map(|k| {
                let z = 1.0 - (2.0 * k as f64 + 1.0) / n as f64; // z = -cos γ in (−1, 1)
                let gamma = (-z).acos().to_degrees();
                let c = (k as f64 * golden).to_degrees().rem_euclid(360.0);
                (c, gamma)
            })
            .collect();
        Self {
            label: format!("fibonacci {n}"),
            directions,
            weights: vec![4.0 * std::f64::consts::PI / n as f64; n],
        }
    }

    /// Number of directions.
    pub fn len(&self) -> usize {
        self.directions.len()
    }

    /// True when empty.
    pub fn is_empty(&self) -> bool {
        self.directions.is_empty()
    }
}

/// Radial errors of an approximation against a reference (see the module table).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RadialErrors {
    /// The direction set's label.
    pub directions: String,
    /// Largest absolute difference, cd.
    pub max_abs_cd: f64,
    /// Direction (C, γ) of the largest difference, degrees.
    pub max_at_deg: (f64, f64),
    /// max_abs_cd as a percentage of the reference I_max.
    pub max_pct: f64,
    /// Solid-angle-weighted RMS difference, cd.
    pub rms_cd: f64,
    /// rms_cd as a percentage of the reference I_max.
    pub rms_pct: f64,
    /// Zotti's relative error (unweighted).
    pub zotti_err: f64,
    /// Zotti's relative error, solid-angle weighted.
    pub zotti_err_solid_angle: f64,
    /// The constant C of Zotti's error, relative to I_max.
    pub zotti_c: f64,
    /// Flux difference, percent of the reference flux over the set.
    pub flux_error_pct: f64,
    /// Misplaced-flux fraction, in [0, 2].
    pub misplaced_flux: f64,
}

/// Default constant of Zotti's relative error, as a fraction of I_max (2 %).
pub const ZOTTI_C: f64 = 0.02;

/// Compare values `a` (approximation) and `m` (reference), in cd, sampled on `set`.
///
/// `i_max` is the reference peak (cd) used for percentages and Zotti's
/// scaling. A zero reference gives zero percentages rather than NaN.
pub fn radial_errors(set: &DirectionSet, m: &[f64], a: &[f64], i_max: f64, zotti_c: f64) -> RadialErrors {
    assert_eq!(m.len(), set.len());
    assert_eq!(a.len(), set.len());
    let scale = if i_max > 0.0 { 1.0 / i_max } else { 0.0 };
    let (mut max_abs, mut at) = (0.0f64, (0.0, 0.0));
    let (mut s2, mut sw, mut z, mut zw, mut zwsum) = (0.0, 0.0, 0.0, 0.0, 0.0);
    let (mut fa, mut fm, mut l1) = (0.0, 0.0, 0.0);
    for k in 0..set.len() {
        let w = set.weights[k];
        let diff = a[k] - m[k];
        if diff.abs() > max_abs {
            max_abs = diff.abs();
            at = set.directions[k];
        }
        s2 += w * diff * diff;
        sw += w;
        let rel = (diff * scale) / (m[k] * scale + zotti_c);
        z += rel * rel;
        zw += w * rel * rel;
        zwsum += w;
        fa += w * a[k];
        fm += w * m[k];
        l1 += w * diff.abs();
    }
    let n = set.len().max(1) as f64;
    let rms = if sw > 0.0 { (s2 / sw).sqrt() } else { 0.0 };
    let pct = |x: f64| 100.0 * x * scale;
    RadialErrors {
        directions: set.label.clone(),
        max_abs_cd: max_abs,
        max_at_deg: at,
        max_pct: pct(max_abs),
        rms_cd: rms,
        rms_pct: pct(rms),
        zotti_err: (z / n).sqrt(),
        zotti_err_solid_angle: if zwsum > 0.0 { (zw / zwsum).sqrt() } else { 0.0 },
        zotti_c,
        flux_error_pct: if fm > 0.0 { 100.0 * (fa - fm) / fm } else { 0.0 },
        misplaced_flux: if fm > 0.0 { l1 / fm } else { 0.0 },
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Symmetry;
    use std::f64::consts::PI;

    #[test]
    fn measured_weights_cover_the_measured_band() {
        let c: Vec<f64> = (0..24).map(|k| k as f64 * 15.0).collect();
        let g: Vec<f64> = vec![0.0, 2.5, 10.0, 45.0, 90.0, 130.5, 180.0];
        let d = Distribution::new(c.clone(), g.clone(), vec![1.0; c.len() * g.len()], Symmetry::None).unwrap();
        let s = DirectionSet::measured(&d);
        let total: f64 = s.weights.iter().sum();
        assert!((total - 4.0 * PI).abs() < 1e-12);
        // Poles appear once.
        assert_eq!(s.directions.iter().filter(|d| d.1 == 0.0).count(), 1);
    }

    #[test]
    fn fibonacci_is_uniform_enough() {
        let s = DirectionSet::fibonacci(20_000);
        // The mean of cos γ over a uniform sphere is 0; of cos² γ it is 1/3.
        let m1: f64 = s.directions.iter().map(|d| d.1.to_radians().cos()).sum::<f64>() / 20_000.0;
        let m2: f64 = s.directions.iter().map(|d| d.1.to_radians().cos().powi(2)).sum::<f64>() / 20_000.0;
        assert!(m1.abs() < 1e-3 && (m2 - 1.0 / 3.0).abs() < 1e-3);
    }

    #[test]
    fn closed_form_errors() {
        let s = DirectionSet::fibonacci(10_000);
        let m = vec![100.0; s.len()];
        let a = vec![110.0; s.len()];
        let e = radial_errors(&s, &m, &a, 100.0, ZOTTI_C);
        assert!((e.max_abs_cd - 10.0).abs() < 1e-12);
        assert!((e.rms_pct - 10.0).abs() < 1e-9);
        assert!((e.flux_error_pct - 10.0).abs() < 1e-9);
        assert!((e.misplaced_flux - 0.1).abs() < 1e-12);
        assert!((e.zotti_err - 0.1 / 1.02).abs() < 1e-12);
        // Identical inputs give zeros, and a zero reference gives no NaN.
        let z = radial_errors(&s, &vec![0.0; s.len()], &vec![0.0; s.len()], 0.0, ZOTTI_C);
        assert_eq!(z.max_pct, 0.0);
        assert!(z.zotti_err.is_finite() && z.misplaced_flux == 0.0);
    }
}
