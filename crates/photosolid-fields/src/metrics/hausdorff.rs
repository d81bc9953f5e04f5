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

mod screened;
use screened::nearest_within;
pub use screened::{one_sided_bounded, one_sided_bounded_within};

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
pub(crate) mod tests;
