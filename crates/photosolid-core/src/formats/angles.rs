//! The one angle-order rule of both readers: angles must ascend by more
//! than [`ANGLE_EPS`] (the model's own rule, see
//! [`Distribution`](crate::model::Distribution)); angles closer than that are
//! duplicates. With the repair option both readers sort and drop the
//! duplicates the same way, through [`repair_order`]; the TM-33 reader
//! collects its distinct angles with it too. One range rule,
//! [`first_outside`], for all three.

use crate::error::{Warning, WarningCode};
use crate::model::{Symmetry, ANGLE_EPS};

/// Index of the first angle that does not ascend by more than
/// [`ANGLE_EPS`] over its predecessor (≥ 1), or `None` when the list is in order.
pub fn first_disorder(angles: &[f64]) -> Option<usize> {
    angles.windows(2).position(|w| w[1] <= w[0] + ANGLE_EPS).map(|i| i + 1)
}

/// Index of the first angle outside `[0, hi]` degrees by more than [`ANGLE_EPS`]
/// (the readers then snap the rest onto the range's ends), or `None`.
pub fn first_outside(angles: &[f64], hi: f64) -> Option<usize> {
    angles.iter().position(|&a| !(-ANGLE_EPS..=hi + ANGLE_EPS).contains(&a))
}

/// The LM-63 Type C symmetry a horizontal angle set (ascending, degrees)
/// names by its ends: one angle rotational, 0..90 quadrant, 0..180 C0-C180,
/// 90..270 C90-C270 (ends within [`ANGLE_EPS`]); `None` for any other set,
/// which the caller reads as a full circle or refuses. One rule for the IES
/// reader and TM-33 documents without a symmetry code.
pub fn lm63_symmetry(horizontal: &[f64]) -> Option<Symmetry> {
    let near = |a: f64, b: f64| (a - b).abs() <= ANGLE_EPS;
    let (&first, &last) = (horizontal.first()?, horizontal.last()?);
    if horizontal.len() == 1 {
        Some(Symmetry::Rotational)
    } else if near(first, 0.0) && near(last, 90.0) {
        Some(Symmetry::Quadrant)
    } else if near(first, 0.0) && near(last, 180.0) {
        Some(Symmetry::C0C180)
    } else if near(first, 90.0) && near(last, 270.0) {
        Some(Symmetry::C90C270)
    } else {
        None
    }
}

/// Whether `b` following `a` is a duplicate (closer than [`ANGLE_EPS`]) rather than out of order.
pub fn is_duplicate(a: f64, b: f64) -> bool {
    (a - b).abs() <= ANGLE_EPS
}

/// The repaired order: indices of `angles` sorted ascending (stable), and
/// of each run of angles within [`ANGLE_EPS`] of the first kept one only that
/// first one. The values of a dropped angle are dropped with it.
pub fn repair_order(angles: &[f64]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..angles.len()).collect();
    order.sort_by(|&a, &b| angles[a].total_cmp(&angles[b]));
    order.dedup_by(|later, kept| is_duplicate(angles[*later], angles[*kept]));
    order
}

/// Planes of `stride` values each, taken in `order`.
pub fn reorder_planes(cd: &[f64], stride: usize, order: &[usize]) -> Vec<f64> {
    let mut out = Vec::with_capacity(order.len() * stride);
    for &i in order {
        out.extend_from_slice(&cd[i * stride..(i + 1) * stride]);
    }
    out
}

/// Inside every plane of `n` values, the values taken in `order`.
pub fn reorder_rows(cd: &[f64], n: usize, order: &[usize]) -> Vec<f64> {
    let planes = cd.len().checked_div(n).unwrap_or(0);
    let mut out = Vec::with_capacity(planes * order.len());
    for p in 0..planes {
        out.extend(order.iter().map(|&i| cd[p * n + i]));
    }
    out
}

/// Drop the last C plane, C = 360 (it is C = 0; `cd` plane-major, `nv` values a
/// plane): kept as C = 0 when there is none, else compared with it (a warning
/// when they differ). One rule for every reader (IES, TM-33).
pub fn drop_360_plane(hs: &mut Vec<f64>, cd: &mut Vec<f64>, nv: usize, warnings: &mut Vec<Warning>) {
    let last = cd.split_off(cd.len() - nv);
    hs.pop();
    if hs[0].abs() <= ANGLE_EPS {
        let diff = last
            .iter()
            .zip(&cd[..nv])
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        let peak = cd.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        if diff > 1e-9 * peak.max(f64::MIN_POSITIVE) {
            warnings.push(Warning::new(
                WarningCode::SeamMismatch,
                format!(
                    "the 360-degree plane differs from the 0-degree plane by up to {} cd; the 0-degree plane is kept",
                    crate::numfmt::significant(diff, 6)
                ),
            ));
        }
    } else {
        hs.insert(0, 0.0);
        let mut v = last;
        v.extend_from_slice(cd);
        *cd = v;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn order_rule_and_repair() {
        assert_eq!(first_disorder(&[0.0, 10.0, 20.0]), None);
        assert_eq!(first_disorder(&[0.0, 10.0, 10.0 + 1e-9]), Some(2));
        assert_eq!(first_disorder(&[0.0, 10.0, 5.0]), Some(2));
        let a = [10.0, 0.0, 10.0 + 1e-9, 5.0];
        let order = repair_order(&a);
        assert_eq!(order, vec![1, 3, 0]);
        let cd = [1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0];
        assert_eq!(reorder_planes(&cd, 2, &order), vec![3.0, 4.0, 7.0, 8.0, 1.0, 2.0]);
        assert_eq!(reorder_rows(&cd, 4, &order), vec![2.0, 4.0, 1.0, 6.0, 8.0, 5.0]);
    }

    #[test]
    fn range_and_symmetry_rules() {
        assert_eq!(first_outside(&[-1e-7, 90.0, 180.0 + 1e-7], 180.0), None);
        assert_eq!(first_outside(&[0.0, 180.01], 180.0), Some(1));
        assert_eq!(first_outside(&[-0.01], 360.0), Some(0));
        assert_eq!(lm63_symmetry(&[45.0]), Some(Symmetry::Rotational));
        assert_eq!(lm63_symmetry(&[0.0, 45.0, 90.0 + 1e-7]), Some(Symmetry::Quadrant));
        assert_eq!(lm63_symmetry(&[0.0, 180.0]), Some(Symmetry::C0C180));
        assert_eq!(lm63_symmetry(&[90.0, 180.0, 270.0]), Some(Symmetry::C90C270));
        assert_eq!(lm63_symmetry(&[0.0, 90.0, 180.0, 270.0]), None);
        assert_eq!(lm63_symmetry(&[]), None);
    }
}
