//! Type A and Type B grids → Type C, through direction vectors.
//!
//! # Frame (docs/domain.md §1.5)
//! Right-handed, z up: x = C0 = H0 horizontal, y = C90, nadir = −z. With
//! counter-clockwise handedness (the default) a positive H points towards +y:
//! - Type B (planes share the y axis; V = plane angle about y, H = angle out of the plane):
//!   `d = (cos H sin V, sin H, −cos H cos V)`;
//! - Type A (V = elevation, H = azimuth about z): `d = (cos V cos H, cos V sin H, sin V)`.
//!
//! Clockwise handedness flips the sign of d_y (of H).
//!
//! # Resampling
//! For each target (C, γ): d, then the source (H, V) (every equivalent
//! parametrisation of d is tried: (H, V), (180 − H, V + 180), (−180 − H, V + 180),
//! each modulo 360, and −H when the grid is laterally symmetric), then
//! bilinear interpolation in the source grid; 0 outside it.
//!
//! The (H, V) of every target direction depend on the target grid only, and
//! which source cell and fractions each lookup uses on the source angles
//! only: both are computed once per process (per target grid, per angle set:
//! a catalogue's floodlights share a few goniometer grids) and kept
//! ([`clear_caches`] forgets them). A file whose grid was seen before costs
//! one four-value lookup per target direction; the numbers are the same bits
//! either way (tested against the reference lookup).
//!
//! # Target grid and symmetry
//! - Step: the smallest spacing between consecutive source angles (both axes),
//!   rounded down to one of 0.5, 1, 1.5, 2, 2.5, 3, 4.5, 5 degrees (divisors of
//!   90, so C0/C90/C180 and γ 90 are grid lines), clamped to [0.5, 5].
//! - γ covers 0..180 with that step.
//! - Laterally symmetric sources (H only ≥ 0, starting at 0: I(H) = I(−H))
//!   mirror d_y, i.e. C ↔ −C: the target is C0-C180, planes 0..180.
//!   Otherwise the target has no symmetry: planes 0..360 − step.

use std::sync::{Arc, Mutex};

use rayon::prelude::*;

use crate::error::ModelError;
use crate::formats::Handedness;
use crate::model::{Distribution, PhotometricType, SourceGrid, Symmetry};

/// The target grid steps (degrees): divisors of 90, so C0/C90/C180 and γ 90 are grid lines.
const STEPS: [f64; 8] = [0.5, 1.0, 1.5, 2.0, 2.5, 3.0, 4.5, 5.0];

/// Whether `grid` is laterally symmetric: its horizontal angles start at 0
/// (I(H) = I(−H); the conversion mirrors d_y).
pub fn laterally_symmetric(grid: &SourceGrid) -> bool {
    grid.horizontal.first().is_some_and(|h| h.abs() <= 1e-9)
}

/// Target grid step (degrees) from the source spacing. See the module docs.
pub fn target_step(grid: &SourceGrid) -> f64 {
    let min_gap = |a: &[f64]| {
        a.windows(2)
            .map(|w| w[1] - w[0])
            .filter(|g| *g > 1e-9)
            .fold(f64::INFINITY, f64::min)
    };
    let g = min_gap(&grid.vertical).min(min_gap(&grid.horizontal));
    if !g.is_finite() {
        return 5.0;
    }
    STEPS.iter().rev().copied().find(|&s| s <= g + 1e-9).unwrap_or(0.5)
}

/// Direction of source angles (H, V) (degrees) with counter-clockwise handedness.
pub fn direction(kind: PhotometricType, h: f64, v: f64) -> [f64; 3] {
    let (sh, ch) = h.to_radians().sin_cos();
    let (sv, cv) = v.to_radians().sin_cos();
    match kind {
        PhotometricType::B => [ch * sv, sh, -ch * cv],
        _ => [cv * ch, cv * sh, sv],
    }
}

/// Canonical source angles (H, V) (degrees) of a unit direction, counter-clockwise handedness.
fn angles_of(kind: PhotometricType, d: [f64; 3]) -> (f64, f64) {
    match kind {
        PhotometricType::B => {
            // H in [−90, 90], V in (−180, 180].
            let h = d[1].clamp(-1.0, 1.0).asin().to_degrees();
            let v = d[0].atan2(-d[2]).to_degrees();
            (h, v)
        }
        _ => {
            let v = d[2].clamp(-1.0, 1.0).asin().to_degrees();
            let h = d[1].atan2(d[0]).to_degrees();
            (h, v)
        }
    }
}

/// Bracket `x` in ascending `a`: (index, fraction), tolerant at the ends
/// (the reference form of [`bracket_from`]).
#[cfg(test)]
fn bracket(a: &[f64], x: f64) -> Option<(usize, f64)> {
    const EPS: f64 = 1e-7;
    let n = a.len();
    if x < a[0] - EPS || x > a[n - 1] + EPS {
        return None;
    }
    if n == 1 {
        return Some((0, 0.0));
    }
    let x = x.clamp(a[0], a[n - 1]);
    let i = a.partition_point(|&y| y <= x).clamp(1, n - 1) - 1;
    let t = (x - a[i]) / (a[i + 1] - a[i]);
    Some((i, t.clamp(0.0, 1.0)))
}

/// `x` shifted by a multiple of 360 into [lo, hi] (tolerance 1e-7), if possible.
fn into_range(x: f64, lo: f64, hi: f64) -> Option<f64> {
    for k in [0.0, -360.0, 360.0, -720.0, 720.0] {
        let y = x + k;
        if y >= lo - 1e-7 && y <= hi + 1e-7 {
            return Some(y);
        }
    }
    None
}

/// Value of the source grid at (H, V), 0 outside; every equivalent parametrisation is tried.
///
/// The reference form of [`Resampler::sample`] (binary searches instead of
/// hunting from the previous sample's brackets): the tests check that both
/// give the same bits.
#[cfg(test)]
fn sample(grid: &SourceGrid, mirror: bool, h: f64, v: f64) -> f64 {
    let (hs, vs) = (&grid.horizontal, &grid.vertical);
    let nv = vs.len();
    let cands = candidates(grid.kind, h, v);
    for &(ch, cv) in &cands {
        for hh in [ch, -ch] {
            if hh != ch && !mirror {
                continue;
            }
            let (Some(hx), Some(vx)) = (
                into_range(hh, hs[0], hs[hs.len() - 1]),
                into_range(cv, vs[0], vs[nv - 1]),
            ) else {
                continue;
            };
            let (Some((ih, th)), Some((iv, tv))) = (bracket(hs, hx), bracket(vs, vx)) else {
                continue;
            };
            let at = |ih: usize, iv: usize| grid.cd[ih * nv + iv];
            let ih1 = (ih + 1).min(hs.len() - 1);
            let iv1 = (iv + 1).min(nv - 1);
            let a = at(ih, iv) * (1.0 - tv) + at(ih, iv1) * tv;
            let b = at(ih1, iv) * (1.0 - tv) + at(ih1, iv1) * tv;
            return a * (1.0 - th) + b * th;
        }
    }
    0.0
}

/// The parametrisations of one direction, in the order they are tried.
///
/// The same direction under (H, V) → (180 − H, V + 180) holds for A and B alike
/// (A: (H + 180, 180 − V), which is the same set after the 360 shifts
/// with roles swapped; both are listed).
#[inline]
fn candidates(kind: PhotometricType, h: f64, v: f64) -> [(f64, f64); 3] {
    match kind {
        PhotometricType::B => [(h, v), (180.0 - h, v + 180.0), (-180.0 - h, v + 180.0)],
        _ => [(h, v), (h + 180.0, 180.0 - v), (h - 180.0, 180.0 - v)],
    }
}

/// [`bracket`] starting from the index `hint` (the previous sample's): the
/// same (index, fraction) for the same `x`, found by stepping instead of a
/// binary search (consecutive target directions are close in the source grid).
#[inline]
fn bracket_from(a: &[f64], x: f64, hint: &mut usize) -> Option<(usize, f64)> {
    const EPS: f64 = 1e-7;
    let n = a.len();
    if x < a[0] - EPS || x > a[n - 1] + EPS {
        return None;
    }
    if n == 1 {
        return Some((0, 0.0));
    }
    let x = x.clamp(a[0], a[n - 1]);
    // The largest i in [0, n − 2] with a[i] <= x (i = 0 when none is),
    // which is `partition_point(|y| y <= x).clamp(1, n − 1) − 1`.
    let mut i = (*hint).min(n - 2);
    while i + 1 < n - 1 && a[i + 1] <= x {
        i += 1;
    }
    while i > 0 && a[i] > x {
        i -= 1;
    }
    *hint = i;
    let t = (x - a[i]) / (a[i + 1] - a[i]);
    Some((i, t.clamp(0.0, 1.0)))
}

/// Bilinear lookups in one source grid, remembering the last brackets.
struct Resampler<'g> {
    grid: &'g SourceGrid,
    mirror: bool,
    h_lo: f64,
    h_hi: f64,
    v_lo: f64,
    v_hi: f64,
    hint_h: usize,
    hint_v: usize,
}

impl<'g> Resampler<'g> {
    fn new(grid: &'g SourceGrid, mirror: bool) -> Self {
        let (hs, vs) = (&grid.horizontal, &grid.vertical);
        Resampler {
            grid,
            mirror,
            h_lo: hs[0],
            h_hi: hs[hs.len() - 1],
            v_lo: vs[0],
            v_hi: vs[vs.len() - 1],
            hint_h: 0,
            hint_v: 0,
        }
    }

    /// The lookup of the source grid at (H, V): every equivalent
    /// parametrisation is tried (the module docs), the first that lies in the
    /// grid is used; [`Tap::OUTSIDE`] (0 cd) when none does.
    #[inline]
    fn tap(&mut self, h: f64, v: f64) -> Tap {
        let grid = self.grid;
        let (hs, vs) = (&grid.horizontal, &grid.vertical);
        let nv = vs.len();
        for (ch, cv) in candidates(grid.kind, h, v) {
            let Some(vx) = into_range(cv, self.v_lo, self.v_hi) else {
                continue;
            };
            for hh in [ch, -ch] {
                if hh != ch && !self.mirror {
                    continue;
                }
                let Some(hx) = into_range(hh, self.h_lo, self.h_hi) else {
                    continue;
                };
                let (Some((ih, th)), Some((iv, tv))) = (
                    bracket_from(hs, hx, &mut self.hint_h),
                    bracket_from(vs, vx, &mut self.hint_v),
                ) else {
                    continue;
                };
                let ih1 = (ih + 1).min(hs.len() - 1);
                let iv1 = (iv + 1).min(nv - 1);
                // `to_type_c_at` refuses grids of u32::MAX / 4 values or more,
                // so the index and the packed steps fit.
                return Tap {
                    base: (ih * nv + iv) as u32,
                    steps: (((ih1 - ih) * nv) << 1 | (iv1 - iv)) as u32,
                    th,
                    tv,
                };
            }
        }
        Tap::OUTSIDE
    }
}

/// One target direction's bilinear lookup in a source grid: the corners
/// `cd[base]`, `cd[base + dv]` (next V), `cd[base + dh]` (next H),
/// `cd[base + dh + dv]` and the fractions along H and V. Packed into 24
/// bytes (`steps` = dh << 1 | dv, dv being 0 or 1): a 1° full target grid's
/// table is read once per converted file, 1.6 MB instead of 2.6 MB.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Tap {
    base: u32,
    steps: u32,
    th: f64,
    tv: f64,
}

impl Tap {
    /// No parametrisation of the direction lies in the grid: 0 cd.
    const OUTSIDE: Tap = Tap {
        base: u32::MAX,
        steps: 0,
        th: 0.0,
        tv: 0.0,
    };

    /// The value of a tap inside the grid (the reference lookup's
    /// expression, term for term).
    #[inline]
    fn apply(&self, cd: &[f64]) -> f64 {
        let (i, tv, th) = (self.base as usize, self.tv, self.th);
        let dv = (self.steps & 1) as usize;
        let dh = (self.steps >> 1) as usize;
        let a = cd[i] * (1.0 - tv) + cd[i + dv] * tv;
        let b = cd[i + dh] * (1.0 - tv) + cd[i + dh + dv] * tv;
        a * (1.0 - th) + b * th
    }
}

/// The taps of every target direction, and the runs of consecutive ones
/// inside the source grid (`[start, end)`): a floodlight's grid covers one
/// hemisphere, so half the target is 0 cd and is never visited.
struct TapTable {
    taps: Vec<Tap>,
    inside: Vec<(u32, u32)>,
}

impl TapTable {
    fn new(taps: Vec<Tap>) -> Self {
        let mut inside = Vec::new();
        let mut start = None;
        for (k, t) in taps.iter().enumerate() {
            match (t.base == u32::MAX, start) {
                (false, None) => start = Some(k),
                (true, Some(s)) => {
                    inside.push((s as u32, k as u32));
                    start = None;
                }
                _ => {}
            }
        }
        if let Some(s) = start {
            inside.push((s as u32, taps.len() as u32));
        }
        TapTable { taps, inside }
    }

    /// The target values for the source values `cd`: 0 outside the grid.
    fn apply(&self, cd: &[f64]) -> Vec<f64> {
        // Filled in order, each value written once (no zeroing pass first).
        let mut out = Vec::with_capacity(self.taps.len());
        for &(start, end) in &self.inside {
            let (start, end) = (start as usize, end as usize);
            out.resize(start, 0.0);
            out.extend(self.taps[start..end].iter().map(|t| t.apply(cd)));
        }
        out.resize(self.taps.len(), 0.0);
        out
    }
}

/// The taps of every target direction for one source grid's angles: they
/// depend on the angles, not on the candela values, and a catalogue's Type B
/// files share a few goniometer grids, so the last few are kept per process.
type Taps = Arc<TapTable>;

#[derive(Clone, PartialEq)]
struct TapsKey {
    geometry: GeometryKey,
    vertical: Vec<f64>,
    horizontal: Vec<f64>,
}

/// Tap tables kept, and the largest one kept (a 1° full target grid has 65,160
/// taps, 1.6 MB; a 0.5° half grid 130,682).
const TAPS_CACHE: usize = 4;
const TAPS_CACHED_MAX: usize = 140_000;

fn taps(key: TapsKey, grid: &SourceGrid, mirror: bool, hv: &[(f64, f64)]) -> Taps {
    let cache = &TAPS;
    let lookup = |cache: &Vec<(TapsKey, Taps)>| cache.iter().find(|e| e.0 == key).map(|e| e.1.clone());
    // A poisoned lock only means another thread panicked while holding it; the Vec is still valid.
    if let Some(t) = lookup(&cache.lock().unwrap_or_else(|e| e.into_inner())) {
        return t;
    }
    const CHUNK: usize = 16 * 1024;
    let fill = |out: &mut [Tap], hv: &[(f64, f64)]| {
        let mut r = Resampler::new(grid, mirror);
        for (o, &(h, v)) in out.iter_mut().zip(hv) {
            *o = r.tap(h, v);
        }
    };
    let mut t = vec![Tap::OUTSIDE; hv.len()];
    if t.len() > 2 * CHUNK {
        t.par_chunks_mut(CHUNK)
            .zip(hv.par_chunks(CHUNK))
            .for_each(|(o, hv)| fill(o, hv));
    } else {
        fill(&mut t, hv);
    }
    let t = Arc::new(TapTable::new(t));
    if t.taps.len() <= TAPS_CACHED_MAX {
        let mut cache = cache.lock().unwrap_or_else(|e| e.into_inner());
        if lookup(&cache).is_none() {
            if cache.len() >= TAPS_CACHE {
                cache.remove(0);
            }
            cache.push((key, t.clone()));
        }
    }
    t
}

/// The source angles (H, V) of every target direction of one target grid,
/// plane-major (`hv[ic * n_gamma + ig]`): they depend on the grid, not on the
/// data, so they are computed once per process for each (type, step,
/// layout, handedness) and shared (a catalogue's Type B files use a handful of steps).
type Geometry = Arc<Vec<(f64, f64)>>;

#[derive(Clone, Copy, PartialEq, Eq)]
struct GeometryKey {
    kind_b: bool,
    step_bits: u64,
    mirror: bool,
    flip: bool,
}

/// At most this many target grids are kept (8 steps x 2 layouts x 2 handednesses x 2 types = 64
/// would be every one; a 0.5° full grid is 4.2 MB).
const GEOMETRY_CACHE: usize = 16;

static GEOMETRIES: Mutex<Vec<(GeometryKey, Geometry)>> = Mutex::new(Vec::new());
static TAPS: Mutex<Vec<(TapsKey, Taps)>> = Mutex::new(Vec::new());

/// Forget the cached target-grid geometries and tap tables, so that the next
/// conversion pays the whole cost (the first file of its grid in a process:
/// `benches/peers.rs` measures it this way too).
pub fn clear_caches() {
    GEOMETRIES.lock().unwrap_or_else(|e| e.into_inner()).clear();
    TAPS.lock().unwrap_or_else(|e| e.into_inner()).clear();
}

fn geometry(kind: PhotometricType, c: &[f64], gamma: &[f64], step: f64, mirror: bool, flip: bool) -> Geometry {
    let cache = &GEOMETRIES;
    let key = GeometryKey {
        kind_b: kind == PhotometricType::B,
        step_bits: step.to_bits(),
        mirror,
        flip,
    };
    // A poisoned lock only means another thread panicked while holding it; the Vec is still valid.
    let lookup = |cache: &Vec<(GeometryKey, Geometry)>| cache.iter().find(|e| e.0 == key).map(|e| e.1.clone());
    if let Some(g) = lookup(&cache.lock().unwrap_or_else(|e| e.into_inner())) {
        return g;
    }
    let n_gamma = gamma.len();
    let trig_gamma: Vec<(f64, f64)> = gamma.iter().map(|g| g.to_radians().sin_cos()).collect();
    let mut hv = vec![(0.0, 0.0); c.len() * n_gamma];
    // Each plane is independent: planes in parallel (a 1° target grid is
    // 65 k directions, each an asin and an atan2).
    hv.par_chunks_mut(n_gamma).zip(c.par_iter()).for_each(|(plane, &cc)| {
        let (sc, ccos) = cc.to_radians().sin_cos();
        for (out, &(sg, cg)) in plane.iter_mut().zip(&trig_gamma) {
            let mut d = [sg * ccos, sg * sc, -cg];
            if flip {
                d[1] = -d[1];
            }
            *out = angles_of(kind, d);
        }
    });
    let g = Arc::new(hv);
    let mut cache = cache.lock().unwrap_or_else(|e| e.into_inner());
    if let Some(g) = lookup(&cache) {
        return g;
    }
    if cache.len() >= GEOMETRY_CACHE {
        cache.remove(0);
    }
    cache.push((key, g.clone()));
    g
}

/// Convert a Type A/B grid to a Type C distribution (see the module docs).
///
/// # Errors
/// [`ModelError::Angles`] (`horizontal`) when the horizontal angles start
/// above 0: then neither the lateral-symmetry layout (0 … 90) nor a full one
/// (−90 … 90) applies; the model's error when the converted grid is not a
/// distribution.
pub fn to_type_c(grid: &SourceGrid, handedness: Handedness) -> Result<Distribution, ModelError> {
    to_type_c_at(grid, handedness, target_step(grid))
}

/// [`to_type_c`] onto the target grid of `step` degrees (one of
/// [`target_step`]'s steps) instead of the one `grid`'s spacing gives: a
/// hold-out rebuilds a grid without some of its angles on the full grid's
/// target, as the reader converted it.
///
/// # Errors
/// As [`to_type_c`]; [`ModelError::Angles`] for a step that is not one of
/// [`target_step`]'s.
pub fn to_type_c_at(grid: &SourceGrid, handedness: Handedness, step: f64) -> Result<Distribution, ModelError> {
    if !STEPS.contains(&step) {
        return Err(ModelError::Angles {
            axis: "target",
            reason: format!("a step of {} degrees", crate::error::Num(step)),
        });
    }
    let hs = &grid.horizontal;
    let h0 = hs[0];
    if h0 > 1e-9 {
        return Err(ModelError::Angles {
            axis: "horizontal",
            reason: format!(
                "start at {}: Type {:?} data starts at 0 (laterally symmetric) or below 0",
                crate::error::Num(h0),
                grid.kind
            ),
        });
    }
    if grid.cd.len() >= (u32::MAX / 4) as usize {
        return Err(ModelError::Intensities(format!(
            "{} values: a Type A/B grid converts up to {} values",
            grid.cd.len(),
            u32::MAX / 4
        )));
    }
    let mirror = laterally_symmetric(grid);
    let n_gamma = (180.0 / step).round() as usize + 1;
    let gamma: Vec<f64> = (0..n_gamma).map(|i| (i as f64 * step).min(180.0)).collect();
    let (symmetry, n_c) = if mirror {
        (Symmetry::C0C180, (180.0 / step).round() as usize + 1)
    } else {
        (Symmetry::None, (360.0 / step).round() as usize)
    };
    let c: Vec<f64> = (0..n_c).map(|i| (i as f64 * step).min(360.0)).collect();
    let flip = handedness == Handedness::Clockwise;
    // The target directions' source angles (cached per target grid), their
    // taps in this source grid (cached per angle set), then one bilinear
    // lookup each.
    let hv = geometry(grid.kind, &c, &gamma, step, mirror, flip);
    let key = TapsKey {
        geometry: GeometryKey {
            kind_b: grid.kind == PhotometricType::B,
            step_bits: step.to_bits(),
            mirror,
            flip,
        },
        vertical: grid.vertical.clone(),
        horizontal: grid.horizontal.clone(),
    };
    let taps = taps(key, grid, mirror, &hv);
    let cd = taps.apply(&grid.cd);
    Distribution::new(c, gamma, cd, symmetry)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn direction_round_trips_through_angles() {
        for kind in [PhotometricType::A, PhotometricType::B] {
            for &(h, v) in &[(10.0, 20.0), (-35.0, 60.0), (80.0, -45.0), (0.0, 0.0)] {
                let d = direction(kind, h, v);
                let (h2, v2) = angles_of(kind, d);
                assert!(
                    (h - h2).abs() < 1e-9 && (v - v2).abs() < 1e-9,
                    "{kind:?} {h} {v} -> {h2} {v2}"
                );
            }
        }
    }

    #[test]
    fn type_b_nadir_is_h0_v0() {
        let d = direction(PhotometricType::B, 0.0, 0.0);
        assert!((d[2] + 1.0).abs() < 1e-12);
        let d = direction(PhotometricType::A, 0.0, -90.0);
        assert!((d[2] + 1.0).abs() < 1e-12);
    }

    /// The fast path (cached source angles, brackets hunted from the previous
    /// sample's) gives the reference lookup's bits on every target direction:
    /// Type A and B, half (mirrored) and full grids, both handednesses,
    /// irregular spacing, a one-angle axis.
    #[test]
    fn fast_resampling_matches_the_reference_bit_for_bit() {
        let irregular = vec![
            -90.0, -85.0, -75.0, -47.5, -33.0, -19.5, -7.0, -1.0, 0.0, 1.0, 3.0, 19.5, 42.5, 85.0, 90.0,
        ];
        let half = vec![0.0, 1.0, 5.0, 17.0, 33.0, 65.0, 90.0];
        let cases = [
            (PhotometricType::B, irregular.clone(), half.clone()),
            (PhotometricType::B, irregular.clone(), irregular.clone()),
            (PhotometricType::A, irregular.clone(), half.clone()),
            (PhotometricType::A, half.clone(), irregular.clone()),
            (
                PhotometricType::B,
                vec![-90.0, 90.0],
                vec![-90.0, -45.0, 0.0, 45.0, 90.0],
            ),
            (
                PhotometricType::B,
                vec![0.0, 90.0, 180.0],
                vec![0.0, 90.0, 180.0, 270.0],
            ),
            (PhotometricType::B, vec![10.0], vec![0.0, 30.0]),
        ];
        for (kind, vertical, horizontal) in cases {
            let n = vertical.len() * horizontal.len();
            let cd: Vec<f64> = (0..n).map(|k| ((k * 7919) % 1000) as f64 * 0.37 + 1.0).collect();
            let grid = SourceGrid {
                kind,
                vertical,
                horizontal,
                cd,
            };
            for hand in [Handedness::CounterClockwise, Handedness::Clockwise] {
                let Ok(d) = to_type_c(&grid, hand) else { continue };
                let mirror = laterally_symmetric(&grid);
                let flip = hand == Handedness::Clockwise;
                for (ic, &c) in d.c_angles_deg().iter().enumerate() {
                    let (sc, ccos) = c.to_radians().sin_cos();
                    for (ig, &g) in d.gamma_angles_deg().iter().enumerate() {
                        let (sg, cg) = g.to_radians().sin_cos();
                        let mut dir = [sg * ccos, sg * sc, -cg];
                        if flip {
                            dir[1] = -dir[1];
                        }
                        let (h, v) = angles_of(kind, dir);
                        let want = sample(&grid, mirror, h, v);
                        assert_eq!(
                            d.value_cd(ic, ig).to_bits(),
                            want.to_bits(),
                            "{kind:?} {hand:?} C {c} gamma {g}: {} vs {want}",
                            d.value_cd(ic, ig)
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn step_is_a_divisor_of_90() {
        let g = SourceGrid {
            kind: PhotometricType::B,
            vertical: vec![-90.0, -87.5, 0.0, 90.0],
            horizontal: vec![0.0, 10.0],
            cd: vec![0.0; 8],
        };
        assert_eq!(target_step(&g), 2.5);
    }
}
