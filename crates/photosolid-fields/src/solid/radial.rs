//! The radial function of a star-shaped solid mesh: r(ω) where the ray from
//! the origin along ω leaves the mesh.
//!
//! A triangle with a vertex at the origin spans no solid angle and is
//! skipped; a ray that hits no other triangle has r = 0 (a zero-intensity
//! region). Triangles are bucketed on a C x γ grid by the angular bounds of
//! their edges (sampled along the great arcs, plus one bucket of margin;
//! triangles whose cone holds a pole take whole rows).

use glam::DVec3;
use rayon::prelude::*;

use crate::model::frame::{direction, unit_angles};
use crate::model::IntensityField;
use crate::solid::Mesh;

/// Columns and rows of the coarsest bucket grid: 2 degrees in C and in γ.
const NC_COARSE: usize = 180;
const NG_COARSE: usize = 90;
/// A mesh with more triangles than this per bucket of the coarsest grid gets a finer
/// grid: a bucket of a 2-degree grid over a 424,000-triangle truth solid held about
/// 240 triangles, and every `distance_bound` measured the distance to each of them
/// (most of `tradeoff`'s time on a synthetic roadway).
const TRIS_PER_COARSE_BUCKET: f64 = 2.0;
/// The finest grid: 1/4 degree (8 times the coarsest in each angle).
const MAX_REFINE: usize = 8;
/// Points closer to a pole than this (degrees) have no meaningful C.
const POLE_DEG: f64 = 1e-6;

/// A ray-castable star-shaped mesh.
///
/// Memory: the mesh's f32 vertex positions (12 bytes a vertex, widened
/// exactly to f64 at each query, so the numbers are those of the mesh), the
/// non-degenerate triangles as vertex indices (12 bytes each) and the
/// buckets in compressed rows (4 bytes per triangle per bucket it touches):
/// about 30 bytes per triangle, where a list per bucket of f64 triangle
/// copies took about 290 (issue 15, peak memory of `compare`).
#[derive(Debug, Clone)]
pub struct RadialMesh {
    grid: BucketGrid,
    positions: Vec<[f32; 3]>,
    tris: Vec<[u32; 3]>,
    /// Bucket b holds `bucket_tris[bucket_start[b]..bucket_start[b + 1]]`.
    bucket_start: Vec<u32>,
    bucket_tris: Vec<u32>,
}

/// Distance along the ray `w` (unit) to triangle `t`, if the ray passes through it.
fn hit(t: &[DVec3; 3], w: DVec3) -> Option<f64> {
    let s = [
        w.dot(t[0].cross(t[1])),
        w.dot(t[1].cross(t[2])),
        w.dot(t[2].cross(t[0])),
    ];
    let (l0, l1, l2) = (t[0].length(), t[1].length(), t[2].length());
    let scale = l0 * l1 + l1 * l2 + l2 * l0;
    let eps = 1e-9 * scale;
    let inside = (s[0] >= -eps && s[1] >= -eps && s[2] >= -eps) || (s[0] <= eps && s[1] <= eps && s[2] <= eps);
    if !inside {
        return None;
    }
    let n = (t[1] - t[0]).cross(t[2] - t[0]);
    let den = n.dot(w);
    if den.abs() <= 1e-12 * n.length() {
        return None;
    }
    let r = n.dot(t[0]) / den;
    (r >= 0.0).then_some(r)
}

impl RadialMesh {
    /// Index the triangles of `mesh` (any unit).
    pub fn new(mesh: &Mesh) -> Self {
        Self::with_refinement(mesh, None)
    }

    /// [`RadialMesh::new`] on the coarsest bucket grid refined `refine` times
    /// in each angle (`None`: as [`BucketGrid::for_triangles`] chooses).
    fn with_refinement(mesh: &Mesh, refine: Option<usize>) -> Self {
        let positions = mesh.positions().to_vec();
        let scale = mesh.max_radius().max(f64::MIN_POSITIVE);
        let widen = |i: u32| glam::Vec3::from_array(positions[i as usize]).as_dvec3();
        let tris: Vec<[u32; 3]> = mesh
            .triangles()
            .iter()
            .copied()
            .filter(|t| t.iter().all(|&i| widen(i).length() > 1e-9 * scale))
            .collect();
        // Each triangle's bucket rectangle, then the rows counted and filled
        // (no list per bucket, no list per triangle).
        let grid = refine.map_or_else(|| BucketGrid::for_triangles(tris.len()), BucketGrid::refined);
        let rects: Vec<CellRect> = tris.par_iter().map(|t| grid.cell_rect(&t.map(widen))).collect();
        let n_buckets = grid.len();
        let mut bucket_start = vec![0u32; n_buckets + 1];
        for r in &rects {
            r.for_each(grid.nc, |b| bucket_start[b + 1] += 1);
        }
        for b in 0..n_buckets {
            bucket_start[b + 1] += bucket_start[b];
        }
        let mut fill = bucket_start.clone();
        let mut bucket_tris = vec![0u32; bucket_start[n_buckets] as usize];
        for (k, r) in rects.iter().enumerate() {
            r.for_each(grid.nc, |b| {
                bucket_tris[fill[b] as usize] = k as u32;
                fill[b] += 1;
            });
        }
        Self {
            grid,
            positions,
            tris,
            bucket_start,
            bucket_tris,
        }
    }

    /// Triangle `k` with its vertices widened to f64.
    fn triangle(&self, k: u32) -> [DVec3; 3] {
        self.tris[k as usize].map(|i| glam::Vec3::from_array(self.positions[i as usize]).as_dvec3())
    }

    /// r(ω) for the unit direction `w`.
    pub fn radius(&self, w: DVec3) -> f64 {
        let (c, g) = unit_angles(w);
        let b = self.grid.bucket(c, g);
        let (s, e) = (self.bucket_start[b] as usize, self.bucket_start[b + 1] as usize);
        let best = self.bucket_tris[s..e]
            .iter()
            .filter_map(|&k| hit(&self.triangle(k), w))
            .fold(None, |m: Option<f64>, r| Some(m.map_or(r, |m| m.max(r))));
        best.unwrap_or(0.0)
    }

    /// The distance (same unit as the mesh) from `p` to the nearest of the
    /// triangles indexed around the direction of `p` (its bucket): an upper
    /// bound of `p`'s distance to the mesh, and near it when the mesh is
    /// close to `p` (the triangle the ray along `p` leaves through is one of
    /// them). `None` for `p` at the origin or a bucket without triangles.
    pub fn distance_bound(&self, p: DVec3) -> Option<f64> {
        let n = p.length();
        if n <= 0.0 || !n.is_finite() {
            return None;
        }
        let (c, g) = unit_angles(p / n);
        let b = self.grid.bucket(c, g);
        let (s, e) = (self.bucket_start[b] as usize, self.bucket_start[b + 1] as usize);
        let d2 = self.bucket_tris[s..e]
            .iter()
            .map(|&k| crate::metrics::bvh::point_triangle_dist2(p, &self.triangle(k)))
            .fold(f64::INFINITY, f64::min);
        d2.is_finite().then(|| d2.sqrt())
    }

    /// r at (C, γ) in degrees.
    pub fn radius_at(&self, c_deg: f64, gamma_deg: f64) -> f64 {
        self.radius(direction(c_deg, gamma_deg))
    }
}

/// The buckets a triangle may be hit in: gamma rows `ig0..=ig1` times C
/// columns `k0..=k1` (taken modulo the grid's columns: the interval may cross the 0/360 seam).
#[derive(Debug, Clone, Copy)]
struct CellRect {
    ig0: u16,
    ig1: u16,
    k0: i16,
    k1: i16,
}

impl CellRect {
    /// Calls `f` with each bucket of the rectangle on a grid of `nc` columns.
    fn for_each(&self, nc: usize, mut f: impl FnMut(usize)) {
        for ig in self.ig0 as usize..=self.ig1 as usize {
            for k in self.k0 as i64..=self.k1 as i64 {
                f(ig * nc + k.rem_euclid(nc as i64) as usize);
            }
        }
    }
}

/// The C x γ grid the triangles are bucketed on: `nc` columns of 360/`nc` degrees,
/// `ng` rows of 180/`ng` degrees.
#[derive(Debug, Clone, Copy)]
struct BucketGrid {
    nc: usize,
    ng: usize,
}

impl BucketGrid {
    /// The coarsest grid (2 degrees), refined by a whole factor for a mesh of more
    /// than [`TRIS_PER_COARSE_BUCKET`] triangles per coarse bucket, so a bucket holds
    /// a few triangles plus the margins of its neighbours', whatever the mesh's size.
    fn for_triangles(n_tris: usize) -> Self {
        let per_bucket = n_tris as f64 / (NC_COARSE * NG_COARSE) as f64;
        Self::refined(((per_bucket / TRIS_PER_COARSE_BUCKET).sqrt().ceil() as usize).clamp(1, MAX_REFINE))
    }

    /// The coarsest grid with each angle's buckets cut into `refine` (1 to [`MAX_REFINE`]).
    fn refined(refine: usize) -> Self {
        let refine = refine.clamp(1, MAX_REFINE);
        Self {
            nc: NC_COARSE * refine,
            ng: NG_COARSE * refine,
        }
    }

    fn len(&self) -> usize {
        self.nc * self.ng
    }

    /// The bucket of the direction at (C, γ) in degrees.
    fn bucket(&self, c: f64, g: f64) -> usize {
        let ic = ((c / 360.0 * self.nc as f64) as usize).min(self.nc - 1);
        let ig = ((g / 180.0 * self.ng as f64) as usize).min(self.ng - 1);
        ig * self.nc + ic
    }

    /// The buckets triangle `t` may be hit in.
    fn cell_rect(&self, t: &[DVec3; 3]) -> CellRect {
        let (nc, ng) = (self.nc, self.ng);
        let pole = |z: f64| hit(t, DVec3::new(0.0, 0.0, z)).is_some();
        // Angles of points along the three edges (great arcs through the cone).
        let mut pts = Vec::with_capacity(27);
        for i in 0..3 {
            let (a, b) = (t[i], t[(i + 1) % 3]);
            let (ua, ub) = (a.normalize(), b.normalize());
            for k in 0..9 {
                let v = ua.lerp(ub, k as f64 / 9.0);
                if v.length() > 1e-12 {
                    pts.push(unit_angles(v.normalize()));
                }
            }
        }
        let dg = 180.0 / ng as f64;
        let dc = 360.0 / nc as f64;
        let mut g_lo = pts.iter().map(|p| p.1).fold(f64::INFINITY, f64::min) - dg;
        let mut g_hi = pts.iter().map(|p| p.1).fold(f64::NEG_INFINITY, f64::max) + dg;
        let (nadir, zenith) = (pole(-1.0), pole(1.0));
        if nadir {
            g_lo = 0.0;
        }
        if zenith {
            g_hi = 180.0;
        }
        let ig0 = ((g_lo.max(0.0) / dg) as usize).min(ng - 1);
        let ig1 = ((g_hi.min(180.0) / dg) as usize).min(ng - 1);
        // C range: the shortest interval holding every point (unless a pole is
        // inside, or a point is on a pole, where C is undefined). Along a great
        // arc that misses the poles C is monotonic, so the points' interval plus
        // one column of margin holds the whole triangle. (Whole rows for every
        // triangle within 6 degrees of a pole filled 80 % of the buckets of a
        // 1/3-degree grid solid: issue 15, peak memory.)
        let on_pole = pts.iter().any(|p| p.1 <= POLE_DEG || p.1 >= 180.0 - POLE_DEG);
        let mut cs: Vec<f64> = pts.iter().map(|p| p.0).collect();
        cs.sort_by(f64::total_cmp);
        let all_c = nadir || zenith || on_pole || cs.is_empty();
        let (c_lo, c_hi) = if all_c {
            (0.0, 360.0)
        } else {
            // Largest gap on the circle; the interval is its complement.
            let mut gap = (cs[0] + 360.0 - cs[cs.len() - 1], cs.len() - 1);
            for i in 0..cs.len() - 1 {
                if cs[i + 1] - cs[i] > gap.0 {
                    gap = (cs[i + 1] - cs[i], i);
                }
            }
            let lo = cs[(gap.1 + 1) % cs.len()];
            let mut hi = cs[gap.1];
            if hi < lo {
                hi += 360.0;
            }
            (lo - dc, hi + dc)
        };
        let (k0, k1) = ((c_lo / dc).floor() as i64, (c_hi / dc).floor() as i64);
        let k1 = k1.min(k0 + nc as i64 - 1);
        // c_lo >= -dc and c_hi < 720 + dc: both fit i16 (at most 1,440 columns).
        CellRect {
            ig0: ig0 as u16,
            ig1: ig1 as u16,
            k0: k0 as i16,
            k1: k1 as i16,
        }
    }
}

/// The measured solid's radial function is an intensity field: exact at the
/// measured directions, linear on the Delaunay triangles between them.
impl IntensityField for RadialMesh {
    fn intensity_cd(&self, c_deg: f64, gamma_deg: f64) -> f64 {
        if !(c_deg.is_finite() && gamma_deg.is_finite()) {
            return 0.0;
        }
        self.radius_at(c_deg, gamma_deg)
    }
    fn intensity_dir_cd(&self, d: DVec3) -> f64 {
        d.try_normalize().map_or(0.0, |u| self.radius(u))
    }
    fn name(&self) -> String {
        "measured".into()
    }
    fn bytes(&self) -> usize {
        (self.positions.len() + self.tris.len()) * 12 + (self.bucket_start.len() + self.bucket_tris.len()) * 4
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solid::{grid_solid, SolidGrid, Units};

    /// A finer bucket grid changes which triangles a query looks at, not the
    /// answer: r(ω) is the same to the bit at 20,000 directions, and the
    /// distance bound of the finer grid (over fewer triangles) is still at
    /// least the coarse grid's (a minimum over more of them).
    #[test]
    fn finer_buckets_give_the_same_radius() {
        let grid = SolidGrid::uniform(240, 120).unwrap();
        let f = |c: f64, g: f64| 100.0 + 900.0 * ((c.to_radians() * 3.0).cos().abs() * g.to_radians().sin());
        let mesh = grid_solid(&f, &grid, Units::Candela).unwrap();
        let auto = RadialMesh::new(&mesh);
        let coarse = RadialMesh::with_refinement(&mesh, Some(1));
        assert!(auto.grid.nc > coarse.grid.nc, "{} triangles", mesh.n_triangles());
        for w in crate::metrics::random_directions(20_000, 7) {
            assert_eq!(auto.radius(w).to_bits(), coarse.radius(w).to_bits(), "{w}");
            let p = w * 700.0;
            let (fine_bound, coarse_bound) = (auto.distance_bound(p).unwrap(), coarse.distance_bound(p).unwrap());
            assert!(fine_bound >= coarse_bound, "{w}: {fine_bound} < {coarse_bound}");
        }
    }
}
