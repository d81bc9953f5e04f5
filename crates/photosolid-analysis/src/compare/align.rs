//! The best C rotation and mirror of one distribution onto another.
//!
//! Two files of one luminaire often differ by a turn of the C0 axis (a lab
//! that mounted it 90° turned) or a mirror (C counted clockwise). For every
//! rotation r in [0, 360) in steps of the file's C grid, with and without a
//! mirror, the moved distribution `a'(C) = a(mirror ? r − C : C − r)` (the
//! convention of [`Distribution::reoriented`]) is compared with `b` by the
//! solid-angle-weighted RMS radial difference (bilinear fields) over a
//! Fibonacci direction set; the smallest wins (ties: no mirror, smallest r).

use rayon::prelude::*;
use serde::Serialize;

use crate::error::ModelError;
use crate::metrics::DirectionSet;
use crate::model::{wrap360, Distribution, Symmetry};
use crate::reconstruct::{Filter, LightTexture};

/// The alignment found.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Alignment {
    /// Rotation applied to FILE's C angles, degrees.
    pub rotate_deg: f64,
    /// Whether FILE's C angles were mirrored (C → −C) before the rotation.
    pub mirror: bool,
    /// Rotation step searched, degrees.
    pub step_deg: f64,
    /// Candidates tried (rotations × mirror).
    pub candidates: usize,
    /// RMS radial difference after alignment, % of OTHER's I_max.
    pub rms_pct: f64,
    /// RMS radial difference without alignment, % of OTHER's I_max.
    pub rms_pct_unaligned: f64,
}

/// The C step of a distribution's full-circle planes (smallest gap, at least 0.5°; 360 for rotational data).
pub fn c_step(d: &Distribution) -> f64 {
    if d.symmetry() == Symmetry::Rotational {
        return 360.0;
    }
    let c: Vec<f64> = d.full_planes().iter().map(|p| p.0).collect();
    let mut step = 360.0f64;
    for (i, &x) in c.iter().enumerate() {
        let next = if i + 1 == c.len() { c[0] + 360.0 } else { c[i + 1] };
        if next - x > 1e-6 {
            step = step.min(next - x);
        }
    }
    step.max(0.5)
}

/// The best rotation and mirror of `a` onto `b` (see the module docs), over `n_dirs` directions.
pub fn best_alignment(a: &Distribution, b: &Distribution, n_dirs: usize) -> Result<Alignment, ModelError> {
    let set = DirectionSet::fibonacci(n_dirs.max(100));
    let (ta, tb) = (LightTexture::new(a)?, LightTexture::new(b)?);
    let (sa, sb) = (ta.sampler(Filter::Bilinear), tb.sampler(Filter::Bilinear));
    let m: Vec<f64> = set.directions.iter().map(|&(c, g)| sb.cd(c, g)).collect();
    let i_max = b.max_cd().max(f64::MIN_POSITIVE);
    let wsum: f64 = set.weights.iter().sum();
    let rms = |rot: f64, mirror: bool| -> f64 {
        let s2: f64 = set
            .directions
            .iter()
            .zip(&m)
            .zip(&set.weights)
            .map(|((&(c, g), &mv), &w)| {
                let c0 = wrap360(if mirror { rot - c } else { c - rot });
                w * (sa.cd(c0, g) - mv).powi(2)
            })
            .sum();
        100.0 * (s2 / wsum).sqrt() / i_max
    };
    let step = c_step(a).min(c_step(b));
    let n_rot = if a.symmetry() == Symmetry::Rotational {
        1
    } else {
        ((360.0 / step).round() as usize).max(1)
    };
    let step = 360.0 / n_rot as f64;
    let cands: Vec<(f64, bool)> = [false, true]
        .iter()
        .flat_map(|&mi| (0..n_rot).map(move |k| (k as f64 * step, mi)))
        .collect();
    let scores: Vec<f64> = cands.par_iter().map(|&(r, mi)| rms(r, mi)).collect();
    let mut best = 0;
    for (k, s) in scores.iter().enumerate() {
        if *s < scores[best] - 1e-9 * scores[best].abs().max(1e-12) {
            best = k;
        }
    }
    Ok(Alignment {
        rotate_deg: cands[best].0,
        mirror: cands[best].1,
        step_deg: step,
        candidates: cands.len(),
        rms_pct: scores[best],
        rms_pct_unaligned: scores[0],
    })
}
