//! Hausdorff distance between solids of revolution, measured on their profile curves.
//!
//! # Why the profile suffices
//! Two surfaces of revolution S1, S2 about the same axis (z) are given by
//! their profiles P1, P2 in the half-plane {(ρ, z) : ρ ≥ 0}. For p ∈ S1 at
//! (ρ, z, azimuth φ) and q ∈ S2 at (ρ', z', φ'):
//! `|p − q|² = ρ² + ρ'² − 2 ρ ρ' cos(φ − φ') + (z − z')² ≥ (ρ − ρ')² + (z − z')²`,
//! with equality at φ' = φ (ρ, ρ' ≥ 0). So the nearest point of S2 to p lies
//! in p's own meridian half-plane, `d(p, S2) = d₂((ρ, z), P2)` (the planar
//! distance), and taking suprema, `h(S1, S2) = h(P1, P2)` for both one-sided
//! distances: the Hausdorff distance of the solids is that of the profiles,
//! with no facets in C at all.
//!
//! The profile of a C-independent field is a polyline through
//! `I(γ_j) (sin γ_j, −cos γ_j)`; its solid of revolution is the field's solid
//! up to the polyline's chord error, which the caller bounds (the
//! γ-refinement of [`crate::solid::adaptive`]).
//!
//! # Certificate
//! As [`super::hausdorff()`], in one dimension less: exact point-to-segment
//! distances; over a segment T of A, `f = d(·, B)` is at most
//! `max(d(v0, K), d(v1, K))` for any segment K of B (distance to a segment
//! is convex) and at most `(f0 + f1 + |T|)/2` (f is 1-Lipschitz); segments
//! are halved, largest upper bound first, until it is within the tolerance
//! of the largest value found.

use std::convert::Infallible;

use glam::DVec2;
use rayon::prelude::*;

use super::hausdorff::{Hausdorff, OneSided, MAX_REFINEMENT_QUERIES};
use super::refine::{ByUpper, Refine, Refinement};
use crate::model::frame::sin_cos_deg;
use crate::model::IntensityField;

/// The meridian profile of a rotationally symmetric solid: points
/// (ρ, z) = I(γ) (sin γ, −cos γ) at ascending γ from 0 to 180 (degrees), in cd.
#[derive(Debug, Clone, PartialEq)]
pub struct Profile {
    gamma: Vec<f64>,
    points: Vec<DVec2>,
}

impl Profile {
    /// The profile of `field` in the plane C = 0 at `gamma_deg` (ascending,
    /// 0 to 180); negative, NaN and round-off intensities (below
    /// [`crate::solid::ZERO_FRACTION`] of the peak) are 0 (the origin).
    pub fn of_field(field: &dyn IntensityField, gamma_deg: &[f64]) -> Self {
        let dirs: Vec<(f64, f64)> = gamma_deg.iter().map(|&g| (0.0, g)).collect();
        let values = crate::reconstruct::eval_all(field, &dirs);
        // Below 1e-9 of the peak a value is round-off of a zero (I0 cos 90° = 6e-17 I0): the
        // origin, as in the grid solids (crate::solid::ZERO_FRACTION).
        let peak = values.iter().copied().fold(0.0, f64::max);
        let zero = crate::model::ZERO_FRACTION * peak;
        let points = gamma_deg
            .iter()
            .zip(values)
            .map(|(&g, v)| {
                let r = if v > zero { v } else { 0.0 };
                let (s, c) = sin_cos_deg(g);
                DVec2::new(r * s, -r * c)
            })
            .collect();
        Self {
            gamma: gamma_deg.to_vec(),
            points,
        }
    }

    /// The polyline's points (ρ, z), cd, at ascending γ.
    pub fn points(&self) -> &[DVec2] {
        &self.points
    }

    /// Segments of the polyline.
    pub fn n_segments(&self) -> usize {
        self.points.len().saturating_sub(1)
    }

    /// The radius (cd) of the profile polyline along the ray at `gamma_deg`:
    /// the ray's intersection with the segment whose γ range holds it (for
    /// a segment to the origin, linear in γ between its ends).
    pub fn radius_at(&self, gamma_deg: f64) -> f64 {
        let n = self.gamma.len();
        if n == 0 {
            return 0.0;
        }
        let j = self.gamma.partition_point(|&g| g <= gamma_deg).clamp(1, n - 1) - 1;
        let (p, q) = (self.points[j], self.points[(j + 1).min(n - 1)]);
        let (s, c) = sin_cos_deg(gamma_deg);
        let w = DVec2::new(s, -c);
        // Solve t w = p + u (q − p): t = cross(p, q − p) / cross(w, q − p).
        // A segment to the origin runs along a ray: the polyline's own radial function drops
        // to 0 across its whole γ interval, while the surface beside it does not; take the
        // radius linear in γ between its ends there, as on a fan of a grid solid's cell.
        if p == DVec2::ZERO || q == DVec2::ZERO {
            let (g0, g1) = (self.gamma[j], self.gamma[(j + 1).min(n - 1)]);
            let u = if g1 > g0 {
                ((gamma_deg - g0) / (g1 - g0)).clamp(0.0, 1.0)
            } else {
                0.0
            };
            return (1.0 - u) * p.length() + u * q.length();
        }
        let e = q - p;
        let den = w.perp_dot(e);
        if den.abs() < 1e-300 {
            // The ray runs along the segment (through the origin): its farther end.
            return p.length().max(q.length());
        }
        (p.perp_dot(e) / den).max(0.0)
    }
}

/// Whether `field` is independent of C, tested on samples: at each of
/// `gamma_deg` and 12 C angles (irregular, so no symmetry plane hides a
/// difference), within 1e-9 of the largest sample (cd).
pub fn is_c_independent(field: &dyn IntensityField, gamma_deg: &[f64]) -> bool {
    const C: [f64; 12] = [
        0.0, 17.3, 45.0, 90.0, 121.7, 135.0, 180.0, 203.1, 225.0, 270.0, 301.9, 337.5,
    ];
    let mut s = vec![0.0; C.len() * gamma_deg.len()];
    field.sample_grid(&C, gamma_deg, &mut s);
    let peak = s.iter().copied().fold(0.0, f64::max);
    if s.iter().any(|v| !v.is_finite()) {
        return false;
    }
    let n = gamma_deg.len();
    (1..C.len()).all(|ic| (0..n).all(|ig| (s[ic * n + ig] - s[ig]).abs() <= 1e-9 * peak))
}

/// Distance from `x` to the segment a–b, squared.
fn segment_dist2(x: DVec2, a: DVec2, b: DVec2) -> f64 {
    let e = b - a;
    let l2 = e.length_squared();
    let t = if l2 > 0.0 {
        ((x - a).dot(e) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (a + t * e - x).length_squared()
}

/// Distances (cd) from 3-D points to the solid of revolution of `profile`:
/// each point's planar distance, in its meridian half-plane (ρ = √(x² + y²), z),
/// to the profile (see the module docs).
pub fn distances_3d(points: &[glam::DVec3], profile: &Profile) -> Vec<f64> {
    points
        .par_iter()
        .map(|p| nearest(DVec2::new(p.x.hypot(p.y), p.z), profile).0)
        .collect()
}

/// Distance and nearest segment of `b` (brute force: profiles have
/// thousands of segments, not millions).
fn nearest(x: DVec2, b: &Profile) -> (f64, u32) {
    let mut best = (f64::INFINITY, u32::MAX);
    for (k, w) in b.points.windows(2).enumerate() {
        let d2 = segment_dist2(x, w[0], w[1]);
        if d2 < best.0 {
            best = (d2, k as u32);
        }
    }
    (best.0.sqrt(), best.1)
}

/// A segment of A, or a piece of one, under refinement: its ends, their
/// distances to B and their nearest segments of B (`u32::MAX`: none).
#[derive(Debug, Clone, Copy)]
struct Seg {
    v: [DVec2; 2],
    f: [f64; 2],
    k: [u32; 2],
}

/// B's segments, against which A's segments are refined (no seeds: a
/// profile's segments are few and queued as cells at once).
struct ProfileCells<'a> {
    b: &'a Profile,
}

impl Refine for ProfileCells<'_> {
    type Cell = Seg;
    type Seed = Infallible;
    type Children = [ByUpper<Seg>; 2];
    const QUERIES_PER_SPLIT: usize = 1;

    fn expand(&self, seed: Infallible) -> Seg {
        match seed {}
    }

    /// The two halves of `s`, its midpoint queried.
    fn split(&self, s: &Seg, lb: &mut f64) -> Self::Children {
        let m = 0.5 * (s.v[0] + s.v[1]);
        let (fm, km) = nearest(m, self.b);
        *lb = lb.max(fm);
        [
            ([s.v[0], m], [s.f[0], fm], [s.k[0], km]),
            ([m, s.v[1]], [fm, s.f[1]], [km, s.k[1]]),
        ]
        .map(|(v, f, k)| ByUpper {
            ub: upper_bound(&v, &f, &k, self.b),
            item: Seg { v, f, k },
        })
    }
}

/// Upper bound of the distance to B over the segment `v` (ends' distances
/// `f`, nearest segments `k`): the Lipschitz bound or the convexity bound over
/// either nearest segment, whichever is smaller.
fn upper_bound(v: &[DVec2; 2], f: &[f64; 2], k: &[u32; 2], b: &Profile) -> f64 {
    let mut best = 0.5 * (f[0] + f[1] + v[0].distance(v[1]));
    for &kk in k {
        if kk == u32::MAX {
            continue;
        }
        let (p, q) = (b.points[kk as usize], b.points[kk as usize + 1]);
        let m = segment_dist2(v[0], p, q).max(segment_dist2(v[1], p, q)).sqrt();
        best = best.min(m);
    }
    best
}

/// One-sided h(A, B) of the solids of revolution of two profiles, to
/// within `tolerance` (cd). Mean and RMS are weighted by the surface of
/// revolution's area (2π ρ ds), from each segment's ends and midpoint.
pub fn one_sided(a: &Profile, b: &Profile, tolerance: f64) -> OneSided {
    if a.n_segments() == 0 || b.n_segments() == 0 {
        let inf = f64::INFINITY;
        return OneSided {
            value: inf,
            bound: 0.0,
            mean: Some(inf),
            rms: Some(inf),
            queries: 0,
            converged: true,
        };
    }
    let near: Vec<(f64, u32)> = a.points.par_iter().map(|&p| nearest(p, b)).collect();
    let mids: Vec<(f64, u32)> = a
        .points
        .par_windows(2)
        .map(|w| nearest(0.5 * (w[0] + w[1]), b))
        .collect();
    let lb = near.iter().chain(&mids).map(|x| x.0).fold(0.0, f64::max);
    let mut refinement = Refinement::new(lb, tolerance);
    queue_halves(a, b, &near, &mids, &mut refinement);
    let refined = refinement.run(&ProfileCells { b }, MAX_REFINEMENT_QUERIES);
    let (mean, rms) = mean_rms(a, &near, &mids);
    OneSided {
        value: refined.lb,
        bound: (refined.ub - refined.lb).max(0.0),
        mean: Some(mean),
        rms: Some(rms),
        queries: near.len() + mids.len() + refined.queries,
        converged: refined.converged,
    }
}

/// Queues both halves of each segment of A (the midpoint is known: `mids`),
/// given its ends' and midpoint's distances and nearest segments of B.
fn queue_halves(
    a: &Profile,
    b: &Profile,
    near: &[(f64, u32)],
    mids: &[(f64, u32)],
    refinement: &mut Refinement<Seg, Infallible>,
) {
    for j in 0..a.n_segments() {
        let (v0, v1) = (a.points[j], a.points[j + 1]);
        let (f0, f1, fm) = (near[j].0, near[j + 1].0, mids[j].0);
        let mid = 0.5 * (v0 + v1);
        for (v, f, k) in [
            ([v0, mid], [f0, fm], [near[j].1, mids[j].1]),
            ([mid, v1], [fm, f1], [mids[j].1, near[j + 1].1]),
        ] {
            refinement.offer(upper_bound(&v, &f, &k, b), Seg { v, f, k });
        }
    }
}

/// Mean and RMS distance (cd) over the surface of revolution of A, weighted
/// by its area 2π ρ ds: Simpson's rule on each segment from its ends' and
/// midpoint's distances.
fn mean_rms(a: &Profile, near: &[(f64, u32)], mids: &[(f64, u32)]) -> (f64, f64) {
    let (mut area, mut sum, mut sum2) = (0.0, 0.0, 0.0);
    for j in 0..a.n_segments() {
        let (v0, v1) = (a.points[j], a.points[j + 1]);
        let (f0, f1, fm) = (near[j].0, near[j + 1].0, mids[j].0);
        let (r0, r1) = (v0.x, v1.x);
        let rm = 0.5 * (r0 + r1);
        let len = v0.distance(v1);
        area += rm * len;
        sum += (f0 * r0 + 4.0 * fm * rm + f1 * r1) / 6.0 * len;
        sum2 += (f0 * f0 * r0 + 4.0 * fm * fm * rm + f1 * f1 * r1) / 6.0 * len;
    }
    if area > 0.0 {
        (sum / area, (sum2 / area).sqrt())
    } else {
        (0.0, 0.0)
    }
}

/// Symmetric Hausdorff distance of the solids of revolution of `a` and `b`, to within `tolerance` (cd).
pub fn hausdorff(a: &Profile, b: &Profile, tolerance: f64) -> Hausdorff {
    let (ab, ba) = rayon::join(|| one_sided(a, b, tolerance), || one_sided(b, a, tolerance));
    Hausdorff::of_sides(ab, ba)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::metrics::hausdorff::MeshRef;

    fn gammas(n: usize) -> Vec<f64> {
        (0..=n).map(|k| 180.0 * k as f64 / n as f64).collect()
    }

    #[test]
    fn spheres_differ_by_their_radii_and_identical_profiles_by_zero() {
        let a = Profile::of_field(&|_c: f64, _g: f64| 10.0, &gammas(360));
        let b = Profile::of_field(&|_c: f64, _g: f64| 12.0, &gammas(360));
        let h = hausdorff(&a, &b, 1e-6);
        assert!((h.value - 2.0).abs() < 1e-3, "{h:?}");
        let z = hausdorff(&a, &a, 1e-6);
        assert!(z.value <= 1e-12 && z.bound <= 1e-12, "{z:?}");
        assert!((a.radius_at(33.3) - 10.0).abs() < 1e-3);
    }

    /// The profile distance equals the 3-D distance between the meshed
    /// solids of revolution (up to the meshes' C facets), on two lobes whose
    /// nearest points are not at equal γ.
    #[test]
    fn profile_distance_matches_the_meshed_solids() {
        use crate::solid::{grid_solid, SolidGrid, Units};
        let f1 = |_c: f64, g: f64| 100.0 * crate::model::frame::cos_deg(g).max(0.0).powi(4) + 5.0;
        let f2 = |_c: f64, g: f64| 90.0 * crate::model::frame::cos_deg(g - 10.0).max(0.0).powi(2) + 5.0;
        let g = gammas(720);
        let h2 = hausdorff(&Profile::of_field(&f1, &g), &Profile::of_field(&f2, &g), 1e-4);
        let grid = SolidGrid::uniform(720, 720).unwrap();
        let (m1, m2) = (
            grid_solid(&f1, &grid, Units::Candela).unwrap(),
            grid_solid(&f2, &grid, Units::Candela).unwrap(),
        );
        let (p1, p2) = (m1.positions_f64(), m2.positions_f64());
        let h3 = crate::metrics::hausdorff(
            MeshRef {
                positions: &p1,
                triangles: m1.triangles(),
            },
            MeshRef {
                positions: &p2,
                triangles: m2.triangles(),
            },
            1e-3,
        );
        // 720 C planes: the facets sit within 100 (1 − cos 0.25°) ≈ 1e-3 cd of the surfaces.
        assert!((h2.value - h3.value).abs() < 0.01, "profile {h2:?} vs mesh {h3:?}");
        assert!(h2.value > 1.0);
    }
}
