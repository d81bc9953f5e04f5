//! The IES grid checks: angle order (with the repair option), the Type C
//! layouts and their symmetry, warnings about the values.

use crate::error::{Num, ParseError, Warning, WarningCode};
use crate::formats::scan::Scanner;
use crate::formats::text::Source;
use crate::formats::{angles, ReadOptions};
use crate::model::{Distribution, Symmetry, ANGLE_EPS};

/// Check that `angles` ascend strictly; with `opts.repair` sort them (stable, so
/// the first of duplicates is kept) and reorder the values with them.
/// `start` marks the list's first value in the stream.
/// `planes`: the angles index planes of `stride` values (horizontal), or rows
/// inside each of `stride` planes (vertical).
#[allow(clippy::too_many_arguments)]
pub(super) fn check_or_repair(
    src: &Source<'_>,
    start: &Scanner<'_>,
    what: &str,
    angles: &mut Vec<f64>,
    stride: usize,
    cd: &mut Vec<f64>,
    planes: bool,
    opts: &ReadOptions,
    warnings: &mut Vec<Warning>,
) -> Result<(), ParseError> {
    let Some(bad) = angles::first_disorder(angles) else {
        return Ok(());
    };
    if !opts.repair {
        let (loc, found) = start.nth(bad);
        let why = if angles::is_duplicate(angles[bad], angles[bad - 1]) {
            "duplicate"
        } else {
            "unsorted"
        };
        return Err(src.invalid(
            loc,
            format!(
                "{what} angles in strictly ascending order (angle #{} = {} follows {}: {why}; \
                 the repair option sorts them)",
                bad + 1,
                Num(angles[bad]),
                Num(angles[bad - 1])
            ),
            found,
        ));
    }
    let n = angles.len();
    let order = angles::repair_order(angles);
    let dropped = n - order.len();
    let new_angles: Vec<f64> = order.iter().map(|&i| angles[i]).collect();
    // Planes of `stride` (vertical count) values each, or rows inside each of `stride` planes of `n` values.
    let new_cd = if planes {
        angles::reorder_planes(cd, stride, &order)
    } else {
        angles::reorder_rows(cd, n, &order)
    };
    warnings.push(Warning::at(
        start.next_line(),
        WarningCode::AnglesRepaired,
        format!("{what} angles were not strictly ascending: sorted, {dropped} duplicate(s) dropped (first kept)"),
    ));
    *angles = new_angles;
    *cd = new_cd;
    Ok(())
}

/// Type C grid → distribution: symmetry from the horizontal angle set (LM-63; docs/domain.md §1.4).
///
/// | H set | symmetry |
/// |---|---|
/// | one angle (0, or anywhere: warned) | rotational |
/// | 0 … 90 | quadrant |
/// | 0 … 180 | C0-C180 |
/// | 90 … 270 with a plane strictly between | C90-C270 |
/// | last angle in (180, 360], first ≥ 0 | none (a 360 plane is checked against 0 and dropped) |
///
/// Anything else (0 … 45, 90 … 180, negative angles) matches no LM-63 layout
/// and is refused rather than guessed. `{90, 270}` alone is refused too: both
/// planes lie on the C90-C270 mirror, so the half circle the 90–270 layout
/// describes (centred on C180) is not measured at all.
pub(super) fn type_c(
    src: &Source<'_>,
    v_start: &Scanner<'_>,
    h_start: &Scanner<'_>,
    vertical: Vec<f64>,
    mut horizontal: Vec<f64>,
    mut cd: Vec<f64>,
    warnings: &mut Vec<Warning>,
) -> Result<Distribution, ParseError> {
    let nv = vertical.len();
    let nh = horizontal.len();
    let near = |a: f64, b: f64| (a - b).abs() <= ANGLE_EPS;
    if let Some(i) = angles::first_outside(&vertical, 180.0) {
        let (loc, found) = v_start.nth(i);
        return Err(src.invalid(
            loc,
            "Type C vertical angles within 0..180 degrees (negative angles suggest Type A/B data marked as C)",
            found,
        ));
    }
    if let Some(i) = angles::first_outside(&horizontal, 360.0) {
        let (loc, found) = h_start.nth(i);
        return Err(src.invalid(loc, "Type C horizontal angles within 0..360 degrees", found));
    }
    // Snap angles within tolerance onto the range ends the model checks exactly.
    let vertical: Vec<f64> = vertical.iter().map(|&v| v.clamp(0.0, 180.0)).collect();
    for h in &mut horizontal {
        *h = h.clamp(0.0, 360.0);
    }
    let first = horizontal[0];
    let symmetry = match angles::lm63_symmetry(&horizontal) {
        Some(Symmetry::Rotational) => {
            if !near(first, 0.0) {
                warnings.push(Warning::new(
                    WarningCode::SinglePlane,
                    format!(
                        "a single horizontal angle at {} degrees: read as rotationally symmetric",
                        Num(first)
                    ),
                ));
            }
            horizontal[0] = 0.0;
            Symmetry::Rotational
        }
        Some(Symmetry::C90C270) if nh == 2 => {
            let (loc, found) = h_start.nth(0);
            return Err(src.invalid(
                loc,
                "a 90-270 horizontal angle set with planes between 90 and 270 (C90-C270 symmetry \
                 describes the half circle around C180; 90 and 270 alone lie on its mirror plane)",
                format!("{found} and `270` only"),
            ));
        }
        Some(s) => s,
        None => full_circle(src, h_start, &mut horizontal, &mut cd, nv, warnings)?,
    };
    Distribution::new(horizontal, vertical, cd, symmetry).map_err(|e| {
        let (loc, _) = h_start.nth(0);
        src.invalid(loc, "a valid Type C grid", e.to_string())
    })
}

/// A horizontal set that names no symmetry: a full circle when its last
/// angle is past 180 (a 360 plane is checked against 0 and dropped); anything
/// else (0 … 45, 90 … 180, negative angles) matches no LM-63 layout.
fn full_circle(
    src: &Source<'_>,
    h_start: &Scanner<'_>,
    horizontal: &mut Vec<f64>,
    cd: &mut Vec<f64>,
    nv: usize,
    warnings: &mut Vec<Warning>,
) -> Result<Symmetry, ParseError> {
    let (first, last, nh) = (horizontal[0], horizontal[horizontal.len() - 1], horizontal.len());
    if last > 180.0 + ANGLE_EPS {
        if (last - 360.0).abs() <= ANGLE_EPS {
            angles::drop_360_plane(horizontal, cd, nv, warnings);
        }
        return Ok(Symmetry::None);
    }
    let (loc, _) = h_start.nth(0);
    Err(src.unsupported(
        loc,
        "a horizontal angle set of LM-63 Type C: {0}, 0..90, 0..180, 90..270 or a last angle in (180, 360]",
        format!("{}..{} ({nh} angles)", Num(first), Num(last)),
    ))
}

/// Negative candela values are kept, with the readers' one warning ([`crate::formats::negative_intensities`]).
pub(super) fn warn_negatives(cd: &[f64], warnings: &mut Vec<Warning>) {
    if let Some(note) = crate::formats::negative_intensities(cd, "cd") {
        warnings.push(Warning::new(WarningCode::NegativeIntensity, note));
    }
}

/// The nadir and zenith are one direction: values that differ between planes are warned about.
pub(super) fn warn_pole_spread(distribution: &Distribution, warnings: &mut Vec<Warning>) {
    let (nadir, zenith) = distribution.pole_spread_cd();
    // The peak is one more pass over up to 65 k values: only asked for when a pole differs.
    let peak = || distribution.max_cd().abs().max(f64::MIN_POSITIVE);
    for (name, spread) in [("nadir (gamma 0)", nadir), ("zenith (gamma 180)", zenith)] {
        if spread > 0.0 && spread > 1e-9 * peak() {
            warnings.push(Warning::new(
                WarningCode::PoleMismatch,
                format!(
                    "the {name} value differs between planes by {} cd; kept as measured",
                    crate::numfmt::significant(spread, 6)
                ),
            ));
        }
    }
}
