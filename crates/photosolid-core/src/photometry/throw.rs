//! Where a luminaire throws its downward light: the horizontal part of the
//! downward flux's centroid, and whether it leans away from the front the
//! luminaire is rated or installed with (`front-mismatch` in `info`,
//! `street-side-mismatch` in `road`).
//!
//! The centroid is `T = ∫_{γ<90°} I(C, γ) (sin γ cos C, sin γ sin C) dΩ`
//! (lm, a vector in the file's horizontal plane), on the bilinear
//! interpolant of the grid: each full-circle plane's share of C (its
//! periodic width) times the γ integral of the linear interpolant, with the
//! plane's direction. `|T| / Φ_down` is 0 for a symmetric distribution and 1
//! for all light along one horizontal direction.

use crate::error::{Warning, WarningCode};
use crate::model::front::{c_separation_deg, Front};
use crate::model::{periodic_widths, Distribution};

/// The smallest lean `|T| / Φ_down` at which a throw counts (5 %).
pub const MIN_THROW_FRACTION: f64 = 0.05;
/// The largest angle between the throw and the front that agrees with it, degrees.
pub const MAX_FRONT_SEPARATION_DEG: f64 = 45.0;

/// The horizontal lean of the downward light.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Throw {
    /// Azimuth of `T`, C degrees in the file's frame, [0, 360).
    pub azimuth_c_deg: f64,
    /// `|T| / Φ_down`, in [0, 1].
    pub fraction: f64,
}

/// ∫ f(γ) sin² γ dγ over [0°, 90°] of the linear interpolant of `values` at `gamma_deg`:
/// sixteen midpoints a segment (the warning's thresholds need two digits, not ten).
fn lean_integral(gamma_deg: &[f64], values: &[f64]) -> f64 {
    const STEPS: usize = 16;
    let mut sum = 0.0;
    for i in 0..gamma_deg.len().saturating_sub(1) {
        let (a, b) = (gamma_deg[i], gamma_deg[i + 1].min(90.0));
        if b <= a {
            continue;
        }
        let h = (b - a) / STEPS as f64;
        for k in 0..STEPS {
            let g = a + (k as f64 + 0.5) * h;
            let t = (g - gamma_deg[i]) / (gamma_deg[i + 1] - gamma_deg[i]);
            let v = values[i] + t * (values[i + 1] - values[i]);
            let s = g.to_radians().sin();
            sum += v * s * s * h.to_radians();
        }
    }
    sum
}

/// The lean of `d`'s downward light; `None` when it sends none down.
pub fn downward_throw(d: &Distribution) -> Option<Throw> {
    let down = super::flux(d).downward_lm;
    if !(down > 0.0 && down.is_finite()) {
        return None;
    }
    let planes = d.full_planes();
    if planes.len() < 2 {
        // One plane stands for every C (rotational symmetry): no lean.
        return Some(Throw {
            azimuth_c_deg: 0.0,
            fraction: 0.0,
        });
    }
    let angles: Vec<f64> = planes.iter().map(|p| p.0).collect();
    let widths = periodic_widths(&angles);
    let g = d.gamma_angles_deg();
    let (mut x, mut y) = (0.0, 0.0);
    for (&(c, ic), w) in planes.iter().zip(&widths) {
        let lean = w.to_radians() * lean_integral(g, d.plane_cd(ic));
        let (s, co) = c.to_radians().sin_cos();
        x += lean * co;
        y += lean * s;
    }
    let fraction = (x.hypot(y) / down).clamp(0.0, 1.0);
    Some(Throw {
        azimuth_c_deg: crate::model::wrap360(y.atan2(x).to_degrees()),
        fraction,
    })
}

/// The throw of `d` when it leans at least [`MIN_THROW_FRACTION`] and more
/// than [`MAX_FRONT_SEPARATION_DEG`] away from `front_c_deg`.
pub fn leans_away_from(d: &Distribution, front_c_deg: f64) -> Option<Throw> {
    downward_throw(d).filter(|t| {
        t.fraction >= MIN_THROW_FRACTION && c_separation_deg(t.azimuth_c_deg, front_c_deg) > MAX_FRONT_SEPARATION_DEG
    })
}

/// `front-mismatch`: BUG rated with `front` while the downward light leans elsewhere.
pub fn front_mismatch(d: &Distribution, front: Front) -> Option<Warning> {
    leans_away_from(d, front.c_deg).map(|t| {
        Warning::new(
            WarningCode::FrontMismatch,
            format!(
                "the downward light leans towards C{:.0} ({:.0} % of the downward flux), {:.0} degrees from the \
                 front C{:.0} ({}) that BUG's forward half is centred on: if C{:.0} is the front, give --front {:.0}",
                t.azimuth_c_deg,
                100.0 * t.fraction,
                c_separation_deg(t.azimuth_c_deg, front.c_deg),
                front.c_deg,
                match front.source {
                    crate::model::FrontSource::Format => "the format's convention",
                    crate::model::FrontSource::Flag => "--front",
                },
                t.azimuth_c_deg,
                t.azimuth_c_deg
            ),
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Symmetry;

    /// A grid over the full circle (15° C steps, 5° γ steps) of `f(c, γ)` (degrees).
    fn grid(f: impl Fn(f64, f64) -> f64) -> Distribution {
        let c: Vec<f64> = (0..24).map(|i| 15.0 * i as f64).collect();
        let g: Vec<f64> = (0..=36).map(|i| 5.0 * i as f64).collect();
        let cd = c
            .iter()
            .flat_map(|&cc| g.iter().map(move |&gg| (cc, gg)))
            .map(|(cc, gg)| f(cc, gg))
            .collect();
        Distribution::new(c, g, cd, Symmetry::None).unwrap()
    }

    #[test]
    fn symmetric_light_does_not_lean_and_a_sideways_lobe_does() {
        let iso = grid(|_, _| 100.0);
        let t = downward_throw(&iso).unwrap();
        assert!(t.fraction < 1e-9, "{t:?}");
        assert!(leans_away_from(&iso, 0.0).is_none());
        // Light only towards C90 at γ 60°: the centroid leans that way.
        let side = grid(|c, g| {
            if (c - 90.0).abs() <= 30.0 && (45.0..=75.0).contains(&g) {
                1000.0
            } else {
                0.0
            }
        });
        let t = downward_throw(&side).unwrap();
        assert!((t.azimuth_c_deg - 90.0).abs() < 1e-6, "{t:?}");
        assert!(t.fraction > 0.7, "{t:?}");
        assert!(leans_away_from(&side, 90.0).is_none());
        assert!(leans_away_from(&side, 135.0).is_none(), "45 degrees away still agrees");
        assert!(leans_away_from(&side, 0.0).is_some());
        let w = front_mismatch(&side, Front::convention(crate::model::Format::Ies)).unwrap();
        assert_eq!(w.code, WarningCode::FrontMismatch);
        assert!(w.message.contains("--front 90"), "{}", w.message);
    }

    #[test]
    fn no_downward_light_has_no_throw() {
        let up = grid(|_, g| if g > 95.0 { 10.0 } else { 0.0 });
        assert!(downward_throw(&up).is_none());
    }
}
