//! Distances to the walls of a solid whose field jumps across rims.
//!
//! A field that jumps across a circle on the sphere ([`Rim`]: a lobe of
//! exponent 0, a hemisphere's step) has a solid with a wall there: in each
//! rim direction `u` the radial segment from `o(u) · u` to
//! `(o(u) + jump) · u`, where `o` is the field without the part that jumps
//! ([`IntensityField::intensity_outside_rim_cd`]). The surface search of
//! [`super::nearest`] reaches the two edges of the wall but not the wall
//! between them, so a point beside the wall is nearer to it than to any
//! point the search finds.
//!
//! The distance from a point `P` to the segment in direction `u` is closed
//! form (`P · u` clamped to the segment); over the rim it is a function of
//! one angle `t`, searched on the arc of the rim that can hold a nearer
//! point than the bound already known (a point of the rim whose ray lies at
//! angle θ from `P`'s is at least `|P| sin θ` away), sampled at most 0.5°
//! apart (64 to 1,024 samples) and then polished by golden-section search
//! around the best samples. Every value
//! is the distance to a point of a wall, so the result never falls below
//! the true distance.

use glam::DVec3;

use crate::minimize::{best_local_minima, golden_section};
use crate::model::{IntensityField, Rim};

/// Samples across the searched arc of a rim, at least.
const ARC_SAMPLES: usize = 64;
/// Samples across the searched arc of a rim, at most.
const MAX_ARC_SAMPLES: usize = 1024;
/// The largest angle (radians, 0.5°) between neighbouring samples on the
/// sphere, as far as [`MAX_ARC_SAMPLES`] allow: a lobe of the largest
/// exponent is about 3° wide at half maximum, so its dip in the wall's
/// outer edge spans several samples.
const ARC_STEP: f64 = 0.5 * std::f64::consts::PI / 180.0;
/// The bracket, in sample spacings, at which the golden-section polish of
/// each of the best samples stops (about 40 steps).
const POLISH_TOL: f64 = 4e-9;
/// Samples polished per rim: the best ones among the local minima.
const POLISHED: usize = 3;

/// The distance (cd) from `p` (a point in cd) to the solid's walls along
/// `rims`, or `upper` when no wall point is nearer than that.
pub(crate) fn distance_to_walls(field: &dyn IntensityField, rims: &[Rim], p: DVec3, upper: f64) -> f64 {
    rims.iter()
        .fold(upper, |best, rim| best.min(distance_to_wall(field, rim, p, best)))
}

/// The wall of one rim, searched where it can be nearer than `upper`.
fn distance_to_wall(field: &dyn IntensityField, rim: &Rim, p: DVec3, upper: f64) -> f64 {
    let Some(arc) = RimArc::new(rim, p, upper) else {
        return upper;
    };
    let dist = |t: f64| {
        let u = arc.direction(t);
        let outside = field.intensity_outside_rim_cd(rim.source, u).max(0.0);
        let along = p.dot(u).clamp(outside, outside + rim.jump_cd);
        let d = (p - along * u).length();
        if d.is_finite() {
            d
        } else {
            f64::INFINITY
        }
    };
    let n = ((arc.width * arc.sin_r / ARC_STEP).ceil() as usize).clamp(ARC_SAMPLES, MAX_ARC_SAMPLES);
    let h = arc.width / n as f64;
    let ts: Vec<f64> = (0..=n).map(|k| arc.start + k as f64 * h).collect();
    let ds: Vec<f64> = ts.iter().map(|&t| dist(t)).collect();
    let mut best = ds.iter().copied().fold(upper, f64::min);
    for k in best_local_minima(&ds, POLISHED) {
        let polished = golden_section(&dist, |&d| d, ts[k] - h, ts[k] + h, POLISH_TOL * h);
        best = best.min(polished);
    }
    best
}

/// The part of a rim, parametrised by its azimuth `t` about the rim's axis,
/// whose rays can come nearer to a point than a bound.
struct RimArc {
    /// The rim's centre and two unit vectors completing a right-handed frame.
    axis: DVec3,
    e1: DVec3,
    e2: DVec3,
    /// Cosine and sine of the rim's angular radius.
    cos_r: f64,
    sin_r: f64,
    /// The arc: azimuths from `start` to `start + width` (radians).
    start: f64,
    width: f64,
}

impl RimArc {
    /// The arc of `rim` within the angle θ of `p`'s direction where
    /// `|p| sin θ < upper` (all of it when `upper ≥ |p|`); `None` when the
    /// rim has no such part or is a single direction.
    fn new(rim: &Rim, p: DVec3, upper: f64) -> Option<Self> {
        let axis = rim.axis.try_normalize()?;
        let cos_r = rim.cos_angle.clamp(-1.0, 1.0);
        let sin_r = (1.0 - cos_r * cos_r).max(0.0).sqrt();
        if sin_r < 1e-12 {
            return None;
        }
        let (e1, e2) = axis.any_orthonormal_pair();
        let m = p.length();
        let full = |start: f64| RimArc {
            axis,
            e1,
            e2,
            cos_r,
            sin_r,
            start,
            width: std::f64::consts::TAU,
        };
        // Within reach from everywhere (or the point is the origin): the whole circle.
        if upper >= m || upper.is_nan() || m == 0.0 {
            return Some(full(0.0));
        }
        let cap = (upper / m).asin();
        let u = p / m;
        let (cos_a, x, y) = (u.dot(axis), u.dot(e1), u.dot(e2));
        let sin_a = (x * x + y * y).sqrt();
        let t0 = y.atan2(x);
        if sin_a < 1e-12 {
            // On the axis: every rim direction is at the same angle.
            return (cos_a * cos_r >= cap.cos()).then(|| full(t0));
        }
        // cos θ(t) = cos_a cos_r + sin_a sin_r cos(t − t0) ≥ cos(cap).
        let need = (cap.cos() - cos_a * cos_r) / (sin_a * sin_r);
        if need > 1.0 {
            return None;
        }
        if need <= -1.0 {
            return Some(full(t0));
        }
        let half = need.acos();
        Some(RimArc {
            start: t0 - half,
            width: 2.0 * half,
            ..full(t0)
        })
    }

    /// The rim's unit direction at azimuth `t`.
    fn direction(&self, t: f64) -> DVec3 {
        let (s, c) = t.sin_cos();
        self.cos_r * self.axis + self.sin_r * (c * self.e1 + s * self.e2)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `base` cd everywhere plus `step` cd where u · axis > 0: a sphere of
    /// radius `base` joined by a wall along the great circle to the
    /// hemisphere of radius `base + step`.
    struct HalfStep {
        axis: DVec3,
        base: f64,
        step: f64,
    }
    impl IntensityField for HalfStep {
        fn intensity_cd(&self, c_deg: f64, gamma_deg: f64) -> f64 {
            self.intensity_dir_cd(crate::model::frame::direction(c_deg, gamma_deg))
        }
        fn intensity_dir_cd(&self, d: DVec3) -> f64 {
            self.base + if d.dot(self.axis) > 0.0 { self.step } else { 0.0 }
        }
        fn intensity_outside_rim_cd(&self, _source: usize, _u: DVec3) -> f64 {
            self.base
        }
        fn name(&self) -> String {
            "half-step".into()
        }
        fn bytes(&self) -> usize {
            0
        }
    }

    fn rim(axis: DVec3, jump: f64) -> Rim {
        Rim {
            axis,
            cos_angle: 0.0,
            jump_cd: jump,
            source: 0,
        }
    }

    /// A point beside the wall, between its inner and outer edges, is as far
    /// from it as from the rim's plane; a point beyond the wall's outer edge
    /// is as far as from that edge (a circle of radius base + step).
    #[test]
    fn the_wall_of_a_hemisphere_step_in_closed_form() {
        let f = HalfStep {
            axis: DVec3::Z,
            base: 100.0,
            step: 50.0,
        };
        let rims = [rim(DVec3::Z, 50.0)];
        for (p, want) in [
            (DVec3::new(120.0, 0.0, -3.0), 3.0),
            (DVec3::new(0.0, -130.0, 2.0), 2.0),
            (DVec3::new(100.0, 100.0, -1.0), 1.0),
            (DVec3::new(170.0, 0.0, -5.0), (20.0f64 * 20.0 + 25.0).sqrt()),
        ] {
            let d = distance_to_walls(&f, &rims, p, f64::INFINITY);
            assert!((d - want).abs() < 1e-9 * want.max(1.0), "{p}: {d} vs {want}");
            // The bound prunes nothing nearer than itself.
            let pruned = distance_to_walls(&f, &rims, p, want * 1.001);
            assert!((pruned - d).abs() < 1e-9 * want.max(1.0), "{p}: {pruned} vs {d}");
            // And a bound below the wall's distance is returned as it is.
            assert_eq!(distance_to_walls(&f, &rims, p, 0.5 * want), 0.5 * want, "{p}");
        }
    }

    /// A tilted rim: the same distances in the rotated frame, and none of
    /// them below the closed form (the search only finds wall points).
    #[test]
    fn a_tilted_rim_gives_the_rotated_distances() {
        let axis = DVec3::new(0.3, -0.4, 0.8).normalize();
        let f = HalfStep {
            axis,
            base: 10.0,
            step: 5.0,
        };
        let (e1, e2) = axis.any_orthonormal_pair();
        for k in 0..24 {
            let t = k as f64 * 0.27;
            let radial = 10.5 + 0.2 * k as f64;
            let off = 0.01 + 0.05 * k as f64;
            let p = radial * (t.cos() * e1 + t.sin() * e2) - off * axis;
            let d = distance_to_walls(&f, &[rim(axis, 5.0)], p, f64::INFINITY);
            let want = if radial <= 15.0 {
                off
            } else {
                ((radial - 15.0).powi(2) + off * off).sqrt()
            };
            assert!(d >= want - 1e-12 && d - want < 1e-9, "k {k}: {d} vs {want}");
        }
    }

    /// A lobe mixture with a hemisphere step (exponent 0, tilted) and a
    /// tilted cos^3 lobe: the surface search with the walls
    /// ([`crate::metrics::distances_to_solid`]) finds, for points around
    /// the solid, a distance no larger than a brute-force minimum over a
    /// dense sampling of the cap that can hold a nearer point (250,000
    /// directions) and of the wall (20,000 rim directions), and without the
    /// walls it misses the points beside the wall.
    #[test]
    fn searched_with_walls_no_farther_than_dense_sampling() {
        use crate::metrics::{distances_to_solid, NearestSearch};
        use crate::reconstruct::{Lobe, Lobes};
        let step_axis = DVec3::new(0.2, 0.1, -0.9).normalize();
        let lobes = Lobes::new(vec![
            Lobe {
                axis: step_axis,
                exponent: 0.0,
                weight_cd: 40.0,
            },
            Lobe {
                axis: DVec3::new(-0.5, 0.3, -0.8).normalize(),
                exponent: 3.0,
                weight_cd: 100.0,
            },
        ]);
        let rims = lobes.rims().expect("a plain mixture has rims");
        assert_eq!(rims.len(), 1);
        let axis = rims[0].axis.normalize();
        let (e1, e2) = axis.any_orthonormal_pair();
        // Points near the rim (where the wall matters) and elsewhere.
        let mut points = Vec::new();
        for k in 0..40 {
            let t = 0.157 * k as f64;
            let tilt = if k % 2 == 0 {
                -0.02 - 0.004 * k as f64
            } else {
                0.6 - 0.03 * k as f64
            };
            let d = (t.cos() * e1 + t.sin() * e2 + tilt * axis).normalize();
            let v = lobes.intensity_dir_cd(d);
            points.push((d, v * (0.7 + 0.015 * k as f64) + 3.0));
        }
        let searched = distances_to_solid(&lobes, &points, &NearestSearch::default());
        let bare = NoRims(&lobes);
        let without = distances_to_solid(&bare, &points, &NearestSearch::default());
        let mut beside_the_wall = 0;
        for (k, (&(d, m), &s)) in points.iter().zip(&searched).enumerate() {
            let p = m * d;
            let brute = dense_cap_distance(&lobes, p).min(dense_wall_distance(&lobes, &rims[0], p));
            assert!(s <= brute + 1e-6 * m, "point {k}: searched {s} > dense {brute}");
            if without[k] > s + 0.5 {
                beside_the_wall += 1;
            }
        }
        assert!(
            beside_the_wall >= 5,
            "only {beside_the_wall} points were nearer to the wall"
        );
    }

    /// A field without its rims: the search alone.
    struct NoRims<'a>(&'a dyn IntensityField);
    impl IntensityField for NoRims<'_> {
        fn intensity_cd(&self, c_deg: f64, gamma_deg: f64) -> f64 {
            self.0.intensity_cd(c_deg, gamma_deg)
        }
        fn intensity_dir_cd(&self, d: DVec3) -> f64 {
            self.0.intensity_dir_cd(d)
        }
        fn is_continuous(&self) -> bool {
            true
        }
        fn name(&self) -> String {
            "no-rims".into()
        }
        fn bytes(&self) -> usize {
            0
        }
    }

    /// The least |p − I(u) u| over 500 x 500 directions of the cap around p
    /// within which a point can be nearer than p's own radial distance.
    fn dense_cap_distance(f: &dyn IntensityField, p: DVec3) -> f64 {
        let (m, d) = (p.length(), p.normalize());
        let own = (m - f.intensity_dir_cd(d)).abs();
        let cap = if own >= m {
            std::f64::consts::PI
        } else {
            (own / m).asin() * 1.01
        };
        let (e1, e2) = d.any_orthonormal_pair();
        let n = 500;
        let mut best = own;
        for i in 0..n {
            let rho = cap * (i as f64 + 0.5) / n as f64;
            for j in 0..n {
                let phi = std::f64::consts::TAU * j as f64 / n as f64;
                let u = rho.cos() * d + rho.sin() * (phi.cos() * e1 + phi.sin() * e2);
                best = best.min((p - f.intensity_dir_cd(u) * u).length());
            }
        }
        best
    }

    /// The least distance from p to the wall over 20,000 rim directions.
    fn dense_wall_distance(f: &dyn IntensityField, rim: &Rim, p: DVec3) -> f64 {
        let axis = rim.axis.normalize();
        let (e1, e2) = axis.any_orthonormal_pair();
        (0..20_000)
            .map(|k| {
                let t = std::f64::consts::TAU * k as f64 / 20_000.0;
                let u = t.cos() * e1 + t.sin() * e2;
                let o = f.intensity_outside_rim_cd(rim.source, u);
                (p - p.dot(u).clamp(o, o + rim.jump_cd) * u).length()
            })
            .fold(f64::INFINITY, f64::min)
    }

    /// A point whose ray lies far from the rim is pruned, and a single
    /// direction (a zero-width rim) has no wall.
    #[test]
    fn arcs_out_of_reach_are_skipped() {
        let r = rim(DVec3::Z, 1.0);
        assert!(RimArc::new(&r, DVec3::new(0.0, 0.0, -100.0), 10.0).is_none());
        let arc = RimArc::new(&r, DVec3::new(100.0, 0.0, -1.0), 10.0).unwrap();
        assert!(arc.width < 0.21 && arc.width > 0.19, "{}", arc.width);
        let point = Rim { cos_angle: 1.0, ..r };
        assert!(RimArc::new(&point, DVec3::X, 10.0).is_none());
    }
}
