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

const NC: usize = 180;
const NG: usize = 90;
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
        let rects: Vec<CellRect> = tris.par_iter().map(|t| cell_rect(&t.map(widen))).collect();
        let mut bucket_start = vec![0u32; NC * NG + 1];
        for r in &rects {
            r.for_each(|b| bucket_start[b + 1] += 1);
        }
        for b in 0..NC * NG {
            bucket_start[b + 1] += bucket_start[b];
        }
        let mut fill = bucket_start.clone();
        let mut bucket_tris = vec![0u32; bucket_start[NC * NG] as usize];
        for (k, r) in rects.iter().enumerate() {
            r.for_each(|b| {
                bucket_tris[fill[b] as usize] = k as u32;
                fill[b] += 1;
            });
        }
        Self {
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
        let b = bucket(c, g);
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
        let b = bucket(c, g);
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

fn bucket(c: f64, g: f64) -> usize {
    let ic = ((c / 360.0 * NC as f64) as usize).min(NC - 1);
    let ig = ((g / 180.0 * NG as f64) as usize).min(NG - 1);
    ig * NC + ic
}

/// The buckets a triangle may be hit in: gamma rows `ig0..=ig1` times C
/// columns `k0..=k1` (taken modulo NC: the interval may cross the 0/360 seam).
#[derive(Debug, Clone, Copy)]
struct CellRect {
    ig0: u16,
    ig1: u16,
    k0: i16,
    k1: i16,
}

impl CellRect {
    fn for_each(&self, mut f: impl FnMut(usize)) {
        for ig in self.ig0 as usize..=self.ig1 as usize {
            for k in self.k0 as i64..=self.k1 as i64 {
                f(ig * NC + k.rem_euclid(NC as i64) as usize);
            }
        }
    }
}

fn cell_rect(t: &[DVec3; 3]) -> CellRect {
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
    let dg = 180.0 / NG as f64;
    let dc = 360.0 / NC as f64;
    let mut g_lo = pts.iter().map(|p| p.1).fold(f64::INFINITY, f64::min) - dg;
    let mut g_hi = pts.iter().map(|p| p.1).fold(f64::NEG_INFINITY, f64::max) + dg;
    let (nadir, zenith) = (pole(-1.0), pole(1.0));
    if nadir {
        g_lo = 0.0;
    }
    if zenith {
        g_hi = 180.0;
    }
    let ig0 = ((g_lo.max(0.0) / dg) as usize).min(NG - 1);
    let ig1 = ((g_hi.min(180.0) / dg) as usize).min(NG - 1);
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
    let k1 = k1.min(k0 + NC as i64 - 1);
    // c_lo >= -dc and c_hi < 720 + dc: both fit i16 (NC = 180 columns of 2 degrees).
    CellRect {
        ig0: ig0 as u16,
        ig1: ig1 as u16,
        k0: k0 as i16,
        k1: k1 as i16,
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
