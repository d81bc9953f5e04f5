//! Lobe mixtures (`lobes:K`): K cosine-power lobes
//! `I(d) = Σ_k w_k · max(0, d · a_k)^{p_k}`, free axes `a_k`, exponents
//! `p_k` ∈ [0, [`MAX_LOBE_EXPONENT`]] and weights `w_k ≥ 0`.
//!
//! LED and reflector distributions are fitted well by a few such lobes
//! (Moreno and Sun 2008, Opt. Express 16(3): sums of 2–3 Gaussian or cosine
//! lobes); Zotti, Neumann and Purgathofer's OpenGL model (2005) is two.
//!
//! # Fit
//! The same family of search as the OpenGL-light fit (`fit::optimize`):
//! the weights are profiled out exactly (for fixed shapes, non-negative
//! linear least squares on the normal equations), the shapes are searched
//! as `u = ln(1 + p)` and tangent coordinates of the axis (a chart centred
//! on the start axis: no singularity at a pole) by a coarse exponent grid
//! and Nelder–Mead. Lobes are added one at a time, each started from the
//! peak of what the lobes so far leave unexplained (the first from the
//! distribution's peak, the next from its next peak), then every lobe is
//! refined in turn with the others fixed (Zotti et al. 2005, §4: alternating
//! refinement). The fit of K lobes is therefore a by-product of the fit of
//! K + 1: [`fit_lobes`] returns every stage.
//!
//! The error minimised is the solid-angle-weighted squared radial error
//! `Σ ΔΩ_k (I_model − I_k)²` over the measured directions (relative to
//! I_max): the quantity the trade table's radial RMS reports. Rotationally
//! symmetric data gets rings ([`Lobes::rings`]): each lobe swept about the
//! vertical axis, its tilt the ring's polar angle (a tilted plain lobe is
//! not rotational; a vertical ring is the plain lobe).
//! Large grids are searched on a thinned copy (at most [`SEARCH_DIRECTIONS`]
//! directions); the final weights come from all of them.
//!
//! # Storage
//! The representation, [`Lobes`], lives in [`crate::reconstruct::lobes`]
//! (20 bytes a lobe); it is re-exported here.

use glam::DVec3;

use super::objective::{ErrorMetric, Samples, DEFAULT_GUARD};
use crate::error::ModelError;
use crate::minimize::nelder_mead;
use crate::model::Distribution;
use crate::reconstruct::lobes::{lobe_factor, ring_cosine};
pub use crate::reconstruct::lobes::{Lobe, Lobes, LOBE_BYTES, MAX_LOBE_EXPONENT};

/// Largest lobe count accepted.
pub const MAX_LOBES: usize = 16;
/// Largest weight of a lobe, relative to I_max (as the OpenGL fit's spots).
pub const MAX_LOBE_WEIGHT: f64 = 10.0;
/// Directions the shape search runs on at most (thinned planes and rows).
pub const SEARCH_DIRECTIONS: usize = 2000;

/// Rounds of alternating refinement at most.
const ROUNDS: usize = 2;
/// Exponents on the coarse grid of a new lobe.
const U_GRID: usize = 17;

/// The data of a lobe fit: unit directions, magnitudes `I / I_max` and
/// solid-angle weights (summing to 1).
struct Data {
    dir: Vec<DVec3>,
    m: Vec<f64>,
    w: Vec<f64>,
    mm: f64,
    /// Distinct directions a lobe's half-maximum cone must hold ([`Data::supported`]).
    support: usize,
    /// Lobes are rings about the vertical axis ([`ring_cosine`]).
    rings: bool,
}

impl Data {
    fn of(s: &Samples) -> Self {
        // One kept plane stands for a ring: two samples on it pin a vertical lobe's width.
        let support = if s.rotational { 2 } else { 3 };
        Self::new(s.dir.clone(), s.m.clone(), s.omega.clone(), support, s.rotational)
    }
    fn new(dir: Vec<DVec3>, m: Vec<f64>, w: Vec<f64>, support: usize, rings: bool) -> Self {
        let mm = w.iter().zip(&m).map(|(w, m)| w * m * m).sum();
        Self {
            dir,
            m,
            w,
            mm,
            support,
            rings,
        }
    }
    /// The cosine between a measured direction and a lobe's axis (of its ring
    /// through `d`'s C-plane when the lobes are rings).
    fn cosine(&self, d: DVec3, axis: DVec3) -> f64 {
        if self.rings {
            ring_cosine(d, axis)
        } else {
            d.dot(axis)
        }
    }
    /// Every `k`-th direction (weights scaled by k), or `None` when small enough.
    fn thinned(&self, max: usize) -> Option<Self> {
        let k = self.dir.len().div_ceil(max.max(1));
        if k <= 1 {
            return None;
        }
        // A prime stride does not alias onto the plane-major grid's rows.
        let k = [2, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37, 41, 43, 47]
            .into_iter()
            .find(|&p| p >= k)
            .unwrap_or(k);
        let idx: Vec<usize> = (0..self.dir.len()).step_by(k).collect();
        Some(Self::new(
            idx.iter().map(|&i| self.dir[i]).collect(),
            idx.iter().map(|&i| self.m[i]).collect(),
            idx.iter().map(|&i| self.w[i] * k as f64).collect(),
            self.support,
            self.rings,
        ))
    }
    /// Exponent `p`, lowered until the lobe's half-maximum cone around `axis`
    /// (`t^p ≥ 1/2`) holds [`Data::support`] distinct measured directions.
    ///
    /// Between measured directions the error sees nothing: without this a
    /// lobe narrower than the grid's spacing, aimed between samples, costs
    /// nothing where it is fitted and rises far above every measurement
    /// where it is not (on a real 5-plane file a p = 800 lobe of 6 I_max
    /// between the kept planes of a hold-out fold: 600 % radial error at the
    /// withheld ones). Three directions pin a peak's position and width on
    /// a grid (two on the kept plane of rotational data).
    fn supported(&self, axis: DVec3, p: f64) -> f64 {
        let mut near: Vec<(f64, DVec3)> = Vec::with_capacity(self.support + 1);
        for &d in &self.dir {
            let t = self.cosine(d, axis);
            // Poles repeat once per plane: a direction already held is not a new sample.
            if near.len() == self.support && t <= near[self.support - 1].0
                || near.iter().any(|(_, e)| e.distance_squared(d) < 1e-18)
            {
                continue;
            }
            let at = near.iter().position(|&(u, _)| t > u).unwrap_or(near.len());
            near.insert(at, (t, d));
            near.truncate(self.support);
        }
        let t = match near.get(self.support - 1) {
            Some(&(t, _)) => t,
            None => return p,
        };
        if t >= 1.0 {
            p
        } else if t <= 0.0 {
            0.0
        } else {
            p.min(0.5f64.ln() / t.ln())
        }
    }
    /// The lobe's values at every direction, its exponent [`Data::supported`].
    fn column(&self, axis: DVec3, p: f64) -> Vec<f64> {
        let p = self.supported(axis, p);
        self.dir.iter().map(|&d| lobe_factor(self.cosine(d, axis), p)).collect()
    }
}

/// One lobe's shape in search coordinates: a chart centred on `centre`.
/// A ring's axis only tilts: its azimuth does not change the ring, so its
/// chart is the one tangent in the vertical plane through the centre
/// (`y` unused), which keeps the search two-dimensional.
#[derive(Debug, Clone, Copy)]
struct Shape {
    centre: DVec3,
    u: f64,
    x: f64,
    y: f64,
    ring: bool,
}

impl Shape {
    fn at(axis: DVec3, u: f64, ring: bool) -> Self {
        Self {
            centre: axis,
            u,
            x: 0.0,
            y: 0.0,
            ring,
        }
    }
    fn axis(&self) -> DVec3 {
        let c = self.centre;
        let moved = if self.ring {
            // Tilt within the vertical plane through the centre (the x-z plane at a pole).
            let h = c.truncate().try_normalize().unwrap_or(glam::DVec2::X);
            let tilt = DVec3::new(h.x * c.z, h.y * c.z, -c.truncate().length());
            let tilt = tilt.try_normalize().unwrap_or(DVec3::new(h.x, h.y, 0.0));
            c + self.x * tilt
        } else {
            let (t1, t2) = c.any_orthonormal_pair();
            c + self.x * t1 + self.y * t2
        };
        moved.try_normalize().unwrap_or(c)
    }
    fn exponent(&self) -> f64 {
        (self.u.exp() - 1.0).clamp(0.0, MAX_LOBE_EXPONENT)
    }
    /// The same shape in a chart centred on its own axis.
    fn recentred(&self) -> Self {
        Self::at(self.axis(), self.u, self.ring)
    }
}

/// Non-negative least squares `min aᵀGa − 2aᵀr`, a ≥ 0, by an active set
/// (Lawson and Hanson 1974) on the small normal equations; each weight
/// capped at [`MAX_LOBE_WEIGHT`].
fn nnls(g: &[Vec<f64>], r: &[f64]) -> Vec<f64> {
    let n = r.len();
    let mut free = vec![true; n];
    let mut a = vec![0.0; n];
    for _ in 0..3 * n + 3 {
        let idx: Vec<usize> = (0..n).filter(|&i| free[i]).collect();
        let sol = solve(g, r, &idx);
        match idx
            .iter()
            .zip(&sol)
            .filter(|(_, v)| **v < 0.0)
            .min_by(|x, y| x.1.total_cmp(y.1))
        {
            Some((&i, _)) => free[i] = false,
            None => {
                a.iter_mut().for_each(|x| *x = 0.0);
                for (&i, &v) in idx.iter().zip(&sol) {
                    a[i] = v;
                }
                // A fixed weight whose gradient asks to grow rejoins the free set.
                let grad = |j: usize| r[j] - (0..n).map(|k| g[j][k] * a[k]).sum::<f64>();
                match (0..n)
                    .filter(|&j| !free[j] && grad(j) > 1e-14)
                    .max_by(|&x, &y| grad(x).total_cmp(&grad(y)))
                {
                    Some(j) => free[j] = true,
                    None => break,
                }
            }
        }
    }
    a.iter()
        .map(|&x| {
            if x.is_finite() {
                x.clamp(0.0, MAX_LOBE_WEIGHT)
            } else {
                0.0
            }
        })
        .collect()
}

/// Solve `G[idx, idx] x = r[idx]` by Gaussian elimination with partial
/// pivoting and a tiny ridge (a lobe that misses every direction has a zero column).
fn solve(g: &[Vec<f64>], r: &[f64], idx: &[usize]) -> Vec<f64> {
    let n = idx.len();
    let scale = idx.iter().map(|&i| g[i][i]).fold(0.0, f64::max);
    let ridge = 1e-12 * scale + 1e-300;
    let mut a: Vec<Vec<f64>> = idx
        .iter()
        .enumerate()
        .map(|(p, &i)| {
            let mut row: Vec<f64> = idx.iter().map(|&j| g[i][j]).collect();
            row[p] += ridge;
            row.push(r[i]);
            row
        })
        .collect();
    for c in 0..n {
        let piv = (c..n)
            .max_by(|&x, &y| a[x][c].abs().total_cmp(&a[y][c].abs()))
            .unwrap_or(c);
        a.swap(c, piv);
        let d = a[c][c];
        if d.abs() < 1e-300 {
            continue;
        }
        let pivot = a[c].clone();
        for row in a.iter_mut().skip(c + 1) {
            let f = row[c] / d;
            for (x, p) in row[c..].iter_mut().zip(&pivot[c..]) {
                *x -= f * p;
            }
        }
    }
    let mut x = vec![0.0; n];
    for c in (0..n).rev() {
        let s: f64 = (c + 1..n).map(|k| a[c][k] * x[k]).sum();
        x[c] = if a[c][c].abs() < 1e-300 {
            0.0
        } else {
            (a[c][n] - s) / a[c][c]
        };
    }
    x
}

/// The search state: the data, the lobes' shapes and their columns, and
/// the normal equations of those columns (`gram[a][b]` = Σ w·c_a·c_b for
/// a ≤ b, mirrored; `rhs[a]` = Σ w·c_a·m): a trial changes one column, so
/// only that column's row is recomputed per evaluation (K + 1 sums of the
/// K (K + 3) / 2 a full rebuild takes), with the same sums in the same order.
struct Search<'a> {
    data: &'a Data,
    shapes: Vec<Shape>,
    cols: Vec<Vec<f64>>,
    gram: Vec<Vec<f64>>,
    rhs: Vec<f64>,
}

/// Σ w·x·y over the directions, x from the lower-numbered column (the
/// order every entry of the normal equations is summed in).
fn weighted_dot(x: &[f64], y: &[f64], w: &[f64]) -> f64 {
    x.iter().zip(y).zip(w).map(|((x, y), w)| w * x * y).sum()
}

impl<'a> Search<'a> {
    /// err² and weights with lobe `j`'s column replaced by `col` (or appended when j = len).
    #[allow(clippy::needless_range_loop)] // the Gram matrix is filled symmetrically
    fn error_with(&self, j: usize, col: &[f64]) -> (f64, Vec<f64>) {
        let n = self.cols.len().max(j + 1);
        let d = self.data;
        let mut g = vec![vec![0.0; n]; n];
        let mut r = vec![0.0; n];
        for a in 0..n {
            if a == j {
                continue;
            }
            r[a] = self.rhs[a];
            for b in a..n {
                if b != j {
                    g[a][b] = self.gram[a][b];
                    g[b][a] = g[a][b];
                }
            }
        }
        r[j] = weighted_dot(col, &d.m, &d.w);
        for b in 0..n {
            let v = match b.cmp(&j) {
                std::cmp::Ordering::Less => weighted_dot(&self.cols[b], col, &d.w),
                std::cmp::Ordering::Equal => weighted_dot(col, col, &d.w),
                std::cmp::Ordering::Greater => weighted_dot(col, &self.cols[b], &d.w),
            };
            g[j][b] = v;
            g[b][j] = v;
        }
        let wts = nnls(&g, &r);
        let mut e = d.mm;
        for a in 0..n {
            let ga: f64 = g[a].iter().zip(&wts).map(|(x, w)| x * w).sum();
            e += wts[a] * (ga - 2.0 * r[a]);
        }
        (e.max(0.0), wts)
    }

    fn eval(&self, j: usize, s: &Shape) -> f64 {
        self.error_with(j, &self.data.column(s.axis(), s.exponent())).0
    }

    /// Coarse exponent grid, then Nelder–Mead in (u, x, y), for lobe `j` from `start`.
    fn shape_search(&self, j: usize, start: Shape, coarse: bool, scale: f64, max_evals: usize) -> Shape {
        let mut best = start;
        let mut best_e = self.eval(j, &best);
        if coarse {
            let um = (1.0 + MAX_LOBE_EXPONENT).ln();
            for i in 0..U_GRID {
                let s = Shape {
                    u: um * i as f64 / (U_GRID - 1) as f64,
                    ..start
                };
                let e = self.eval(j, &s);
                if e < best_e {
                    (best, best_e) = (s, e);
                }
            }
        }
        let mut f = |v: &[f64]| {
            let s = Shape {
                u: v[0].clamp(0.0, (1.0 + MAX_LOBE_EXPONENT).ln()),
                x: v[1],
                y: v.get(2).copied().unwrap_or(0.0),
                ..best
            };
            self.eval(j, &s)
        };
        let dims = if best.ring { 2 } else { 3 };
        let steps = [0.3 * scale, 0.1 * scale, 0.1 * scale];
        let ftol = 1e-15 + 1e-10 * best_e;
        let start = [best.u, best.x, best.y];
        let (x, e, _) = nelder_mead(&mut f, &start[..dims], &steps[..dims], max_evals, ftol, 1e-6);
        if e < best_e {
            let s = Shape {
                u: x[0].clamp(0.0, (1.0 + MAX_LOBE_EXPONENT).ln()),
                x: x[1],
                y: x.get(2).copied().unwrap_or(0.0),
                ..best
            };
            return s.recentred();
        }
        best.recentred()
    }

    fn set(&mut self, j: usize, s: Shape) {
        // Keep the exponent the error was evaluated with: above the cap of
        // Data::supported the error is flat, and the search may have drifted there.
        let s = Shape {
            u: self.data.supported(s.axis(), s.exponent()).ln_1p(),
            ..s
        };
        let col = self.data.column(s.axis(), s.exponent());
        if j == self.shapes.len() {
            self.shapes.push(s);
            self.cols.push(col);
        } else {
            self.shapes[j] = s;
            self.cols[j] = col;
        }
        self.update_normal_equations(j);
    }

    /// A search over `shapes` whose columns are `cols`, its normal equations built.
    fn new(data: &'a Data, shapes: Vec<Shape>, cols: Vec<Vec<f64>>) -> Self {
        let mut s = Self {
            data,
            shapes,
            cols,
            gram: Vec::new(),
            rhs: Vec::new(),
        };
        for j in 0..s.cols.len() {
            s.update_normal_equations(j);
        }
        s
    }

    /// Column `j`'s row of the normal equations, after it changed or was appended.
    fn update_normal_equations(&mut self, j: usize) {
        let n = self.cols.len();
        self.gram.resize(n, Vec::new());
        for row in &mut self.gram {
            row.resize(n, 0.0);
        }
        self.rhs.resize(n, 0.0);
        let (d, col) = (self.data, &self.cols[j]);
        self.rhs[j] = weighted_dot(col, &d.m, &d.w);
        for b in 0..n {
            let v = if b <= j {
                weighted_dot(&self.cols[b], col, &d.w)
            } else {
                weighted_dot(col, &self.cols[b], &d.w)
            };
            self.gram[j][b] = v;
            self.gram[b][j] = v;
        }
    }
}

/// Fit mixtures of 1 to `max_count` lobes to `d` (see the module docs).
/// Element `k − 1` is the mixture of k lobes.
///
/// # Errors
/// [`ModelError::Parameter`] (`lobes`) for a count of 0 or above
/// [`MAX_LOBES`]; [`ModelError::AllZero`] for data without light.
pub fn fit_lobes(d: &Distribution, max_count: usize) -> Result<Vec<Lobes>, ModelError> {
    if max_count == 0 || max_count > MAX_LOBES {
        return Err(ModelError::Parameter {
            name: "lobes",
            value: max_count.to_string(),
            reason: format!("the lobe count K must be 1 to {MAX_LOBES}"),
        });
    }
    let s = Samples::new(d, ErrorMetric::SolidAngle, DEFAULT_GUARD)?;
    let full = Data::of(&s);
    let thin = full.thinned(SEARCH_DIRECTIONS);
    let data = thin.as_ref().unwrap_or(&full);
    let mut search = Search::new(data, Vec::new(), Vec::new());
    let mut stages = Vec::with_capacity(max_count);
    for k in 0..max_count {
        let new = start_axes(&search, s.rotational)
            .into_iter()
            .map(|axis| {
                let found = search.shape_search(k, Shape::at(axis, 1.0, s.rotational), true, 1.0, 150);
                (search.eval(k, &found), found)
            })
            .min_by(|a, b| a.0.total_cmp(&b.0))
            .map_or_else(|| Shape::at(DVec3::NEG_Z, 1.0, s.rotational), |(_, found)| found);
        search.set(k, new);
        // Alternating refinement: every lobe with the others fixed, while it gains.
        let mut e = search.error_with(k, &search.cols[k]).0;
        for _round in 0..ROUNDS {
            for j in 0..=k {
                let r = search.shape_search(j, search.shapes[j], false, 0.3, 60);
                search.set(j, r);
            }
            let now = search.error_with(k, &search.cols[k]).0;
            let gain = e - now;
            e = now;
            if gain <= 1e-6 * e + 1e-15 {
                break;
            }
        }
        stages.push(weighted(&full, &search.shapes, s.i_max));
    }
    Ok(stages)
}

/// The start axes of the next lobe: the direction of the largest residual
/// (measured minus the lobes so far), the data's peak for the first lobe;
/// for rotational data (rings) also the vertical towards the residual's
/// hemisphere, a plain lobe, which a peak a grid step off the pole would
/// otherwise start as a narrow ring.
fn start_axes(search: &Search<'_>, rotational: bool) -> Vec<DVec3> {
    let d = search.data;
    let wts = if search.cols.is_empty() {
        Vec::new()
    } else {
        let last = search.cols.len() - 1;
        search.error_with(last, &search.cols[last]).1
    };
    let model = |i: usize| -> f64 { search.cols.iter().zip(&wts).map(|(c, w)| c[i] * w).sum() };
    let best = (0..d.dir.len())
        .max_by(|&a, &b| (d.m[a] - model(a)).total_cmp(&(d.m[b] - model(b))))
        .map_or(DVec3::NEG_Z, |i| d.dir[i]);
    if rotational {
        vec![if best.z > 0.0 { DVec3::Z } else { DVec3::NEG_Z }, best]
    } else {
        vec![best]
    }
}

/// The mixture of `shapes` with weights solved on all of `full`, in cd.
fn weighted(full: &Data, shapes: &[Shape], i_max: f64) -> Lobes {
    let cols = shapes.iter().map(|s| full.column(s.axis(), s.exponent())).collect();
    let search = Search::new(full, shapes.to_vec(), cols);
    let last = shapes.len() - 1;
    let (_, wts) = search.error_with(last, &search.cols[last]);
    let mixture = if full.rings { Lobes::rings } else { Lobes::new };
    mixture(
        shapes
            .iter()
            .zip(&wts)
            .map(|(s, w)| Lobe {
                axis: s.axis(),
                exponent: full.supported(s.axis(), s.exponent()),
                weight_cd: w * i_max,
            })
            .collect(),
    )
}
