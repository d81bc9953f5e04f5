//! The canonical intensity distribution: absolute candela on a Type C grid.
//!
//! # Frame and angles
//! Angles are in **degrees**. γ (gamma) runs from 0 (nadir, −z) to 180
//! (zenith, +z); C is the azimuth about z, C0 = +x, C90 = +y (right-handed,
//! counter-clockwise seen from above). The direction of (C, γ) is
//! `d = (sin γ cos C, sin γ sin C, −cos γ)`.
//!
//! # What is guaranteed
//! A [`Distribution`] always holds:
//! - γ angles: at least one, finite, ascending by more than [`ANGLE_EPS`]
//!   (so no writer's rounding can merge two), inside [0, 180];
//! - C angles: the same, inside the range its [`Symmetry`] stores (see
//!   [`Symmetry::stored_range`]); C90-C270 data has a plane between 90 and 270;
//! - one intensity in cd per (C, γ) pair, C-major (γ fastest), inside the
//!   model's valid range ([`check_intensities`]): finite, |v| ≤ [`MAX_CD`],
//!   a peak of 0 or at least [`MIN_PEAK_CD`] (a table whose every value is
//!   below it is round-off, and is stored as zero). Every derived quantity (flux,
//!   averages, normalised values) is then finite; [`Distribution::scaled`]
//!   keeps the range or fails.
//!
//! Intensity is zero outside the measured γ range (hemisphere or partial
//! data); nothing is extrapolated. Negative values may be present when a file
//! holds them (readers warn); [`Distribution::clamp_negative`] removes them.

use serde::Serialize;

use crate::error::{ModelError, Num};

/// Tolerance (degrees) under which two angles are the same angle.
pub const ANGLE_EPS: f64 = 1e-6;

/// Largest intensity magnitude (cd) of the model. The brightest searchlights
/// reach about 1e9 cd; the bound leaves room for that while keeping every
/// derived sum (flux ≤ 4π × this, trapezoid and pole averages, squared
/// errors of fits) far from `f64` overflow.
pub const MAX_CD: f64 = 1e12;

/// Smallest non-zero peak (cd) of the model: the largest |value| is either 0
/// (an all-zero distribution) or at least this. Normalising by the peak
/// (textures, fits, solids) then stays below 1e21 and never divides by a
/// subnormal number. A table whose every |value| is below it holds only
/// round-off (e.g. cos 90° × 1e-6 cd = 6e-23 cd) and is stored as all zero
/// ([`flush_round_off`]).
pub const MIN_PEAK_CD: f64 = 1e-9;

/// Check a table of intensities against the model's valid range: every value
/// finite with |v| ≤ [`MAX_CD`], and the largest |v| either 0 or at least
/// [`MIN_PEAK_CD`] (run [`flush_round_off`] first to accept round-off tables).
/// On failure returns the index of the offending value and why.
pub fn check_intensities(cd: &[f64]) -> Result<(), (usize, String)> {
    // Almost every table is valid: one branch-free pass proves it (a parse
    // spent a quarter of its time in the indexed loop below), and only a
    // table that fails it is walked again to say where and why.
    let (all_in_range, peak) = abs_peak_in_range(cd);
    if all_in_range && (peak == 0.0 || peak >= MIN_PEAK_CD) {
        return Ok(());
    }
    let mut peak = (0.0f64, 0usize);
    for (i, &v) in cd.iter().enumerate() {
        if !v.is_finite() {
            return Err((i, format!("{} is not finite", Num(v))));
        }
        if v.abs() > MAX_CD {
            return Err((i, format!("|{}| cd exceeds the model's bound of {MAX_CD:e} cd", Num(v))));
        }
        if v.abs() > peak.0 {
            peak = (v.abs(), i);
        }
    }
    if peak.0 > 0.0 && peak.0 < MIN_PEAK_CD {
        return Err((
            peak.1,
            format!(
                "the peak |{}| cd is below the model's smallest non-zero peak {MIN_PEAK_CD:e} cd",
                Num(peak.0)
            ),
        ));
    }
    Ok(())
}

/// Whether every value is finite with |v| ≤ [`MAX_CD`], and the largest |v|
/// (cd), in one pass the compiler vectorises (lanes of running maxima and
/// flags, no early exit); a NaN fails the range test.
fn abs_peak_in_range(cd: &[f64]) -> (bool, f64) {
    const LANES: usize = 8;
    // v × 0 is 0 for a finite v and NaN for ±∞ or NaN: a sum of them is 0
    // exactly when every value is finite (the running maximum skips NaN).
    let mut peak = [0.0f64; LANES];
    let mut not_finite = [0.0f64; LANES];
    let chunks = cd.chunks_exact(LANES);
    let tail = chunks.remainder();
    for chunk in chunks {
        for k in 0..LANES {
            let a = chunk[k].abs();
            not_finite[k] += a * 0.0;
            peak[k] = if a > peak[k] { a } else { peak[k] };
        }
    }
    let mut nan = not_finite.iter().sum::<f64>();
    let mut top = peak.iter().fold(0.0f64, |m, &p| if p > m { p } else { m });
    for &v in tail {
        let a = v.abs();
        nan += a * 0.0;
        top = if a > top { a } else { top };
    }
    (nan == 0.0 && top <= MAX_CD, top)
}

/// The largest value of a slice of finite values (−∞ when empty), in one
/// vectorised pass.
fn max_of(values: &[f64]) -> f64 {
    const LANES: usize = 8;
    let mut lanes = [f64::NEG_INFINITY; LANES];
    let chunks = values.chunks_exact(LANES);
    let tail = chunks.remainder();
    for chunk in chunks {
        for k in 0..LANES {
            lanes[k] = if chunk[k] > lanes[k] { chunk[k] } else { lanes[k] };
        }
    }
    lanes
        .iter()
        .chain(tail)
        .fold(f64::NEG_INFINITY, |m, &v| if v > m { v } else { m })
}

/// Set every value to 0 when all |values| are below [`MIN_PEAK_CD`] (the
/// table is round-off); returns whether it did. NaN is left for
/// [`check_intensities`] to refuse.
pub fn flush_round_off(cd: &mut [f64]) -> bool {
    let round_off = cd.iter().all(|v| v.abs() < MIN_PEAK_CD) && cd.iter().any(|&v| v != 0.0);
    if round_off {
        cd.iter_mut().for_each(|v| *v = 0.0);
    }
    round_off
}

/// Which symmetry the stored C-planes rely on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Symmetry {
    /// No symmetry: planes anywhere in [0, 360) (EULUMDAT Isym 0, IES 0-360).
    None,
    /// Rotationally symmetric about the vertical axis: one plane, C = 0 (Isym 1, IES {0}).
    Rotational,
    /// Mirror symmetric about the C0-C180 plane: I(C) = I(360 − C); planes in [0, 180] (Isym 2, IES 0-180).
    C0C180,
    /// Mirror symmetric about the C90-C270 plane: I(C) = I(180 − C); planes in [90, 270] (Isym 3, IES 90-270).
    C90C270,
    /// Symmetric about both planes: planes in [0, 90] (Isym 4, IES 0-90).
    Quadrant,
}

impl Symmetry {
    /// The closed C range (degrees) whose planes are stored.
    pub fn stored_range(self) -> (f64, f64) {
        match self {
            Symmetry::None => (0.0, 360.0),
            Symmetry::Rotational => (0.0, 0.0),
            Symmetry::C0C180 => (0.0, 180.0),
            Symmetry::C90C270 => (90.0, 270.0),
            Symmetry::Quadrant => (0.0, 90.0),
        }
    }

    /// EULUMDAT's Isym code.
    pub fn isym(self) -> u8 {
        match self {
            Symmetry::None => 0,
            Symmetry::Rotational => 1,
            Symmetry::C0C180 => 2,
            Symmetry::C90C270 => 3,
            Symmetry::Quadrant => 4,
        }
    }

    /// From EULUMDAT's Isym code.
    pub fn from_isym(isym: i64) -> Option<Self> {
        Some(match isym {
            0 => Symmetry::None,
            1 => Symmetry::Rotational,
            2 => Symmetry::C0C180,
            3 => Symmetry::C90C270,
            4 => Symmetry::Quadrant,
            _ => return None,
        })
    }

    /// Fold any C (degrees, any real) into the stored range through the
    /// symmetry. The result lies in [`Symmetry::stored_range`] (for `None`, in [0, 360)).
    #[inline]
    pub fn fold(self, c: f64) -> f64 {
        let c = wrap360(c);
        match self {
            Symmetry::None => c,
            Symmetry::Rotational => 0.0,
            Symmetry::C0C180 => {
                if c > 180.0 {
                    360.0 - c
                } else {
                    c
                }
            }
            Symmetry::C90C270 => {
                if c < 90.0 {
                    180.0 - c
                } else if c > 270.0 {
                    540.0 - c
                } else {
                    c
                }
            }
            Symmetry::Quadrant => {
                let c = if c > 180.0 { 360.0 - c } else { c };
                if c > 90.0 {
                    180.0 - c
                } else {
                    c
                }
            }
        }
    }

    /// All images of C under the symmetry group, wrapped to [0, 360).
    pub fn images(self, c: f64) -> Vec<f64> {
        let v = match self {
            Symmetry::None => vec![c],
            Symmetry::Rotational => vec![c],
            Symmetry::C0C180 => vec![c, 360.0 - c],
            Symmetry::C90C270 => vec![c, 180.0 - c],
            Symmetry::Quadrant => vec![c, 180.0 - c, 180.0 + c, 360.0 - c],
        };
        v.into_iter().map(wrap360).collect()
    }

    /// Human name.
    pub fn describe(self) -> &'static str {
        match self {
            Symmetry::None => "none",
            Symmetry::Rotational => "rotational",
            Symmetry::C0C180 => "C0-C180 plane",
            Symmetry::C90C270 => "C90-C270 plane",
            Symmetry::Quadrant => "quadrant (both planes)",
        }
    }
}

/// Wrap an angle in degrees into [0, 360). Values within [`ANGLE_EPS`] of 360 become 0.
#[inline]
pub fn wrap360(c: f64) -> f64 {
    // Nearly every caller passes an angle already in range (an atan2 wrapped
    // once, then a lookup's tap wraps it again): `rem_euclid` returns it
    // unchanged there, without its `fmod`.
    if (0.0..360.0 - ANGLE_EPS).contains(&c) {
        return c;
    }
    let mut w = c.rem_euclid(360.0);
    if w >= 360.0 - ANGLE_EPS {
        w = 0.0;
    }
    w
}

/// The measured γ range.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum GammaRange {
    /// 0-90: nothing measured above the horizontal.
    Lower,
    /// 90-180: nothing measured below the horizontal.
    Upper,
    /// 0-180: the full sphere.
    Full,
    /// Anything else, e.g. 0-130.5 (degrees).
    Partial {
        /// First measured γ (degrees).
        from: f64,
        /// Last measured γ (degrees).
        to: f64,
    },
}

/// Absolute intensity (cd) on a Type C grid. See the module docs for the invariants.
#[derive(Debug, Clone, PartialEq)]
pub struct Distribution {
    c: Vec<f64>,
    gamma: Vec<f64>,
    cd: Vec<f64>,
    symmetry: Symmetry,
}

fn check_ascending(axis: &'static str, v: &[f64], lo: f64, hi: f64) -> Result<(), ModelError> {
    if v.is_empty() {
        return Err(ModelError::Angles {
            axis,
            reason: "no angles".into(),
        });
    }
    for (i, &a) in v.iter().enumerate() {
        if !a.is_finite() || a < lo - ANGLE_EPS || a > hi + ANGLE_EPS {
            return Err(ModelError::Angles {
                axis,
                reason: format!("angle #{} = {} is outside [{lo}, {hi}]", i + 1, Num(a)),
            });
        }
        if i > 0 && a <= v[i - 1] + ANGLE_EPS {
            return Err(ModelError::Angles {
                axis,
                reason: format!(
                    "not strictly ascending by more than {ANGLE_EPS} degrees: angle #{} = {} follows {}",
                    i + 1,
                    Num(a),
                    Num(v[i - 1])
                ),
            });
        }
    }
    Ok(())
}

impl Distribution {
    /// Build a distribution, checking every invariant.
    ///
    /// `cd` is C-major: `cd[ic * gamma.len() + ig]`. For [`Symmetry::None`] a
    /// trailing C = 360 plane must already be removed (readers check it equals C = 0).
    pub fn new(c: Vec<f64>, gamma: Vec<f64>, cd: Vec<f64>, symmetry: Symmetry) -> Result<Self, ModelError> {
        check_ascending("gamma", &gamma, 0.0, 180.0)?;
        let (lo, hi) = symmetry.stored_range();
        check_ascending("C", &c, lo, hi)?;
        match symmetry {
            Symmetry::Rotational if c.len() != 1 => {
                return Err(ModelError::Angles {
                    axis: "C",
                    reason: format!("rotational symmetry stores one plane, got {}", c.len()),
                })
            }
            Symmetry::None if c.last().is_some_and(|&l| l >= 360.0 - ANGLE_EPS) => {
                return Err(ModelError::Angles {
                    axis: "C",
                    reason: "C = 360 duplicates C = 0; drop it".into(),
                })
            }
            Symmetry::C0C180 | Symmetry::C90C270 | Symmetry::Quadrant
                if (c[0] - lo).abs() > ANGLE_EPS || (c[c.len() - 1] - hi).abs() > ANGLE_EPS =>
            {
                return Err(ModelError::Angles {
                    axis: "C",
                    reason: format!(
                        "{} symmetry needs planes from {lo} to {hi}, got {} to {}",
                        symmetry.describe(),
                        Num(c[0]),
                        Num(c[c.len() - 1])
                    ),
                });
            }
            _ => {}
        }
        if cd.len() != c.len() * gamma.len() {
            return Err(ModelError::Intensities(format!(
                "{} values for {} C-planes x {} gamma angles",
                cd.len(),
                c.len(),
                gamma.len()
            )));
        }
        let mut cd = cd;
        flush_round_off(&mut cd);
        if let Err((i, why)) = check_intensities(&cd) {
            return Err(ModelError::Intensities(format!(
                "value at C = {}, gamma = {}: {why}",
                Num(c[i / gamma.len()]),
                Num(gamma[i % gamma.len()])
            )));
        }
        if symmetry == Symmetry::C90C270 && c.len() < 3 {
            return Err(ModelError::Angles {
                axis: "C",
                reason: "C90-C270 symmetry needs a plane between 90 and 270: the planes 90 and 270 alone \
                         both lie on its mirror plane, so the half circle it stores is not measured"
                    .into(),
            });
        }
        Ok(Self { c, gamma, cd, symmetry })
    }

    /// Stored C-plane angles (degrees), ascending, within the symmetry's stored range.
    pub fn c_angles_deg(&self) -> &[f64] {
        &self.c
    }
    /// γ angles (degrees), ascending, within [0, 180].
    pub fn gamma_angles_deg(&self) -> &[f64] {
        &self.gamma
    }
    /// All intensities (cd), C-major, γ fastest.
    pub fn intensities_cd(&self) -> &[f64] {
        &self.cd
    }
    /// Intensities (cd) of stored plane `ic` at every γ.
    pub fn plane_cd(&self, ic: usize) -> &[f64] {
        let n = self.gamma.len();
        &self.cd[ic * n..(ic + 1) * n]
    }
    /// Intensity (cd) at stored plane `ic`, γ index `ig`.
    pub fn value_cd(&self, ic: usize, ig: usize) -> f64 {
        self.cd[ic * self.gamma.len() + ig]
    }
    /// The symmetry the stored planes rely on.
    pub fn symmetry(&self) -> Symmetry {
        self.symmetry
    }
    /// Number of stored C-planes.
    pub fn n_c(&self) -> usize {
        self.c.len()
    }
    /// Number of γ angles.
    pub fn n_gamma(&self) -> usize {
        self.gamma.len()
    }

    /// The measured γ range.
    pub fn gamma_range(&self) -> GammaRange {
        let (a, b) = (self.gamma[0], self.gamma[self.gamma.len() - 1]);
        let near = |x: f64, y: f64| (x - y).abs() <= ANGLE_EPS;
        if near(a, 0.0) && near(b, 180.0) {
            GammaRange::Full
        } else if near(a, 0.0) && near(b, 90.0) {
            GammaRange::Lower
        } else if near(a, 90.0) && near(b, 180.0) {
            GammaRange::Upper
        } else {
            GammaRange::Partial { from: a, to: b }
        }
    }

    /// Largest intensity (cd) and its direction (C, γ) in degrees, C of the stored plane.
    pub fn max_cd_at_deg(&self) -> (f64, f64, f64) {
        let mut best = (f64::NEG_INFINITY, 0.0, 0.0);
        let n = self.gamma.len();
        for (i, &v) in self.cd.iter().enumerate() {
            if v > best.0 {
                best = (v, self.c[i / n], self.gamma[i % n]);
            }
        }
        best
    }

    /// Largest intensity (cd).
    pub fn max_cd(&self) -> f64 {
        // The same value as `max_cd_at_deg().0` without tracking where: every
        // reader asks for it (the pole check), on up to 65 k values.
        max_of(&self.cd)
    }

    /// The same distribution with every value multiplied by `factor` (finite),
    /// refused when a scaled value exceeds the model's range ([`check_intensities`]);
    /// a result that is all round-off becomes zero ([`flush_round_off`]).
    pub fn scaled(&self, factor: f64) -> Result<Self, ModelError> {
        if !factor.is_finite() {
            return Err(ModelError::Parameter {
                name: "scale",
                value: Num(factor).to_string(),
                reason: "must be finite".into(),
            });
        }
        let mut d = self.clone();
        d.cd.iter_mut().for_each(|v| *v *= factor);
        flush_round_off(&mut d.cd);
        check_intensities(&d.cd).map_err(|(_, why)| ModelError::Parameter {
            name: "scale",
            value: Num(factor).to_string(),
            reason: format!("the scaled distribution leaves the model's range: {why}"),
        })?;
        Ok(d)
    }

    /// Negative values set to 0; returns how many were changed.
    pub fn clamp_negative(&mut self) -> usize {
        let mut n = 0;
        for v in &mut self.cd {
            if *v < 0.0 {
                *v = 0.0;
                n += 1;
            }
        }
        n
    }

    /// Index of the stored plane at angle `c` (degrees), exact within [`ANGLE_EPS`].
    pub fn find_plane(&self, c: f64) -> Option<usize> {
        let i = self.c.partition_point(|&x| x < c - ANGLE_EPS);
        (i < self.c.len() && (self.c[i] - c).abs() <= ANGLE_EPS).then_some(i)
    }

    /// The full-circle C-planes: for each angle in [0, 360) (ascending) the
    /// index of the stored plane holding its values.
    ///
    /// Every image of every stored plane under the symmetry is listed, so
    /// non-uniform grids stay on their own knots. A rotational distribution
    /// maps to one plane at C = 0 (callers treat it as constant in C).
    pub fn full_planes(&self) -> Vec<(f64, usize)> {
        let mut out: Vec<(f64, usize)> = Vec::with_capacity(self.c.len() * 4);
        for (i, &c) in self.c.iter().enumerate() {
            for img in self.symmetry.images(c) {
                out.push((img, i));
            }
        }
        out.sort_by(|a, b| a.0.total_cmp(&b.0));
        out.dedup_by(|a, b| (a.0 - b.0).abs() <= ANGLE_EPS);
        // Every image maps back to a stored plane with identical values by
        // construction; re-resolve through `fold` so that planes shared by
        // two images (e.g. C90 under Quadrant) point at the canonical one.
        for e in &mut out {
            if let Some(ic) = self.find_plane(self.symmetry.fold(e.0)) {
                e.1 = ic;
            }
        }
        out
    }

    /// Expand to [`Symmetry::None`] over [0, 360): every stored value appears
    /// unchanged at each of its symmetric images. A rotational distribution
    /// is expanded to `rotational_planes` evenly spaced planes (at least 1).
    pub fn expand(&self, rotational_planes: usize) -> Distribution {
        let planes: Vec<(f64, usize)> = if self.symmetry == Symmetry::Rotational {
            let n = rotational_planes.max(1);
            (0..n).map(|k| (k as f64 * 360.0 / n as f64, 0)).collect()
        } else {
            self.full_planes()
        };
        let mut cd = Vec::with_capacity(planes.len() * self.gamma.len());
        for &(_, ic) in &planes {
            cd.extend_from_slice(self.plane_cd(ic));
        }
        Distribution {
            c: planes.iter().map(|p| p.0).collect(),
            gamma: self.gamma.clone(),
            cd,
            symmetry: Symmetry::None,
        }
    }

    /// Intensity (cd) at a stored-grid γ index for any C (degrees) that is
    /// one of the full-circle plane angles; `None` if C is not a grid plane.
    pub fn value_at_plane_cd(&self, c: f64, ig: usize) -> Option<f64> {
        let ic = self.find_plane(self.symmetry.fold(c))?;
        Some(self.value_cd(ic, ig))
    }

    /// The smallest symmetry the data actually has, within `tol` (cd,
    /// absolute). Only symmetries whose mirror planes exist in the grid are
    /// considered, and only when the planes bounding their stored range exist
    /// (so the result can always be passed to [`Distribution::with_symmetry`]).
    /// Order of preference: rotational, quadrant, C0-C180, C90-C270, none.
    pub fn detect_symmetry(&self, tol: f64) -> Symmetry {
        let full = self.full_planes();
        let get = |c: f64| -> Option<&[f64]> {
            let c = wrap360(c);
            let i = full.partition_point(|p| p.0 < c - ANGLE_EPS);
            let i = if i == full.len() && c > 360.0 - 1e-3 { 0 } else { i };
            (i < full.len() && (full[i].0 - c).abs() <= ANGLE_EPS).then(|| self.plane_cd(full[i].1))
        };
        let close = |a: &[f64], b: &[f64]| a.iter().zip(b).all(|(x, y)| (x - y).abs() <= tol);
        let holds = |map: &dyn Fn(f64) -> f64| {
            full.iter().all(|&(c, ic)| match get(map(c)) {
                Some(other) => close(self.plane_cd(ic), other),
                None => false,
            })
        };
        let p0 = self.plane_cd(full[0].1);
        if full.iter().all(|&(_, ic)| close(self.plane_cd(ic), p0)) {
            return Symmetry::Rotational;
        }
        // A half or quadrant can only be stored when its boundary planes exist.
        let has = |c: f64| get(c).is_some();
        let s02 = has(0.0) && has(180.0) && holds(&|c| 360.0 - c);
        // C90-C270 also needs a plane strictly between its mirror halves (see `new`).
        let between = full.iter().any(|p| p.0 > 90.0 + ANGLE_EPS && p.0 < 270.0 - ANGLE_EPS);
        let s39 = has(90.0) && has(270.0) && between && holds(&|c| 180.0 - c);
        match (s02, s39) {
            (true, true) => Symmetry::Quadrant,
            (true, false) => Symmetry::C0C180,
            (false, true) => Symmetry::C90C270,
            _ => Symmetry::None,
        }
    }

    /// Re-store the data with symmetry `target`, keeping only the planes in
    /// its stored range. The caller is responsible for the data having that
    /// symmetry (see [`Distribution::detect_symmetry`]); values are taken from
    /// the planes as they are. Fails if the needed planes do not exist.
    pub fn with_symmetry(&self, target: Symmetry) -> Result<Distribution, ModelError> {
        if target == self.symmetry {
            return Ok(self.clone());
        }
        let full = self.full_planes();
        let (lo, hi) = target.stored_range();
        let mut c = Vec::new();
        let mut cd = Vec::new();
        let mut push = |angle: f64, ic: usize| {
            c.push(angle);
            cd.extend_from_slice(self.plane_cd(ic));
        };
        match target {
            Symmetry::Rotational => push(0.0, full[0].1),
            Symmetry::None => {
                for &(a, ic) in &full {
                    push(a, ic);
                }
            }
            Symmetry::C90C270 => {
                for &(a, ic) in &full {
                    if a >= lo - ANGLE_EPS && a <= hi + ANGLE_EPS {
                        push(a, ic);
                    }
                }
            }
            Symmetry::C0C180 | Symmetry::Quadrant => {
                for &(a, ic) in &full {
                    if a <= hi + ANGLE_EPS {
                        push(a, ic);
                    }
                }
                // C = 180 (or 90) may only exist as an image of 0 in `full`; handled above.
            }
        }
        Distribution::new(c, self.gamma.clone(), cd, target)
    }

    /// The distribution re-oriented in C: each plane at C moves to
    /// `(mirror ? −C : C) + rotate_deg` (degrees). Used to change the C0
    /// convention between files (e.g. a lab that mounted the luminaire 90°
    /// turned, or measured clockwise). The result is stored with the
    /// smallest symmetry the moved data has (exactly, tolerance 0), so a
    /// symmetric file stays compact when the move preserves its symmetry.
    pub fn reoriented(&self, rotate_deg: f64, mirror: bool) -> Result<Distribution, ModelError> {
        if !rotate_deg.is_finite() {
            return Err(ModelError::Parameter {
                name: "rotate-c",
                value: rotate_deg.to_string(),
                reason: "must be finite degrees".into(),
            });
        }
        if self.symmetry == Symmetry::Rotational {
            return Ok(self.clone());
        }
        let full = self.full_planes();
        let mut moved: Vec<(f64, usize)> = full
            .iter()
            .map(|&(c, ic)| (wrap360(if mirror { -c } else { c } + rotate_deg), ic))
            .collect();
        moved.sort_by(|a, b| a.0.total_cmp(&b.0));
        moved.dedup_by(|a, b| (a.0 - b.0).abs() <= ANGLE_EPS);
        let mut cd = Vec::with_capacity(moved.len() * self.gamma.len());
        for &(_, ic) in &moved {
            cd.extend_from_slice(self.plane_cd(ic));
        }
        let d = Distribution::new(
            moved.iter().map(|m| m.0).collect(),
            self.gamma.clone(),
            cd,
            Symmetry::None,
        )?;
        let s = d.detect_symmetry(0.0);
        d.with_symmetry(s)
    }

    /// Largest spread (cd) between planes of the value at γ = 0 and at
    /// γ = 180 (when measured): (nadir spread, zenith spread).
    pub fn pole_spread_cd(&self) -> (f64, f64) {
        let spread = |ig: usize| {
            let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
            for ic in 0..self.c.len() {
                let v = self.value_cd(ic, ig);
                lo = lo.min(v);
                hi = hi.max(v);
            }
            hi - lo
        };
        let n = self.gamma.len();
        let nadir = if self.gamma[0].abs() <= ANGLE_EPS {
            spread(0)
        } else {
            0.0
        };
        let zenith = if (self.gamma[n - 1] - 180.0).abs() <= ANGLE_EPS {
            spread(n - 1)
        } else {
            0.0
        };
        (nadir, zenith)
    }

    /// The same distribution with the γ = 0 and γ = 180 values replaced by
    /// their average over the full circle of planes (weighted by each plane's
    /// share of the circle), so that the value at a pole does not depend on C.
    pub fn with_averaged_poles(&self) -> Distribution {
        let mut d = self.clone();
        let n = self.gamma.len();
        let full = self.full_planes();
        let weights: Vec<f64> = periodic_widths(&full.iter().map(|p| p.0).collect::<Vec<_>>());
        let total: f64 = weights.iter().sum();
        for ig in [0, n - 1] {
            let g = self.gamma[ig];
            if g.abs() > ANGLE_EPS && (g - 180.0).abs() > ANGLE_EPS {
                continue;
            }
            let avg = full
                .iter()
                .zip(&weights)
                .map(|(&(_, ic), w)| self.value_cd(ic, ig) * w)
                .sum::<f64>()
                / total;
            for ic in 0..self.c.len() {
                d.cd[ic * n + ig] = avg;
            }
        }
        d
    }
}

/// Trapezoid weights (degrees) of sorted angles on the periodic [0, 360)
/// circle: each angle gets half the gap to each neighbour, wrapping at 360.
/// One angle gets the whole circle.
pub fn periodic_widths(c: &[f64]) -> Vec<f64> {
    let n = c.len();
    if n == 1 {
        return vec![360.0];
    }
    (0..n)
        .map(|i| {
            let prev = if i == 0 { c[n - 1] - 360.0 } else { c[i - 1] };
            let next = if i + 1 == n { c[0] + 360.0 } else { c[i + 1] };
            0.5 * (next - prev)
        })
        .collect()
}

#[cfg(test)]
mod tests;
