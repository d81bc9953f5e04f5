//! Type A and Type B grids → Type C, through direction vectors.
//!
//! # Frame (docs/domain.md §1.5)
//! Right-handed, z up: x = C0 = H0 horizontal, y = C90, nadir = −z. With
//! counter-clockwise handedness (the default) a positive H points towards +y:
//! - Type B (planes share the y axis; V = plane angle about y, H = angle out of the plane):
//!   `d = (cos H sin V, sin H, −cos H cos V)`;
//! - Type A (V = elevation, H = azimuth about z): `d = (cos V cos H, cos V sin H, sin V)`.
//!
//! Clockwise handedness flips the sign of d_y (of H).
//!
//! # Resampling
//! For each target (C, γ): d, then the source (H, V) (every equivalent
//! parametrisation of d is tried: (H, V), (180 − H, V + 180), (−180 − H, V + 180),
//! each modulo 360, and −H when the grid is laterally symmetric), then
//! bilinear interpolation in the source grid; 0 outside it.
//!
//! # Target grid and symmetry
//! - Step: the smallest spacing between consecutive source angles (both axes),
//!   rounded down to one of 0.5, 1, 1.5, 2, 2.5, 3, 4.5, 5 degrees (divisors of
//!   90, so C0/C90/C180 and γ 90 are grid lines), clamped to [0.5, 5].
//! - γ covers 0..180 with that step.
//! - Laterally symmetric sources (H only ≥ 0, starting at 0: I(H) = I(−H))
//!   mirror d_y, i.e. C ↔ −C: the target is C0-C180, planes 0..180.
//!   Otherwise the target has no symmetry: planes 0..360 − step.

use rayon::prelude::*;

use crate::formats::Handedness;
use crate::model::{Distribution, PhotometricType, SourceGrid, Symmetry};

/// Target grid step (degrees) from the source spacing. See the module docs.
pub fn target_step(grid: &SourceGrid) -> f64 {
    let min_gap = |a: &[f64]| {
        a.windows(2)
            .map(|w| w[1] - w[0])
            .filter(|g| *g > 1e-9)
            .fold(f64::INFINITY, f64::min)
    };
    let g = min_gap(&grid.vertical).min(min_gap(&grid.horizontal));
    const STEPS: [f64; 8] = [0.5, 1.0, 1.5, 2.0, 2.5, 3.0, 4.5, 5.0];
    if !g.is_finite() {
        return 5.0;
    }
    STEPS.iter().rev().copied().find(|&s| s <= g + 1e-9).unwrap_or(0.5)
}

/// Direction of source angles (H, V) (degrees) with counter-clockwise handedness.
pub fn direction(kind: PhotometricType, h: f64, v: f64) -> [f64; 3] {
    let (sh, ch) = h.to_radians().sin_cos();
    let (sv, cv) = v.to_radians().sin_cos();
    match kind {
        PhotometricType::B => [ch * sv, sh, -ch * cv],
        _ => [cv * ch, cv * sh, sv],
    }
}

/// Canonical source angles (H, V) (degrees) of a unit direction, counter-clockwise handedness.
fn angles_of(kind: PhotometricType, d: [f64; 3]) -> (f64, f64) {
    match kind {
        PhotometricType::B => {
            // H in [−90, 90], V in (−180, 180].
            let h = d[1].clamp(-1.0, 1.0).asin().to_degrees();
            let v = d[0].atan2(-d[2]).to_degrees();
            (h, v)
        }
        _ => {
            let v = d[2].clamp(-1.0, 1.0).asin().to_degrees();
            let h = d[1].atan2(d[0]).to_degrees();
            (h, v)
        }
    }
}

/// Bracket `x` in ascending `a`: (index, fraction), tolerant at the ends.
fn bracket(a: &[f64], x: f64) -> Option<(usize, f64)> {
    const EPS: f64 = 1e-7;
    let n = a.len();
    if x < a[0] - EPS || x > a[n - 1] + EPS {
        return None;
    }
    if n == 1 {
        return Some((0, 0.0));
    }
    let x = x.clamp(a[0], a[n - 1]);
    let i = a.partition_point(|&y| y <= x).clamp(1, n - 1) - 1;
    let t = (x - a[i]) / (a[i + 1] - a[i]);
    Some((i, t.clamp(0.0, 1.0)))
}

/// `x` shifted by a multiple of 360 into [lo, hi] (tolerance 1e-7), if possible.
fn into_range(x: f64, lo: f64, hi: f64) -> Option<f64> {
    for k in [0.0, -360.0, 360.0, -720.0, 720.0] {
        let y = x + k;
        if y >= lo - 1e-7 && y <= hi + 1e-7 {
            return Some(y);
        }
    }
    None
}

/// Value of the source grid at (H, V), 0 outside; every equivalent parametrisation is tried.
fn sample(grid: &SourceGrid, mirror: bool, h: f64, v: f64) -> f64 {
    let (hs, vs) = (&grid.horizontal, &grid.vertical);
    let nv = vs.len();
    // The same direction under (H, V) → (180 − H, V + 180) holds for A and B alike
    // (A: (H + 180, 180 − V), which is the same set after the 360 shifts below
    // with roles swapped; both are listed).
    let cands: [(f64, f64); 4] = match grid.kind {
        PhotometricType::B => [(h, v), (180.0 - h, v + 180.0), (-180.0 - h, v + 180.0), (h, v)],
        _ => [(h, v), (h + 180.0, 180.0 - v), (h - 180.0, 180.0 - v), (h, v)],
    };
    for &(ch, cv) in &cands[..3] {
        for hh in [ch, -ch] {
            if hh != ch && !mirror {
                continue;
            }
            let (Some(hx), Some(vx)) = (
                into_range(hh, hs[0], hs[hs.len() - 1]),
                into_range(cv, vs[0], vs[nv - 1]),
            ) else {
                continue;
            };
            let (Some((ih, th)), Some((iv, tv))) = (bracket(hs, hx), bracket(vs, vx)) else {
                continue;
            };
            let at = |ih: usize, iv: usize| grid.cd[ih * nv + iv];
            let ih1 = (ih + 1).min(hs.len() - 1);
            let iv1 = (iv + 1).min(nv - 1);
            let a = at(ih, iv) * (1.0 - tv) + at(ih, iv1) * tv;
            let b = at(ih1, iv) * (1.0 - tv) + at(ih1, iv1) * tv;
            return a * (1.0 - th) + b * th;
        }
    }
    0.0
}

/// Convert a Type A/B grid to a Type C distribution (see the module docs).
///
/// Fails (with a message) when the horizontal angles start above 0: then
/// neither the lateral-symmetry layout (0 … 90) nor a full one (−90 … 90) applies.
pub fn to_type_c(grid: &SourceGrid, handedness: Handedness) -> Result<Distribution, String> {
    let hs = &grid.horizontal;
    let h0 = hs[0];
    if h0 > 1e-9 {
        return Err(format!(
            "horizontal angles start at {}: Type {:?} data starts at 0 (laterally symmetric) or below 0",
            crate::error::Num(h0),
            grid.kind
        ));
    }
    let mirror = h0.abs() <= 1e-9;
    let step = target_step(grid);
    let n_gamma = (180.0 / step).round() as usize + 1;
    let gamma: Vec<f64> = (0..n_gamma).map(|i| (i as f64 * step).min(180.0)).collect();
    let (symmetry, n_c) = if mirror {
        (Symmetry::C0C180, (180.0 / step).round() as usize + 1)
    } else {
        (Symmetry::None, (360.0 / step).round() as usize)
    };
    let c: Vec<f64> = (0..n_c).map(|i| (i as f64 * step).min(360.0)).collect();
    let flip = handedness == Handedness::Clockwise;
    // Each target plane is independent: planes in parallel (a 1° target grid
    // is 65 k directions, each an asin, an atan2 and a bilinear lookup).
    let trig_gamma: Vec<(f64, f64)> = gamma.iter().map(|g| g.to_radians().sin_cos()).collect();
    let mut cd = vec![0.0; n_c * n_gamma];
    cd.par_chunks_mut(n_gamma).zip(c.par_iter()).for_each(|(plane, &cc)| {
        let (sc, ccos) = cc.to_radians().sin_cos();
        for (out, &(sg, cg)) in plane.iter_mut().zip(&trig_gamma) {
            let mut d = [sg * ccos, sg * sc, -cg];
            if flip {
                d[1] = -d[1];
            }
            let (h, v) = angles_of(grid.kind, d);
            *out = sample(grid, mirror, h, v);
        }
    });
    Distribution::new(c, gamma, cd, symmetry).map_err(|e| e.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn direction_round_trips_through_angles() {
        for kind in [PhotometricType::A, PhotometricType::B] {
            for &(h, v) in &[(10.0, 20.0), (-35.0, 60.0), (80.0, -45.0), (0.0, 0.0)] {
                let d = direction(kind, h, v);
                let (h2, v2) = angles_of(kind, d);
                assert!(
                    (h - h2).abs() < 1e-9 && (v - v2).abs() < 1e-9,
                    "{kind:?} {h} {v} -> {h2} {v2}"
                );
            }
        }
    }

    #[test]
    fn type_b_nadir_is_h0_v0() {
        let d = direction(PhotometricType::B, 0.0, 0.0);
        assert!((d[2] + 1.0).abs() < 1e-12);
        let d = direction(PhotometricType::A, 0.0, -90.0);
        assert!((d[2] + 1.0).abs() < 1e-12);
    }

    #[test]
    fn step_is_a_divisor_of_90() {
        let g = SourceGrid {
            kind: PhotometricType::B,
            vertical: vec![-90.0, -87.5, 0.0, 90.0],
            horizontal: vec![0.0, 10.0],
            cd: vec![0.0; 8],
        };
        assert_eq!(target_step(&g), 2.5);
    }
}
