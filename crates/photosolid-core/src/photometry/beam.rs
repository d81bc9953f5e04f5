//! Beam and field angles (IES: of I_max; CIE: of the centre-beam intensity).

use serde::Serialize;

use crate::model::{Distribution, ANGLE_EPS};

/// Intensities (cd) at every γ of the grid in the half-plane C (degrees,
/// any value): the stored plane when C is a grid plane, otherwise linear
/// interpolation between the two neighbouring full-circle planes.
pub fn plane_profile(d: &Distribution, c: f64) -> Vec<f64> {
    let c = crate::model::wrap360(c);
    let planes = d.full_planes();
    let n = planes.len();
    if n == 1 {
        return d.plane_cd(planes[0].1).to_vec();
    }
    let i = planes.partition_point(|p| p.0 < c - ANGLE_EPS);
    if i < n && (planes[i].0 - c).abs() <= ANGLE_EPS {
        return d.plane_cd(planes[i].1).to_vec();
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
    d.plane_cd(lo.1)
        .iter()
        .zip(d.plane_cd(hi.1))
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
/// full-sphere data), when γ = 0 is not measured (CIE), when the maximum the
/// IES walk starts from is not downward (γ > 90° on its side), or when the
/// angle would pass 180° (a globe: the spread is not a beam);
/// [`undefined_reason`] says which.
pub fn spread_angle(d: &Distribution, c: f64, fraction: f64, of_max: bool) -> Option<f64> {
    spread(d, c, fraction, of_max).ok()
}

/// Why [`spread_angle`] has no value.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Undefined {
    /// No positive reference intensity, no crossing on a side, or no γ = 0 (CIE).
    NoCrossing,
    /// The maximum lies above the horizontal, at this γ (degrees).
    PeakNotDownward(f64),
    /// The spread would be this many degrees, past 180°.
    PastHalfTurn(f64),
}

impl std::fmt::Display for Undefined {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Undefined::NoCrossing => {
                f.write_str("the intensity does not fall to the threshold on both sides of the peak")
            }
            Undefined::PeakNotDownward(g) => write!(f, "the peak lies at gamma {g:.1} degrees, above the horizontal"),
            Undefined::PastHalfTurn(a) => write!(f, "the angle would be {a:.2} degrees, past 180"),
        }
    }
}

/// Why the IES angle at `fraction` of I_max in the plane pair (C, C + 180)
/// is undefined, `None` when it is defined.
pub fn undefined_reason(d: &Distribution, c: f64, fraction: f64) -> Option<Undefined> {
    spread(d, c, fraction, true).err()
}

/// [`spread_angle`], with the reason when there is none.
fn spread(d: &Distribution, c: f64, fraction: f64, of_max: bool) -> Result<f64, Undefined> {
    let angle = raw_spread(d, c, fraction, of_max)?;
    // 1e-3°, not ANGLE_EPS: a beam of exactly half a turn stays one after a
    // format stores its intensities to 8 significant digits (a threshold met
    // exactly then moves the crossing by about 1e-5°).
    if angle > 180.0 + 1e-3 {
        return Err(Undefined::PastHalfTurn(angle));
    }
    Ok(angle)
}

/// The spread, degrees, without the half-turn check of [`spread`].
fn raw_spread(d: &Distribution, c: f64, fraction: f64, of_max: bool) -> Result<f64, Undefined> {
    let g = d.gamma_angles_deg();
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
        let (k, &m) = val
            .iter()
            .enumerate()
            .max_by(|x, y| x.1.total_cmp(y.1))
            .ok_or(Undefined::NoCrossing)?;
        (k, m)
    } else {
        if !has_zero {
            return Err(Undefined::NoCrossing);
        }
        let k = theta.iter().position(|&t| t == g[0]).ok_or(Undefined::NoCrossing)?;
        (k, val[k])
    };
    if reference <= 0.0 || !reference.is_finite() {
        return Err(Undefined::NoCrossing);
    }
    // The peak is downward when any direction holding the maximum is (an isotropic
    // source holds it everywhere).
    let downward = |t: f64| t.abs() <= 90.0 + ANGLE_EPS;
    if !downward(theta[start]) && !val.iter().zip(&theta).any(|(&v, &t)| v == reference && downward(t)) {
        return Err(Undefined::PeakNotDownward(theta[start].abs()));
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
    let left = walk(-1).ok_or(Undefined::NoCrossing)?;
    let right = walk(1).ok_or(Undefined::NoCrossing)?;
    Ok(right - left)
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::photometry::test_support::{rot, uniform};
    use std::f64::consts::PI;

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
        assert_eq!(beam_angles(&rot(g.clone(), |_| 1.0)).ies_beam_deg[0], None);
        assert_eq!(
            undefined_reason(&rot(g.clone(), |_| 1.0), 0.0, 0.5),
            Some(Undefined::NoCrossing)
        );
        // A globe brighter sideways than down: the 50 % crossing lies past 180° of spread.
        let globe = rot(g.clone(), |x| 1.0 + 0.9 * x.sin() - 0.6 * (x / 2.0).sin().powi(8));
        assert_eq!(beam_angles(&globe).ies_beam_deg[0], None);
        assert!(matches!(undefined_reason(&globe, 0.0, 0.5), Some(Undefined::PastHalfTurn(a)) if a > 180.0));
        // An uplight: its peak is at the zenith.
        let up = rot(g, |x| if x >= PI / 2.0 { (-x.cos()).powi(4) } else { 0.0 });
        assert_eq!(undefined_reason(&up, 0.0, 0.5), Some(Undefined::PeakNotDownward(180.0)));
    }
}
