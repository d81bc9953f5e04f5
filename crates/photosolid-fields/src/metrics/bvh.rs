//! A bounding-volume hierarchy over triangles for exact closest-point queries.
//!
//! Binary tree of axis-aligned boxes, built top-down by splitting the
//! centroids at the median of the box's longest axis (leaves of at most
//! [`LEAF_SIZE`] triangles), stored flat. A query descends nearest child
//! first and prunes every box farther than the best distance found, so the
//! result is the exact (f64) distance to the closest triangle.

use glam::DVec3;

/// Triangles per leaf. Leaves of 4 query 10 % faster than leaves of 8
/// (`benches/compare.rs`) for about 16 bytes more per triangle of nodes
/// (BENCHMARKS.md, "Peak memory").
pub const LEAF_SIZE: usize = 4;

/// Axis-aligned box.
#[derive(Debug, Clone, Copy)]
struct Aabb {
    lo: DVec3,
    hi: DVec3,
}

impl Aabb {
    fn empty() -> Self {
        Self {
            lo: DVec3::INFINITY,
            hi: DVec3::NEG_INFINITY,
        }
    }
    fn grow(&mut self, p: DVec3) {
        self.lo = self.lo.min(p);
        self.hi = self.hi.max(p);
    }
    /// Squared distance from p to the box (0 inside).
    #[inline]
    fn dist2(&self, p: DVec3) -> f64 {
        // Per axis: lo − p below the box, p − hi above it, 0 inside.
        let v = (self.lo - p).max(p - self.hi).max(DVec3::ZERO);
        v.dot(v)
    }
}

#[derive(Debug, Clone, Copy)]
struct Node {
    bounds: Aabb,
    /// Leaf: first triangle in `tris` (leaf order); inner: index of the left child (right = left + 1).
    start: u32,
    /// Leaf: triangle count (> 0); inner: 0.
    count: u32,
}

/// A BVH over a triangle mesh (positions in any consistent unit, e.g. cd).
///
/// Memory: a copy of the vertex positions (24 bytes a vertex) and the
/// triangles as vertex indices in leaf order (12 bytes each), so a leaf's
/// triangles are contiguous; about 50 bytes per triangle with the nodes, where
/// three f64 corners per triangle took 72 bytes alone (issue 15, peak memory).
#[derive(Debug, Clone)]
pub struct Bvh {
    nodes: Vec<Node>,
    positions: Vec<DVec3>,
    tris: Vec<[u32; 3]>,
}

impl Bvh {
    /// Build over `triangles` (indices into `positions`), copying the positions.
    pub fn build(positions: &[DVec3], triangles: &[[u32; 3]]) -> Self {
        Self::build_owned(positions.to_vec(), triangles)
    }

    /// Build over `triangles` (indices into `positions`), keeping `positions`
    /// without a copy (see [`Bvh::positions`]).
    pub fn build_owned(positions: Vec<DVec3>, triangles: &[[u32; 3]]) -> Self {
        let corners = |t: u32| triangles[t as usize].map(|i| positions[i as usize]);
        let centroids: Vec<DVec3> = (0..triangles.len() as u32)
            .map(|t| {
                let v = corners(t);
                (v[0] + v[1] + v[2]) / 3.0
            })
            .collect();
        let mut order: Vec<u32> = (0..triangles.len() as u32).collect();
        let mut nodes = Vec::with_capacity(2 * triangles.len() / LEAF_SIZE + 2);
        nodes.push(Node {
            bounds: Aabb::empty(),
            start: 0,
            count: 0,
        });
        // Explicit stack: (node index, start, end).
        let mut stack = vec![(0usize, 0usize, triangles.len())];
        while let Some((ni, s, e)) = stack.pop() {
            let mut b = Aabb::empty();
            for &t in &order[s..e] {
                for p in corners(t) {
                    b.grow(p);
                }
            }
            nodes[ni].bounds = b;
            if e - s <= LEAF_SIZE {
                nodes[ni].start = s as u32;
                nodes[ni].count = (e - s) as u32;
                continue;
            }
            let mut cb = Aabb::empty();
            for &t in &order[s..e] {
                cb.grow(centroids[t as usize]);
            }
            let extent = cb.hi - cb.lo;
            let axis = (0..3).max_by(|&a, &b| extent[a].total_cmp(&extent[b])).unwrap_or(0);
            let mid = (s + e) / 2;
            order[s..e].select_nth_unstable_by(mid - s, |&a, &b| {
                centroids[a as usize][axis].total_cmp(&centroids[b as usize][axis])
            });
            let left = nodes.len();
            nodes.push(Node {
                bounds: Aabb::empty(),
                start: 0,
                count: 0,
            });
            nodes.push(Node {
                bounds: Aabb::empty(),
                start: 0,
                count: 0,
            });
            nodes[ni].start = left as u32;
            nodes[ni].count = 0;
            stack.push((left, s, mid));
            stack.push((left + 1, mid, e));
        }
        drop(centroids);
        // Leaves hold `start..start + count` of the triangles in this order.
        let tris = order.iter().map(|&t| triangles[t as usize]).collect();
        Self { nodes, positions, tris }
    }

    /// The vertex positions the BVH was built over.
    pub fn positions(&self) -> &[DVec3] {
        &self.positions
    }

    /// Number of triangles.
    pub fn len(&self) -> usize {
        self.tris.len()
    }

    /// True when there are no triangles.
    pub fn is_empty(&self) -> bool {
        self.tris.is_empty()
    }

    /// Exact distance from `p` to the closest triangle (infinity when empty).
    pub fn distance(&self, p: DVec3) -> f64 {
        self.distance2_below(p, f64::INFINITY).sqrt()
    }

    /// Squared distance to the closest triangle, searching only below `best2`
    /// (a known upper bound, e.g. from a neighbouring query).
    pub fn distance2_below(&self, p: DVec3, best2: f64) -> f64 {
        self.nearest_below(p, best2).0
    }

    /// The triangle `i` (as numbered by [`Bvh::nearest_below`]) as three points.
    pub fn triangle(&self, i: u32) -> [DVec3; 3] {
        self.tris[i as usize].map(|v| self.positions[v as usize])
    }

    /// Squared distance to the closest triangle and its index (in leaf
    /// order, for [`Bvh::triangle`]), searching only below `best2`. The index
    /// is `u32::MAX` when nothing lies below `best2`.
    pub fn nearest_below(&self, p: DVec3, best2: f64) -> (f64, u32) {
        let (d2, t, _) = self.nearest_below_or_within(p, best2, f64::NEG_INFINITY);
        (d2, t)
    }

    /// [`Bvh::nearest_below`] that stops at the first triangle whose squared
    /// distance is at most `accept2`: the third value says whether the search
    /// ran to the end (`true`: the distance and nearest triangle) or stopped
    /// there (`false`: a triangle within `accept2`, so an upper bound of the
    /// distance). A caller that only needs to know the distance is below some
    /// radius saves the rest of the search, most of it where the mesh is nearly
    /// equidistant from `p` (a point deep inside a solid: every box around it
    /// is about as near as the nearest triangle).
    pub fn nearest_below_or_within(&self, p: DVec3, mut best2: f64, accept2: f64) -> (f64, u32, bool) {
        let mut best_t = u32::MAX;
        if self.tris.is_empty() {
            return (f64::INFINITY, best_t, true);
        }
        // Each entry carries its box's squared distance, computed once when its
        // parent was opened: a popped node is pruned against the best distance
        // found since without recomputing it.
        let mut stack: [(u32, f64); 64] = [(0, 0.0); 64];
        stack[0] = (0, self.nodes[0].bounds.dist2(p));
        let mut sp = 1usize;
        while sp > 0 {
            sp -= 1;
            let (ni, box2) = stack[sp];
            if box2 >= best2 {
                continue;
            }
            let n = &self.nodes[ni as usize];
            if n.count > 0 {
                for t in n.start..n.start + n.count {
                    let d2 = point_triangle_dist2(p, &self.triangle(t));
                    if d2 < best2 {
                        best2 = d2;
                        best_t = t;
                    }
                }
                if best2 <= accept2 && best_t != u32::MAX {
                    return (best2, best_t, false);
                }
            } else {
                let (l, r) = (n.start, n.start + 1);
                let dl = self.nodes[l as usize].bounds.dist2(p);
                let dr = self.nodes[r as usize].bounds.dist2(p);
                // Push the farther child first so the nearer one is searched first;
                // a child already beyond the best distance is not pushed.
                let (near, far) = if dl <= dr {
                    ((l, dl), (r, dr))
                } else {
                    ((r, dr), (l, dl))
                };
                if sp + 2 > stack.len() {
                    // Depth beyond 64 cannot happen with median splits below 2^32 triangles.
                    unreachable!("BVH deeper than its stack");
                }
                if far.1 < best2 {
                    stack[sp] = far;
                    sp += 1;
                }
                if near.1 < best2 {
                    stack[sp] = near;
                    sp += 1;
                }
            }
        }
        (best2, best_t, true)
    }
}

/// Squared distance from `p` to triangle `t`, by the Voronoi-region cases of
/// Ericson, *Real-Time Collision Detection* §5.1.5 (exact for degenerate triangles too).
pub fn point_triangle_dist2(p: DVec3, t: &[DVec3; 3]) -> f64 {
    let [a, b, c] = *t;
    let ab = b - a;
    let ac = c - a;
    let ap = p - a;
    let d1 = ab.dot(ap);
    let d2 = ac.dot(ap);
    let closest = |q: DVec3| p.distance_squared(q);
    if d1 <= 0.0 && d2 <= 0.0 {
        return ap.dot(ap);
    }
    let bp = p - b;
    let d3 = ab.dot(bp);
    let d4 = ac.dot(bp);
    if d3 >= 0.0 && d4 <= d3 {
        return bp.dot(bp);
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        let v = d1 / (d1 - d3);
        return closest(a + v * ab);
    }
    let cp = p - c;
    let d5 = ab.dot(cp);
    let d6 = ac.dot(cp);
    if d6 >= 0.0 && d5 <= d6 {
        return cp.dot(cp);
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        let w = d2 / (d2 - d6);
        return closest(a + w * ac);
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return closest(b + w * (c - b));
    }
    let denom = va + vb + vc;
    if denom.abs() < f64::MIN_POSITIVE {
        // Degenerate (zero-area) triangle: the nearest of its edges.
        let seg = |u: DVec3, w: DVec3| {
            let e = w - u;
            let l2 = e.dot(e);
            let s = if l2 > 0.0 {
                ((p - u).dot(e) / l2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            closest(u + s * e)
        };
        return seg(a, b).min(seg(b, c)).min(seg(a, c));
    }
    let v = vb / denom;
    let w = vc / denom;
    closest(a + ab * v + ac * w)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A search stopped within a radius returns a triangle at the distance it
    /// returns, within that radius; one that ran to the end returns what
    /// [`Bvh::nearest_below`] returns. Points inside, on and outside a sphere.
    #[test]
    fn stopped_search_returns_a_triangle_within_its_radius() {
        let (p, t) = crate::metrics::hausdorff::tests::sphere(10.0, [0.0; 3], 20, 40);
        let bvh = Bvh::build(&p, &t);
        let mut stopped = 0;
        for k in 0..200 {
            let x = k as f64;
            let q = DVec3::new((0.37 * x).sin(), (0.71 * x).cos(), (0.13 * x).sin()) * (0.1 * x);
            let (exact2, exact_t) = bvh.nearest_below(q, f64::INFINITY);
            for accept in [0.5 * exact2.sqrt(), exact2.sqrt() + 0.5, exact2.sqrt() + 5.0] {
                let (d2, tri, ran_to_end) = bvh.nearest_below_or_within(q, f64::INFINITY, accept * accept);
                assert_eq!(point_triangle_dist2(q, &bvh.triangle(tri)), d2, "point {k}");
                if ran_to_end {
                    assert_eq!((d2, tri), (exact2, exact_t), "point {k}");
                } else {
                    assert!(d2 <= accept * accept && d2 >= exact2, "point {k}: {d2} vs {exact2}");
                    stopped += 1;
                }
            }
            // A radius below the distance never stops the search.
            assert!(bvh.nearest_below_or_within(q, f64::INFINITY, 0.25 * exact2).2);
        }
        assert!(stopped > 100, "only {stopped} searches stopped early");
    }

    #[test]
    fn point_triangle_regions() {
        let t = [DVec3::ZERO, DVec3::X, DVec3::Y];
        let d = |p: [f64; 3]| point_triangle_dist2(DVec3::from_array(p), &t).sqrt();
        assert!((d([0.2, 0.2, 2.0]) - 2.0).abs() < 1e-12); // face
        assert!((d([-1.0, -1.0, 0.0]) - 2f64.sqrt()).abs() < 1e-12); // vertex a
        assert!((d([0.5, -1.0, 0.0]) - 1.0).abs() < 1e-12); // edge ab
        assert!((d([1.0, 1.0, 0.0]) - 0.5f64.sqrt()).abs() < 1e-12); // edge bc
        assert!((d([3.0, 0.0, 0.0]) - 2.0).abs() < 1e-12); // vertex b
        let degenerate = [DVec3::ZERO, DVec3::X, 2.0 * DVec3::X];
        assert!((point_triangle_dist2(DVec3::new(1.0, 1.0, 0.0), &degenerate).sqrt() - 1.0).abs() < 1e-12);
    }

    #[test]
    fn bvh_matches_brute_force() {
        // A bumpy grid of triangles and pseudo-random query points.
        let n = 30;
        let mut pos = Vec::new();
        for i in 0..=n {
            for j in 0..=n {
                let (x, y) = (i as f64, j as f64);
                pos.push(DVec3::new(x, y, (x * 0.7).sin() * (y * 0.3).cos() * 3.0));
            }
        }
        let mut tris = Vec::new();
        for i in 0..n {
            for j in 0..n {
                let a = (i * (n + 1) + j) as u32;
                let b = a + 1;
                let c = a + (n + 1) as u32;
                tris.push([a, b, c]);
                tris.push([b, c + 1, c]);
            }
        }
        let bvh = Bvh::build(&pos, &tris);
        let mut s = 12345u64;
        let mut rnd = || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            (s % 10_000) as f64 / 10_000.0
        };
        for _ in 0..300 {
            let p = DVec3::new(rnd() * 40.0 - 5.0, rnd() * 40.0 - 5.0, rnd() * 20.0 - 10.0);
            let brute = tris
                .iter()
                .map(|t| point_triangle_dist2(p, &[pos[t[0] as usize], pos[t[1] as usize], pos[t[2] as usize]]))
                .fold(f64::INFINITY, f64::min)
                .sqrt();
            assert!((bvh.distance(p) - brute).abs() < 1e-12);
        }
    }
}
