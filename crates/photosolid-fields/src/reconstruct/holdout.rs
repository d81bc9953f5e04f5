//! Hold-out validation: thin the measured grid, reconstruct what was removed
//! from the rest with each filter, and measure the error.
//!
//! Thinning keeps every K-th measured angle (indices 0, K, 2K, …) plus the
//! range ends (poles and band ends in γ; the first and last stored plane in C
//! unless the symmetry is none, where C is periodic) and drops the others.
//! K = 2 drops every other angle; K ≤ 1 keeps the axis whole. This is the
//! convention of the hold-out reference table (docs/domain.md §11) ("drop C/γ 4/8" keeps one plane
//! in 4 and one row in 8).
//!
//! Errors are over the dropped samples (every (C, γ) whose plane or row was
//! dropped), in percent of the original I_max. `rms_all_percent` is the RMS
//! over every measured sample instead, the kept ones included (zero error
//! for interpolating filters, the smoothing error for mitchell and bspline):
//! the convention of the hold-out reference table (docs/domain.md §11), whose figures it reproduces
//! (e.g. OutdoorRoadway 2/2 bilinear 0.53 %, Catmull-Rom 0.29 %). The flux
//! error compares the flux of the original grid with that of the same grid
//! holding the reconstructed values at the dropped samples, by the crate's
//! flux rule ([`crate::photometry::flux()`]).

use serde::Serialize;

use crate::error::ModelError;
use crate::model::{Distribution, IntensityField, Symmetry, ANGLE_EPS};

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

impl HoldoutReport {
    /// Reports as a text table, one row per filter (errors in % of I_max).
    pub fn table(reports: &[HoldoutReport]) -> String {
        use std::fmt::Write;
        let mut s = format!(
            "{:<16} {:>9} {:>9} {:>9} {:>22} {:>10} {:>8}\n",
            "filter", "rms %", "rms-all %", "max %", "max at (C, gamma)", "flux %", "clamped"
        );
        for r in reports {
            let _ = writeln!(
                s,
                "{:<16} {:>9.3} {:>9.3} {:>9.3} {:>22} {:>+10.3} {:>8}",
                r.filter.to_string(),
                r.rms_percent,
                r.rms_all_percent,
                r.max_percent,
                format!("({:.1}, {:.1})", r.max_at.0, r.max_at.1),
                r.flux_error_percent,
                r.clamped
            );
        }
        s
    }
}

/// Kept indices of an axis of `n` angles.
fn kept(n: usize, step: usize, keep_last: bool) -> Vec<usize> {
    kept_with_offset(n, step, 0, keep_last)
}

/// Kept indices of an axis of `n` angles: those `≡ offset (mod step)`, the
/// first one, and the last one when `keep_last`.
fn kept_with_offset(n: usize, step: usize, offset: usize, keep_last: bool) -> Vec<usize> {
    let step = step.max(1);
    (0..n)
        .filter(|&i| i % step == offset % step || i == 0 || (keep_last && i + 1 == n))
        .collect()
}

/// The distribution on the kept stored planes `kc` and γ rows `kg` of `dist`.
fn thinned(dist: &Distribution, kc: &[usize], kg: &[usize]) -> Result<Distribution, ModelError> {
    let (c, g) = (dist.c_angles_deg(), dist.gamma_angles_deg());
    Distribution::new(
        kc.iter().map(|&i| c[i]).collect(),
        kg.iter().map(|&i| g[i]).collect(),
        kc.iter()
            .flat_map(|&ic| kg.iter().map(move |&ig| dist.value_cd(ic, ig)))
            .collect(),
        dist.symmetry(),
    )
}

/// One fold of a k-fold hold-out ([`kfold`]): the data that is kept, and the
/// stored samples `(ic, ig)` of the original grid that are withheld from it.
#[derive(Debug, Clone, PartialEq)]
pub struct Fold {
    /// `C` when whole C-planes are withheld, `gamma` for whole γ rows.
    pub axis: &'static str,
    /// The kept data.
    pub kept: Distribution,
    /// Withheld samples, indices into the original stored grid.
    pub withheld: Vec<(usize, usize)>,
}

/// k-fold hold-out folds of the measured grid (k ≥ 2). On each axis with at
/// least 3 angles, fold `f` keeps every k-th plane (row) starting at index
/// `f` and withholds the rest, so over the k folds of an axis every sample
/// is withheld k − 1 times: with k = 2, exactly once per axis. The first
/// plane and the first and last γ rows (poles, band ends) and, unless C is
/// periodic (symmetry none), the last stored plane are always kept:
/// withholding a band end would test extrapolation, which the
/// reconstructions do not do (zero outside the band).
///
/// # Errors
/// [`ModelError::Parameter`] for k < 2 or a grid with nothing to withhold.
pub fn kfold(dist: &Distribution, k: usize) -> Result<Vec<Fold>, ModelError> {
    if k < 2 {
        return Err(ModelError::Parameter {
            name: "folds",
            value: k.to_string(),
            reason: "a k-fold hold-out needs k >= 2".into(),
        });
    }
    let periodic = dist.symmetry() == Symmetry::None;
    let all_c: Vec<usize> = (0..dist.n_c()).collect();
    let all_g: Vec<usize> = (0..dist.n_gamma()).collect();
    let mut folds = Vec::new();
    for axis in ["C", "gamma"] {
        let n = if axis == "C" { dist.n_c() } else { dist.n_gamma() };
        if n < 3 {
            continue;
        }
        for f in 0..k {
            let keep = kept_with_offset(n, k, f, axis == "gamma" || !periodic);
            if keep.len() == n {
                continue;
            }
            let (kc, kg) = if axis == "C" {
                (keep.clone(), all_g.clone())
            } else {
                (all_c.clone(), keep.clone())
            };
            let dropped: Vec<usize> = (0..n).filter(|i| keep.binary_search(i).is_err()).collect();
            // A pole is one direction shared by every plane: dropping planes does not withhold it.
            let g = dist.gamma_angles_deg();
            let off_pole: Vec<usize> = all_g
                .iter()
                .copied()
                .filter(|&ig| g[ig] > ANGLE_EPS && g[ig] < 180.0 - ANGLE_EPS)
                .collect();
            let withheld = if axis == "C" {
                dropped
                    .iter()
                    .flat_map(|&ic| off_pole.iter().map(move |&ig| (ic, ig)))
                    .collect()
            } else {
                all_c
                    .iter()
                    .flat_map(|&ic| dropped.iter().map(move |&ig| (ic, ig)))
                    .collect()
            };
            folds.push(Fold {
                axis,
                kept: thinned(dist, &kc, &kg)?,
                withheld,
            });
        }
    }
    if folds.is_empty() {
        return Err(ModelError::Parameter {
            name: "folds",
            value: k.to_string(),
            reason: format!(
                "a {} x {} grid has nothing to withhold (an axis needs 3 or more angles)",
                dist.n_c(),
                dist.n_gamma()
            ),
        });
    }
    Ok(folds)
}

/// Flux (lm) of `cd` (C-major on the stored planes of `d`), by the one
/// flux rule of the crate ([`crate::photometry::flux()`]).
fn flux(d: &Distribution, cd: &[f64]) -> f64 {
    Distribution::new(
        d.c_angles_deg().to_vec(),
        d.gamma_angles_deg().to_vec(),
        cd.to_vec(),
        d.symmetry(),
    )
    .map(|x| crate::photometry::flux(&x).total_lm)
    .unwrap_or(0.0)
}

/// The kept stored C-plane and γ-row indices of `spec` on `dist` and the
/// thinned grid holding only them.
///
/// # Errors
/// [`ModelError::AllZero`] for data without light (errors are relative to
/// I_max); [`ModelError::Parameter`] (`holdout`) when `spec` drops nothing.
fn plan(dist: &Distribution, spec: HoldoutSpec) -> Result<(Vec<usize>, Vec<usize>, Distribution), ModelError> {
    if dist.max_cd() <= 0.0 {
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
    let thin = thinned(dist, &kc, &kg)?;
    Ok((kc, kg, thin))
}

/// The hold-out of a [`HoldoutSpec`] for any representation
/// ([`holdout_split`]): what to rebuild it from and where to measure it.
#[derive(Debug, Clone)]
pub struct HoldoutSplit {
    /// The thinned grid: the kept samples only.
    pub kept: Distribution,
    /// The samples it drops, as (C°, γ°, cd).
    pub dropped: Vec<(f64, f64, f64)>,
}

impl HoldoutSplit {
    /// The largest |field − measured| over the dropped samples, % of
    /// `i_max_cd` (the [`HoldoutReport::max_percent`] of any
    /// representation); 0 when nothing is dropped or `i_max_cd` is not positive.
    pub fn max_percent(&self, field: &dyn IntensityField, i_max_cd: f64) -> f64 {
        if i_max_cd.is_nan() || i_max_cd <= 0.0 {
            return 0.0;
        }
        let worst = self
            .dropped
            .iter()
            .map(|&(c, g, v)| (field.intensity_cd(c, g) - v).abs())
            .fold(0.0, f64::max);
        100.0 * worst / i_max_cd
    }
}

/// The hold-out of `spec` on `dist` for any representation.
///
/// # Errors
/// As [`holdout`].
pub fn holdout_split(dist: &Distribution, spec: HoldoutSpec) -> Result<HoldoutSplit, ModelError> {
    let (kc, kg, kept) = plan(dist, spec)?;
    let (c, g) = (dist.c_angles_deg(), dist.gamma_angles_deg());
    let mut dropped = Vec::new();
    for (ic, &cc) in c.iter().enumerate() {
        for (ig, &gg) in g.iter().enumerate() {
            if kc.binary_search(&ic).is_err() || kg.binary_search(&ig).is_err() {
                dropped.push((cc, gg, dist.value_cd(ic, ig)));
            }
        }
    }
    Ok(HoldoutSplit { kept, dropped })
}

/// Run the hold-out test of `dist` for each filter.
///
/// # Errors
/// [`ModelError::Parameter`] when the spec drops nothing;
/// [`ModelError::AllZero`] when the original or the thinned data is all zero.
pub fn holdout(dist: &Distribution, spec: HoldoutSpec, filters: &[Filter]) -> Result<Vec<HoldoutReport>, ModelError> {
    let i_max = dist.max_cd();
    let (kc, kg, thin) = plan(dist, spec)?;
    let c = dist.c_angles_deg();
    let g = dist.gamma_angles_deg();
    let tex = LightTexture::new(&thin)?;
    let is_kept_c: Vec<bool> = (0..dist.n_c()).map(|i| kc.binary_search(&i).is_ok()).collect();
    let is_kept_g: Vec<bool> = (0..dist.n_gamma()).map(|i| kg.binary_search(&i).is_ok()).collect();
    let flux0 = flux(dist, dist.intensities_cd());

    let mut out = Vec::with_capacity(filters.len());
    for &filter in filters {
        // Every sample of the grid, kept or dropped (the kept ones for `rms_all_percent`).
        let grid = tex.eval_grid_cd(filter, c, g);
        let mut cd = dist.intensities_cd().to_vec();
        let (mut n, mut sum2, mut max, mut max_at, mut clamped) = (0usize, 0.0, 0.0f64, (0.0, 0.0), 0usize);
        let mut sum2_all = 0.0;
        for ic in 0..dist.n_c() {
            for ig in 0..dist.n_gamma() {
                let raw = grid[ic * dist.n_gamma() + ig];
                if is_kept_c[ic] && is_kept_g[ig] {
                    let e = raw.max(0.0) - dist.value_cd(ic, ig);
                    sum2_all += e * e;
                    continue;
                }
                clamped += usize::from(raw < 0.0);
                let r = raw.max(0.0);
                let e = (r - dist.value_cd(ic, ig)).abs();
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
        assert!((flux(&d, d.intensities_cd()) - 4.0 * std::f64::consts::PI).abs() < 1e-12);
        // Lambertian on a fine grid: π I0 (piecewise-linear error only).
        let g: Vec<f64> = (0..=900).map(|k| k as f64 * 0.1).collect();
        let v: Vec<f64> = g.iter().map(|x| x.to_radians().cos().max(0.0)).collect();
        let d = Distribution::new(vec![0.0, 90.0], g, [v.clone(), v].concat(), Symmetry::Quadrant).unwrap();
        assert!((flux(&d, d.intensities_cd()) - std::f64::consts::PI).abs() < 1e-5);
    }

    /// The grid evaluation the hold-out runs on gives, at every pair, the bits of the
    /// per-query reconstruction: every filter, the 0/360 seam, C outside the stored
    /// half (mirrored), γ outside the measured band (0) and a bisymmetric file.
    #[test]
    fn grid_evaluation_is_the_per_query_one() {
        let c: Vec<f64> = (0..=6).map(|k| k as f64 * 15.0).collect();
        let g: Vec<f64> = (0..=18).map(|k| k as f64 * 5.0).collect();
        let v: Vec<f64> = c
            .iter()
            .flat_map(|&cc| {
                g.iter()
                    .map(move |&gg| 100.0 + 80.0 * (gg.to_radians() * 2.0).sin() * (1.0 + (cc.to_radians()).cos()))
            })
            .collect();
        let d = Distribution::new(c, g, v, Symmetry::Quadrant).unwrap();
        let tex = LightTexture::new(&d).unwrap();
        let cq: Vec<f64> = vec![-10.0, 0.0, 7.5, 90.0, 135.0, 270.0, 359.9, 360.0, 725.0];
        let gq: Vec<f64> = vec![0.0, 2.5, 45.0, 89.0, 90.0, 95.0, 180.0];
        for filter in Filter::ALL {
            let grid = tex.eval_grid_cd(filter, &cq, &gq);
            for (i, &cc) in cq.iter().enumerate() {
                for (j, &gg) in gq.iter().enumerate() {
                    let one = tex.eval_cd(filter, cc, gg);
                    assert_eq!(
                        grid[i * gq.len() + j].to_bits(),
                        one.to_bits(),
                        "{filter} at C {cc}, γ {gg}"
                    );
                }
            }
        }
    }

    #[test]
    fn kept_indices_keep_ends() {
        assert_eq!(kept(7, 2, true), vec![0, 2, 4, 6]);
        assert_eq!(kept(8, 4, true), vec![0, 4, 7]);
        assert_eq!(kept(8, 4, false), vec![0, 4]);
        assert_eq!(kept(5, 1, true), vec![0, 1, 2, 3, 4]);
        assert_eq!(kept_with_offset(7, 2, 1, true), vec![0, 1, 3, 5, 6]);
    }

    #[test]
    fn two_folds_withhold_every_inner_sample_once_per_axis() {
        let c: Vec<f64> = (0..8).map(|k| k as f64 * 45.0).collect();
        let g: Vec<f64> = (0..=6).map(|k| k as f64 * 30.0).collect();
        let d = Distribution::new(c, g, vec![1.0; 56], Symmetry::None).unwrap();
        let folds = kfold(&d, 2).unwrap();
        assert_eq!(folds.len(), 4);
        for axis in ["C", "gamma"] {
            let mut count = vec![0; 56];
            for f in folds.iter().filter(|f| f.axis == axis) {
                for &(ic, ig) in &f.withheld {
                    count[ic * 7 + ig] += 1;
                }
            }
            for ic in 0..8 {
                for ig in 0..7 {
                    // Periodic C: every plane but the first, off the poles; γ: every row but the ends.
                    let inner = if axis == "C" {
                        ic != 0 && ig != 0 && ig != 6
                    } else {
                        ig != 0 && ig != 6
                    };
                    assert_eq!(count[ic * 7 + ig], usize::from(inner), "{axis} ({ic}, {ig})");
                }
            }
        }
        assert!(kfold(&d, 1).is_err());
        let one = Distribution::new(vec![0.0], vec![0.0, 90.0], vec![1.0, 1.0], Symmetry::Rotational).unwrap();
        assert!(kfold(&one, 2).is_err());
    }
}
