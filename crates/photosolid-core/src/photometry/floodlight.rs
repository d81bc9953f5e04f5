//! Floodlight beam and field spreads and the NEMA type of a Type B grid.
//!
//! Floodlight catalogues quote, after NEMA FL 11-1982 ("Floodlight
//! Performance") and the IES Lighting Handbook (floodlight classification),
//! the angular extent of the beam in the **Type B** frame: in the horizontal
//! plane and in the vertical plane through the peak intensity, the full angle
//! over which the intensity stays at or above a fraction of I_max: 50 % (the
//! beam spread) and 10 % (the field spread). The NEMA type of each plane
//! classifies the 10 % spread (NEMA FL 11 defines beam spread at 10 % of
//! maximum candlepower): 10-18° type 1, 18-29° 2, 29-46° 3, 46-70° 4,
//! 70-100° 5, 100-130° 6, 130° and above 7; written `6H x 5V`.
//!
//! The spreads are read off the file's own Type B grid ([`SourceGrid`]),
//! linearly interpolated between measured angles, walking out from the peak
//! until the intensity first falls below the threshold; a profile still at or
//! above it at the last measured angle ends there (as
//! [`spread_angle`](super::spread_angle) does). A grid whose horizontal angles
//! start at 0 is laterally symmetric (LM-63) and mirrored about H = 0, as the
//! reader mirrors it.

use serde::Serialize;

use crate::model::{PhotometricType, SourceGrid};

/// A spread in the two planes through the peak, degrees.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Spread {
    /// In the horizontal plane (varying H at the peak's V), degrees.
    pub horizontal: f64,
    /// In the vertical plane (varying V at the peak's H), degrees.
    pub vertical: f64,
}

/// Beam and field spreads of a Type B (floodlight) grid and its NEMA type.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Floodlight {
    /// Full angles where I >= 50 % of I_max, degrees.
    pub beam_spread_deg: Spread,
    /// Full angles where I >= 10 % of I_max, degrees.
    pub field_spread_deg: Spread,
    /// NEMA type of the horizontal field spread (1-7; `None` below 10°).
    pub nema_horizontal: Option<u8>,
    /// NEMA type of the vertical field spread (1-7; `None` below 10°).
    pub nema_vertical: Option<u8>,
}

impl Floodlight {
    /// The NEMA designation, e.g. `6H x 5V`; `None` when a spread is under 10°
    /// (narrower than NEMA type 1).
    pub fn nema_type(&self) -> Option<String> {
        Some(format!("{}H x {}V", self.nema_horizontal?, self.nema_vertical?))
    }
}

/// NEMA floodlight type (NEMA FL 11-1982; IES Lighting Handbook) of a spread
/// in degrees: 10-18° 1, 18-29° 2, 29-46° 3, 46-70° 4, 70-100° 5, 100-130° 6,
/// 130° and above 7; `None` under 10° or when not finite.
pub fn nema_type(spread_deg: f64) -> Option<u8> {
    const LOWER: [f64; 7] = [10.0, 18.0, 29.0, 46.0, 70.0, 100.0, 130.0];
    if !spread_deg.is_finite() {
        return None;
    }
    LOWER.iter().rposition(|&lo| spread_deg >= lo).map(|i| i as u8 + 1)
}

/// The spreads of `grid` when it is a Type B grid with a positive peak; `None` otherwise.
pub fn floodlight(grid: &SourceGrid) -> Option<Floodlight> {
    let (hs, vs) = (&grid.horizontal, &grid.vertical);
    let nv = vs.len();
    if grid.kind != PhotometricType::B || hs.is_empty() || nv == 0 || grid.cd.len() != hs.len() * nv {
        return None;
    }
    let (peak, max) = grid
        .cd
        .iter()
        .copied()
        .enumerate()
        .fold((0, f64::NEG_INFINITY), |b, (i, v)| if v > b.1 { (i, v) } else { b });
    if !(max > 0.0 && max.is_finite()) {
        return None;
    }
    let (ih, iv) = (peak / nv, peak % nv);
    let row: Vec<f64> = (0..hs.len()).map(|h| grid.cd[h * nv + iv]).collect();
    let col: Vec<f64> = grid.cd[ih * nv..(ih + 1) * nv].to_vec();
    let mirror = hs[0].abs() <= 1e-9 && hs.len() > 1;
    let (h_angles, h_values, h_peak) = if mirror {
        // Laterally symmetric: the profile over -H..H.
        let mut a: Vec<f64> = hs[1..].iter().rev().map(|x| -x).collect();
        let mut v: Vec<f64> = row[1..].iter().rev().copied().collect();
        let p = a.len() + ih;
        a.extend_from_slice(hs);
        v.extend_from_slice(&row);
        (a, v, p)
    } else {
        (hs.clone(), row, ih)
    };
    let spread = |fraction: f64| Spread {
        horizontal: extent(&h_angles, &h_values, h_peak, fraction * max),
        vertical: extent(vs, &col, iv, fraction * max),
    };
    let (beam, field) = (spread(0.5), spread(0.1));
    Some(Floodlight {
        beam_spread_deg: beam,
        field_spread_deg: field,
        nema_horizontal: nema_type(field.horizontal),
        nema_vertical: nema_type(field.vertical),
    })
}

/// Full angle around index `peak` of the ascending `angles` where `values`
/// stay >= `threshold`: linear crossings, or the grid's end when none.
fn extent(angles: &[f64], values: &[f64], peak: usize, threshold: f64) -> f64 {
    let crossing = |from: usize, to: usize| {
        // Linear between the last sample at/above and the first below.
        let (a0, a1, v0, v1) = (angles[from], angles[to], values[from], values[to]);
        a0 + (a1 - a0) * (v0 - threshold) / (v0 - v1)
    };
    let hi = (peak + 1..angles.len())
        .find(|&j| values[j] < threshold)
        .map_or(angles[angles.len() - 1], |j| crossing(j - 1, j));
    let lo = (0..peak)
        .rev()
        .find(|&j| values[j] < threshold)
        .map_or(angles[0], |j| crossing(j + 1, j));
    hi - lo
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid(hs: Vec<f64>, vs: Vec<f64>, f: impl Fn(f64, f64) -> f64) -> SourceGrid {
        let cd = hs
            .iter()
            .flat_map(|&h| vs.iter().map(move |&v| (h, v)))
            .map(|(h, v)| f(h, v))
            .collect();
        SourceGrid {
            kind: PhotometricType::B,
            vertical: vs,
            horizontal: hs,
            cd,
        }
    }

    fn steps(from: f64, to: f64, step: f64) -> Vec<f64> {
        let n = ((to - from) / step).round() as usize;
        (0..=n).map(|i| from + step * i as f64).collect()
    }

    #[test]
    fn nema_types_follow_the_fl11_table() {
        for (s, t) in [
            (9.99, None),
            (10.0, Some(1)),
            (17.9, Some(1)),
            (18.0, Some(2)),
            (28.9, Some(2)),
            (29.0, Some(3)),
            (45.9, Some(3)),
            (46.0, Some(4)),
            (69.9, Some(4)),
            (70.0, Some(5)),
            (99.9, Some(5)),
            (100.0, Some(6)),
            (129.9, Some(6)),
            (130.0, Some(7)),
            (180.0, Some(7)),
            (f64::NAN, None),
        ] {
            assert_eq!(nema_type(s), t, "{s}");
        }
    }

    /// A pyramid I = 1000 (1 - |H|/a)(1 - |V|/b): piecewise linear, so the
    /// grid's linear crossings are exact: 50 % at a/2, 10 % at 0.9 a.
    #[test]
    fn piecewise_linear_lobe_gives_exact_spreads() {
        let (a, b) = (80.0, 40.0);
        let g = grid(steps(-90.0, 90.0, 5.0), steps(-90.0, 90.0, 2.5), |h: f64, v: f64| {
            1000.0 * (1.0 - h.abs() / a).max(0.0) * (1.0 - v.abs() / b).max(0.0)
        });
        let f = floodlight(&g).unwrap();
        assert!((f.beam_spread_deg.horizontal - a).abs() < 1e-9, "{f:?}");
        assert!((f.beam_spread_deg.vertical - b).abs() < 1e-9, "{f:?}");
        assert!((f.field_spread_deg.horizontal - 1.8 * a).abs() < 1e-9, "{f:?}");
        assert!((f.field_spread_deg.vertical - 1.8 * b).abs() < 1e-9, "{f:?}");
        // 144° -> 7, 72° -> 5.
        assert_eq!(f.nema_type().as_deref(), Some("7H x 5V"));
    }

    /// cos^p lobes about the Type B axis, H and V separable: half-value angle
    /// acos(0.5^(1/p)), tenth-value angle acos(0.1^(1/p)); a 0.25° grid is
    /// within 0.01° of them. The laterally symmetric half grid (H from 0) gives
    /// the same spreads.
    #[test]
    fn cosine_power_lobe_matches_its_closed_form() {
        let (p, q) = (8.0, 30.0);
        let lobe = move |h: f64, v: f64| 5000.0 * h.to_radians().cos().powf(p) * v.to_radians().cos().powf(q);
        let half = |p: f64, k: f64| 2.0 * k.powf(1.0 / p).acos().to_degrees();
        for hs in [steps(-90.0, 90.0, 0.25), steps(0.0, 90.0, 0.25)] {
            let f = floodlight(&grid(hs, steps(-90.0, 90.0, 0.25), lobe)).unwrap();
            assert!((f.beam_spread_deg.horizontal - half(p, 0.5)).abs() < 0.01, "{f:?}");
            assert!((f.beam_spread_deg.vertical - half(q, 0.5)).abs() < 0.01, "{f:?}");
            assert!((f.field_spread_deg.horizontal - half(p, 0.1)).abs() < 0.01, "{f:?}");
            assert!((f.field_spread_deg.vertical - half(q, 0.1)).abs() < 0.01, "{f:?}");
        }
    }

    #[test]
    fn type_a_and_dark_grids_have_no_spreads() {
        let mut g = grid(vec![0.0, 10.0], vec![0.0, 10.0], |_, _| 1.0);
        g.kind = PhotometricType::A;
        assert!(floodlight(&g).is_none());
        assert!(floodlight(&grid(vec![0.0, 10.0], vec![0.0, 10.0], |_, _| 0.0)).is_none());
    }
}
