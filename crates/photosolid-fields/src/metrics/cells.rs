//! Exact distances to the solid of a field made of constant cells
//! ([`ConstantCells`]: a nearest lookup of a texture or of the data).
//!
//! Such a solid is, per cell, a patch of the sphere of radius r_ij over the
//! cell's C × γ rectangle, and, per edge between two cells of different
//! value, a radial wall: the segment from the lower to the higher value
//! along every direction of the edge (what a mesh of the solid closes the
//! jump with). The distance from a point p = ρ u to each piece is a
//! non-decreasing function of one angle, the smallest angle θ between u and
//! the piece's directions:
//! - a patch: `|p − r ω|² = ρ² + r² − 2 ρ r cos θ`, decreasing in cos θ;
//! - a wall: the distance from p to the segment {t ω : r_lo ≤ t ≤ r_hi},
//!   `ρ sin θ` where the foot `ρ cos θ` falls inside it, else the distance to
//!   its nearer end, again non-decreasing in θ (each point of the segment
//!   moves away from p as ω turns away from u).
//!
//! The smallest angle to a cell is 0 inside it, else the smallest angle to
//! its boundary: two meridian arcs (great circles) and two parallels
//! (small circles), on each of which `u · ω` is a sinusoid of the arc's
//! parameter, largest at one point (an arc end or the sinusoid's peak). So
//! every distance is a closed form; no sampling and no mesh. Only the cells
//! that can hold a nearer point are visited: the start distance d (to the
//! patch of u's own cell) bounds the answer, and a point of the solid at
//! angle θ from u is at least ρ sin θ away, so only the cap θ ≤ asin(d / ρ)
//! around u is searched.

use std::f64::consts::PI;

use glam::DVec3;
use rayon::prelude::*;

use super::largest::{largest_of, LargestDistance};
use crate::model::frame::unit_angles;
use crate::model::ConstantCells;

/// The distance (cd) from each point `(dir, m)` (the point m · dir, `dir`
/// a unit vector of the luminaire frame, m a finite intensity ≥ 0 cd: a
/// measured value) to the solid of `cells`, in order (in parallel). Exact up
/// to rounding. `cells` must hold what [`ConstantCells`] documents (γ edges
/// 0 to 180 and C edges 0 to 360, increasing; one value per cell).
pub fn distances_to_cells(cells: &ConstantCells, points: &[(DVec3, f64)]) -> Vec<f64> {
    let grid = Grid::new(cells);
    points.par_iter().map(|&(dir, m)| grid.distance(dir, m)).collect()
}

/// The largest of [`distances_to_cells`] over `points` when it exceeds
/// `floor` (cd), bit for bit, searching only the points that can set it
/// ([`largest_of`]): a point's distance is at most the distance to its own
/// cell's patch along its own direction, one lookup.
pub fn largest_distance_to_cells(cells: &ConstantCells, points: &[(DVec3, f64)], floor: f64) -> LargestDistance {
    let grid = Grid::new(cells);
    let bounds: Vec<f64> = points.par_iter().map(|&(dir, m)| grid.start(dir, m).0).collect();
    largest_of(&bounds, floor, |k| grid.distance(points[k].0, points[k].1))
}

/// A point whose search is not over at its start: its unit direction, C and
/// γ (radians) and |p| (cd).
#[derive(Clone, Copy)]
struct Query {
    u: DVec3,
    cu: f64,
    gu: f64,
    rho: f64,
}

/// The cells with their edges in radians, and the edges' sines and cosines
/// (a search visits each edge many times).
struct Grid<'a> {
    cells: &'a ConstantCells,
    gamma: Vec<f64>,
    c: Vec<f64>,
    /// (sin, cos) of each γ edge.
    gamma_trig: Vec<(f64, f64)>,
    /// (sin, cos) of each C edge.
    c_trig: Vec<(f64, f64)>,
    rows: usize,
    cols: usize,
}

/// One query's view of a meridian edge C = c: u·ω(γ) = A sin γ + B cos γ,
/// peaking at γ* = atan2(A, B) (computed once per edge and query, not once
/// per cell beside it).
#[derive(Clone, Copy)]
struct Meridian {
    a: f64,
    b: f64,
    peak: f64,
    at_peak: f64,
}

impl Meridian {
    fn new(u: DVec3, (sc, cc): (f64, f64)) -> Self {
        let (a, b) = (u.x * cc + u.y * sc, -u.z);
        let peak = a.atan2(b);
        Self {
            a,
            b,
            peak,
            at_peak: a * peak.sin() + b * peak.cos(),
        }
    }

    /// Largest u·ω over γ in [g0, g1] (radians) with their (sin, cos).
    fn max_dot(&self, (g0, t0): (f64, (f64, f64)), (g1, t1): (f64, (f64, f64))) -> f64 {
        let at = |(s, c): (f64, f64)| self.a * s + self.b * c;
        let mut best = at(t0).max(at(t1));
        if (g0..=g1).contains(&self.peak) {
            best = best.max(self.at_peak);
        }
        best
    }
}

impl<'a> Grid<'a> {
    fn new(cells: &'a ConstantCells) -> Self {
        let (rows, cols) = cells.shape();
        debug_assert_eq!(cells.values_cd.len(), rows * cols, "one value per cell");
        debug_assert!(
            cells.gamma_edges_deg.first() == Some(&0.0) && cells.gamma_edges_deg.last() == Some(&180.0),
            "γ edges from 0 to 180"
        );
        debug_assert!(
            cells.c_edges_deg.first() == Some(&0.0) && cells.c_edges_deg.last() == Some(&360.0),
            "C edges from 0 to 360"
        );
        Self {
            cells,
            gamma: cells.gamma_edges_deg.iter().map(|g| g.to_radians()).collect(),
            c: cells.c_edges_deg.iter().map(|c| c.to_radians()).collect(),
            gamma_trig: cells.gamma_edges_deg.iter().map(|g| g.to_radians().sin_cos()).collect(),
            c_trig: cells.c_edges_deg.iter().map(|c| c.to_radians().sin_cos()).collect(),
            rows,
            cols,
        }
    }

    /// Index of the interval of `edges` holding `x` (clamped to the first and last).
    fn interval(edges: &[f64], x: f64) -> usize {
        let n = edges.len() - 1;
        edges[1..n].partition_point(|&e| e <= x)
    }

    /// Where the search of [`Grid::distance`] starts: the distance to the
    /// patch of the point's own cell along its own direction (never less
    /// than the answer), and the point to search from; `None` when that
    /// start is the answer.
    fn start(&self, dir: DVec3, m: f64) -> (f64, Option<Query>) {
        if self.rows == 0 || self.cols == 0 || self.cells.values_cd.is_empty() {
            return (m.abs(), None);
        }
        let Some(u) = dir.try_normalize() else {
            return (self.cells.values_cd.iter().copied().fold(f64::INFINITY, f64::min), None);
        };
        debug_assert!(m.is_finite(), "a measured value is finite");
        let rho = m.max(0.0);
        let (c_deg, g_deg) = unit_angles(u);
        let (cu, gu) = (c_deg.to_radians(), g_deg.to_radians());
        let (iu, ju) = (Self::interval(&self.gamma, gu), Self::interval(&self.c, cu));
        let best = (rho - self.cells.value(iu, ju)).abs();
        (best, (best != 0.0).then_some(Query { u, cu, gu, rho }))
    }

    fn distance(&self, dir: DVec3, m: f64) -> f64 {
        let (mut best, point) = self.start(dir, m);
        let Some(q) = point else {
            return best;
        };
        let Query { u, cu, gu, rho } = q;
        // The cap around u that can hold a nearer point, as rows and columns.
        let cap = if best < rho { (best / rho).asin() } else { PI };
        let (g_lo, g_hi) = (gu - cap, gu + cap);
        let rows = Self::interval(&self.gamma, g_lo.max(0.0))..=Self::interval(&self.gamma, g_hi.min(PI));
        let cols: Vec<usize> = if g_lo <= 0.0 || g_hi >= PI || cap >= PI / 2.0 {
            (0..self.cols).collect()
        } else {
            let half = (cap.sin() / gu.sin()).min(1.0).asin();
            self.columns_between(cu - half, cu + half)
        };
        // Each column's two meridian edges, once for all its rows; the
        // parallels' peak C (where u·ω is largest along any parallel).
        let meridians: Vec<(Meridian, Meridian)> = cols
            .iter()
            .map(|&j| (Meridian::new(u, self.c_trig[j]), Meridian::new(u, self.c_trig[j + 1])))
            .collect();
        let c_peak = u.y.atan2(u.x).rem_euclid(2.0 * PI);
        for i in rows {
            for (&j, m) in cols.iter().zip(&meridians) {
                best = best.min(self.cell_distance(&q, c_peak, (i, j), m));
            }
        }
        best
    }

    /// The columns meeting C in [a, b] radians (wraps through 0).
    fn columns_between(&self, a: f64, b: f64) -> Vec<usize> {
        let tau = 2.0 * PI;
        if b - a >= tau {
            return (0..self.cols).collect();
        }
        let start = a.rem_euclid(tau);
        let end = start + (b - a);
        let mut j = Self::interval(&self.c, start);
        let (mut out, mut turns) = (vec![j], 0.0);
        // Walk east until a column's (unwrapped) east edge reaches the end.
        while self.c[j + 1] + turns < end && out.len() < self.cols {
            j += 1;
            if j == self.cols {
                (j, turns) = (0, turns + tau);
            }
            out.push(j);
        }
        out
    }

    /// The largest u·ω over the parallel γ = edge `i`, C from edge `j` to
    /// edge `j + 1`: u·ω(C) = sin γ (u_x cos C + u_y sin C) − u_z cos γ,
    /// peaking at `c_peak` = atan2(u_y, u_x).
    fn max_dot_parallel(&self, u: DVec3, c_peak: f64, i: usize, j: usize) -> f64 {
        let (sg, cg) = self.gamma_trig[i];
        let at = |(sc, cc): (f64, f64)| u.dot(DVec3::new(sg * cc, sg * sc, -cg));
        let mut best = at(self.c_trig[j]).max(at(self.c_trig[j + 1]));
        if (self.c[j]..=self.c[j + 1]).contains(&c_peak) {
            best = best.max(at(c_peak.sin_cos()));
        }
        best
    }

    /// The distance from p = ρ u to cell (i, j)'s patch and to the walls on
    /// its four edges; `m` the cell's west and east meridian edges for `u`.
    fn cell_distance(&self, q: &Query, c_peak: f64, (i, j): (usize, usize), m: &(Meridian, Meridian)) -> f64 {
        let Query { u, cu, gu, rho } = *q;
        let (g0, g1) = (self.gamma[i], self.gamma[i + 1]);
        let (c0, c1) = (self.c[j], self.c[j + 1]);
        let r = self.cells.value(i, j);
        // The four edges: their largest u·ω, and the neighbour across each.
        let (top, bottom) = ((g0, self.gamma_trig[i]), (g1, self.gamma_trig[i + 1]));
        let west = m.0.max_dot(top, bottom);
        let east = m.1.max_dot(top, bottom);
        let north = self.max_dot_parallel(u, c_peak, i, j);
        let south = self.max_dot_parallel(u, c_peak, i + 1, j);
        let inside = (g0..=g1).contains(&gu) && (c0..=c1).contains(&cu);
        let cos_patch = if inside {
            1.0
        } else {
            west.max(east).max(north).max(south)
        };
        let mut best = patch_distance(rho, r, cos_patch);
        let neighbours = [
            (west, Some((i, (j + self.cols - 1) % self.cols))),
            (east, Some((i, (j + 1) % self.cols))),
            (north, i.checked_sub(1).map(|k| (k, j))),
            (south, (i + 1 < self.rows).then_some((i + 1, j))),
        ];
        for (cos, other) in neighbours {
            if let Some((a, b)) = other {
                let s = self.cells.value(a, b);
                if s != r {
                    best = best.min(wall_distance(rho, r.min(s), r.max(s), cos));
                }
            }
        }
        best
    }
}

/// Distance from p = ρ u to the point r ω with u·ω = `cos`.
fn patch_distance(rho: f64, r: f64, cos: f64) -> f64 {
    (rho * rho + r * r - 2.0 * rho * r * cos).max(0.0).sqrt()
}

/// Distance from p = ρ u to the segment {t ω : lo ≤ t ≤ hi} with u·ω = `cos`.
fn wall_distance(rho: f64, lo: f64, hi: f64, cos: f64) -> f64 {
    let foot = rho * cos;
    if foot < lo {
        patch_distance(rho, lo, cos)
    } else if foot > hi {
        patch_distance(rho, hi, cos)
    } else {
        rho * (1.0 - cos * cos).max(0.0).sqrt()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::frame::direction;

    fn uniform(rows: usize, cols: usize, value: impl Fn(usize, usize) -> f64) -> ConstantCells {
        let edges = |n: usize, span: f64| (0..=n).map(|k| span * k as f64 / n as f64).collect();
        ConstantCells {
            gamma_edges_deg: edges(rows, 180.0),
            c_edges_deg: edges(cols, 360.0),
            values_cd: (0..rows * cols).map(|k| value(k / cols, k % cols)).collect(),
        }
    }

    /// Every cell equal: a sphere, no walls; the distance is |ρ − r| everywhere.
    #[test]
    fn a_constant_field_is_a_sphere() {
        let cells = uniform(9, 12, |_, _| 100.0);
        for (c, g, m) in [
            (0.0, 0.0, 50.0),
            (359.9, 90.0, 150.0),
            (33.0, 180.0, 100.0),
            (200.0, 71.0, 0.0),
        ] {
            let d = distances_to_cells(&cells, &[(direction(c, g), m)])[0];
            assert!((d - (m - 100.0f64).abs()).abs() < 1e-9, "({c}, {g}, {m}): {d}");
        }
    }

    /// Two hemispheres (r = 100 below the horizon, 10 above): a point just
    /// above the horizon at radius 100 is nearest the wall; one far above
    /// the upper patch is nearest that patch.
    #[test]
    fn a_step_has_a_wall() {
        let cells = uniform(2, 4, |i, _| if i == 0 { 100.0 } else { 10.0 });
        // 1° above the horizon (γ = 91°), ρ = 100: the wall at γ = 90° is 100 sin 1° away.
        let d = distances_to_cells(&cells, &[(direction(10.0, 91.0), 100.0)])[0];
        assert!((d - 100.0 * 1f64.to_radians().sin()).abs() < 1e-9, "{d}");
        // Straight up at 30 cd: the upper patch is 20 away.
        let d = distances_to_cells(&cells, &[(direction(0.0, 180.0), 30.0)])[0];
        assert!((d - 20.0).abs() < 1e-9, "{d}");
        // On the wall itself (γ = 90°, ρ between 10 and 100): 0.
        let d = distances_to_cells(&cells, &[(direction(45.0, 90.0), 55.0)])[0];
        assert!(d < 1e-9, "{d}");
    }

    /// The nearest piece near the edge of the searched cap: the point 100 u
    /// (u at C 80°, γ 90°) over a 10 cd cell is 90 cd from its own patch; a
    /// 50 cd band starting 60° away at C 140° is √7500 = 86.6 cd away, inside
    /// the cap asin(90/100) = 64° (a cap any narrower would miss it).
    #[test]
    fn the_cap_reaches_far_pieces() {
        let cells = uniform(36, 72, |_, j| if j == 28 { 50.0 } else { 10.0 });
        let d = distances_to_cells(&cells, &[(direction(80.0, 90.0), 100.0)])[0];
        assert!((d - 7500f64.sqrt()).abs() < 1e-9, "{d}");
        // The same across the seam: the band at C 0°-5°, the point at C 300°; the
        // column window [235.8°, 364.2°] wraps through C = 0.
        let cells = uniform(36, 72, |_, j| if j == 0 { 50.0 } else { 10.0 });
        let d = distances_to_cells(&cells, &[(direction(300.0, 90.0), 100.0)])[0];
        assert!((d - 7500f64.sqrt()).abs() < 1e-9, "{d}");
    }

    /// Against a brute-force minimum over points sampled densely on every
    /// patch and wall: never above it (the exact minimum is at most any
    /// sample), and within the sampling's own spacing below it.
    #[test]
    fn matches_dense_sampling_of_patches_and_walls() {
        // A coarse grid (every cap holds many cells) and a fine one (small
        // caps: the row and column windows, and their walk through C = 0).
        dense_check(6, 8, 40);
        dense_check(36, 72, 6);
    }

    fn dense_check(rows: usize, cols: usize, n: usize) {
        let cells = uniform(rows, cols, |i, j| 10.0 + ((i * 7 + j * 3) % 5) as f64 * 20.0);
        let mut surface = Vec::new();
        let cd = |i: usize, j: usize| cells.value(i, j);
        for i in 0..rows {
            for j in 0..cols {
                let (g0, g1) = (cells.gamma_edges_deg[i], cells.gamma_edges_deg[i + 1]);
                let (c0, c1) = (cells.c_edges_deg[j], cells.c_edges_deg[j + 1]);
                for a in 0..=n {
                    for b in 0..=n {
                        let (g, c) = (
                            g0 + (g1 - g0) * a as f64 / n as f64,
                            c0 + (c1 - c0) * b as f64 / n as f64,
                        );
                        surface.push(cd(i, j) * direction(c, g));
                        // The east wall and the south wall of this cell, sampled along their radial span.
                        let (e, s) = (
                            cd(i, (j + 1) % cols),
                            if i + 1 < rows { cd(i + 1, j) } else { cd(i, j) },
                        );
                        let t = b as f64 / n as f64;
                        let r_e = cd(i, j) + (e - cd(i, j)) * t;
                        surface.push(r_e * direction(c1, g0 + (g1 - g0) * a as f64 / n as f64));
                        let r_s = cd(i, j) + (s - cd(i, j)) * a as f64 / n as f64;
                        surface.push(r_s * direction(c0 + (c1 - c0) * t, g1));
                    }
                }
            }
        }
        let dirs = crate::metrics::random_directions(200, 11);
        let mut rng = 0.37f64;
        let points: Vec<(DVec3, f64)> = dirs
            .iter()
            .map(|&d| {
                rng = (rng * 9301.0 + 0.49297).fract();
                (d, 120.0 * rng)
            })
            .collect();
        let exact = distances_to_cells(&cells, &points);
        // Samples are at most (180 / rows) / n degrees (and 80 / n cd radially)
        // apart: the nearest sample is within about that of the nearest point.
        let step = (180.0 / rows as f64).max(360.0 / cols as f64) / n as f64;
        let spacing = 120.0 * step.to_radians() + 80.0 / n as f64;
        for ((d, m), e) in points.iter().zip(&exact) {
            let p = *m * *d;
            let brute = surface.iter().map(|s| (p - *s).length()).fold(f64::INFINITY, f64::min);
            assert!(*e <= brute + 1e-9, "{d} {m}: exact {e} above a sample's {brute}");
            assert!(
                *e >= brute - spacing,
                "{d} {m}: exact {e} far below the samples' {brute}"
            );
        }
    }
}
