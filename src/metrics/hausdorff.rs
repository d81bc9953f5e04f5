//! Hausdorff distance between triangle meshes, with a certified bound.
//!
//! One-sided `h(A, B) = sup_{a ∈ A} inf_{b ∈ B} |a − b|`; symmetric
//! `H = max(h(A, B), h(B, A))` (Ashdown 1999; Wallner 2008 §7).
//!
//! # How the supremum is certified
//! Point-to-triangle distances are exact (a [`Bvh`] over B). Over a triangle
//! T of A with vertices v_i, two upper bounds of `sup_T f`, `f(x) = d(x, B)`:
//! - *convexity*: for any one triangle K of B, `f(x) ≤ d(x, K)`, and the
//!   distance to a convex set is convex, so its maximum over T is at a
//!   vertex: `sup_T f ≤ max_i d(v_i, K)`. K is tried as the nearest B
//!   triangle of each vertex; this bound is tight once T is small against B;
//! - *Lipschitz*: f is 1-Lipschitz, so `sup_T f ≤ min_i (f_i + max_{x∈T} |x − v_i|)`
//!   and `≤ max_i f_i + L/√3` (no point of a triangle is farther than L/√3
//!   from all three vertices, L the longest edge).
//!
//! Every value of f actually
//! evaluated is a lower bound of the supremum. Triangles are refined
//! (midpoint subdivision into 4), largest upper bound first, until the
//! largest upper bound is within `tolerance` of the largest value found. The
//! result is `value` (attained, so `h ≥ value`) and `bound` with
//! `h ≤ value + bound`: e.g. "H = 12.31 cd (+0.05)".
//!
//! Both bounds hold as well with an upper bound `f_i ≥ f(v_i)` and any
//! triangle K of B. The supremum-only search ([`one_sided_bounded`]) uses
//! that: a point that cannot raise the largest value found, nor keep its
//! triangles above the tolerance, stops its search at the first triangle of
//! B within that radius and keeps the distance to it (`measure_batch`).
//!
//! Mean and RMS distance are area-weighted estimates from each triangle's
//! vertex values (weight 1/4) and centroid value (weight 3/4); they are
//! estimates, not certified.

use glam::DVec3;
use rayon::prelude::*;
use serde::Serialize;

use super::bvh::Bvh;
use super::refine::{ByUpper, Refine, Refinement};

/// A borrowed triangle mesh.
#[derive(Debug, Clone, Copy)]
pub struct MeshRef<'a> {
    /// Vertex positions (any consistent unit; photometric solids use cd).
    pub positions: &'a [DVec3],
    /// Triangles as vertex indices.
    pub triangles: &'a [[u32; 3]],
}

/// One direction of the Hausdorff distance.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct OneSided {
    /// Largest distance found (a lower bound of the supremum, attained).
    pub value: f64,
    /// Certified gap: the supremum is at most `value + bound`.
    pub bound: f64,
    /// Area-weighted mean distance (estimate); `None` when only the
    /// supremum was searched ([`one_sided_bounded`]).
    pub mean: Option<f64>,
    /// Area-weighted RMS distance (estimate); `None` as `mean`.
    pub rms: Option<f64>,
    /// Distance queries made (vertices plus refinement points).
    pub queries: usize,
    /// Whether refinement reached the requested tolerance; false when it
    /// stopped at [`MAX_REFINEMENT_QUERIES`] ("partial: bound not reached":
    /// `bound` is then larger than the tolerance asked for).
    pub converged: bool,
}

/// Symmetric Hausdorff distance with both one-sided parts.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Hausdorff {
    /// max(h(A,B), h(B,A)) as attained.
    pub value: f64,
    /// Certified gap of `value`.
    pub bound: f64,
    /// h(A, B).
    pub a_to_b: OneSided,
    /// h(B, A).
    pub b_to_a: OneSided,
}

/// Refinement stops after this many extra queries per direction (about a
/// second of work on one core), reporting the bound reached and
/// [`OneSided::converged`] = false: a tolerance of 0 cannot be reached and
/// must not run on for minutes.
pub const MAX_REFINEMENT_QUERIES: usize = 2_000_000;

/// A triangle of A, or a piece of one, under refinement: its vertices, their
/// distances to B and their nearest triangles of B (`u32::MAX`: none).
#[derive(Debug, Clone, Copy)]
struct Cell {
    v: [DVec3; 3],
    f: [f64; 3],
    k: [u32; 3],
}

/// The smaller of the Lipschitz bound and the convexity bound over each
/// candidate triangle `k` of B (the vertices' nearest triangles, and for a
/// mesh triangle its centroid's: with identical meshes that is the triangle
/// itself, so the bound is 0 at once).
fn upper_bound(v: &[DVec3; 3], f: &[f64; 3], k: &[u32], b: &Bvh) -> f64 {
    let mut best = lipschitz_bound(v, f);
    for (i, &ki) in k.iter().enumerate() {
        if ki == u32::MAX || (i > 0 && k[..i].contains(&ki)) {
            continue;
        }
        let tri = b.triangle(ki);
        let m = v
            .iter()
            .map(|&p| super::bvh::point_triangle_dist2(p, &tri))
            .fold(0.0, f64::max)
            .sqrt();
        best = best.min(m);
    }
    best
}

fn lipschitz_bound(v: &[DVec3; 3], f: &[f64; 3]) -> f64 {
    let e = [v[0].distance(v[1]), v[1].distance(v[2]), v[2].distance(v[0])];
    let far = [e[0].max(e[2]), e[0].max(e[1]), e[1].max(e[2])];
    let cone = (0..3).map(|i| f[i] + far[i]).fold(f64::INFINITY, f64::min);
    let longest = e[0].max(e[1]).max(e[2]);
    let fmax = f[0].max(f[1]).max(f[2]);
    cone.min(fmax + longest / 3f64.sqrt())
}

fn area(v: &[DVec3; 3]) -> f64 {
    0.5 * (v[1] - v[0]).cross(v[2] - v[0]).length()
}

/// Distances from every point of `points` to `b`, in parallel; consecutive
/// points warm-start each other's search (p_k's distance to p_{k−1}'s nearest triangle).
pub fn distances(points: &[DVec3], b: &Bvh) -> Vec<f64> {
    nearest(points, b).into_iter().map(|x| x.0).collect()
}

/// The squared distance a nearest-triangle search below the distance bound
/// `bound` starts from: slightly above it, so the triangle at exactly that
/// distance is kept (infinite for an infinite bound).
fn search_limit2(bound: f64) -> f64 {
    (bound * (1.0 + 1e-12) + 1e-300).powi(2)
}

/// Distance and nearest triangle of `b` for every point (see [`distances`]).
pub fn nearest(points: &[DVec3], b: &Bvh) -> Vec<(f64, u32)> {
    nearest_below_bounds(points, b, &[])
}

/// [`nearest`] with `upper[k]` an upper bound of point k's distance to `b`
/// (empty: none): each search starts below the smaller of it and the warm
/// start of [`distances`], so a tight bound prunes all but a few boxes. The
/// answers are those of [`nearest`], the triangle's index included: the
/// search visits the boxes in the same order and only skips boxes that hold
/// nothing nearer than the bound.
pub fn nearest_below_bounds(points: &[DVec3], b: &Bvh, upper: &[f64]) -> Vec<(f64, u32)> {
    let mut out = vec![(0.0, u32::MAX); points.len()];
    let upper_of = |k: usize| upper.get(k).copied().unwrap_or(f64::INFINITY);
    out.par_chunks_mut(512)
        .zip(points.par_chunks(512))
        .enumerate()
        .for_each(|(chunk, (o, p))| {
            let first = chunk * 512;
            // The previous point's nearest triangle: p_k's distance to it bounds
            // p_k's distance to B, never looser than the Lipschitz bound
            // d(p_{k-1}) + |p_k - p_{k-1}|, and far tighter between neighbours.
            let mut prev = u32::MAX;
            for k in 0..p.len() {
                let warm = if prev == u32::MAX {
                    f64::INFINITY
                } else {
                    super::bvh::point_triangle_dist2(p[k], &b.triangle(prev)).sqrt()
                };
                let bound = warm.min(upper_of(first + k));
                let (d2, t) = b.nearest_below(p[k], search_limit2(bound));
                o[k] = (d2.sqrt(), t);
                if t != u32::MAX {
                    prev = t;
                }
            }
        });
    out
}

/// Triangles per parallel chunk of the first passes; fixed so that the sums
/// are added in the same order on every run and machine.
const CHUNK: usize = 4096;

/// Sums over a chunk of A's triangles: area, the area-weighted distance and
/// squared distance (vertices 1/4, centroid 3/4), and the largest centroid distance.
#[derive(Debug, Clone, Copy, Default)]
struct Moments {
    area: f64,
    sum: f64,
    sum2: f64,
    max: f64,
}

/// A's triangles against B's BVH, as the cells of a [`Refinement`]. A seed is
/// a whole triangle of A by index: 16 bytes queued where a [`Cell`] takes 120,
/// so the queue of a mesh's own triangles stays small (issue 15: peak memory
/// of `compare`); only the triangles refined first become cells.
struct MeshCells<'a> {
    a: MeshRef<'a>,
    /// Distance to B and nearest triangle of B of each vertex of A.
    near: &'a [(f64, u32)],
    b: &'a Bvh,
    /// Whether a split's midpoint search may stop at any triangle within the
    /// largest distance found ([`split_cell`]): a supremum-only search;
    /// false where the distances feed a mean.
    supremum_only: bool,
}

impl MeshCells<'_> {
    /// The positions of triangle `t`'s vertices.
    fn vertices(&self, t: &[u32; 3]) -> [DVec3; 3] {
        t.map(|i| self.a.positions[i as usize])
    }

    /// The distances to B of triangle `t`'s vertices.
    fn distances(&self, t: &[u32; 3]) -> [f64; 3] {
        t.map(|i| self.near[i as usize].0)
    }

    /// An upper bound of the distance to B of centroid `c` of triangle `t`
    /// (vertices `v` at distances `f`): its distance to the B triangle
    /// nearest to each vertex, and each vertex's distance plus the way to the
    /// centroid. The first is near the centroid's own distance on a smooth
    /// pair of solids, where the second exceeds it by a third of the triangle,
    /// and a loose start makes the search visit every box within it.
    fn centroid_hint(&self, t: &[u32; 3], v: &[DVec3; 3], f: &[f64; 3], c: DVec3) -> f64 {
        (0..3)
            .map(|i| {
                let k = self.near[t[i] as usize].1;
                let via_triangle = if k == u32::MAX {
                    f64::INFINITY
                } else {
                    super::bvh::point_triangle_dist2(c, &self.b.triangle(k)).sqrt()
                };
                via_triangle.min(f[i] + c.distance(v[i]))
            })
            .fold(f64::INFINITY, f64::min)
    }

    /// Each chunk's [`Moments`] and the nearest B triangle of each of its
    /// triangles' centroids.
    ///
    /// Mean and RMS: vertex values alone can all be 0 when A's vertices lie on
    /// B (an interpolating reconstruction against the measured points), so
    /// each triangle's centroid is queried too (warm-started from its
    /// vertices) and weighted 3/4 against the vertices' 1/4. This pass comes
    /// before any triangle is queued: the centroids raise the lower bound, so
    /// fewer triangles need to wait for refinement.
    fn centroid_pass(&self) -> Vec<(Moments, Vec<u32>)> {
        self.a
            .triangles
            .par_chunks(CHUNK)
            .map(|chunk| {
                let mut m = Moments::default();
                let mut centroid_nearest = Vec::with_capacity(chunk.len());
                for t in chunk {
                    let (v, f) = (self.vertices(t), self.distances(t));
                    let c = (v[0] + v[1] + v[2]) / 3.0;
                    let hint = self.centroid_hint(t, &v, &f, c);
                    let (d2, kc) = self.b.nearest_below(c, search_limit2(hint));
                    let d = d2.sqrt();
                    centroid_nearest.push(kc);
                    let ar = area(&v);
                    m.area += ar;
                    m.sum += 0.25 * ar * (f[0] + f[1] + f[2]) / 3.0 + 0.75 * ar * d;
                    m.sum2 += 0.25 * ar * (f[0] * f[0] + f[1] * f[1] + f[2] * f[2]) / 3.0 + 0.75 * ar * d * d;
                    m.max = m.max.max(d);
                }
                (m, centroid_nearest)
            })
            .collect()
    }

    /// Queues as seeds the triangles of A whose upper bound needs refining
    /// (bounded over their vertices' and centroid's nearest B triangles),
    /// in parallel chunks; the rest are pruned.
    fn queue_triangles(&self, moments: &[(Moments, Vec<u32>)], refinement: &mut Refinement<Cell, u32>) {
        let r = &*refinement;
        let queued: Vec<(Vec<ByUpper<u32>>, f64)> = self
            .a
            .triangles
            .par_chunks(CHUNK)
            .zip(moments.par_iter())
            .enumerate()
            .map(|(ci, (chunk, (_, centroid_nearest)))| {
                let mut keep = Vec::new();
                let mut pruned = 0.0f64;
                for (j, t) in chunk.iter().enumerate() {
                    let k = t.map(|i| self.near[i as usize].1);
                    let candidates = [k[0], k[1], k[2], centroid_nearest[j]];
                    let ub = upper_bound(&self.vertices(t), &self.distances(t), &candidates, self.b);
                    if r.needs_refining(ub) {
                        keep.push(ByUpper {
                            ub,
                            item: (ci * CHUNK + j) as u32,
                        });
                    } else {
                        pruned = pruned.max(ub);
                    }
                }
                (keep, pruned)
            })
            .collect();
        refinement.reserve_seeds(queued.iter().map(|q| q.0.len()).sum());
        for (keep, pruned) in queued {
            refinement.add_seeds(keep, pruned);
        }
    }
}

impl Refine for MeshCells<'_> {
    type Cell = Cell;
    type Seed = u32;
    type Children = [ByUpper<Cell>; 4];
    const QUERIES_PER_SPLIT: usize = 3;

    fn expand(&self, t: u32) -> Cell {
        let t = &self.a.triangles[t as usize];
        Cell {
            v: self.vertices(t),
            f: self.distances(t),
            k: t.map(|i| self.near[i as usize].1),
        }
    }

    fn split(&self, c: &Cell, lb: &mut f64) -> Self::Children {
        split_cell(c, self.b, lb, self.supremum_only).map(|(v, f, k)| ByUpper {
            ub: upper_bound(&v, &f, &k, self.b),
            item: Cell { v, f, k },
        })
    }
}

/// One-sided Hausdorff distance h(A, B) to within `tolerance` (same unit as positions).
pub fn one_sided(a: MeshRef<'_>, b: &Bvh, tolerance: f64) -> OneSided {
    one_sided_below_bounds(a, b, tolerance, &[])
}

/// [`one_sided`], the same numbers, with `upper[i]` an upper bound of vertex
/// i's distance to B (empty: none) to start its nearest-triangle search
/// below ([`nearest_below_bounds`]).
pub fn one_sided_below_bounds(a: MeshRef<'_>, b: &Bvh, tolerance: f64, upper: &[f64]) -> OneSided {
    let near = nearest_below_bounds(a.positions, b, upper);
    let cells = MeshCells {
        a,
        near: &near,
        b,
        supremum_only: false,
    };
    let moments = cells.centroid_pass();
    let mut total = Moments::default();
    for (m, _) in &moments {
        total.area += m.area;
        total.sum += m.sum;
        total.sum2 += m.sum2;
        total.max = total.max.max(m.max);
    }
    let lb = near.iter().map(|x| x.0).fold(0.0, f64::max).max(total.max);
    let mut refinement = Refinement::new(lb, tolerance);
    cells.queue_triangles(&moments, &mut refinement);
    let refined = refinement.run(&cells, MAX_REFINEMENT_QUERIES);
    let (mean, rms) = if total.area > 0.0 {
        (total.sum / total.area, (total.sum2 / total.area).sqrt())
    } else {
        (0.0, 0.0)
    };
    OneSided {
        value: refined.lb,
        bound: (refined.ub - refined.lb).max(0.0),
        mean: Some(mean),
        rms: Some(rms),
        queries: near.len() + a.triangles.len() + refined.queries,
        converged: refined.converged,
    }
}

/// Triangles of A screened in the first round of [`one_sided_bounded`];
/// each round screens twice the last (most files need one or two rounds,
/// a smooth difference everywhere needs many), at most [`SCREEN_BATCH_MAX`].
const SCREEN_BATCH: usize = 256;
const SCREEN_BATCH_MAX: usize = 16_384;

/// h(A, B) alone, to within `tolerance`, searching only the triangles of A
/// that can set it: `upper[i]` must be an upper bound of vertex i's
/// distance to B (e.g. its distance to some triangles of B near it; the
/// certificate is only as good as these bounds). Mean and RMS are not
/// computed (`None`): they need every vertex.
///
/// Each triangle's Lipschitz bound from `upper` is an upper bound of
/// `d(·, B)` over it. Triangles are screened from the largest such bound
/// down, in batches: their vertices' and centroids' distances raise
/// the lower bound, and screening stops at the first bound within the
/// tolerance of it. Every triangle not screened is pruned with its bound
/// (so the certified upper bound covers all of A); the screened ones are
/// refined as [`one_sided`] refines every triangle.
pub fn one_sided_bounded(a: MeshRef<'_>, b: &Bvh, tolerance: f64, upper: &[f64]) -> OneSided {
    one_sided_bounded_within(a, b, tolerance, upper, &[])
}

/// [`one_sided_bounded`] with an upper bound of `d(·, B)` over each whole triangle
/// of A as well (`within[k]` for triangle k; empty: none), taken where it is lower
/// than the Lipschitz bound, in the screening order and for the screened triangles.
/// Two meshes with the same triangles give one ([`corresponding_bounds`]).
pub fn one_sided_bounded_within(a: MeshRef<'_>, b: &Bvh, tolerance: f64, upper: &[f64], within: &[f64]) -> OneSided {
    let upper_of = |i: u32| upper.get(i as usize).copied().unwrap_or(f64::INFINITY);
    let within_of = |k: u32| within.get(k as usize).copied().unwrap_or(f64::INFINITY);
    let mut order: Vec<(f64, u32)> = a
        .triangles
        .par_iter()
        .enumerate()
        .map(|(k, t)| {
            let v = t.map(|i| a.positions[i as usize]);
            (lipschitz_bound(&v, &t.map(upper_of)).min(within_of(k as u32)), k as u32)
        })
        .collect();
    let s = screen(a, b, tolerance.max(0.0), &mut order, upper_of, within_of);
    let cells = MeshCells {
        a,
        near: &s.near,
        b,
        supremum_only: true,
    };
    let mut refinement = Refinement::new(s.lb, tolerance);
    let kept: Vec<(Option<ByUpper<u32>>, f64)> = order[..s.screened]
        .par_iter()
        .zip(s.centroid_nearest.par_iter())
        .map(|(&(_, k), &kc)| {
            let t = &a.triangles[k as usize];
            let cand = [
                s.near[t[0] as usize].1,
                s.near[t[1] as usize].1,
                s.near[t[2] as usize].1,
                kc,
            ];
            let ub = upper_bound(&cells.vertices(t), &cells.distances(t), &cand, b);
            let whole = within_of(k);
            if whole < ub && !refinement.needs_refining(whole) {
                // The whole triangle's bound clears it: no piece needs refining.
                (None, whole)
            } else if refinement.needs_refining(ub) {
                (Some(ByUpper { ub, item: k }), 0.0)
            } else {
                (None, ub)
            }
        })
        .collect();
    let unscreened = order.get(s.screened).map_or(0.0, |x| x.0);
    let pruned = kept.iter().map(|x| x.1).fold(unscreened, f64::max);
    refinement.add_seeds(kept.into_iter().filter_map(|x| x.0).collect(), pruned);
    let refined = refinement.run(&cells, MAX_REFINEMENT_QUERIES);
    OneSided {
        value: refined.lb,
        bound: (refined.ub - refined.lb).max(0.0),
        mean: None,
        rms: None,
        queries: s.queries + refined.queries,
        converged: refined.converged,
    }
}

/// What the screening of [`one_sided_bounded`] found.
struct Screened {
    /// Each vertex's distance and nearest B triangle for the screened
    /// triangles' vertices, or an upper bound attained by the triangle given
    /// where the search stopped early ([`measure_batch`]); the upper bound and
    /// none (`u32::MAX`) for the rest and where the bound needed no search.
    near: Vec<(f64, u32)>,
    /// Largest distance evaluated.
    lb: f64,
    /// Distance queries made.
    queries: usize,
    /// How many triangles of the order were screened (a prefix).
    screened: usize,
    /// The nearest B triangle of each screened triangle's centroid, in order.
    centroid_nearest: Vec<u32>,
}

/// Screens the triangles of A in `order` (each with an upper bound of its
/// distance to B, in any order) from the largest bound down, in doubling
/// batches, until the next one's bound is within `tol` of the largest
/// distance found. On return `order` starts with the screened triangles in
/// the order they were screened, then the largest bound of the rest (with
/// the vertices' final distances), then the others.
///
/// Every batch tightens the bounds of the triangles around the vertices it
/// measured, so the rest are bounded again and ordered again: largest
/// bound first, ties by index, so the order is the same on every run. Only
/// the triangles still above the stop (bound > largest distance + `tol`)
/// can be screened, and a bound only falls while the largest distance only
/// rises: those are bounded and sorted after each batch, the others when a
/// batch reaches past them (the last) and at the end. The screened triangles and
/// the bound returned are those of a full sort after every batch (a full
/// sort and bound of every triangle after each batch was most of the
/// screening's time on a 434,000-triangle truth solid: BENCHMARKS.md).
fn screen(
    a: MeshRef<'_>,
    b: &Bvh,
    tol: f64,
    order: &mut [(f64, u32)],
    upper_of: impl Fn(u32) -> f64 + Sync,
    within_of: impl Fn(u32) -> f64 + Sync,
) -> Screened {
    let n = a.positions.len();
    let mut s = Screened {
        near: (0..n).map(|i| (upper_of(i as u32), u32::MAX)).collect(),
        lb: 0.0,
        queries: 0,
        screened: 0,
        centroid_nearest: Vec::new(),
    };
    let bound = |near: &[(f64, u32)], k: u32| {
        let t = &a.triangles[k as usize];
        let v = t.map(|i| a.positions[i as usize]);
        lipschitz_bound(&v, &t.map(|i| near[i as usize].0)).min(within_of(k))
    };
    let mut measured = vec![false; n];
    let mut batch_len = SCREEN_BATCH;
    // order = [screened | above the stop, sorted | the rest]
    let mut above = sort_above(order, s.lb + tol);
    let mut rebounded = false;
    while s.screened < order.len() && order[s.screened].0 > s.lb + tol {
        let end = (s.screened + batch_len).min(order.len());
        if end > above {
            // The batch reaches past the triangles above the stop: it takes
            // the largest of the rest, bounded now. The others stay below the
            // stop (their bounds only fall, the stop only rises), so this is
            // the last batch.
            let near = &s.near;
            order[above..].par_iter_mut().for_each(|(ub, k)| *ub = bound(near, *k));
            top_sorted(&mut order[above..], end - above);
            above = end;
        }
        let batch = &order[s.screened..end];
        batch_len = (2 * batch_len).min(SCREEN_BATCH_MAX);
        measure_batch(a, b, (batch, tol), &mut s, &mut measured, &upper_of);
        s.screened += batch.len();
        // The vertices just measured tighten the bounds of the triangles above the stop.
        let near = &s.near;
        order[s.screened..above]
            .par_iter_mut()
            .for_each(|(ub, k)| *ub = bound(near, *k));
        above = s.screened + sort_above(&mut order[s.screened..above], s.lb + tol);
        rebounded = true;
    }
    // The rest's largest bound, with the final distances, next in the order.
    if rebounded {
        let near = &s.near;
        order[above..].par_iter_mut().for_each(|(ub, k)| *ub = bound(near, *k));
    }
    top_sorted(&mut order[s.screened..], 1);
    s
}

/// Measures the vertices of `batch` not measured before (`measured`) and its
/// triangles' centroids against `b`, into `s` (distances, largest distance,
/// queries, the centroids' nearest triangles); `upper_of` bounds a vertex's
/// distance, `tol` is the screening's tolerance.
///
/// A point's search stops at the first triangle of B within its *accept*
/// radius, which is at most the largest distance found before the batch, so
/// a point stopped there could not have raised it: the largest distance is
/// the one the full searches give. A vertex's radius is also at most
/// `lb + tol − L/√3`, L the longest edge of its triangles in the batch, so
/// every triangle of the batch whose vertices all stop there has a
/// Lipschitz bound within the stop and needs no refining. Where B is nearly
/// equidistant from the point (deep inside a solid far from the other), the
/// full search opens every box about as near as the nearest triangle; the
/// stopped one opens one path. Such a vertex keeps an upper bound of its
/// distance and a triangle of B within it, which is all the bounds use.
fn measure_batch(
    a: MeshRef<'_>,
    b: &Bvh,
    (batch, tol): (&[(f64, u32)], f64),
    s: &mut Screened,
    measured: &mut [bool],
    upper_of: &(impl Fn(u32) -> f64 + Sync),
) {
    let lb = s.lb;
    // (vertex, L/√3 of its longest triangle in the batch), one entry a vertex.
    let mut fresh: Vec<(u32, f64)> = batch
        .iter()
        .flat_map(|&(_, k)| {
            let t = a.triangles[k as usize];
            let slack = longest_edge(&t.map(|i| a.positions[i as usize])) / 3f64.sqrt();
            t.map(|i| (i, slack))
        })
        .filter(|&(i, _)| !measured[i as usize])
        .collect();
    fresh.sort_unstable_by(|x, y| x.0.cmp(&y.0).then(y.1.total_cmp(&x.1)));
    fresh.dedup_by_key(|x| x.0);
    let found: Vec<(f64, u32)> = fresh
        .par_iter()
        .map(|&(i, slack)| {
            let accept = lb.min(lb + tol - slack);
            let upper = upper_of(i);
            if upper <= accept {
                // Its bound is already as good as any answer: no search.
                return (upper, u32::MAX);
            }
            nearest_within(b, a.positions[i as usize], upper, accept)
        })
        .collect();
    for (&(i, _), &d) in fresh.iter().zip(&found) {
        s.near[i as usize] = d;
        measured[i as usize] = true;
        s.lb = s.lb.max(d.0);
    }
    let near = &s.near;
    let centroids: Vec<(f64, u32)> = batch
        .par_iter()
        .map(|&(_, k)| {
            let t = &a.triangles[k as usize];
            let v = t.map(|i| a.positions[i as usize]);
            let c = (v[0] + v[1] + v[2]) / 3.0;
            let hint = (0..3)
                .map(|i| near[t[i] as usize].0 + c.distance(v[i]))
                .fold(f64::INFINITY, f64::min);
            // A centroid's distance only raises the largest one: anything within it will do.
            if hint <= lb {
                return (hint, u32::MAX);
            }
            nearest_within(b, c, hint, lb)
        })
        .collect();
    s.queries += found.iter().chain(&centroids).filter(|d| d.1 != u32::MAX).count();
    s.lb = centroids.iter().fold(s.lb, |m, c| m.max(c.0));
    s.centroid_nearest.extend(centroids.iter().map(|c| c.1));
}

/// The longest edge of a triangle.
fn longest_edge(v: &[DVec3; 3]) -> f64 {
    v[0].distance(v[1]).max(v[1].distance(v[2])).max(v[2].distance(v[0]))
}

/// Largest bound first; ties by index, so the screening order is the same on every run.
fn by_bound(x: &(f64, u32), y: &(f64, u32)) -> std::cmp::Ordering {
    y.0.total_cmp(&x.0).then(x.1.cmp(&y.1))
}

/// Moves the entries of `order` whose bound is above `stop` to its front,
/// sorted [`by_bound`], and returns how many there are.
fn sort_above(order: &mut [(f64, u32)], stop: f64) -> usize {
    let mut n = 0;
    for i in 0..order.len() {
        if order[i].0 > stop {
            order.swap(i, n);
            n += 1;
        }
    }
    order[..n].par_sort_unstable_by(by_bound);
    n
}

/// Puts the first `m` entries of `order` [`by_bound`] at its front, sorted.
fn top_sorted(order: &mut [(f64, u32)], m: usize) {
    let m = m.min(order.len());
    if m == 0 {
        return;
    }
    if m < order.len() {
        order.select_nth_unstable_by(m - 1, by_bound);
    }
    order[..m].par_sort_unstable_by(by_bound);
}

/// Distance and nearest triangle of `b` from `p`, whose distance is at most
/// `hint`: the search skips everything farther. Should nothing lie within
/// the hint (a bound that was not one), the search is repeated unbounded, so
/// the distance returned is always attained. The search stops at the first
/// triangle within `accept` (cd; 0 or less: never), whose distance is then
/// returned: an upper bound of the distance, attained by that triangle.
fn nearest_within(b: &Bvh, p: DVec3, hint: f64, accept: f64) -> (f64, u32) {
    let accept2 = if accept > 0.0 {
        accept * accept
    } else {
        f64::NEG_INFINITY
    };
    let (d2, t) = if hint.is_finite() {
        let (d2, t, _) = b.nearest_below_or_within(p, search_limit2(hint), accept2);
        (d2, t)
    } else {
        (f64::INFINITY, u32::MAX)
    };
    if t == u32::MAX {
        let (d2, t, _) = b.nearest_below_or_within(p, f64::INFINITY, accept2);
        return (d2.sqrt(), t);
    }
    (d2.sqrt(), t)
}

/// One side of a two-sided search: a mesh held by its BVH, the triangles it was
/// built from, and upper bounds of its vertices' distances to the other mesh
/// (same unit as the mesh; empty where a search takes none).
pub type Side<'a> = (&'a Bvh, &'a [[u32; 3]], &'a [f64]);

/// [`hausdorff_bvh`] searching only for the supremum on each side
/// ([`one_sided_bounded`]): each side is (BVH, triangles, upper bounds of
/// its vertices' distances to the other mesh). No mean or RMS.
pub fn hausdorff_bvh_bounded(a: Side<'_>, b: Side<'_>, tolerance: f64) -> Hausdorff {
    both_sides(a, b, tolerance, one_sided_bounded)
}

/// H from `one_sided` run on each side in parallel (A against B's BVH with
/// A's bounds, and B against A's).
fn both_sides(
    a: Side<'_>,
    b: Side<'_>,
    tolerance: f64,
    one_sided: impl Fn(MeshRef<'_>, &Bvh, f64, &[f64]) -> OneSided + Sync,
) -> Hausdorff {
    let (ma, mb) = (mesh_of(a.0, a.1), mesh_of(b.0, b.1));
    let (ab, ba) = rayon::join(
        || one_sided(ma, b.0, tolerance, a.2),
        || one_sided(mb, a.0, tolerance, b.2),
    );
    Hausdorff::of_sides(ab, ba)
}

/// [`hausdorff_bvh_bounded`] with an upper bound of each triangle's distance to the
/// other mesh (`within.0` for A's triangles, `within.1` for B's;
/// [`one_sided_bounded_within`]).
pub fn hausdorff_bvh_bounded_within(a: Side<'_>, b: Side<'_>, tolerance: f64, within: (&[f64], &[f64])) -> Hausdorff {
    let (ma, mb) = (mesh_of(a.0, a.1), mesh_of(b.0, b.1));
    let (ab, ba) = rayon::join(
        || one_sided_bounded_within(ma, b.0, tolerance, a.2, within.0),
        || one_sided_bounded_within(mb, a.0, tolerance, b.2, within.1),
    );
    Hausdorff::of_sides(ab, ba)
}

/// Upper bounds of each triangle's distance to the other mesh for two meshes with
/// the same triangles (vertex i of one corresponds to vertex i of the other; the
/// caller checks the triangle lists are equal): a point Σ λ_i a_i of triangle
/// (a_1, a_2, a_3) is within |Σ λ_i (a_i − b_i)| ≤ max_i |a_i − b_i| of the point
/// Σ λ_i b_i of the other mesh's triangle (b_1, b_2, b_3), whatever the shapes. The
/// bound holds for both meshes' triangles alike; the margin (1e-9 relative plus
/// 1e-7 of `scale`, the larger mesh's radius) covers rounding.
pub fn corresponding_bounds(a: &[DVec3], b: &[DVec3], triangles: &[[u32; 3]], scale: f64) -> Vec<f64> {
    let margin = 1e-7 * scale;
    triangles
        .par_iter()
        .map(|t| {
            let d = t
                .map(|i| a[i as usize].distance(b[i as usize]))
                .into_iter()
                .fold(0.0, f64::max);
            d * (1.0 + 1e-9) + margin
        })
        .collect()
}

/// The mesh a BVH holds, with the triangles it was built from.
fn mesh_of<'a>(b: &'a Bvh, triangles: &'a [[u32; 3]]) -> MeshRef<'a> {
    MeshRef {
        positions: b.positions(),
        triangles,
    }
}

impl Hausdorff {
    /// The symmetric distance of two one-sided ones: the larger attained
    /// value, and the gap to the larger certified upper bound.
    pub(crate) fn of_sides(a_to_b: OneSided, b_to_a: OneSided) -> Self {
        let value = a_to_b.value.max(b_to_a.value);
        let ub = (a_to_b.value + a_to_b.bound).max(b_to_a.value + b_to_a.bound);
        Hausdorff {
            value,
            bound: (ub - value).max(0.0),
            a_to_b,
            b_to_a,
        }
    }
}

/// The four children of `c` (its edge midpoints queried against `b`, each
/// warm-started from the parent's vertices by the Lipschitz bound); raises
/// `lb` to the largest midpoint distance.
///
/// With `supremum_only`, a midpoint's search stops at the first triangle
/// within `lb`: a midpoint that near cannot raise `lb`, and the children
/// are bounded with the distance to that triangle, an upper bound of the
/// midpoint's. A child whose bound is then above the tolerance is split
/// again, as it would be on the exact distance whenever that is within the
/// tolerance of `lb` too: the exact search is skipped where it costs most,
/// at points about equidistant from much of B (a point on the axis of a
/// rotational solid is as near to a whole ring of its triangles).
fn split_cell(c: &Cell, b: &Bvh, lb: &mut f64, supremum_only: bool) -> [([DVec3; 3], [f64; 3], [u32; 3]); 4] {
    let mid = |i: usize, j: usize| 0.5 * (c.v[i] + c.v[j]);
    let m = [mid(0, 1), mid(1, 2), mid(2, 0)];
    let accept = if supremum_only { *lb } else { f64::NEG_INFINITY };
    let mut fm = [0.0; 3];
    let mut km = [u32::MAX; 3];
    for j in 0..3 {
        let hint = (0..3)
            .map(|i| c.f[i] + m[j].distance(c.v[i]))
            .fold(f64::INFINITY, f64::min);
        let (d, t) = nearest_within(b, m[j], hint, accept);
        fm[j] = d;
        km[j] = t;
        *lb = lb.max(fm[j]);
    }
    [
        ([c.v[0], m[0], m[2]], [c.f[0], fm[0], fm[2]], [c.k[0], km[0], km[2]]),
        ([m[0], c.v[1], m[1]], [fm[0], c.f[1], fm[1]], [km[0], c.k[1], km[1]]),
        ([m[2], m[1], c.v[2]], [fm[2], fm[1], c.f[2]], [km[2], km[1], c.k[2]]),
        ([m[0], m[1], m[2]], [fm[0], fm[1], fm[2]], km),
    ]
}

/// Symmetric Hausdorff distance between `a` and `b` to within `tolerance`.
/// Either mesh empty gives infinity (no point of the other is near anything).
pub fn hausdorff(a: MeshRef<'_>, b: MeshRef<'_>, tolerance: f64) -> Hausdorff {
    let (ba, bb) = rayon::join(
        || Bvh::build(a.positions, a.triangles),
        || Bvh::build(b.positions, b.triangles),
    );
    hausdorff_bvh((&ba, a.triangles), (&bb, b.triangles), tolerance)
}

/// [`hausdorff`] over meshes already held by their BVHs (positions from
/// [`Bvh::positions`], triangles as given to the build).
pub fn hausdorff_bvh(a: (&Bvh, &[[u32; 3]]), b: (&Bvh, &[[u32; 3]]), tolerance: f64) -> Hausdorff {
    hausdorff_bvh_below_bounds((a.0, a.1, &[]), (b.0, b.1, &[]), tolerance)
}

/// [`hausdorff_bvh`], the same numbers, each side with upper bounds of its
/// vertices' distances to the other mesh (empty: none) to start the searches
/// below ([`one_sided_below_bounds`]).
pub fn hausdorff_bvh_below_bounds(a: Side<'_>, b: Side<'_>, tolerance: f64) -> Hausdorff {
    both_sides(a, b, tolerance, one_sided_below_bounds)
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// A UV sphere of radius r centred at c.
    pub(crate) fn sphere(r: f64, c: [f64; 3], n_lat: usize, n_lon: usize) -> (Vec<DVec3>, Vec<[u32; 3]>) {
        let mut pos = vec![DVec3::new(c[0], c[1], c[2] - r)];
        for i in 1..n_lat {
            let th = std::f64::consts::PI * i as f64 / n_lat as f64;
            for j in 0..n_lon {
                let ph = 2.0 * std::f64::consts::PI * j as f64 / n_lon as f64;
                pos.push(DVec3::new(
                    c[0] + r * th.sin() * ph.cos(),
                    c[1] + r * th.sin() * ph.sin(),
                    c[2] - r * th.cos(),
                ));
            }
        }
        pos.push(DVec3::new(c[0], c[1], c[2] + r));
        let top = (pos.len() - 1) as u32;
        let idx = |i: usize, j: usize| (1 + (i - 1) * n_lon + (j % n_lon)) as u32;
        let mut t = Vec::new();
        for j in 0..n_lon {
            t.push([0, idx(1, j + 1), idx(1, j)]);
            t.push([top, idx(n_lat - 1, j), idx(n_lat - 1, j + 1)]);
        }
        for i in 1..n_lat - 1 {
            for j in 0..n_lon {
                t.push([idx(i, j), idx(i, j + 1), idx(i + 1, j)]);
                t.push([idx(i, j + 1), idx(i + 1, j + 1), idx(i + 1, j)]);
            }
        }
        (pos, t)
    }

    #[test]
    fn queued_triangles_stay_small() {
        // Issue 15: a mesh's own triangles wait as 16-byte seeds, not 120-byte cells.
        assert_eq!(std::mem::size_of::<ByUpper<u32>>(), 16);
        assert_eq!(std::mem::size_of::<ByUpper<Cell>>(), 120);
    }

    type Solid = (Vec<DVec3>, Vec<[u32; 3]>);

    /// A sphere of radius 10 and the two solids it is searched against: the
    /// same sphere with a bump (a few vertices pushed out along their rays),
    /// and a larger, shifted sphere (different everywhere).
    fn sphere_bumped_and_shifted() -> (Solid, [Solid; 2]) {
        let a = sphere(10.0, [0.0; 3], 40, 80);
        let (mut p2, t2) = sphere(10.0, [0.0; 3], 40, 80);
        for p in p2.iter_mut().filter(|p| p.z > 9.5) {
            *p *= 1.3;
        }
        (a, [(p2, t2), sphere(11.0, [0.4, -0.2, 0.1], 30, 60)])
    }

    /// Upper bounds of each vertex's distance to `b` (`exact`, the distances
    /// themselves): tight, loose and none.
    fn vertex_bounds(exact: &[f64]) -> [(&'static str, Vec<f64>); 3] {
        [
            ("tight", exact.iter().map(|d| d * (1.0 + 1e-9) + 1e-9).collect()),
            ("loose", exact.iter().map(|d| 2.0 * d + 1.0).collect()),
            ("none", vec![f64::INFINITY; exact.len()]),
        ]
    }

    /// The pruned search certifies the same H as the full one: on meshes
    /// that differ in one place (a bump), everywhere (offset spheres), and
    /// with A deep inside B (a small sphere within a large one, each point
    /// about as near to much of B: the searches that stop within the largest
    /// distance), with tight vertex bounds, loose ones and none (every
    /// triangle screened), both intervals [value, value + bound] overlap, the
    /// bound is within the tolerance, and on the bump a tight bound queries far less.
    #[test]
    fn bounded_search_certifies_the_full_searchs_h() {
        let (sphere_a, [bumped, shifted]) = sphere_bumped_and_shifted();
        let deep = (sphere(1.0, [0.2, -0.1, 0.3], 20, 40), sphere(12.0, [0.0; 3], 50, 100));
        let tol = 1e-3;
        for (case, ((pa, ta), (pb, tb))) in [
            ("bump", (&sphere_a, &bumped)),
            ("shifted", (&sphere_a, &shifted)),
            ("deep inside", (&deep.0, &deep.1)),
        ] {
            let ma = MeshRef {
                positions: pa,
                triangles: ta,
            };
            let bvh_b = Bvh::build(pb, tb);
            let full = one_sided(ma, &bvh_b, tol);
            for (name, upper) in vertex_bounds(&distances(pa, &bvh_b)) {
                let b = one_sided_bounded(ma, &bvh_b, tol, &upper);
                assert!(b.converged && b.bound <= tol + 1e-12, "{case}, {name}: {b:?}");
                assert!(
                    b.value <= full.value + full.bound + 1e-12 && full.value <= b.value + b.bound + 1e-12,
                    "{case}, {name}: bounded {b:?} vs full {full:?}"
                );
                assert!(b.mean.is_none() && b.rms.is_none());
                if case == "bump" && name == "tight" {
                    assert!(
                        b.queries * 4 < full.queries,
                        "{name}: {} vs {} queries",
                        b.queries,
                        full.queries
                    );
                }
            }
        }
    }

    /// The screening as it was: every triangle bounded again and the whole
    /// rest sorted after each batch. [`screen`] must screen the same
    /// triangles in the same order, find the same distances and return the
    /// same largest bound of the rest.
    fn screen_by_full_sorts(
        a: MeshRef<'_>,
        b: &Bvh,
        tol: f64,
        order: &mut [(f64, u32)],
        upper: &[f64],
        within: &[f64],
    ) -> Screened {
        let n = a.positions.len();
        let mut s = Screened {
            near: (0..n).map(|i| (upper[i], u32::MAX)).collect(),
            lb: 0.0,
            queries: 0,
            screened: 0,
            centroid_nearest: Vec::new(),
        };
        order.sort_by(by_bound);
        let mut measured = vec![false; n];
        let mut batch_len = SCREEN_BATCH;
        while s.screened < order.len() && order[s.screened].0 > s.lb + tol {
            let end = (s.screened + batch_len).min(order.len());
            batch_len = (2 * batch_len).min(SCREEN_BATCH_MAX);
            let lb = s.lb;
            let mut fresh: Vec<u32> = order[s.screened..end]
                .iter()
                .flat_map(|&(_, k)| a.triangles[k as usize])
                .filter(|&i| !measured[i as usize])
                .collect();
            fresh.sort_unstable();
            fresh.dedup();
            for i in fresh {
                // The accept radius from the vertex's longest triangle in the batch.
                let slack = order[s.screened..end]
                    .iter()
                    .map(|&(_, k)| a.triangles[k as usize])
                    .filter(|t| t.contains(&i))
                    .map(|t| longest_edge(&t.map(|j| a.positions[j as usize])) / 3f64.sqrt())
                    .fold(f64::NEG_INFINITY, f64::max);
                let accept = lb.min(lb + tol - slack);
                measured[i as usize] = true;
                if upper[i as usize] <= accept {
                    continue;
                }
                s.near[i as usize] = nearest_within(b, a.positions[i as usize], upper[i as usize], accept);
                s.lb = s.lb.max(s.near[i as usize].0);
                s.queries += 1;
            }
            for &(_, k) in &order[s.screened..end] {
                let t = &a.triangles[k as usize];
                let v = t.map(|i| a.positions[i as usize]);
                let c = (v[0] + v[1] + v[2]) / 3.0;
                let hint = (0..3)
                    .map(|i| s.near[t[i] as usize].0 + c.distance(v[i]))
                    .fold(f64::INFINITY, f64::min);
                if hint <= lb {
                    s.centroid_nearest.push(u32::MAX);
                    continue;
                }
                let d = nearest_within(b, c, hint, lb);
                s.centroid_nearest.push(d.1);
                s.lb = s.lb.max(d.0);
                s.queries += 1;
            }
            s.screened = end;
            for (ub, k) in order[s.screened..].iter_mut() {
                let t = &a.triangles[*k as usize];
                let v = t.map(|i| a.positions[i as usize]);
                *ub = lipschitz_bound(&v, &t.map(|i| s.near[i as usize].0)).min(within[*k as usize]);
            }
            order[s.screened..].sort_by(by_bound);
        }
        s
    }

    /// [`screen`] bounds and sorts only the triangles that can still be
    /// screened, and gives what the full bound and sort after every batch
    /// gave: the same screened triangles in the same order, the same
    /// distances and nearest triangles, queries and largest distance, and
    /// the same bounds of the rest, the largest next. Bumped and shifted spheres, with
    /// tight, loose and no vertex bounds and with and without whole-triangle
    /// bounds, at tolerances that stop at once, early and late.
    #[test]
    fn screening_is_the_full_sorts_screening() {
        let ((p1, t1), others) = sphere_bumped_and_shifted();
        let ma = MeshRef {
            positions: &p1,
            triangles: &t1,
        };
        let mut screened_any = false;
        for (pb, tb) in &others {
            let bvh_b = Bvh::build(pb, tb);
            let sampled: Vec<f64> = (0..t1.len()).map(|k| 0.5 + (k % 7) as f64).collect();
            let no_within = vec![f64::INFINITY; t1.len()];
            for (_, upper) in vertex_bounds(&distances(&p1, &bvh_b)) {
                for within in [&no_within, &sampled] {
                    for tol in [1e-3, 0.05, 0.5, 100.0] {
                        let start: Vec<(f64, u32)> = t1
                            .iter()
                            .enumerate()
                            .map(|(k, t)| {
                                let v = t.map(|i| p1[i as usize]);
                                (
                                    lipschitz_bound(&v, &t.map(|i| upper[i as usize])).min(within[k]),
                                    k as u32,
                                )
                            })
                            .collect();
                        let (mut got_order, mut want_order) = (start.clone(), start);
                        let got = screen(
                            ma,
                            &bvh_b,
                            tol,
                            &mut got_order,
                            |i| upper[i as usize],
                            |k| within[k as usize],
                        );
                        let want = screen_by_full_sorts(ma, &bvh_b, tol, &mut want_order, &upper, within);
                        assert_eq!(got.screened, want.screened, "tol {tol}");
                        assert_eq!(got_order[..got.screened], want_order[..want.screened], "tol {tol}");
                        assert_eq!(got_order.get(got.screened), want_order.get(want.screened), "tol {tol}");
                        // Every bound of the rest, with the final distances, as the full sort left them.
                        let mut rest = got_order[got.screened..].to_vec();
                        rest.sort_by(by_bound);
                        assert_eq!(rest, want_order[want.screened..], "tol {tol}");
                        assert_eq!(got.near, want.near, "tol {tol}");
                        assert_eq!(got.centroid_nearest, want.centroid_nearest, "tol {tol}");
                        assert_eq!((got.lb, got.queries), (want.lb, want.queries), "tol {tol}");
                        screened_any |= got.screened > SCREEN_BATCH && got.screened < t1.len();
                    }
                }
            }
        }
        assert!(
            screened_any,
            "no case screened past the first batch and stopped before the end"
        );
    }

    /// Two meshes with the same triangles, the second bumped and twisted: the
    /// corresponding-vertex bound of each triangle holds over it (sampled at
    /// barycentric points), and the search that takes it certifies the full search's
    /// h with fewer queries than the search without it.
    #[test]
    fn corresponding_bounds_certify_the_full_searchs_h() {
        let ((p1, t1), [(mut p2, t2), _]) = sphere_bumped_and_shifted();
        assert_eq!(t1, t2);
        // A twist too: every vertex moved sideways a little, so no vertex keeps its ray.
        for p in p2.iter_mut() {
            *p += DVec3::new(0.02 * p.y, -0.02 * p.x, 0.01);
        }
        let within = corresponding_bounds(&p1, &p2, &t1, 13.0);
        let (ma, mb) = (
            MeshRef {
                positions: &p1,
                triangles: &t1,
            },
            MeshRef {
                positions: &p2,
                triangles: &t2,
            },
        );
        let bvh_b = Bvh::build(mb.positions, mb.triangles);
        for (k, t) in t1.iter().enumerate().step_by(97) {
            for (l1, l2) in [(0.2, 0.3), (0.6, 0.1), (1.0 / 3.0, 1.0 / 3.0), (0.05, 0.9)] {
                let q = p1[t[0] as usize] * l1 + p1[t[1] as usize] * l2 + p1[t[2] as usize] * (1.0 - l1 - l2);
                let d = distances(&[q], &bvh_b)[0];
                assert!(d <= within[k], "triangle {k}: {d} > {}", within[k]);
            }
        }
        let tol = 1e-3;
        let full = one_sided(ma, &bvh_b, tol);
        let exact = distances(&p1, &bvh_b);
        let upper: Vec<f64> = exact.iter().map(|d| 2.0 * d + 1.0).collect();
        let plain = one_sided_bounded(ma, &bvh_b, tol, &upper);
        let with = one_sided_bounded_within(ma, &bvh_b, tol, &upper, &within);
        assert!(with.converged && with.bound <= tol + 1e-12, "{with:?}");
        assert!(
            with.value <= full.value + full.bound + 1e-12 && full.value <= with.value + with.bound + 1e-12,
            "with the triangle bounds {with:?} vs full {full:?}"
        );
        // Both prune: the searches stopped within the largest distance already
        // make the plain one cheap here, so the two are not ordered.
        for (name, q) in [("with", with.queries), ("plain", plain.queries)] {
            assert!(q * 4 < full.queries, "{name}: {q} vs {} queries", full.queries);
        }
    }

    #[test]
    fn concentric_spheres_give_the_radius_difference() {
        let (p1, t1) = sphere(10.0, [0.0; 3], 40, 80);
        let (p2, t2) = sphere(12.0, [0.0; 3], 50, 100);
        let h = hausdorff(
            MeshRef {
                positions: &p1,
                triangles: &t1,
            },
            MeshRef {
                positions: &p2,
                triangles: &t2,
            },
            1e-3,
        );
        // Polygonal spheres: the inscribed facets sit inside the true spheres by at most
        // r (1 − cos(half the angular step)), so H lies within that of |r1 − r2| = 2.
        let sag = 12.0 * (1.0 - (std::f64::consts::PI / 50.0).cos());
        assert!((h.value - 2.0).abs() <= sag + 1e-3, "{h:?}");
        assert!(h.bound <= 1e-3 + 1e-12);
        // h(big -> small) is the larger side (the big sphere's vertices are 2 away; the
        // small sphere's facet centres are farther from the big sphere than its vertices).
        assert!(h.a_to_b.value >= 2.0 - 1e-9);
    }

    #[test]
    fn identical_meshes_give_zero_without_refinement() {
        // Each triangle's centroid has the triangle itself as its nearest: the convexity
        // bound over it is 0, so nothing waits for refinement (issue 12: 8 s on 323 k triangles).
        let (p, t) = sphere(10.0, [0.0; 3], 60, 120);
        let m = MeshRef {
            positions: &p,
            triangles: &t,
        };
        let h = hausdorff(m, m, 1e-9);
        // Centroids differ from the triangle by round-off only (1e-15 of the radius).
        assert!(h.value <= 1e-12 && h.bound == 0.0, "{h:?}");
        assert_eq!(h.a_to_b.queries, p.len() + t.len());
        assert!(h.a_to_b.converged && h.b_to_a.converged);
    }

    #[test]
    fn bound_is_certified_against_dense_sampling() {
        // Offset spheres: the sup lies inside faces, not only at vertices.
        let (p1, t1) = sphere(10.0, [0.0; 3], 12, 24);
        let (p2, t2) = sphere(10.0, [1.5, 0.0, 0.0], 12, 24);
        let a = MeshRef {
            positions: &p1,
            triangles: &t1,
        };
        let bvh = Bvh::build(&p2, &t2);
        let h = one_sided(a, &bvh, 1e-4);
        // Dense barycentric sampling never exceeds the certified upper bound.
        let mut dense: f64 = 0.0;
        for t in &t1 {
            let v = [p1[t[0] as usize], p1[t[1] as usize], p1[t[2] as usize]];
            for i in 0..=20 {
                for j in 0..=(20 - i) {
                    let (u, w) = (i as f64 / 20.0, j as f64 / 20.0);
                    let x = v[0] + u * (v[1] - v[0]) + w * (v[2] - v[0]);
                    dense = dense.max(bvh.distance(x));
                }
            }
        }
        assert!(
            dense <= h.value + h.bound + 1e-9,
            "dense {dense} > {} + {}",
            h.value,
            h.bound
        );
        assert!(
            h.value >= dense - 0.05,
            "refinement found {} but sampling {dense}",
            h.value
        );
    }
}
