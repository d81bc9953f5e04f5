//! Hold-out validation: thin the measured grid, reconstruct what was removed
//! from the rest with each filter, and measure the error.
//!
//! Thinning keeps every K-th measured angle (indices 0, K, 2K, …) plus the
//! range ends (poles and band ends in γ; the first and last stored plane in C
//! unless the symmetry is none, where C is periodic) and drops the others.
//! K = 2 drops every other angle; K ≤ 1 keeps the axis whole. This is the
//! convention of the PEERS reference table ("drop C/γ 4/8" keeps one plane
//! in 4 and one row in 8).
//!
//! Errors are over the dropped samples (every (C, γ) whose plane or row was
//! dropped), in percent of the original I_max. `rms_all_percent` is the RMS
//! over every measured sample instead, the kept ones included (zero error
//! for interpolating filters, the smoothing error for mitchell and bspline):
//! the convention of the PEERS reference table, whose figures it reproduces
//! (e.g. OutdoorRoadway 2/2 bilinear 0.53 %, Catmull-Rom 0.29 %). The flux
//! error compares the flux of the original grid with that of the same grid
//! holding the reconstructed values at the dropped samples, by the crate's
//! flux rule ([`crate::photometry::flux`]).

use serde::Serialize;

use crate::error::ModelError;
use crate::model::{Distribution, Symmetry};

use super::filter::Filter;
use super::texture::LightTexture;

/// Which angles to keep (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct HoldoutSpec {
    /// Keep every K-th stored C-plane (K ≤ 1: keep all).
    pub c_step: usize,
    /// Keep every K-th γ row (K ≤ 1: keep all).
    pub gamma_step: usize,
}

/// The result of one filter.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct HoldoutReport {
    /// The filter.
    pub filter: Filter,
    /// The thinning.
    pub spec: HoldoutSpec,
    /// Stored C-planes and γ rows kept.
    pub kept: (usize, usize),
    /// Number of reconstructed (dropped) samples.
    pub dropped_samples: usize,
    /// Root mean square error over the dropped samples, % of I_max.
    pub rms_percent: f64,
    /// Root mean square error over all measured samples (kept ones too), % of I_max.
    pub rms_all_percent: f64,
    /// Largest absolute error, % of I_max.
    pub max_percent: f64,
    /// Where the largest error is: (C, γ) in degrees.
    pub max_at: (f64, f64),
    /// (reconstructed flux − measured flux) / measured flux, %. 0 when the measured flux is 0.
    pub flux_error_percent: f64,
    /// Dropped samples whose negative overshoot was clamped to 0.
    pub clamped: usize,
}

/// Kept indices of an axis of `n` angles.
fn kept(n: usize, step: usize, keep_last: bool) -> Vec<usize> {
    let step = step.max(1);
    (0..n).filter(|&i| i % step == 0 || (keep_last && i + 1 == n)).collect()
}

/// Flux (lm) of `cd` (C-major on the stored planes of `d`), by the one
/// flux rule of the crate ([`crate::photometry::flux`]).
fn flux(d: &Distribution, cd: &[f64]) -> f64 {
    Distribution::new(
        d.c_angles().to_vec(),
        d.gamma_angles().to_vec(),
        cd.to_vec(),
        d.symmetry(),
    )
    .map(|x| crate::photometry::flux(&x).total_lm)
    .unwrap_or(0.0)
}

/// Run the hold-out test of `dist` for each filter.
///
/// # Errors
/// [`ModelError::Parameter`] when the spec drops nothing;
/// [`ModelError::AllZero`] when the original or the thinned data is all zero.
pub fn holdout(dist: &Distribution, spec: HoldoutSpec, filters: &[Filter]) -> Result<Vec<HoldoutReport>, ModelError> {
    let i_max = dist.max_cd();
    if i_max <= 0.0 {
        return Err(ModelError::AllZero("hold-out errors are relative to I_max"));
    }
    let periodic = dist.symmetry() == Symmetry::None;
    let kc = kept(dist.n_c(), spec.c_step, !periodic);
    let kg = kept(dist.n_gamma(), spec.gamma_step, true);
    if kc.len() == dist.n_c() && kg.len() == dist.n_gamma() {
        return Err(ModelError::Parameter {
            name: "holdout",
            value: format!("{}/{}", spec.c_step, spec.gamma_step),
            reason: "drops nothing on this grid; use a step of 2 or more on an axis with 3 or more angles".into(),
        });
    }
    let c = dist.c_angles();
    let g = dist.gamma_angles();
    let thin = Distribution::new(
        kc.iter().map(|&i| c[i]).collect(),
        kg.iter().map(|&i| g[i]).collect(),
        kc.iter()
            .flat_map(|&ic| kg.iter().map(move |&ig| dist.value(ic, ig)))
            .collect(),
        dist.symmetry(),
    )?;
    let tex = LightTexture::new(&thin)?;
    let is_kept_c: Vec<bool> = (0..dist.n_c()).map(|i| kc.binary_search(&i).is_ok()).collect();
    let is_kept_g: Vec<bool> = (0..dist.n_gamma()).map(|i| kg.binary_search(&i).is_ok()).collect();
    let flux0 = flux(dist, dist.intensities());

    let mut out = Vec::with_capacity(filters.len());
    for &filter in filters {
        let s = tex.sampler(filter);
        let mut cd = dist.intensities().to_vec();
        let (mut n, mut sum2, mut max, mut max_at, mut clamped) = (0usize, 0.0, 0.0f64, (0.0, 0.0), 0usize);
        let mut sum2_all = 0.0;
        for ic in 0..dist.n_c() {
            for ig in 0..dist.n_gamma() {
                if is_kept_c[ic] && is_kept_g[ig] {
                    let e = s.cd(c[ic], g[ig]) - dist.value(ic, ig);
                    sum2_all += e * e;
                    continue;
                }
                let raw = s.unclamped().cd(c[ic], g[ig]);
                clamped += usize::from(raw < 0.0);
                let r = raw.max(0.0);
                let e = (r - dist.value(ic, ig)).abs();
                cd[ic * dist.n_gamma() + ig] = r;
                n += 1;
                sum2 += e * e;
                sum2_all += e * e;
                if e > max {
                    max = e;
                    max_at = (c[ic], g[ig]);
                }
            }
        }
        let flux1 = flux(dist, &cd);
        out.push(HoldoutReport {
            filter,
            spec,
            kept: (kc.len(), kg.len()),
            dropped_samples: n,
            rms_percent: 100.0 * (sum2 / n as f64).sqrt() / i_max,
            rms_all_percent: 100.0 * (sum2_all / (dist.n_c() * dist.n_gamma()) as f64).sqrt() / i_max,
            max_percent: 100.0 * max / i_max,
            max_at,
            flux_error_percent: if flux0 != 0.0 {
                100.0 * (flux1 - flux0) / flux0
            } else {
                0.0
            },
            clamped,
        });
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn flux_rule_is_exact_for_isotropic_and_lambertian() {
        let g: Vec<f64> = (0..=36).map(|k| k as f64 * 5.0).collect();
        let d = Distribution::new(vec![0.0], g.clone(), vec![1.0; 37], Symmetry::Rotational).unwrap();
        assert!((flux(&d, d.intensities()) - 4.0 * std::f64::consts::PI).abs() < 1e-12);
        // Lambertian on a fine grid: π I0 (piecewise-linear error only).
        let g: Vec<f64> = (0..=900).map(|k| k as f64 * 0.1).collect();
        let v: Vec<f64> = g.iter().map(|x| x.to_radians().cos().max(0.0)).collect();
        let d = Distribution::new(vec![0.0, 90.0], g, [v.clone(), v].concat(), Symmetry::Quadrant).unwrap();
        assert!((flux(&d, d.intensities()) - std::f64::consts::PI).abs() < 1e-5);
    }

    #[test]
    fn kept_indices_keep_ends() {
        assert_eq!(kept(7, 2, true), vec![0, 2, 4, 6]);
        assert_eq!(kept(8, 4, true), vec![0, 4, 7]);
        assert_eq!(kept(8, 4, false), vec![0, 4]);
        assert_eq!(kept(5, 1, true), vec![0, 1, 2, 3, 4]);
    }
}
