//! The distance from a point to the photometric solid of a field, found on
//! the solid itself: no mesh is built.
//!
//! The solid of a field f is S = { f(ω) ω : |ω| = 1 } (cd as length). For a
//! point p = m ω_p (m = |p|):
//! - U = |f(ω_p) − m| is the distance to the surface point in p's own
//!   direction, so d(p, S) ≤ U.
//! - A surface point in a direction at angle θ ≤ 90° from ω_p is at least
//!   m sin θ from p (the closest point of that ray to p), and beyond 90° at
//!   least m. So for any d ≥ d(p, S) the nearest point of S lies in the cap
//!   θ ≤ asin(d / m) around ω_p, and the cap shrinks as better points are found.
//!
//! [`distance_to_solid`] samples the cap ring by ring from ω_p outward
//! ([`NearestSearch::rings`] rings across the starting cap, more where the
//! step would exceed the field's knot spacing
//! ([`IntensityField::knot_spacing_deg`], at most 64 rings), points on a ring
//! as far apart as the rings), stops at the first ring outside the cap of the
//! best distance so far, polishes the best [`NearestSearch::seeds`] samples
//! and every other sample within one step's change of the best (at most 24
//! in all; fewer in a small cap, below) by pattern search on the sphere to a sixteenth of the step, and
//! the best [`NearestSearch::seeds`] of those down to
//! [`NearestSearch::stop_rad`], leaving out any in the basin of one already
//! polished and any too far to come nearer than the best so far
//! (`final_polish`). A small cap (below) whose only seed is its nearest
//! sample skips the rough polish, which only ranks seeds: its final polish
//! starts from the sample at a quarter step. In a small cap (U ≤ 0.1 m, nearly every
//! point of a good reconstruction) only the nearest sample and the samples
//! that are local minima of the samples (no nearer sample within 1.5
//! steps) are polished: there a sample with a nearer neighbour lies on a
//! slope into that neighbour's basin, and polishing it too cost 4.5 times
//! the rough polishes for the same minima (without it no H moved by more
//! than 6e-7 % of I_max and no mean distance by more than 3e-5 %, on eleven
//! real comparisons and the 103 corpus files' default `compare`). The
//! second and third nearest samples are no exception: they are nearly
//! always the nearest one's neighbours. Polishing them as well took 40 % of
//! the lookups of a real roadway file's search (28.5 against 17.1 million
//! for its 51,337 withheld points; its default `compare` 19.5 against
//! 13.0 s, BENCHMARKS.md), and without it no H of the 103 corpus files' default `compare`
//! (721 rows) moved by more than 5.6e-6 % of I_max, no mean surface distance
//! by more than 4.2e-5 % and no RMS by more than 1.5e-5 %, each upwards (a
//! basin those neighbours reached and the nearest sample's polish did not).
//! In a larger cap a basin can hide behind a ridge, sampled only on its rim
//! (every sample polished: one H 0.03 % of I_max lower on the corpus).
//! When U ≥ m (p at
//! or near the origin, or an error as large as the value) the cap is the
//! whole sphere and a Fibonacci lattice seeds the search instead.
//!
//! The result is a distance to a point of S, so never below d(p, S); it
//! equals d(p, S) when the nearest point lies in the basin of a polished
//! seed, i.e. unless the solid has a feature narrower than the sampling
//! step inside the cap (the step is the cap's radius over the rings).
//! A bilinear lookup of a noisy plane has a basin between every two knots
//! along it: with 8 rings a point 1.4 times a measured value of
//! `photompy/LLIA001477-003.ies` (γ every 0.5°, a 16.6° cap, 2.1° steps)
//! was put 0.47 % of I_max further from the solid than it is; sampling no
//! coarser than the knots finds it (`tests/it/nearest.rs`).
//! `compare`'s `withheld` reference uses it for the largest distance from a
//! withheld measured point to the solid rebuilt without it.

use glam::DVec3;
use rayon::prelude::*;

use std::f64::consts::FRAC_1_SQRT_2;

use super::largest::{largest_of, LargestDistance};
use super::radial::{tangents, DirectionSet};
use super::walls::distance_to_walls;
use crate::model::{frame, IntensityField, Rim};

/// The sampling of [`distance_to_solid`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NearestSearch {
    /// Rings sampled across the starting cap (its radius over this is the step).
    pub rings: usize,
    /// Directions of the Fibonacci lattice when the cap is the whole sphere.
    pub sphere: usize,
    /// Samples polished to the end by pattern search, the best of those
    /// polished roughly first: in a large cap the best `seeds` samples and
    /// every other within one step's change of the best (at most 24); in a
    /// small cap the nearest sample and the local minima among those; on
    /// the whole sphere the best `seeds` (module documentation).
    pub seeds: usize,
    /// The pattern search stops when its step is below this, radians.
    pub stop_rad: f64,
}

impl Default for NearestSearch {
    /// 8 rings (a 1° step on an 8° cap), 1,024 directions on the whole
    /// sphere, 3 seeds, a final step of 1e-7 rad (a relative distance error
    /// of order 1e-14 near a smooth minimum). At 1e-6 a real roadway file's
    /// default `compare` made 8 % fewer lookups, but where the minimum lies
    /// on a crease the pattern search stops a step short: one H of the
    /// corpus (a bilinear lookup of `rpr-sdk/ies_light_1.ies`) rose by
    /// 1.3e-4 % of I_max (docs/history/benchmarks-to-2026-12-07.md, "The surface search's lone seeds").
    fn default() -> Self {
        Self {
            rings: 8,
            sphere: 1024,
            seeds: 3,
            stop_rad: 1e-7,
        }
    }
}

/// A candidate: a unit direction, the field there (cd) and the distance
/// from p to the surface point there (cd).
#[derive(Debug, Clone, Copy)]
struct Candidate {
    w: DVec3,
    r: f64,
    d: f64,
}

/// The distance (cd) from the point `m · dir` (`dir` a unit direction of the
/// luminaire frame, `m` ≥ 0 in cd) to the solid of `field`. The direction is
/// given apart from `m` so that a point at the origin (a zero measurement)
/// still starts in its own direction: where the field is 0 there too, the
/// distance is 0 at once. See the module documentation for the search and
/// what it guarantees.
pub fn distance_to_solid(field: &dyn IntensityField, dir: DVec3, m: f64, search: &NearestSearch) -> f64 {
    let (own, m) = own_point(dir, m);
    let p = m * own;
    let at = |w: DVec3| candidate(field, p, w);
    let first = at(own);
    let u = first.d;
    if u == 0.0 || !m.is_finite() {
        return if u.is_finite() { u } else { 0.0 };
    }
    let mut samples = vec![first];
    let cap = (u / m).min(1.0).asin();
    let rings = rings_across(cap, field.knot_spacing_deg(), search);
    if u < m {
        sample_cap(own, m, &at, cap / rings as f64, rings, &mut samples);
    } else {
        for &(c, g) in &DirectionSet::fibonacci(search.sphere).directions {
            samples.push(at(frame::direction(c, g)));
        }
    }
    samples.sort_by(|a, b| a.d.total_cmp(&b.d));
    if samples[0].d == 0.0 {
        return 0.0; // on the solid: nothing is nearer
    }
    let step = if u < m {
        cap / rings as f64
    } else {
        (4.0 * std::f64::consts::PI / search.sphere.max(1) as f64).sqrt()
    };
    let r_max = samples.iter().map(|s| s.r).fold(m, f64::max);
    let seeds = search.seeds.max(1);
    let small_cap = u < m && u <= SMALL_CAP * m;
    let picked = pick_seeds(&samples, (u, m), small_cap, step, r_max, seeds);
    // A small cap whose samples have one local minimum, the nearest: the rough
    // polish ranks seeds, and there is none to rank it against, so the final
    // polish starts from it (a quarter step: its first Newton moves stay
    // within half a step, in the sample's basin). This is 74 % of a real
    // roadway file's withheld points; going straight to the final polish
    // saved 16 % of that file's lookups.
    if small_cap && picked.len() == 1 {
        return polish(picked[0], step / LONE_SEED_STEP_DIV, search.stop_rad, true, &at)
            .d
            .min(u);
    }
    // Every seed to a sixteenth of the step (its basin's bottom, roughly),
    // then the best few to the end.
    let mut rough: Vec<Candidate> = picked
        .into_iter()
        .map(|s| polish(s, step, step / 16.0, false, &at))
        .collect();
    rough.sort_by(|a, b| a.d.total_cmp(&b.d));
    final_polish(&rough, seeds, step / 16.0, r_max, search.stop_rad, u, &at)
}

/// The samples (sorted nearest first) whose basins may hold the minimum, at
/// most [`MAX_SEEDS`]: within what one step can change the distance (a
/// surface point moves by about r · step, twice for a steep flank, `r_max`
/// the largest radius seen, cd) and a local minimum of the samples in a small
/// cap (there one with a nearer sample beside it is on a slope into that
/// sample's basin; the nearest sample always); in a larger cap every sample
/// of the window, the best `seeds` always. On the whole sphere (`u ≥ m`: a
/// point near the origin) the lattice is coarse and the window would take
/// every sample: the best `seeds` only. `(u, m)`: the distance in p's own
/// direction and |p|, cd; `small_cap`: U ≤ [`SMALL_CAP`] · m.
fn pick_seeds(
    samples: &[Candidate],
    (u, m): (f64, f64),
    small_cap: bool,
    step: f64,
    r_max: f64,
    seeds: usize,
) -> Vec<Candidate> {
    let window = if u < m {
        samples[0].d + 2.0 * step * r_max
    } else {
        samples[0].d
    };
    let near = (NEIGHBOUR_STEPS * step).min(std::f64::consts::PI).cos();
    // Samples are sorted nearest first: a sample is a discrete local minimum
    // when no nearer one lies within a neighbour's reach of it.
    let local_min = |k: usize| samples[..k].iter().all(|o| o.w.dot(samples[k].w) < near);
    samples
        .iter()
        .enumerate()
        .take_while(|&(k, s)| k < seeds || s.d <= window)
        .filter(|&(k, _)| {
            if u >= m {
                k < seeds // the whole sphere
            } else if small_cap {
                k == 0 || local_min(k)
            } else {
                true // a larger cap: the whole window
            }
        })
        .take(MAX_SEEDS)
        .map(|(_, &s)| s)
        .collect()
}

/// The best distance (at most `best`, cd) of the final polishes, to
/// `stop_rad`, of the `seeds` nearest `rough` results (sorted nearest first,
/// each polished to `fine` radians), leaving out the ones that cannot
/// change it: a result beside one already polished (within
/// [`SAME_BASIN_STEPS`] × `fine`: the rough polish stopped there in the
/// same basin, and the final polish of either ends at its bottom) and a
/// result further than the nearest distance found so far plus the most a
/// polish within `fine` of it can gain (the surface point moves by about
/// r · `fine`, twice for a steep flank: the window rule of the seeds). On
/// a real roadway file's default `compare` these two rules leave one final
/// polish a point where there were 1.3-1.9 (docs/history/benchmarks-to-2026-12-07.md, "The surface
/// search's final polish").
fn final_polish(
    rough: &[Candidate],
    seeds: usize,
    fine: f64,
    r_max: f64,
    stop_rad: f64,
    mut best: f64,
    at: &dyn Fn(DVec3) -> Candidate,
) -> f64 {
    let same_basin = (SAME_BASIN_STEPS * fine).min(std::f64::consts::PI).cos();
    let gain = 2.0 * fine * r_max;
    let mut polished: Vec<DVec3> = Vec::with_capacity(seeds);
    for s in rough.iter().take(seeds) {
        if s.d - gain > best {
            break; // sorted: every later one is further still
        }
        if polished.iter().any(|w| w.dot(s.w) >= same_basin) {
            continue;
        }
        best = best.min(polish(*s, fine, stop_rad, true, at).d);
        polished.push(s.w);
    }
    best
}

/// A lone seed's final polish starts at the sample step over this ([`distance_to_solid`]).
const LONE_SEED_STEP_DIV: f64 = 4.0;

/// Rough results within this many rough polish steps of each other share
/// a basin ([`final_polish`]).
const SAME_BASIN_STEPS: f64 = 2.0;

/// p's unit direction and |p| (cd) as the search takes them: a zero or
/// non-finite direction is straight down, a negative m the point on the
/// opposite side, a non-finite m infinitely far.
fn own_point(dir: DVec3, m: f64) -> (DVec3, f64) {
    let own = dir.try_normalize().unwrap_or(DVec3::NEG_Z);
    let (own, m) = if m < 0.0 { (-own, -m) } else { (own, m) };
    (own, if m.is_finite() { m } else { f64::INFINITY })
}

/// The surface point in unit direction `w` (a non-finite value read as 0)
/// and its distance from `p`.
fn candidate(field: &dyn IntensityField, p: DVec3, w: DVec3) -> Candidate {
    let r = field.intensity_dir_cd(w);
    let r = if r.is_finite() { r } else { 0.0 };
    Candidate {
        w,
        r,
        d: p.distance(r * w),
    }
}

/// What [`distance_to_solid`] returns at most for the same point: U, the
/// distance to the surface point in p's own direction (where the search
/// starts, and what it returns for a point infinitely far, 0 when U is not
/// finite), for one lookup.
fn own_distance(field: &dyn IntensityField, dir: DVec3, m: f64) -> f64 {
    let (own, m) = own_point(dir, m);
    let u = candidate(field, m * own, own).d;
    if u.is_finite() {
        u
    } else {
        0.0
    }
}

/// The largest [`distance_to_solid`] over `points`, when it exceeds `floor`
/// (cd; a distance already found elsewhere, 0 for none), searching only the
/// points that can set it ([`largest_of`]): a point's distance is at most U,
/// the distance to the surface point in its own direction (the search starts
/// there and never returns more), which costs one lookup. The value is bit
/// for bit the largest of [`distances_to_solid`] over the same points
/// whenever that exceeds `floor`. For a good reconstruction nearly every
/// point's U is below the largest distance, and few are searched.
pub fn largest_distance_to_solid(
    field: &dyn IntensityField,
    points: &[(DVec3, f64)],
    search: &NearestSearch,
    floor: f64,
) -> LargestDistance {
    let bounds: Vec<f64> = points.par_iter().map(|&(dir, m)| own_distance(field, dir, m)).collect();
    let rims = field.rims().unwrap_or_default();
    largest_of(&bounds, floor, |k| {
        distance_with_walls(field, &rims, points[k].0, points[k].1, search)
    })
}

/// [`distance_to_solid`], or the distance to a wall of the solid along one
/// of `rims` (the field's, [`IntensityField::rims`]) when that is nearer.
fn distance_with_walls(field: &dyn IntensityField, rims: &[Rim], dir: DVec3, m: f64, search: &NearestSearch) -> f64 {
    let d = distance_to_solid(field, dir, m, search);
    if rims.is_empty() {
        return d;
    }
    let (own, m) = own_point(dir, m);
    if !m.is_finite() {
        return d;
    }
    distance_to_walls(field, rims, m * own, d)
}

/// The sine of the largest cap radius (U / m) whose extra seeds are only the
/// local minima of its samples (module documentation).
const SMALL_CAP: f64 = 0.1;

/// At most this many rings across a cap, whatever the field's knot spacing
/// (about π · 64² = 13,000 samples in a cap sampled to its rim).
const MAX_RINGS: usize = 64;

/// At most this many samples are polished (the window's cap).
const MAX_SEEDS: usize = 24;

/// Samples within this many steps of each other are neighbours: the next
/// sample on the ring and on the rings inside and outside (the rings are a
/// step apart, the samples on a ring at most a step).
const NEIGHBOUR_STEPS: f64 = 1.5;

/// Rings across a cap of `cap` radians: the search's, more where its step
/// would exceed the field's knot spacing (a basin can be that narrow), at
/// most [`MAX_RINGS`].
fn rings_across(cap: f64, knot_spacing_deg: Option<f64>, search: &NearestSearch) -> usize {
    let by_knots = knot_spacing_deg
        .filter(|s| s.is_finite() && *s > 0.0)
        .map_or(0.0, |s| (cap / s.to_radians()).ceil())
        .min(MAX_RINGS as f64) as usize;
    by_knots.max(search.rings).max(1)
}

/// The distance (cd) to the solid of `field` of every point `(dir, m)`, in
/// order (in parallel): [`distance_to_solid`], and for a field with rims
/// ([`IntensityField::rims`]: a lobe of exponent 0) the nearer of that and
/// the walls along them (`metrics::walls`).
pub fn distances_to_solid(field: &dyn IntensityField, points: &[(DVec3, f64)], search: &NearestSearch) -> Vec<f64> {
    let rims = field.rims().unwrap_or_default();
    points
        .par_iter()
        .map(|&(dir, m)| distance_with_walls(field, &rims, dir, m, search))
        .collect()
}

/// Sample the cap around `own` (p's direction, |p| = `m`) with `rings`
/// rings `step` radians apart (`out[0]` is the sample at `own`), stopping
/// at the first ring outside the cap of the best distance so far.
fn sample_cap(own: DVec3, m: f64, at: &dyn Fn(DVec3) -> Candidate, step: f64, rings: usize, out: &mut Vec<Candidate>) {
    let (e1, e2) = own.any_orthonormal_pair();
    let mut best = out[0].d;
    for i in 1..=rings {
        let theta = step * i as f64;
        // Every direction from here outward is at least m sin(theta) from p.
        if m * theta.sin() >= best {
            break;
        }
        let (st, ct) = theta.sin_cos();
        let n = ((std::f64::consts::TAU * st / step).ceil() as usize).clamp(6, 256);
        for k in 0..n {
            let (sp, cp) = (std::f64::consts::TAU * k as f64 / n as f64).sin_cos();
            let c = at((own * ct + (e1 * cp + e2 * sp) * st).normalize());
            best = best.min(c.d);
            out.push(c);
        }
    }
}

/// Pattern search on the sphere from `start`: try the eight tangent
/// neighbours at `step` radians (and, with `newton`, the minimum of the
/// quadratic through them), move to the best that is closer, else halve the
/// step; stop below `stop_rad`, or when no neighbour is nearer and the
/// quadratic model's minimum is within `stop_rad` (converged). Returns the
/// nearest point found.
///
/// The eight neighbours and the centre determine a quadratic model of d² in
/// the tangent plane (central differences along C and γ, the mixed term from
/// the diagonals). Near a smooth minimum its Newton point is nearer than any
/// neighbour and the step shrinks to the move's length (at most 8x a round),
/// so the final polish converges in a few rounds instead of crawling a step
/// at a time (about 2.8 moves per halving before). On a crease (a bilinear
/// lookup's minimum along C or γ) the model is poor, its point is not nearer,
/// and the search is the plain pattern search. The rough polish, which
/// decides the basin, never takes the Newton step: a jump of up to two steps
/// could leave a seed's basin for a shallower one (measured: up to 0.03 % of
/// I_max on a real file when the rough polish took it too).
///
/// A neighbour move that follows another with no halving between them
/// (a Newton move may lie between) is followed by pattern moves (Hooke and
/// Jeeves 1961): along the sum of the two, doubling while nearer
/// ([`pattern_moves`]). A narrow valley that runs across the eight
/// directions (where the model has no minimum: its curvature along the
/// valley is not positive) is otherwise followed in a zigzag of single
/// steps, each halving shrinking them further: on a real roadway file 255
/// polishes of one row stopped at the round limit still moving (one from
/// 13.22 to 12.80 cd in its 400 rounds, still falling; docs/history/benchmarks-to-2026-12-07.md,
/// "The surface search's pattern moves").
fn polish(start: Candidate, step: f64, stop_rad: f64, newton: bool, at_dir: &dyn Fn(DVec3) -> Candidate) -> Candidate {
    let mut at = start;
    let mut step = step.max(stop_rad);
    // Where the neighbour move before the last one started (none after a halving).
    let mut base: Option<DVec3> = None;
    // 64 shrinks take any step below 1e-19 rad; moves are bounded too.
    for _ in 0..400 {
        if step < stop_rad {
            break;
        }
        // Along C and γ (the creases of a bilinear or texture lookup run
        // there, and a minimum on a crease is reached along it) and the diagonals.
        let (ec, eg) = tangents(at.w);
        let (d1, d2) = ((ec + eg) * FRAC_1_SQRT_2, (ec - eg) * FRAC_1_SQRT_2);
        let (s, c) = step.sin_cos();
        let n = [ec, -ec, eg, -eg, d1, -d1, d2, -d2].map(|e| at_dir((at.w * c + e * s).normalize()));
        let neighbour = n.iter().fold(at, |b, &x| if x.d < b.d { x } else { b });
        let model = newton.then(|| newton_move(at, &n, step, (ec, eg))).flatten();
        // Converged: no neighbour is nearer and the model's minimum is
        // within `stop_rad` of `at` (moving there would change the distance
        // by about r · stop_rad², far below an f64's resolution of it).
        if neighbour.d >= at.d && model.is_some_and(|(_, len)| len < stop_rad) {
            break;
        }
        let newton = model.map(|(t, len)| (at_dir((at.w * len.cos() + t * len.sin()).normalize()), len));
        match newton {
            // `neighbour` is never further than `at`: nearer than it is nearer than both.
            Some((x, len)) if x.d < neighbour.d => {
                at = x;
                step = len.clamp(step / 8.0, step);
            }
            _ if neighbour.d < at.d => {
                let from = at.w;
                at = neighbour;
                if let Some(b) = base {
                    at = pattern_moves(at, at.w - b, at_dir);
                }
                base = Some(from);
            }
            _ => {
                base = None;
                step *= 0.5;
            }
        }
    }
    at
}

/// The pattern moves after two neighbour moves: from `at`, steps
/// of 1, 2, 4 and 8 times `along` (a chord of the unit sphere: the two moves
/// together), each from where the last one landed, while each comes nearer.
/// A move is only taken when it is nearer, so a basin is only left for a
/// nearer point.
fn pattern_moves(mut at: Candidate, along: DVec3, at_dir: &dyn Fn(DVec3) -> Candidate) -> Candidate {
    let mut k = 1.0;
    while k <= MAX_PATTERN_MOVE {
        let Some(w) = (at.w + along * k).try_normalize() else {
            break;
        };
        let x = at_dir(w);
        if x.d.partial_cmp(&at.d) != Some(std::cmp::Ordering::Less) {
            break; // not nearer
        }
        at = x;
        k *= 2.0;
    }
    at
}

/// The longest pattern move, in chords of the two neighbour moves before it
/// ([`pattern_moves`]): 15 of them in all at most. Doubling up to 64 (127
/// in all) moved a real roadway file's catmull-rom mean surface distance by
/// 1.4e-9 cd and saved 0.05 % of its lookups.
const MAX_PATTERN_MOVE: f64 = 8.0;

/// The Newton move of the quadratic model of d² through the centre `at`
/// and its eight neighbours `n` (order: +C, −C, +γ, −γ, +diagonal,
/// −diagonal, +anti-diagonal, −anti-diagonal, all `h` radians away along
/// the tangents `(ec, eg)` of C and γ at `at`): the unit tangent and its
/// length (radians), when the model has a minimum within two steps.
fn newton_move(at: Candidate, n: &[Candidate; 8], h: f64, (ec, eg): (DVec3, DVec3)) -> Option<(DVec3, f64)> {
    let f0 = at.d * at.d;
    let f = n.map(|x| x.d * x.d);
    let h2 = h * h;
    let (gx, gy) = ((f[0] - f[1]) / (2.0 * h), (f[2] - f[3]) / (2.0 * h));
    let (hxx, hyy) = ((f[0] + f[1] - 2.0 * f0) / h2, (f[2] + f[3] - 2.0 * f0) / h2);
    // The diagonals are at (±h/√2, ±h/√2): their sums cancel all but the mixed term.
    let hxy = (f[4] + f[5] - f[6] - f[7]) / (2.0 * h2);
    let det = hxx * hyy - hxy * hxy;
    if !(hxx > 0.0 && det > 0.0) {
        return None;
    }
    let (dx, dy) = ((-hyy * gx + hxy * gy) / det, (hxy * gx - hxx * gy) / det);
    let len = dx.hypot(dy);
    if !(len > 0.0 && len <= 2.0 * h) {
        return None;
    }
    Some(((ec * dx + eg * dy) / len, len))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The Newton move lands on the minimum of a quadratic d² exactly (the
    /// stencil's central differences and mixed term are exact for it), and
    /// a saddle or a maximum gives no move.
    #[test]
    fn newton_move_finds_the_minimum_of_a_quadratic() {
        let w = frame::direction(30.0, 70.0);
        let (ec, eg) = tangents(w);
        let (x0, y0) = (0.01, -0.02);
        let cand = |f: &dyn Fn(f64, f64) -> f64, x: f64, y: f64| Candidate {
            w,
            r: 1.0,
            d: f(x, y).sqrt(),
        };
        let stencil = |f: &dyn Fn(f64, f64) -> f64, h: f64| {
            let a = h * FRAC_1_SQRT_2;
            [
                (h, 0.0),
                (-h, 0.0),
                (0.0, h),
                (0.0, -h),
                (a, a),
                (-a, -a),
                (a, -a),
                (-a, a),
            ]
            .map(|(x, y)| cand(f, x, y))
        };
        let bowl = |x: f64, y: f64| 4.0 + 3.0 * (x - x0).powi(2) + 2.0 * (y - y0).powi(2) + (x - x0) * (y - y0);
        let h = 0.02;
        let (t, len) = newton_move(cand(&bowl, 0.0, 0.0), &stencil(&bowl, h), h, (ec, eg)).unwrap();
        let got = t * len;
        let want = ec * x0 + eg * y0;
        assert!((got - want).length() < 1e-12, "{got} vs {want}");
        let saddle = |x: f64, y: f64| 4.0 + 3.0 * x * x - 2.0 * y * y + x;
        assert!(newton_move(cand(&saddle, 0.0, 0.0), &stencil(&saddle, h), h, (ec, eg)).is_none());
        let cap = |x: f64, y: f64| 4.0 - x * x - y * y + 0.1 * x;
        assert!(newton_move(cand(&cap, 0.0, 0.0), &stencil(&cap, h), h, (ec, eg)).is_none());
        // A minimum beyond two steps is left to the pattern search.
        let far = |x: f64, y: f64| 4.0 + (x - 0.1).powi(2) + y * y;
        assert!(newton_move(cand(&far, 0.0, 0.0), &stencil(&far, h), h, (ec, eg)).is_none());
    }

    /// A narrow valley oblique to C and γ whose floor falls linearly (so
    /// the quadratic model has no minimum until the floor turns up, 0.05 rad
    /// along it): the pattern moves follow it to the bottom (474 lookups),
    /// where single neighbour moves zigzag down it and stop at the round
    /// limit 4.9e-4 above the bottom (3,201 lookups).
    #[test]
    fn pattern_moves_follow_a_narrow_oblique_valley() {
        let w0 = frame::direction(30.0, 70.0);
        let (ec, eg) = tangents(w0);
        let floor = |x: f64| 0.01 * ((x - 0.05).powi(2) + 1e-8).sqrt();
        let dist = |w: DVec3| {
            let (x, y) = (w.dot(ec), w.dot(eg));
            1.0 + 1e4 * (y - 0.3 * x).powi(2) + floor(x)
        };
        let lookups = std::cell::Cell::new(0usize);
        let at = |w: DVec3| {
            lookups.set(lookups.get() + 1);
            Candidate { w, r: 1.0, d: dist(w) }
        };
        let end = polish(at(w0), 1e-3, 1e-7, true, &at);
        // The floor's bottom, 1 + 0.01 · 1e-4 (the valley's at y = 0.3 x).
        let bottom = 1.0 + 1e-6;
        assert!(end.d - bottom < 1e-9, "{} above the bottom", end.d - bottom);
        assert!(lookups.get() < 1_000, "{} lookups", lookups.get());
    }

    /// The final polish runs once a basin: a rough result beside one already
    /// polished costs no lookup, nor does one too far to come nearer, while
    /// a distinct basin as near as the best is polished too.
    #[test]
    fn final_polish_skips_a_polished_basin_and_far_results() {
        // From the centre of the isotropic solid every direction is as near
        // (100 cd): every rough result is a basin's bottom.
        let iso = |_: f64, _: f64| 100.0;
        let p = DVec3::ZERO;
        let lookups = std::cell::Cell::new(0usize);
        let at = |w: DVec3| {
            lookups.set(lookups.get() + 1);
            candidate(&iso, p, w)
        };
        let (fine, r_max, stop) = (1e-3, 100.0, 1e-7);
        let near = |deg: f64| candidate(&iso, p, frame::direction(0.0, deg));
        let cost = |rough: &[Candidate]| {
            lookups.set(0);
            let d = final_polish(rough, 3, fine, r_max, stop, f64::INFINITY, &at);
            assert!((d - 100.0).abs() < 1e-9, "{d}");
            lookups.get()
        };
        let one = cost(&[near(0.0)]);
        assert!(one > 0);
        // 0.05° is under two fine steps (0.11°): the same basin.
        assert_eq!(cost(&[near(0.0), near(0.05)]), one);
        // 10° away and as near: another basin, polished (rounding of the
        // 100 cd moves the two polishes a little differently).
        let two = cost(&[near(0.0), near(10.0)]);
        assert!(two > 3 * one / 2, "{two} lookups against {one} for one polish");
        // Further than the best plus what a fine step can gain (0.2 cd): left out.
        let far = Candidate {
            d: 100.0 + 1.0,
            ..near(10.0)
        };
        assert_eq!(cost(&[near(0.0), far]), one);
    }

    /// The isotropic source: S is the sphere of radius I0, d = | |p| − I0 |.
    #[test]
    fn sphere_distances_are_exact() {
        let iso = |_: f64, _: f64| 100.0;
        let s = NearestSearch::default();
        for (p, want) in [
            (DVec3::new(0.0, 0.0, -50.0), 50.0),
            (DVec3::new(30.0, 40.0, 0.0), 50.0),
            (DVec3::new(0.0, 0.0, 130.0), 30.0),
            (DVec3::ZERO, 100.0),
            (DVec3::new(0.0, 100.0, 0.0), 0.0),
        ] {
            let d = distance_to_solid(&iso, p.normalize_or(DVec3::NEG_Z), p.length(), &s);
            assert!((d - want).abs() <= 1e-9 * 100.0, "{p}: {d} vs {want}");
        }
    }

    /// The Lambertian downlight I0 cos γ (lower hemisphere): S is the sphere
    /// of radius I0/2 about (0, 0, −I0/2); the nearest point is usually in
    /// another direction than p's own, often far from it.
    #[test]
    fn lambertian_sphere_distances_are_exact() {
        let i0 = 1000.0;
        let lambert = move |_: f64, g: f64| if g < 90.0 { i0 * g.to_radians().cos() } else { 0.0 };
        let centre = DVec3::new(0.0, 0.0, -0.5 * i0);
        let s = NearestSearch::default();
        let mut worst: f64 = 0.0;
        for k in 0..200 {
            let (c, g) = ((k as f64 * 37.0) % 360.0, 5.0 + (k as f64 * 0.41) % 80.0);
            let m = i0 * (0.3 + 0.9 * ((k * 7) % 11) as f64 / 10.0);
            let p = m * frame::direction(c, g);
            let want = (p.distance(centre) - 0.5 * i0).abs();
            let d = distance_to_solid(&lambert, p.normalize(), p.length(), &s);
            assert!(d >= want - 1e-9 * i0, "{p}: {d} below the true {want}");
            worst = worst.max(d - want);
        }
        assert!(worst <= 1e-6 * i0, "largest excess {worst} cd");
    }

    /// Non-finite values and points count as finite distances.
    #[test]
    fn extremes_stay_finite() {
        let nan = |_: f64, _: f64| f64::NAN;
        let s = NearestSearch::default();
        assert_eq!(distance_to_solid(&nan, DVec3::NEG_Z, 2.0, &s), 2.0);
        let zero = |_: f64, _: f64| 0.0;
        assert_eq!(distance_to_solid(&zero, DVec3::new(0.6, 0.0, 0.8), 5.0, &s), 5.0);
        // A zero measurement where the field is zero: on the solid at once.
        let down = |_: f64, g: f64| if g < 90.0 { 10.0 } else { 0.0 };
        assert_eq!(distance_to_solid(&down, DVec3::Z, 0.0, &s), 0.0);
        // At the origin where the field is not zero: the nearest zero elsewhere.
        assert_eq!(distance_to_solid(&down, DVec3::NEG_Z, 0.0, &s), 0.0);
        let iso = |_: f64, _: f64| 1.0;
        assert!(distance_to_solid(&iso, DVec3::X, f64::INFINITY, &s).is_finite());
        assert!(distance_to_solid(&iso, DVec3::splat(f64::NAN), 1.0, &s).is_finite());
    }
}
