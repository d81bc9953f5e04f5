//! The error functions of the fit and the exact cut-off profile.
//!
//! # Error (Zotti, Neumann, Purgathofer 2005, §3 "The Error Function"; docs/domain.md §6)
//! The data are scaled to magnitudes `m = I / I_max` (max 1); for the model
//! `a` (same scale) the error is
//! `err = sqrt(Σ_k w_k ((a_k − m_k) / (m_k + C))²)` over every measured
//! direction `k` of the full circle of planes (symmetry expanded), with
//! - [`ErrorMetric::Relative`]: `w_k = 1/N`, Zotti et al.'s formula (every
//!   (θ, φ) pair counts once, so the poles, where every plane meets, count
//!   once per plane);
//! - [`ErrorMetric::SolidAngle`]: `w_k = ΔΩ_k / Σ ΔΩ` (= ΔΩ_k / 4π on
//!   full-sphere data), the cell's share of the measured sphere, so the poles
//!   are not over-weighted. Normalising by the measured solid angle keeps the
//!   two errors on one scale for hemisphere data too.
//!
//! `C` ([`DEFAULT_GUARD`] = 0.02, i.e. 2 % of I_max) keeps dark directions
//! from dividing by zero and sets where "relative" turns into "absolute":
//! where `m ≫ C` a direction's error is its relative error (1 % off at the
//! peak costs about 1 %), where `m ≪ C` it is the absolute error in units of
//! `C·I_max` (light of 2 % of I_max in a dark direction costs 100 %).
//! Negative measured values count as 0.
//!
//! Writing `ρ_k = w_k / (m_k + C)²`, `err² = Σ ρ_k (a_k − m_k)²` is a
//! weighted least-squares problem that is linear in the light weights: for
//! fixed shapes the weights come from the normal equations (docs/domain.md §7.2).
//!
//! # Cut-off profile
//! For one spot of fixed axis and exponent, every cut-off is tried at once:
//! the directions are binned by their angle to the axis (900 bins, about
//! 0.1° each; only the occupied ones are summed and walked), prefix
//! sums of `ρ s²`, `ρ s m`, `ρ s b` give the optimal weights (2×2
//! non-negative least squares with the other light `b`) for every bin
//! boundary in O(N), and the best boundary is refined exactly among
//! the data's own breakpoints (the directions in the neighbouring bins,
//! sorted). The cut-off reported is the midpoint between the last lit and the
//! first dark direction: the data cannot place it better than that.

use serde::Serialize;

use glam::DVec3;

use super::fastmath;
use crate::error::ModelError;
use crate::model::frame::grid_directions;
use crate::model::{periodic_widths, Distribution, Symmetry};

/// Default guard constant `C` of the error, relative to I_max (2 %).
pub const DEFAULT_GUARD: f64 = 0.02;

/// Largest on-axis intensity of a fitted spot, relative to I_max. A spot whose
/// axis points between measured directions could otherwise grow a huge,
/// unmeasured spike; 10 I_max leaves any real fit free.
pub const MAX_RELATIVE_WEIGHT: f64 = 10.0;

/// Grids of at least this many directions get a thinned copy for the search's
/// exploratory stage ([`Samples::thinned`]).
const THIN_FROM: usize = 1500;
/// About how many directions the thinned copy keeps: exploration needs the
/// shape of the distribution, not every reading (a 360 × 181 grid, 65,160
/// directions, is explored on 1,860; the refinement runs on the full grid).
const THIN_TO: usize = 2000;

/// Number of coarse cut-off bins over [0°, 90°].
const N_BINS: usize = 900;

/// Which error the fit minimises.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Default)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "kebab-case")]
pub enum ErrorMetric {
    /// Zotti et al.'s relative radial error (2005, §3), every measured (C, γ) pair weighted 1/N.
    #[default]
    Relative,
    /// The same, each direction weighted by its solid angle ΔΩ_k / Σ ΔΩ.
    SolidAngle,
}

impl ErrorMetric {
    /// CLI name.
    pub fn name(self) -> &'static str {
        match self {
            ErrorMetric::Relative => "relative",
            ErrorMetric::SolidAngle => "solid-angle",
        }
    }
}

/// The measured directions, scaled magnitudes and weights of one fit.
#[derive(Debug, Clone)]
pub(crate) struct Samples {
    /// Unit directions (luminaire frame).
    pub dir: Vec<DVec3>,
    /// Magnitudes m = max(I, 0) / I_max.
    pub m: Vec<f64>,
    /// ρ = w / (m + C)².
    pub rho: Vec<f64>,
    /// Solid-angle share of each direction (sums to 1), for mean directions.
    pub omega: Vec<f64>,
    /// I_max, cd.
    pub i_max: f64,
    /// Σ ρ m².
    pub mm: f64,
    /// Σ ρ.
    pub rho_sum: f64,
    /// Σ ρ m.
    pub rho_m: f64,
    /// Whether the data is rotationally symmetric (one plane kept).
    pub rotational: bool,
    /// Whether any direction lies strictly below / above the horizontal.
    pub measured: [bool; 2],
    /// Whether any direction strictly below / above the horizontal is lit (m > 0).
    pub lit: [bool; 2],
    /// Number of full-circle planes and of γ angles (directions are plane-major).
    pub shape: (usize, usize),
}

impl Samples {
    /// Directions and weights of `d` for `metric` with guard `guard` (relative to I_max).
    pub fn new(d: &Distribution, metric: ErrorMetric, guard: f64) -> Result<Self, ModelError> {
        if !(guard.is_finite() && guard > 0.0) {
            return Err(ModelError::Parameter {
                name: "guard",
                value: guard.to_string(),
                reason: "must be a positive fraction of I_max".into(),
            });
        }
        let i_max = d.max_cd();
        if i_max.is_nan() || i_max <= 0.0 {
            return Err(ModelError::AllZero("fitting OpenGL lights needs some light"));
        }
        // Identical planes: keep one, so the model's axis can be fixed vertical
        // and the sums are n_C times shorter (the mean error is the same).
        let rot_d;
        let d = if d.symmetry() != Symmetry::Rotational && d.detect_symmetry(1e-9 * i_max) == Symmetry::Rotational {
            rot_d = d.with_symmetry(Symmetry::Rotational)?;
            &rot_d
        } else {
            d
        };
        let rotational = d.symmetry() == Symmetry::Rotational;
        let Directions {
            dir,
            m,
            mut omega,
            measured,
            lit,
            shape,
        } = Directions::of(d, i_max);
        let n = dir.len();
        let total: f64 = omega.iter().sum();
        if total > 0.0 {
            omega.iter_mut().for_each(|o| *o /= total);
        } else {
            // A single γ angle spans no solid angle: fall back to equal shares.
            omega.iter_mut().for_each(|o| *o = 1.0 / n as f64);
        }
        let rho = weights(&m, &omega, metric, guard);
        let mm = rho.iter().zip(&m).map(|(r, x)| r * x * x).sum();
        let rho_sum = rho.iter().sum();
        let rho_m = rho.iter().zip(&m).map(|(r, x)| r * x).sum();
        Ok(Self {
            dir,
            m,
            rho,
            omega,
            i_max,
            mm,
            rho_sum,
            rho_m,
            rotational,
            measured,
            lit,
            shape,
        })
    }

    /// Every k-th plane and every k-th γ angle (the last γ kept; k ≥ 2, chosen so
    /// that about [`THIN_TO`] directions remain), for the exploratory stage of the
    /// search on large grids; `None` when the grid is small enough (under
    /// [`THIN_FROM`] directions) to search on directly. The weights keep their
    /// ratios, so the error is the full one's up to sampling.
    pub fn thinned(&self) -> Option<Samples> {
        let (np, ng) = self.shape;
        if self.len() < THIN_FROM {
            return None;
        }
        let mut keep = Vec::new();
        // The same stride in planes and in γ, at least 2, so that about THIN_TO remain.
        let stride = ((self.len() as f64 / THIN_TO as f64).sqrt().ceil() as usize).max(2);
        for i in (0..np).step_by(if np >= 8 { stride } else { 1 }) {
            for j in 0..ng {
                if j % stride == 0 || j + 1 == ng {
                    keep.push(i * ng + j);
                }
            }
        }
        let f = self.len() as f64 / keep.len() as f64;
        let pick = |v: &Vec<f64>| keep.iter().map(|&k| v[k]).collect::<Vec<f64>>();
        let rho: Vec<f64> = keep.iter().map(|&k| self.rho[k] * f).collect();
        let m = pick(&self.m);
        let mm = rho.iter().zip(&m).map(|(r, x)| r * x * x).sum();
        let rho_sum = rho.iter().sum();
        let rho_m = rho.iter().zip(&m).map(|(r, x)| r * x).sum();
        Some(Samples {
            dir: keep.iter().map(|&k| self.dir[k]).collect(),
            omega: pick(&self.omega),
            m,
            rho,
            i_max: self.i_max,
            mm,
            rho_sum,
            rho_m,
            rotational: self.rotational,
            measured: self.measured,
            lit: self.lit,
            shape: (0, 0),
        })
    }

    /// Number of directions.
    pub fn len(&self) -> usize {
        self.m.len()
    }

    /// err² of a model giving magnitude `a(d)` (relative to I_max), evaluated directly.
    pub fn error_sq(&self, a: impl Fn(DVec3) -> f64) -> f64 {
        self.dir
            .iter()
            .zip(&self.m)
            .zip(&self.rho)
            .map(|((&d, &m), &r)| {
                let e = a(d) - m;
                r * e * e
            })
            .sum()
    }

    /// err² and the largest |a − m| (relative to I_max) of a model giving magnitude
    /// `a(d)`, in one pass over the directions.
    pub fn error_sq_and_max(&self, a: impl Fn(DVec3) -> f64) -> (f64, f64) {
        self.dir
            .iter()
            .zip(&self.m)
            .zip(&self.rho)
            .fold((0.0, 0.0f64), |(sq, max), ((&d, &m), &r)| {
                let e = a(d) - m;
                (sq + r * e * e, max.max(e.abs()))
            })
    }
}

/// The measured directions of a distribution and their magnitudes, before the
/// error's weights: what [`Samples::new`] weights.
struct Directions {
    /// Unit directions (luminaire frame), plane-major over the full circle of planes.
    dir: Vec<DVec3>,
    /// Magnitudes m = max(I, 0) / I_max.
    m: Vec<f64>,
    /// Solid angle of each direction's cell, sr (the plane's width times its γ band).
    omega: Vec<f64>,
    /// Whether any direction lies strictly below / above the horizontal.
    measured: [bool; 2],
    /// Whether any direction strictly below / above the horizontal is lit (m > 0).
    lit: [bool; 2],
    /// Number of full-circle planes and of γ angles.
    shape: (usize, usize),
}

impl Directions {
    /// Every measured direction of `d` (its planes expanded to the full circle), with
    /// magnitudes relative to `i_max` (cd) and cells half-way to the neighbours.
    fn of(d: &Distribution, i_max: f64) -> Self {
        let planes = d.full_planes();
        let widths = periodic_widths(&planes.iter().map(|p| p.0).collect::<Vec<_>>());
        let g = d.gamma_angles_deg();
        let ng = g.len();
        let band = gamma_bands(g);
        let n = planes.len() * ng;
        let c: Vec<f64> = planes.iter().map(|p| p.0).collect();
        let dir = grid_directions(&c, g);
        let mut m = Vec::with_capacity(n);
        let mut omega = Vec::with_capacity(n);
        let mut measured = [false; 2];
        let mut lit = [false; 2];
        for (&(_, ic), w) in planes.iter().zip(&widths) {
            let v = d.plane_cd(ic);
            for j in 0..ng {
                let mk = v[j].max(0.0) / i_max;
                m.push(mk);
                omega.push(w.to_radians() * band[j]);
                let h = if g[j] < 90.0 {
                    Some(0)
                } else if g[j] > 90.0 {
                    Some(1)
                } else {
                    None
                };
                if let Some(h) = h {
                    measured[h] = true;
                    lit[h] |= mk > 0.0;
                }
            }
        }
        Self {
            dir,
            m,
            omega,
            measured,
            lit,
            shape: (planes.len(), ng),
        }
    }
}

/// The γ band of each angle of `g` (degrees, ascending) as cos(lower edge) −
/// cos(upper edge), the solid angle of its cell per radian of plane width (sr/rad);
/// each band reaches half-way to its neighbours, inside the measured range.
fn gamma_bands(g: &[f64]) -> Vec<f64> {
    let ng = g.len();
    (0..ng)
        .map(|j| {
            let lo = if j == 0 { g[0] } else { 0.5 * (g[j - 1] + g[j]) };
            let hi = if j + 1 == ng {
                g[ng - 1]
            } else {
                0.5 * (g[j] + g[j + 1])
            };
            (lo.to_radians().cos() - hi.to_radians().cos()).max(0.0)
        })
        .collect()
}

/// ρ = w / (m + C)² of each direction with magnitude `m` and solid-angle share
/// `omega` (summing to 1), for `metric` (w = 1/N, or the share) and guard `guard` = C.
fn weights(m: &[f64], omega: &[f64], metric: ErrorMetric, guard: f64) -> Vec<f64> {
    let n = m.len();
    m.iter()
        .zip(omega)
        .map(|(&mk, &o)| {
            let w = match metric {
                ErrorMetric::Relative => 1.0 / n as f64,
                ErrorMetric::SolidAngle => o,
            };
            w / ((mk + guard) * (mk + guard))
        })
        .collect()
}

/// The other light of a two-light combination, held fixed while one spot's
/// shape is searched; its weight stays free (solved with the spot's).
#[derive(Debug, Clone)]
pub(crate) enum Other {
    /// No other light.
    None,
    /// A point light: b ≡ 1.
    Point,
    /// Another spot's unit-weight factor at every direction.
    Shape(Vec<f64>),
}

/// Best weights and cut-off for one spot shape (axis, exponent).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Profile {
    /// err² at the optimum.
    pub e: f64,
    /// Cut-off, degrees in [0, 90].
    pub cutoff_deg: f64,
    /// Spot weight, relative to I_max.
    pub w_spot: f64,
    /// Other light's weight, relative to I_max (0 without one).
    pub w_other: f64,
}

/// Evaluates the cut-off profile; owns its scratch buffers (one per thread).
pub(crate) struct Profiler<'a> {
    s: &'a Samples,
    other: Other,
    b2: f64,
    bm: f64,
    /// The sums of the last profile's occupied cut-off bins ([`FrontOf::slot_bin`]),
    /// 24 bytes per bin.
    bins: Vec<Bin>,
    /// The directions in front of the last axis profiled, with what does not depend on
    /// the exponent: searches try many exponents at one axis (the coarse grid, the
    /// golden-section polish, every evaluation of rotational data).
    front: FrontOf,
    /// t^p of each direction in front, for the last profile's exponent.
    factor: Vec<f64>,
    window: Vec<(f64, f64, f64, f64)>,
    /// Number of profile evaluations so far.
    pub evals: usize,
}

/// The bins are uniform in q = sin(θ/2) = sqrt((1 − t)/2) (no acos per
/// direction; q is within 11 % of linear in θ on [0°, 90°]).
const Q_MAX: f64 = std::f64::consts::FRAC_1_SQRT_2;

/// θ in degrees of q = sin(θ/2).
#[inline]
fn theta_deg(q: f64) -> f64 {
    2.0 * q.min(1.0).asin().to_degrees()
}

impl<'a> Profiler<'a> {
    pub fn new(s: &'a Samples, other: Other) -> Self {
        let (b2, bm) = match &other {
            Other::None => (0.0, 0.0),
            Other::Point => (s.rho_sum, s.rho_m),
            Other::Shape(b) => b
                .iter()
                .zip(&s.rho)
                .zip(&s.m)
                .fold((0.0, 0.0), |(x, y), ((&b, &r), &m)| (x + r * b * b, y + r * b * m)),
        };
        Self {
            s,
            other,
            b2,
            bm,
            bins: Vec::new(),
            window: Vec::new(),
            front: FrontOf::with_capacity(s.len()),
            factor: Vec::with_capacity(s.len()),
            evals: 0,
        }
    }

    /// Number of directions profiled.
    pub fn len(&self) -> usize {
        self.s.len()
    }

    /// Optimal (non-negative) weights and err² for the spot sums (Σρs², Σρsm, Σρsb).
    #[inline]
    fn solve(&self, s2: f64, sm: f64, sb: f64) -> (f64, f64, f64) {
        let mm = self.s.mm;
        let mut best = (mm, 0.0, 0.0);
        // Spot alone.
        if s2 > 0.0 && sm > 0.0 {
            let w = sm / s2;
            if w <= MAX_RELATIVE_WEIGHT {
                let e = mm - w * sm;
                if e < best.0 {
                    best = (e, w, 0.0);
                }
            }
        }
        if matches!(self.other, Other::None) {
            return best;
        }
        let (b2, bm) = (self.b2, self.bm);
        // Other alone.
        if b2 > 0.0 && bm > 0.0 {
            let w = bm / b2;
            let e = mm - w * bm;
            if e < best.0 {
                best = (e, 0.0, w);
            }
        }
        // Both (the 2×2 normal equations), when well conditioned and feasible.
        let det = s2 * b2 - sb * sb;
        if det > 1e-12 * s2 * b2 {
            let ws = (sm * b2 - bm * sb) / det;
            let wo = (bm * s2 - sm * sb) / det;
            if ws >= 0.0 && wo >= 0.0 && ws <= MAX_RELATIVE_WEIGHT {
                let e = mm - ws * sm - wo * bm;
                if e < best.0 {
                    best = (e, ws, wo);
                }
            }
        }
        best
    }

    /// The best cut-off and weights for a spot with unit `axis` and exponent `p`.
    pub fn profile(&mut self, axis: DVec3, p: f64) -> Profile {
        self.evals += 1;
        self.bin_directions(axis, p);
        let boundary = self.best_bin_boundary();
        self.best_split_near(boundary).into_profile()
    }

    /// Fills the bins ([`Bin`]) with the directions in front of a unit-weight spot
    /// with unit `axis` and exponent `p`, each binned by q = sin(θ/2) of its angle θ
    /// to the axis.
    fn bin_directions(&mut self, axis: DVec3, p: f64) {
        self.front.aim(self.s, axis, &self.other);
        let front = &self.front;
        // t^p = exp(p ln t) (`spot_factor(t, p, 0)` for t in [0, 1]: p = 0 lights every
        // direction in front, t = 0 is dark for p > 0), in one pass that runs in vector lanes.
        self.factor.clear();
        if p == 0.0 {
            self.factor.resize(front.ln_t.len(), 1.0);
        } else {
            self.factor
                .extend(front.ln_t.iter().map(|&l| fastmath::exp_nonpositive(p * l)));
        }
        // Only the bins some direction falls in: an axis near the grid's own lights a
        // few rings (19 at 5° steps for a vertical axis), and clearing and walking all
        // 900 bins cost more than the directions on grids of a few thousand readings.
        self.bins.clear();
        self.bins.resize(front.slot_bin.len(), Bin::default());
        let terms = front.rho.iter().zip(&front.rho_m).zip(&front.rho_b);
        for ((&slot, &sv), ((&rho, &rho_m), &rho_b)) in front.slot.iter().zip(&self.factor).zip(terms) {
            let bin = &mut self.bins[slot as usize];
            bin.s2 += rho * sv * sv;
            bin.sm += rho_m * sv;
            bin.sb += rho_b * sv;
        }
    }

    /// The coarse cut-off: the bin boundary j (the bins below j lit, the rest dark)
    /// of the smallest error, 0 when no lit bin beats the spot off.
    fn best_bin_boundary(&self) -> usize {
        let (mut s2, mut sm, mut sb) = (0.0, 0.0, 0.0);
        let mut best_j = 0;
        let mut best_e = self.solve(0.0, 0.0, 0.0).0;
        for (bin, &j) in self.bins.iter().zip(&self.front.slot_bin) {
            s2 += bin.s2;
            sm += bin.sm;
            sb += bin.sb;
            let e = self.solve(s2, sm, sb).0;
            if e < best_e {
                best_e = e;
                best_j = j as usize + 1;
            }
        }
        best_j
    }

    /// The exact cut-off: the best split among the directions of the bins around
    /// bin boundary `best_j` (the coarse one), every direction below them lit.
    fn best_split_near(&mut self, best_j: usize) -> Split {
        let lo = best_j.saturating_sub(2);
        let hi = (best_j + 1).min(N_BINS - 1);
        let (mut s2, mut sm, mut sb) = (0.0, 0.0, 0.0);
        let below = self.front.slot_bin.partition_point(|&j| (j as usize) < lo);
        for bin in &self.bins[..below] {
            s2 += bin.s2;
            sm += bin.sm;
            sb += bin.sb;
        }
        let mut q_in = f64::NEG_INFINITY; // largest lit q below the window
        let mut q_after = f64::INFINITY; // smallest dark q above the window
        self.window.clear();
        let front = &self.front;
        for (i, (&bin, &q)) in front.bin.iter().zip(&front.q).enumerate() {
            let b = bin as usize;
            if b < lo {
                q_in = q_in.max(q);
            } else if b > hi {
                q_after = q_after.min(q);
            } else {
                // The window's few directions: their terms, as the bins summed them.
                let sv = self.factor[i];
                self.window
                    .push((q, front.rho[i] * sv * sv, front.rho_m[i] * sv, front.rho_b[i] * sv));
            }
        }
        self.window.sort_unstable_by(|a, b| a.0.total_cmp(&b.0));
        let (e, w_spot, w_other) = self.solve(s2, sm, sb);
        let q_dark = self.window.first().map_or(q_after, |w| w.0);
        let mut best = Split {
            e,
            w_spot,
            w_other,
            q_lit: q_in,
            q_dark,
        };
        let mut i = 0;
        while i < self.window.len() {
            // Directions at the same angle are lit or dark together.
            let q = self.window[i].0;
            while i < self.window.len() && self.window[i].0 <= q + 1e-12 {
                s2 += self.window[i].1;
                sm += self.window[i].2;
                sb += self.window[i].3;
                i += 1;
            }
            let (e, w_spot, w_other) = self.solve(s2, sm, sb);
            if e < best.e {
                let q_dark = self.window.get(i).map_or(q_after, |w| w.0);
                best = Split {
                    e,
                    w_spot,
                    w_other,
                    q_lit: q,
                    q_dark,
                };
            }
        }
        best
    }
}

/// One cut-off bin's sums over its directions (ρs², ρsm, ρsb).
#[derive(Debug, Clone, Copy, Default)]
struct Bin {
    s2: f64,
    sm: f64,
    sb: f64,
}

/// The directions in front of one axis (t = cos θ ≥ 0), with what their factor t^p
/// and their cut-off bins need that does not depend on the exponent; rebuilt when
/// the axis changes. One array per quantity, so the passes over them run in
/// vector lanes.
#[derive(Debug, Clone)]
struct FrontOf {
    /// The axis these directions belong to (`None` before the first profile).
    axis: Option<DVec3>,
    /// Cut-off bin of q.
    bin: Vec<u32>,
    /// Index of the direction's bin among the occupied ones ([`FrontOf::slot_bin`]).
    slot: Vec<u32>,
    /// The occupied cut-off bins, ascending.
    slot_bin: Vec<u32>,
    /// Scratch: the slot of each of the [`N_BINS`] bins while the slots are numbered.
    slot_of_bin: Vec<u32>,
    /// q = sin(θ/2) = sqrt((1 − t)/2).
    q: Vec<f64>,
    /// ln t (−∞ at t = 0).
    ln_t: Vec<f64>,
    /// The direction's weight ρ.
    rho: Vec<f64>,
    /// ρ m: its weight times its measured magnitude.
    rho_m: Vec<f64>,
    /// ρ b: its weight times the other light's unit-weight factor.
    rho_b: Vec<f64>,
}

impl FrontOf {
    fn with_capacity(n: usize) -> Self {
        Self {
            axis: None,
            bin: Vec::with_capacity(n),
            slot: Vec::with_capacity(n),
            slot_bin: Vec::new(),
            slot_of_bin: vec![0; N_BINS],
            q: Vec::with_capacity(n),
            ln_t: Vec::with_capacity(n),
            rho: Vec::with_capacity(n),
            rho_m: Vec::with_capacity(n),
            rho_b: Vec::with_capacity(n),
        }
    }

    /// Make these the directions of `s` in front of unit `axis` (kept when it is
    /// the axis they already belong to).
    fn aim(&mut self, s: &Samples, axis: DVec3, other: &Other) {
        if self.axis == Some(axis) {
            return;
        }
        self.axis = Some(axis);
        self.rho.clear();
        self.rho_m.clear();
        self.rho_b.clear();
        // t first, in `ln_t`; the passes below turn it into q, the bin and ln t.
        self.ln_t.clear();
        for (k, d) in s.dir.iter().enumerate() {
            let t = d.dot(axis);
            // A cut-off of at most 90° never reaches directions behind the spot.
            if t < 0.0 {
                continue;
            }
            // The other light's unit-weight factor here.
            let b = match other {
                Other::None => 0.0,
                Other::Point => 1.0,
                Other::Shape(b) => b[k],
            };
            let rho = s.rho[k];
            self.ln_t.push(t.min(1.0));
            self.rho.push(rho);
            self.rho_m.push(rho * s.m[k]);
            self.rho_b.push(rho * b);
        }
        let scale = N_BINS as f64 / Q_MAX;
        self.q.clear();
        self.q.extend(self.ln_t.iter().map(|&t| (0.5 * (1.0 - t)).sqrt()));
        self.bin.clear();
        self.bin
            .extend(self.q.iter().map(|&q| ((q * scale) as u32).min(N_BINS as u32 - 1)));
        for t in &mut self.ln_t {
            *t = fastmath::ln_unit(*t);
        }
        self.number_slots();
    }

    /// Number the occupied bins in ascending order ([`FrontOf::slot_bin`]) and give
    /// each direction its bin's number ([`FrontOf::slot`]).
    fn number_slots(&mut self) {
        const EMPTY: u32 = u32::MAX;
        self.slot_of_bin.fill(EMPTY);
        for &b in &self.bin {
            self.slot_of_bin[b as usize] = 0;
        }
        self.slot_bin.clear();
        for (b, slot) in self.slot_of_bin.iter_mut().enumerate() {
            if *slot != EMPTY {
                *slot = self.slot_bin.len() as u32;
                self.slot_bin.push(b as u32);
            }
        }
        self.slot.clear();
        self.slot.extend(self.bin.iter().map(|&b| self.slot_of_bin[b as usize]));
    }
}

/// A split of the directions in front of a spot into lit and dark, with the
/// weights that fit it best.
struct Split {
    /// err² with these weights (may round below 0).
    e: f64,
    /// Spot weight, relative to I_max.
    w_spot: f64,
    /// Other light's weight, relative to I_max.
    w_other: f64,
    /// q = sin(θ/2) of the last lit direction (−∞: none).
    q_lit: f64,
    /// q of the first dark direction (+∞: none).
    q_dark: f64,
}

impl Split {
    /// The profile of this split: the cut-off (degrees in [0, 90]) half-way between
    /// the last lit and the first dark direction, the data cannot place it better.
    fn into_profile(self) -> Profile {
        let cutoff_deg = if self.w_spot == 0.0 || !self.q_lit.is_finite() {
            // Nothing lit: the spot is off; any cut-off will do.
            0.0
        } else if !self.q_dark.is_finite() {
            90.0
        } else {
            (0.5 * (theta_deg(self.q_lit) + theta_deg(self.q_dark))).clamp(0.0, 90.0)
        };
        Profile {
            e: self.e.max(0.0),
            cutoff_deg,
            w_spot: self.w_spot,
            w_other: self.w_other,
        }
    }
}
