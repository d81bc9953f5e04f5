//! The `withheld` reference of a Type A or B file: the hold-out withholds
//! the goniometer's own readings, not points of the Type C grid the reader
//! converted them to.
//!
//! A Type B floodlight's 45 × 45 readings become a 1° Type C grid of 65,160
//! values, each a bilinear interpolation of four readings. Withholding
//! points of that grid measures a reconstruction against interpolated
//! values (and 128,000 of them: 8-21 s a `compare`). Here each fold drops
//! every k-th horizontal (or vertical) angle of the file, converts the
//! remaining readings to Type C on the full grid's target exactly as the
//! reader does ([`to_type_c_at`]), and measures every reconstruction at the
//! dropped readings' directions against the values the file measured there.
//! The axis ends are always kept (withholding them would test
//! extrapolation), as [`crate::reconstruct::kfold`] keeps a Type C grid's.
//!
//! Only when the file's readings rebuild the compared distribution bit for
//! bit (the conversion is deterministic) are they used; a distribution
//! changed after reading falls back to the Type C hold-out, and the
//! comparison's reference text says which was used.

use glam::DVec3;

use super::withheld::FoldPoints;
use super::SourceMeasurements;
use crate::error::ModelError;
use crate::formats::ies::type_ab::{direction as source_direction, laterally_symmetric, target_step, to_type_c_at};
use crate::formats::Handedness;
use crate::metrics::DirectionSet;
use crate::model::frame::unit_angles;
use crate::model::{Distribution, PhotometricType, SourceGrid};
use crate::reconstruct::Fold;

/// The folds of a hold-out and the withheld points of each.
pub(super) type Folds = (Vec<Fold>, Vec<FoldPoints>);

/// The k-fold hold-out of `src`'s readings (k ≥ 2): for each axis with at
/// least 3 angles and each f < k, a fold keeping the angles whose index is
/// f modulo k and both ends. `scale` is what the file's values were
/// multiplied by to give `a` (the normalisation): the kept data and the
/// readings are scaled alike. `None` when `src` is not a Type A/B grid,
/// does not rebuild `a` bit for bit, or nothing can be withheld.
///
/// # Errors
/// The conversion's, for a kept grid that does not convert.
pub(super) fn source_folds(
    a: &Distribution,
    scale: f64,
    src: &SourceMeasurements,
    k: usize,
) -> Result<Option<Folds>, ModelError> {
    let g = &src.grid;
    let (nh, nv) = (g.horizontal.len(), g.vertical.len());
    if g.kind == PhotometricType::C || k < 2 || nh == 0 || nv == 0 || g.cd.len() != nh * nv {
        return Ok(None);
    }
    let step = target_step(g);
    let rebuilt = to_type_c_at(g, src.handedness, step).and_then(|d| d.scaled(scale));
    if rebuilt.ok().as_ref() != Some(a) {
        return Ok(None);
    }
    let mut folds = Vec::new();
    let mut points = Vec::new();
    for (axis, n) in [("horizontal", nh), ("vertical", nv)] {
        if n < 3 {
            continue;
        }
        for f in 0..k {
            let keep: Vec<bool> = (0..n).map(|i| i == 0 || i == n - 1 || i % k == f).collect();
            if keep.iter().all(|&x| x) {
                continue;
            }
            let (kept_grid, withheld) = split(g, axis == "horizontal", &keep);
            let kept = to_type_c_at(&kept_grid, src.handedness, step)?.scaled(scale)?;
            let mut p = reading_points(g, &withheld, src.handedness, axis);
            p.measured_cd.iter_mut().for_each(|v| *v *= scale);
            points.push(p);
            folds.push(Fold { axis, kept, withheld });
        }
    }
    Ok((!folds.is_empty()).then_some((folds, points)))
}

/// The grid with only the kept angles of one axis (`horizontal`, else the
/// vertical one), and the withheld readings as (horizontal, vertical) indices.
fn split(g: &SourceGrid, horizontal: bool, keep: &[bool]) -> (SourceGrid, Vec<(usize, usize)>) {
    let nv = g.vertical.len();
    let kept_of = |angles: &[f64], on_axis: bool| -> Vec<f64> {
        angles
            .iter()
            .zip(keep)
            .filter(|&(_, &k)| k || !on_axis)
            .map(|(&x, _)| x)
            .collect()
    };
    let (hs, vs) = if horizontal {
        (kept_of(&g.horizontal, true), g.vertical.clone())
    } else {
        (g.horizontal.clone(), kept_of(&g.vertical, true))
    };
    let mut cd = Vec::with_capacity(hs.len() * vs.len());
    let mut withheld = Vec::new();
    for ih in 0..g.horizontal.len() {
        for iv in 0..nv {
            let kept = if horizontal { keep[ih] } else { keep[iv] };
            if kept {
                cd.push(g.cd[ih * nv + iv]);
            } else {
                withheld.push((ih, iv));
            }
        }
    }
    // Dropping a whole vertical angle keeps every plane's other readings in order.
    let grid = SourceGrid {
        kind: g.kind,
        vertical: vs,
        horizontal: hs,
        cd,
    };
    (grid, withheld)
}

/// The withheld readings as points: each reading's direction (and, for a
/// laterally symmetric grid, 0 ≤ H, its mirror image at −H), its measured
/// value and its solid angle on the goniometer's grid (half-way to the
/// neighbouring angles, clamped at the ends). Readings at the frame's pole
/// are left out.
fn reading_points(g: &SourceGrid, withheld: &[(usize, usize)], handedness: Handedness, axis: &str) -> FoldPoints {
    let nv = g.vertical.len();
    let mirror = laterally_symmetric(g);
    let flip = handedness == Handedness::Clockwise;
    let mut set = DirectionSet {
        label: format!("withheld {axis} angles of the Type {:?} grid", g.kind),
        directions: Vec::with_capacity(2 * withheld.len()),
        weights: Vec::with_capacity(2 * withheld.len()),
    };
    let mut measured_cd = Vec::with_capacity(2 * withheld.len());
    let mut stored = Vec::with_capacity(2 * withheld.len());
    for &(ih, iv) in withheld {
        let (h, v) = (g.horizontal[ih], g.vertical[iv]);
        // A reading at the frame's pole (Type B: H = ±90; Type A: V = ±90) shares its
        // direction with the kept readings at the other angles: nothing is withheld there
        // (as `kfold` withholds no pole row).
        let pole = match g.kind {
            PhotometricType::A => v,
            _ => h,
        };
        if pole.abs() >= 90.0 - 1e-9 {
            continue;
        }
        let weight = cell_solid_angle(g, ih, iv, mirror);
        let images: &[f64] = if mirror && h > 1e-9 { &[1.0, -1.0] } else { &[1.0] };
        for &sign in images {
            let [x, y, z] = source_direction(g.kind, sign * h, v);
            let d = DVec3::new(x, if flip { -y } else { y }, z);
            set.directions.push(unit_angles(d.normalize()));
            set.weights.push(weight);
            measured_cd.push(g.cd[ih * nv + iv]);
            stored.push((ih, iv));
        }
    }
    FoldPoints {
        set,
        measured_cd,
        stored,
    }
}

/// The solid angle (sr) of reading (ih, iv)'s cell: half-way to the
/// neighbouring angles on each axis, clamped at the grid's ends (at H = 0 of
/// a laterally symmetric grid, the cell reaches as far below 0 as above).
/// Type B: dΩ = cos H dH dV; Type A: dΩ = cos V dV dH.
fn cell_solid_angle(g: &SourceGrid, ih: usize, iv: usize, mirror: bool) -> f64 {
    let span = |a: &[f64], i: usize| -> (f64, f64) {
        let lo = if i == 0 { a[0] } else { 0.5 * (a[i - 1] + a[i]) };
        let hi = if i + 1 == a.len() {
            a[i]
        } else {
            0.5 * (a[i] + a[i + 1])
        };
        (lo, hi)
    };
    let (mut h_lo, h_hi) = span(&g.horizontal, ih);
    if mirror && ih == 0 {
        h_lo = -h_hi;
    }
    let (v_lo, v_hi) = span(&g.vertical, iv);
    let (h_lo, h_hi, v_lo, v_hi) = (
        h_lo.to_radians(),
        h_hi.to_radians(),
        v_lo.to_radians(),
        v_hi.to_radians(),
    );
    match g.kind {
        PhotometricType::A => (v_hi.sin() - v_lo.sin()).abs() * (h_hi - h_lo).abs(),
        _ => (h_hi.sin() - h_lo.sin()).abs() * (v_hi - v_lo).abs(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The readings' cells tile the grid's range: their solid angles add up
    /// to the closed form of the range (Type B: (sin H1 − sin H0)(V1 − V0);
    /// Type A: (sin V1 − sin V0)(H1 − H0); a laterally symmetric grid counts
    /// its mirror half, which the images cover, once per image).
    #[test]
    fn cells_tile_the_measured_range() {
        let irregular = vec![-90.0, -60.0, -25.0, -5.0, 0.0, 5.0, 25.0, 60.0, 90.0];
        let vertical = vec![-90.0, -45.0, -10.0, 0.0, 10.0, 45.0, 90.0];
        for kind in [PhotometricType::A, PhotometricType::B] {
            let g = SourceGrid {
                kind,
                vertical: vertical.clone(),
                horizontal: irregular.clone(),
                cd: vec![1.0; irregular.len() * vertical.len()],
            };
            let total: f64 = (0..irregular.len())
                .flat_map(|ih| (0..vertical.len()).map(move |iv| (ih, iv)))
                .map(|(ih, iv)| cell_solid_angle(&g, ih, iv, false))
                .sum();
            // Both axes span -90..90: (sin 90° − sin −90°) · π for either type.
            let want = 2.0 * std::f64::consts::PI;
            assert!((total - want).abs() < 1e-12, "{kind:?}: {total} vs {want}");
            // Laterally symmetric: H 0..90; each H > 0 reading has two images.
            let half = SourceGrid {
                horizontal: irregular[4..].to_vec(),
                cd: vec![1.0; 5 * vertical.len()],
                ..g.clone()
            };
            let pts = reading_points(
                &half,
                &(0..5)
                    .flat_map(|ih| (0..vertical.len()).map(move |iv| (ih, iv)))
                    .collect::<Vec<_>>(),
                Handedness::CounterClockwise,
                "horizontal",
            );
            // Readings at the frame's pole are left out: add their cells (and images) back.
            let poles: f64 = (0..5)
                .flat_map(|ih| (0..vertical.len()).map(move |iv| (ih, iv)))
                .filter(|&(ih, iv)| match kind {
                    PhotometricType::A => vertical[iv].abs() >= 90.0,
                    _ => half.horizontal[ih].abs() >= 90.0,
                })
                .map(|(ih, iv)| cell_solid_angle(&half, ih, iv, true) * if ih == 0 { 1.0 } else { 2.0 })
                .sum();
            let total: f64 = pts.set.weights.iter().sum::<f64>() + poles;
            assert!((total - want).abs() < 1e-12, "{kind:?} mirrored: {total} vs {want}");
            let (n_h, n_v) = match kind {
                PhotometricType::A => (1 + 2 * 4, vertical.len() - 2),
                _ => (1 + 2 * 3, vertical.len()),
            };
            assert_eq!(pts.set.len(), n_h * n_v, "{kind:?}");
        }
    }

    /// Each point is its reading's direction, clockwise handedness mirrors
    /// it, and its value is the reading.
    #[test]
    fn points_are_the_readings_directions() {
        let g = SourceGrid {
            kind: PhotometricType::B,
            vertical: vec![-30.0, 0.0, 40.0],
            horizontal: vec![-20.0, 0.0, 35.0],
            cd: (0..9).map(f64::from).collect(),
        };
        for handedness in [Handedness::CounterClockwise, Handedness::Clockwise] {
            let p = reading_points(&g, &[(2, 2)], handedness, "vertical");
            assert_eq!(p.measured_cd, vec![8.0]);
            let [x, y, z] = source_direction(PhotometricType::B, 35.0, 40.0);
            let y = if handedness == Handedness::Clockwise { -y } else { y };
            let (c, gamma) = p.set.directions[0];
            let d = crate::model::frame::direction(c, gamma);
            assert!((d - DVec3::new(x, y, z)).length() < 1e-12, "{handedness:?}: {d}");
        }
    }
}
