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
//!
//! # The maximum between the directions
//! Over a finite set, `max_abs_cd` is a lower bound of the supremum of
//! abs(a − m) over the sphere: the peak of an interpolating filter's error
//! lies between the measured directions, and between the set's directions.
//! Where both fields can be evaluated anywhere, [`refine_max`] climbs from
//! the largest samples ([`MaxRefinement`]: a pattern search on the sphere,
//! the seeds at least one set spacing apart) and
//! [`RadialErrors::with_refined_max`] replaces the maximum with the largest
//! value found, keeping the sampled one (`sampled_max_abs_cd`). Every value
//! is attained at a stated direction, so the refined max is still a lower
//! bound, equal to the supremum to within the search's final step wherever
//! the highest peak lies in the basin of one of the seeds. RMS, Zotti's
//! errors and the flux figures stay over the set (they are integrals).

use glam::DVec3;
use serde::Serialize;

use crate::model::{frame, periodic_widths, Distribution, IntensityField, ANGLE_EPS};

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
    /// The largest absolute difference over the set's directions alone, cd
    /// (equal to `max_abs_cd` unless the maximum was refined).
    pub sampled_max_abs_cd: f64,
    /// sampled_max_abs_cd as a percentage of the reference I_max.
    pub sampled_max_pct: f64,
    /// Local searches of the refined maximum ([`MaxRefinement::seeds`]); 0: not refined.
    pub refined_seeds: usize,
}

impl RadialErrors {
    /// These errors with the maximum refined between the set's directions
    /// (`r` from [`refine_max`] on the same values; `i_max` the reference
    /// peak, cd): `max_abs_cd`, `max_at_deg` and `max_pct` become the refined
    /// ones (never below the sampled maximum), the sampled maximum stays in
    /// `sampled_max_abs_cd` / `sampled_max_pct`. A non-finite `r.value` is ignored.
    pub fn with_refined_max(mut self, r: &RefinedMax, i_max: f64) -> Self {
        self.refined_seeds = r.seeds;
        if r.value.is_finite() && r.value > self.max_abs_cd {
            self.max_abs_cd = r.value;
            self.max_at_deg = r.at_deg;
            self.max_pct = if i_max > 0.0 { 100.0 * r.value / i_max } else { 0.0 };
        }
        self
    }
}

/// How [`refine_max`] searches for the largest difference between the
/// directions of a set: a compass (pattern) search on the sphere from each
/// seed, polling the four directions ±C and ±γ (great-circle steps) and
/// halving the step where none improves, in two stages: every seed to
/// `coarse_step_deg`, then the `finalists` largest to `min_step_deg`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct MaxRefinement {
    /// Searches started, from the largest samples at least one set spacing
    /// (sqrt(4π/N) rad, N directions) apart.
    pub seeds: usize,
    /// Searches continued past `coarse_step_deg`: the largest after the first stage.
    pub finalists: usize,
    /// Step at which the first stage stops, degrees of arc.
    pub coarse_step_deg: f64,
    /// Step at which the search stops, degrees of arc: the maximum found is
    /// a local maximum to within this step (no improving move of that size).
    pub min_step_deg: f64,
    /// Polling rounds at most per stage (a safety cap; each round moves or halves every search).
    pub max_rounds: usize,
}

/// The refinement of the comparisons' radial maximum: 32 seeds, the best 4
/// refined to 0.001°.
pub const MAX_REFINEMENT: MaxRefinement = MaxRefinement {
    seeds: 32,
    finalists: 4,
    coarse_step_deg: 0.05,
    min_step_deg: 0.001,
    max_rounds: 64,
};

impl MaxRefinement {
    /// What the refined maximum over `set` is, in words, for reports: e.g.
    /// `max over 20000 directions (fibonacci 20000), refined locally around the 32 largest (pattern search to 0.001 deg)`.
    pub fn describe(&self, set: &DirectionSet) -> String {
        format!(
            "max over {} directions ({}), refined locally around the {} largest (pattern search to {} deg)",
            set.len(),
            set.label,
            self.seeds,
            self.min_step_deg
        )
    }
}

/// The result of [`refine_max`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct RefinedMax {
    /// The largest absolute difference found, cd (at least the sampled maximum).
    pub value: f64,
    /// Where, (C, γ) degrees.
    pub at_deg: (f64, f64),
    /// Searches run (seeds found, at most [`MaxRefinement::seeds`]).
    pub seeds: usize,
    /// Directions evaluated by the searches.
    pub evaluations: usize,
}

/// One local search of [`refine_max`].
struct Climb {
    w: DVec3,
    at: (f64, f64),
    value: f64,
    step_rad: f64,
}

/// Unit tangents along +C and +γ at the unit direction `w` (any orthonormal
/// pair at a pole, where C is undefined).
pub(super) fn tangents(w: DVec3) -> (DVec3, DVec3) {
    let rho = (w.x * w.x + w.y * w.y).sqrt();
    if rho < 1e-9 {
        return w.any_orthonormal_pair();
    }
    let (cc, sc) = (w.x / rho, w.y / rho);
    // ∂w/∂γ of w = (sin γ cos C, sin γ sin C, −cos γ), −cos γ = w.z.
    (DVec3::new(-sc, cc, 0.0), DVec3::new(-w.z * cc, -w.z * sc, rho))
}

/// Values at a batch of directions `(C, gamma)` in radians, one per direction.
pub type EvalDirections<'a> = dyn Fn(&[(f64, f64)]) -> Vec<f64> + 'a;

/// Run the searches of `climbs` whose step is at least `stop_rad` until
/// every step is below it (or `max_rounds` rounds); returns the evaluations made.
fn climb(climbs: &mut [Climb], eval: &EvalDirections<'_>, stop_rad: f64, max_rounds: usize) -> usize {
    let mut evaluations = 0;
    for _ in 0..max_rounds {
        let active: Vec<usize> = (0..climbs.len()).filter(|&i| climbs[i].step_rad >= stop_rad).collect();
        if active.is_empty() {
            break;
        }
        let mut points = Vec::with_capacity(4 * active.len());
        let mut dirs = Vec::with_capacity(4 * active.len());
        for &i in &active {
            let s = &climbs[i];
            let (e1, e2) = tangents(s.w);
            let (sin, cos) = s.step_rad.sin_cos();
            for e in [e1, -e1, e2, -e2] {
                let p = (s.w * cos + e * sin).normalize();
                points.push(p);
                dirs.push(frame::unit_angles(p));
            }
        }
        let values = eval(&dirs);
        evaluations += dirs.len();
        for (k, &i) in active.iter().enumerate() {
            let best = (4 * k..4 * k + 4)
                .filter(|&j| values.get(j).is_some_and(|v| v.is_finite()))
                .max_by(|&a, &b| values[a].total_cmp(&values[b]));
            let s = &mut climbs[i];
            match best {
                Some(j) if values[j] > s.value => {
                    s.w = points[j];
                    s.at = dirs[j];
                    s.value = values[j];
                }
                _ => s.step_rad *= 0.5,
            }
        }
    }
    evaluations
}

/// The largest abs(a − m) near the largest samples of a set: `abs_diff[k]`
/// is abs(a − m) (cd) at `set.directions[k]`, `eval` gives abs(a − m) (cd)
/// at any batch of (C, γ) directions (degrees). Seeds: the largest samples,
/// at least the set's spacing sqrt(4π/N) apart; each climbs by pattern
/// search ([`MaxRefinement`]), starting at half the spacing. Returns the
/// largest value evaluated (the sampled maximum when nothing larger is
/// found, 0 for an empty set), where it is, and the cost. Non-finite
/// values are never taken.
pub fn refine_max(set: &DirectionSet, abs_diff: &[f64], eval: &EvalDirections<'_>, r: &MaxRefinement) -> RefinedMax {
    assert_eq!(abs_diff.len(), set.len());
    let mut order: Vec<usize> = (0..set.len())
        .filter(|&k| abs_diff[k].is_finite() && abs_diff[k] > 0.0)
        .collect();
    let by_value = |a: &usize, b: &usize| abs_diff[*b].total_cmp(&abs_diff[*a]);
    // The seeds come from the largest few hundred samples (a partial sort).
    let pool = (16 * r.seeds).max(1);
    if order.len() > pool {
        order.select_nth_unstable_by(pool - 1, by_value);
        order.truncate(pool);
    }
    order.sort_unstable_by(by_value);
    let Some(&first) = order.first() else {
        return RefinedMax {
            value: 0.0,
            at_deg: set.directions.first().copied().unwrap_or((0.0, 0.0)),
            seeds: 0,
            evaluations: 0,
        };
    };
    let spacing = (4.0 * std::f64::consts::PI / set.len() as f64).sqrt();
    let cos_sep = spacing.min(std::f64::consts::PI).cos();
    let mut climbs: Vec<Climb> = Vec::with_capacity(r.seeds);
    for &k in &order {
        if climbs.len() >= r.seeds {
            break;
        }
        let (c, g) = set.directions[k];
        let w = frame::direction(c, g);
        if climbs.iter().all(|s| s.w.dot(w) < cos_sep) {
            climbs.push(Climb {
                w,
                at: (c, g),
                value: abs_diff[k],
                step_rad: 0.5 * spacing,
            });
        }
    }
    let mut evaluations = climb(&mut climbs, eval, r.coarse_step_deg.to_radians(), r.max_rounds);
    climbs.sort_by(|a, b| b.value.total_cmp(&a.value));
    let finalists = r.finalists.min(climbs.len());
    evaluations += climb(
        &mut climbs[..finalists],
        eval,
        r.min_step_deg.to_radians(),
        r.max_rounds,
    );
    let best = climbs
        .iter()
        .filter(|s| s.value > abs_diff[first])
        .max_by(|a, b| a.value.total_cmp(&b.value));
    RefinedMax {
        value: best.map_or(abs_diff[first], |s| s.value),
        at_deg: best.map_or(set.directions[first], |s| s.at),
        seeds: climbs.len(),
        evaluations,
    }
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
        sampled_max_abs_cd: max_abs,
        sampled_max_pct: pct(max_abs),
        refined_seeds: 0,
    }
}

/// The radial errors of the field `approx` against the field `reference`
/// over `set` (`reference_values`: the reference's intensity at every
/// direction of `set`, cd, evaluated once for many approximations), the
/// maximum refined between the directions by `refinement` ([`refine_max`];
/// `None`: the maximum over the set only). Fields are evaluated in batches
/// ([`IntensityField::intensity_batch_cd`]); `i_max` (cd) and `zotti_c` as in [`radial_errors`].
pub fn field_radial_errors(
    set: &DirectionSet,
    reference_values: &[f64],
    reference: &dyn IntensityField,
    approx: &dyn IntensityField,
    i_max: f64,
    zotti_c: f64,
    refinement: Option<&MaxRefinement>,
) -> RadialErrors {
    let a = approx.intensity_batch_cd(&set.directions);
    let rad = radial_errors(set, reference_values, &a, i_max, zotti_c);
    let Some(r) = refinement else { return rad };
    let diffs: Vec<f64> = a.iter().zip(reference_values).map(|(a, m)| (a - m).abs()).collect();
    let eval = |dirs: &[(f64, f64)]| -> Vec<f64> {
        let (a, m) = rayon::join(
            || approx.intensity_batch_cd(dirs),
            || reference.intensity_batch_cd(dirs),
        );
        a.iter().zip(&m).map(|(a, m)| (a - m).abs()).collect()
    };
    let refined = refine_max(set, &diffs, &eval, r);
    rad.with_refined_max(&refined, i_max)
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

    /// The dense brute-force maximum of abs(a − m) over `n` Fibonacci directions, cd.
    fn dense_max(reference: &dyn IntensityField, approx: &dyn IntensityField, n: usize) -> f64 {
        let dense = DirectionSet::fibonacci(n);
        let (a, m) = (
            approx.intensity_batch_cd(&dense.directions),
            reference.intensity_batch_cd(&dense.directions),
        );
        a.iter().zip(&m).map(|(a, m)| (a - m).abs()).fold(0.0, f64::max)
    }

    /// Mitchell on the synthetic road luminaire (10° x 5° grid) against its
    /// closed form: the refined max over 20,000 directions is at least the
    /// sampled one and at least a brute-force maximum over 200,000 directions
    /// (to 0.5 %), is attained where it says, and no point of a 0.01° grid
    /// within 1° of it is larger (a local maximum). The brute force is itself
    /// a lower bound, not a check from above: here its largest sample (259.43
    /// cd at C 90.0, γ 67.4) lies on the slope of the peak the refinement finds
    /// (260.998 cd at C 90.0, γ 66.3), 0.6 % higher.
    #[test]
    fn refined_max_matches_a_dense_brute_force_max() {
        use crate::reconstruct::{Filter, LightTexture};
        use crate::synth::{GridSpec, Synth};
        let lum = Synth::Roadway
            .build(&GridSpec::uniform(10.0, 5.0).unwrap(), 9000.0)
            .unwrap();
        let truth = Synth::Roadway.truth(9000.0);
        let texture = LightTexture::new(lum.distribution()).unwrap();
        let field = Box::new(texture.sampler(Filter::Mitchell {
            b: 1.0 / 3.0,
            c: 1.0 / 3.0,
        }));
        let set = DirectionSet::fibonacci(20_000);
        let m = truth.intensity_batch_cd(&set.directions);
        let i_max = lum.distribution().max_cd();
        let sampled = field_radial_errors(&set, &m, &truth, &*field, i_max, ZOTTI_C, None);
        let refined = field_radial_errors(&set, &m, &truth, &*field, i_max, ZOTTI_C, Some(&MAX_REFINEMENT));
        let dense = dense_max(&truth, &*field, 200_000);
        eprintln!(
            "mitchell 10x5: sampled {:.5} %, refined {:.5} %, dense 200k {:.5} %",
            sampled.max_pct,
            refined.max_pct,
            100.0 * dense / i_max
        );
        assert_eq!(refined.sampled_max_abs_cd, sampled.max_abs_cd);
        assert_eq!(refined.refined_seeds, MAX_REFINEMENT.seeds);
        assert!(refined.max_abs_cd >= sampled.max_abs_cd);
        assert!(
            refined.max_abs_cd >= dense * (1.0 - 5e-3),
            "{} < {dense}",
            refined.max_abs_cd
        );
        let (c, g) = refined.max_at_deg;
        let at = (field.intensity_cd(c, g) - truth.intensity_cd(c, g)).abs();
        assert!(
            (at - refined.max_abs_cd).abs() <= 1e-9 * i_max,
            "{at} vs {}",
            refined.max_abs_cd
        );
        // A local maximum: nothing larger on a 0.01° grid within 1° of it.
        let w = frame::direction(c, g);
        let (e1, e2) = w.any_orthonormal_pair();
        let cap: Vec<(f64, f64)> = (-100..=100)
            .flat_map(|i| (-100..=100).map(move |j| (i, j)))
            .map(|(i, j)| {
                let (x, y) = ((0.01 * i as f64).to_radians(), (0.01 * j as f64).to_radians());
                frame::unit_angles((w + e1 * x + e2 * y).normalize())
            })
            .collect();
        let (a, t) = (field.intensity_batch_cd(&cap), truth.intensity_batch_cd(&cap));
        let local = a.iter().zip(&t).map(|(a, m)| (a - m).abs()).fold(0.0, f64::max);
        assert!(
            local <= refined.max_abs_cd * (1.0 + 1e-9),
            "{local} > {}",
            refined.max_abs_cd
        );
        // Integrals stay over the set.
        assert_eq!(refined.rms_cd, sampled.rms_cd);
        assert_eq!(refined.flux_error_pct, sampled.flux_error_pct);
        assert!(refined.max_pct.is_finite() && refined.sampled_max_pct.is_finite());
    }

    /// A narrow bump (half-width 0.5°) between the directions of a coarse
    /// set: the sampled max misses most of it, the refined max finds its
    /// top to within the final step; at a pole too, where C is undefined.
    #[test]
    fn refinement_finds_a_peak_between_the_directions() {
        for (pc, pg) in [(37.3, 61.7), (0.0, 0.0), (210.0, 179.9)] {
            let p = frame::direction(pc, pg);
            let bump = move |c: f64, g: f64| {
                let t = frame::direction(c, g).dot(p).clamp(-1.0, 1.0).acos().to_degrees();
                100.0 * (-(t / 0.5).powi(2)).exp()
            };
            let zero = |_: f64, _: f64| 0.0;
            let set = DirectionSet::fibonacci(2000);
            let m = vec![0.0; set.len()];
            let sampled = field_radial_errors(&set, &m, &zero, &bump, 100.0, ZOTTI_C, None);
            let refined = field_radial_errors(&set, &m, &zero, &bump, 100.0, ZOTTI_C, Some(&MAX_REFINEMENT));
            assert!(sampled.max_abs_cd < 90.0, "{pc} {pg}: sampled {}", sampled.max_abs_cd);
            assert!(refined.max_abs_cd > 99.99, "{pc} {pg}: refined {}", refined.max_abs_cd);
            assert!(refined.max_abs_cd <= 100.0);
            assert_eq!(refined.sampled_max_pct, sampled.max_pct);
        }
    }

    /// Nothing to refine: identical fields stay at zero, and non-finite
    /// values (a broken field) are never taken as the maximum.
    #[test]
    fn refinement_of_zero_and_non_finite_errors() {
        let set = DirectionSet::fibonacci(500);
        let f = |c: f64, g: f64| 10.0 + c.to_radians().cos() * g / 180.0;
        let m = f.intensity_batch_cd(&set.directions);
        let e = field_radial_errors(&set, &m, &f, &f, 11.0, ZOTTI_C, Some(&MAX_REFINEMENT));
        assert_eq!((e.max_abs_cd, e.max_pct, e.refined_seeds), (0.0, 0.0, 0));
        // All zero, I_max 0 included: zeros, no NaN.
        let zero = |_: f64, _: f64| 0.0;
        let z = field_radial_errors(
            &set,
            &vec![0.0; set.len()],
            &zero,
            &zero,
            0.0,
            ZOTTI_C,
            Some(&MAX_REFINEMENT),
        );
        assert_eq!((z.max_abs_cd, z.max_pct, z.sampled_max_pct), (0.0, 0.0, 0.0));
        assert!(z.rms_pct.is_finite() && z.zotti_err.is_finite());
        let nan_near = |c: f64, g: f64| {
            if (g - 90.0).abs() < 1.0 {
                f64::NAN
            } else {
                f(c, g) + 1.0
            }
        };
        let e = field_radial_errors(&set, &m, &f, &nan_near, 11.0, ZOTTI_C, Some(&MAX_REFINEMENT));
        assert!(e.max_abs_cd.is_finite() && e.max_pct.is_finite(), "{e:?}");
        assert!((e.max_abs_cd - 1.0).abs() < 1e-9, "{}", e.max_abs_cd);
    }

    /// A spot (1000 cos^20 γ inside a 25° cut-off, 0 outside: a step of 140
    /// cd, 14 % of I_max, along the cut-off circle) against the same without
    /// the cut-off and with a 1 % C ripple: the refined max is finite, never
    /// below the sampled one, bounded, and attained where it says.
    #[test]
    fn refinement_across_a_spot_cutoff() {
        let spot = |_: f64, g: f64| {
            if g <= 25.0 {
                1000.0 * g.to_radians().cos().powi(20)
            } else {
                0.0
            }
        };
        let smooth =
            |c: f64, g: f64| 1000.0 * g.to_radians().cos().max(0.0).powi(20) * (1.0 + 0.01 * c.to_radians().sin());
        for n in [500, 5000] {
            let set = DirectionSet::fibonacci(n);
            let m = spot.intensity_batch_cd(&set.directions);
            let e = field_radial_errors(&set, &m, &spot, &smooth, 1000.0, ZOTTI_C, Some(&MAX_REFINEMENT));
            assert!(e.max_abs_cd.is_finite() && e.max_pct.is_finite(), "{e:?}");
            assert!(e.max_abs_cd >= e.sampled_max_abs_cd && e.max_pct >= e.sampled_max_pct);
            assert!(e.max_abs_cd <= 1000.0 * 1.02);
            let (c, g) = e.max_at_deg;
            assert!(((smooth(c, g) - spot(c, g)).abs() - e.max_abs_cd).abs() <= 1e-9);
        }
    }
}
