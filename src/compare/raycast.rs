//! The radial function of a star-shaped solid mesh: r(ω) where the ray from
//! the origin along ω leaves the mesh.
//!
//! A triangle with a vertex at the origin spans no solid angle and is
//! skipped; a ray that hits no other triangle has r = 0 (a zero-intensity
//! region). Triangles are bucketed on a C x γ grid by the angular bounds of
//! their edges (sampled along the great arcs, plus one bucket of margin;
//! triangles whose cone holds a pole take whole rows).

use rayon::prelude::*;

use crate::solid::Mesh;

const NC: usize = 180;
const NG: usize = 90;

/// A ray-castable star-shaped mesh.
#[derive(Debug, Clone)]
pub struct RadialMesh {
    tris: Vec<[[f64; 3]; 3]>,
    buckets: Vec<Vec<u32>>,
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn norm(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}

/// (C, γ) degrees of a direction (luminaire frame: γ = 0 is −z).
fn angles(d: [f64; 3]) -> (f64, f64) {
    let n = norm(d);
    let g = (-d[2] / n).clamp(-1.0, 1.0).acos().to_degrees();
    let c = d[1].atan2(d[0]).to_degrees().rem_euclid(360.0);
    (c, g)
}

/// The unit direction of (C, γ) in degrees.
pub fn direction(c_deg: f64, gamma_deg: f64) -> [f64; 3] {
    let (sg, cg) = gamma_deg.to_radians().sin_cos();
    let (sc, cc) = c_deg.to_radians().sin_cos();
    [sg * cc, sg * sc, -cg]
}

/// Distance along the ray `w` (unit) to triangle `t`, if the ray passes through it.
fn hit(t: &[[f64; 3]; 3], w: [f64; 3]) -> Option<f64> {
    let s = [
        dot(w, cross(t[0], t[1])),
        dot(w, cross(t[1], t[2])),
        dot(w, cross(t[2], t[0])),
    ];
    let scale = norm(t[0]) * norm(t[1]) + norm(t[1]) * norm(t[2]) + norm(t[2]) * norm(t[0]);
    let eps = 1e-9 * scale;
    let inside = (s[0] >= -eps && s[1] >= -eps && s[2] >= -eps) || (s[0] <= eps && s[1] <= eps && s[2] <= eps);
    if !inside {
        return None;
    }
    let n = cross(
        [t[1][0] - t[0][0], t[1][1] - t[0][1], t[1][2] - t[0][2]],
        [t[2][0] - t[0][0], t[2][1] - t[0][1], t[2][2] - t[0][2]],
    );
    let den = dot(n, w);
    if den.abs() <= 1e-12 * norm(n) {
        return None;
    }
    let r = dot(n, t[0]) / den;
    (r >= 0.0).then_some(r)
}

impl RadialMesh {
    /// Index the triangles of `mesh` (any unit).
    pub fn new(mesh: &Mesh) -> Self {
        let p = mesh.positions();
        let scale = mesh.max_radius().max(f64::MIN_POSITIVE);
        let tris: Vec<[[f64; 3]; 3]> = mesh
            .triangles()
            .iter()
            .map(|t| t.map(|i| p[i as usize].map(f64::from)))
            .filter(|v| v.iter().all(|x| norm(*x) > 1e-9 * scale))
            .collect();
        let cells: Vec<Vec<usize>> = tris.par_iter().map(cells_of).collect();
        let mut buckets = vec![Vec::new(); NC * NG];
        for (k, cs) in cells.iter().enumerate() {
            for &c in cs {
                buckets[c].push(k as u32);
            }
        }
        Self { tris, buckets }
    }

    /// r(ω) for the unit direction `w`.
    pub fn radius(&self, w: [f64; 3]) -> f64 {
        let (c, g) = angles(w);
        let b = bucket(c, g);
        let best = self.buckets[b]
            .iter()
            .filter_map(|&k| hit(&self.tris[k as usize], w))
            .fold(None, |m: Option<f64>, r| Some(m.map_or(r, |m| m.max(r))));
        best.unwrap_or(0.0)
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

fn cells_of(t: &[[f64; 3]; 3]) -> Vec<usize> {
    let pole = |z: f64| hit(t, [0.0, 0.0, z]).is_some();
    // Angles of points along the three edges (great arcs through the cone).
    let mut pts = Vec::with_capacity(27);
    for i in 0..3 {
        let (a, b) = (t[i], t[(i + 1) % 3]);
        let (ua, ub) = (a.map(|x| x / norm(a)), b.map(|x| x / norm(b)));
        for k in 0..9 {
            let s = k as f64 / 9.0;
            let v = [
                ua[0] * (1.0 - s) + ub[0] * s,
                ua[1] * (1.0 - s) + ub[1] * s,
                ua[2] * (1.0 - s) + ub[2] * s,
            ];
            if norm(v) > 1e-12 {
                pts.push(angles(v));
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
    // C range: the shortest interval holding every point (unless a pole is inside, or near a pole).
    let near_pole = g_lo <= 2.0 * dg || g_hi >= 180.0 - 2.0 * dg;
    let mut cs: Vec<f64> = pts.iter().map(|p| p.0).collect();
    cs.sort_by(f64::total_cmp);
    let all_c = nadir || zenith || near_pole || cs.is_empty();
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
    let mut out = Vec::new();
    let (k0, k1) = ((c_lo / dc).floor() as i64, (c_hi / dc).floor() as i64);
    let k1 = k1.min(k0 + NC as i64 - 1);
    for ig in ig0..=ig1 {
        for k in k0..=k1 {
            out.push(ig * NC + k.rem_euclid(NC as i64) as usize);
        }
    }
    out
}
