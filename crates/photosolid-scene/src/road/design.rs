//! Road design: does a layout meet its lighting class, and how far may one
//! `[road]` key (the spacing, as a rule) go while it does.
//!
//! [`judge`] computes the road and holds its figures against a class of
//! EN 13201-2 ([`super::classes`]). [`maximize`] finds the largest value of a
//! key in a range that meets the class without assuming that any criterion
//! is monotone in the key: it scans the range at a step, then bisects on a
//! lattice of [`RESOLUTION`] anchored at the range's start between the
//! largest passing scan point and the next one, so that the answer passes
//! and the lattice point one resolution beyond it was computed and fails.
//! A passing stretch narrower than the step beyond a failing scan point is
//! not seen; the scan's samples are returned so a user can look.

use rayon::prelude::*;
use serde::Serialize;

use super::classes::{ClassVerdict, Comparison, Family, LightingClass};
use super::layout::{Road, RoadKey};
use super::quantities::{evaluate, Overall, RoadOptions, RoadResult};
use super::RoadError;
use crate::compare::Progress;

/// The resolution of [`maximize`]'s bisection, in the key's unit (m or degrees).
pub const RESOLUTION: f64 = 0.01;
/// Scan points of the default step: the step is (end − start) / this.
pub const DEFAULT_STEPS: f64 = 100.0;
/// The default range of `spacing_m`, in mounting heights: from 1 h to 6 h.
pub const DEFAULT_SPACING_RANGE_H: (f64, f64) = (1.0, 6.0);

/// A road computed and judged against a class.
#[derive(Debug, Clone)]
pub struct Judged {
    /// The road's figures.
    pub result: RoadResult,
    /// The verdict.
    pub verdict: ClassVerdict,
}

/// Compute `road` and judge it against `class`.
///
/// # Errors
/// As [`evaluate`]; [`RoadError::CannotJudge`] when a figure the class needs
/// is undefined (an observer who sees no luminance for an M class, an unlit
/// field for a C or P class).
pub fn judge(road: &Road, class: &LightingClass, options: &RoadOptions) -> Result<Judged, RoadError> {
    let result = evaluate(road, options)?;
    check_computable(&result, class)?;
    let verdict = class.verdict(&result.overall);
    Ok(Judged { result, verdict })
}

/// [`RoadError::CannotJudge`] when `class` needs a figure `result` could not compute.
fn check_computable(result: &RoadResult, class: &LightingClass) -> Result<(), RoadError> {
    let cannot = |criterion: &'static str, reason: &str| {
        Err(RoadError::CannotJudge {
            class: class.name,
            criterion,
            reason: reason.to_string(),
        })
    };
    match class.family {
        Family::M if result.lanes.iter().any(|l| l.l_av_cd_m2 <= 0.0) => cannot(
            "ti_pct",
            "an observer sees no road luminance (L_av = 0), so U_o, U_l and TI are undefined",
        ),
        Family::C | Family::P if result.overall.e_av_lux <= 0.0 => cannot(
            "e_av_lux",
            "the field is unlit (E_av = 0), so its uniformity is undefined",
        ),
        _ => Ok(()),
    }
}

/// What [`maximize`] searches: a key over `start..=end` (the key's unit),
/// scanned at `step`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SearchRange {
    /// The key varied.
    pub key: RoadKey,
    /// First value.
    pub start: f64,
    /// Last value.
    pub end: f64,
    /// Scan step (a multiple of [`RESOLUTION`]).
    pub step: f64,
}

impl SearchRange {
    /// The range of `key` over `start..=end` scanned at `step` (default
    /// (end − start) / 100), the step rounded to a multiple of [`RESOLUTION`].
    ///
    /// # Errors
    /// [`RoadError::Invalid`] naming the key for an empty range (end ≤ start),
    /// a step under [`RESOLUTION`] or over the range, or an end point the key
    /// cannot take.
    pub fn new(key: RoadKey, start: f64, end: f64, step: Option<f64>) -> Result<SearchRange, RoadError> {
        let invalid = |reason: String| RoadError::Invalid {
            key: key.as_str(),
            reason,
        };
        if !(start.is_finite() && end.is_finite() && end > start) {
            return Err(invalid(format!("range {start}:{end} is empty: expected START < END")));
        }
        key.check(start)?;
        key.check(end)?;
        let step = step.unwrap_or((end - start) / DEFAULT_STEPS);
        let step = (step / RESOLUTION).round().max(1.0) * RESOLUTION;
        if !(step.is_finite() && step <= end - start + 1e-9) {
            return Err(invalid(format!("step {step} is longer than the range {start}:{end}")));
        }
        Ok(SearchRange { key, start, end, step })
    }

    /// The default range of `key` for `road`: `spacing_m` from 1 to 6
    /// mounting heights; other keys have none (`None`: give one).
    pub fn default_for(key: RoadKey, road: &Road) -> Option<(f64, f64)> {
        (key == RoadKey::SpacingM).then(|| {
            let h = road.mounting_height_m;
            (DEFAULT_SPACING_RANGE_H.0 * h, DEFAULT_SPACING_RANGE_H.1 * h)
        })
    }

    /// The value of lattice point `m` (`start + m · RESOLUTION`, rounded to 1e-9).
    fn value(&self, m: i64) -> f64 {
        ((self.start + m as f64 * RESOLUTION) * 1e9).round() / 1e9
    }

    /// The lattice index of the last point in the range.
    fn last(&self) -> i64 {
        ((self.end - self.start) / RESOLUTION + 1e-6).floor() as i64
    }

    /// The lattice indices of the scan points: every step, and the range's last point.
    fn scan_points(&self) -> Vec<i64> {
        let every = (self.step / RESOLUTION).round().max(1.0) as i64;
        let last = self.last();
        let mut points: Vec<i64> = (0..=last).step_by(every as usize).collect();
        if points.last() != Some(&last) {
            points.push(last);
        }
        points
    }
}

/// One computed point of a search.
#[derive(Debug, Clone, Serialize)]
pub struct Sample {
    /// The key's value.
    pub value: f64,
    /// Whether the class passes there.
    pub pass: bool,
    /// Each criterion's achieved value, in the class's order (`null` when the
    /// road could not be computed there).
    pub achieved: Vec<Option<f64>>,
    /// Why the road could not be judged there, when it could not.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub error: Option<String>,
}

/// One criterion's signed distance to its limit at the answer.
#[derive(Debug, Clone, Serialize)]
pub struct Margin {
    /// The criterion (an `overall` key).
    pub name: &'static str,
    /// `>=` or `<=`.
    pub comparison: Comparison,
    /// Signed distance, positive when it passes, in `unit`.
    pub margin: f64,
    /// Unit.
    pub unit: &'static str,
}

/// A value another key was held at (`--grid`).
#[derive(Debug, Clone, Copy, Serialize)]
pub struct Held {
    /// The key.
    pub key: RoadKey,
    /// Its value.
    pub value: f64,
}

/// The answer of [`maximize`] (JSON `maximize`: `key, value, range, step,
/// margins`, or `value: null` and `reason`).
#[derive(Debug, Clone, Serialize)]
pub struct Maximized {
    /// The key maximised.
    pub key: RoadKey,
    /// The largest value that meets the class, or `None` when none in the range does.
    pub value: Option<f64>,
    /// Why there is no value.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reason: Option<String>,
    /// `[start, end]` searched.
    pub range: [f64; 2],
    /// The scan step.
    pub step: f64,
    /// The bisection's resolution.
    pub resolution: f64,
    /// Per criterion, the signed distance to its limit at `value` (empty without one).
    pub margins: Vec<Margin>,
    /// The next lattice point beyond `value` (`value` + resolution), computed
    /// and failing; `None` when `value` is the range's end.
    pub next_value: Option<f64>,
    /// The class.
    pub class: &'static str,
    /// The criteria's names, the order of each sample's `achieved`.
    pub criteria: Vec<&'static str>,
    /// The criteria's limits, in that order.
    pub required: Vec<f64>,
    /// The key held at a value of `--grid`, when there is one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub grid: Option<Held>,
    /// Every computed point, by value.
    pub samples: Vec<Sample>,
    /// Number of road calculations.
    pub evaluations: usize,
}

/// Judge `road` with `range.key` at lattice point `m`: a sample, and the
/// figures when it could be computed.
fn sample_at(
    road: &Road,
    class: &LightingClass,
    range: &SearchRange,
    m: i64,
    options: &RoadOptions,
) -> Result<(Sample, Option<Overall>), RoadError> {
    let value = range.value(m);
    let at = range.key.set(road, value)?;
    match judge(&at, class, options) {
        Ok(j) => Ok((
            Sample {
                value,
                pass: j.verdict.pass,
                achieved: j.verdict.criteria.iter().map(|c| Some(c.achieved)).collect(),
                error: None,
            },
            Some(j.result.overall),
        )),
        Err(e @ (RoadError::CannotJudge { .. } | RoadError::NothingInView)) => Ok((
            Sample {
                value,
                pass: false,
                achieved: vec![None; class.limits.len()],
                error: Some(e.to_string()),
            },
            None,
        )),
        Err(e) => Err(e),
    }
}

/// The largest value of `range.key` that meets `class` (module docs); each
/// computed point is reported to `progress` (the bisection's as one more).
///
/// # Errors
/// [`RoadError`] when the road cannot be computed at a point for another
/// reason than an unlit field or observer (those points fail).
pub fn maximize(
    road: &Road,
    class: &LightingClass,
    range: &SearchRange,
    options: &RoadOptions,
    progress: Option<&Progress<'_>>,
) -> Result<Maximized, RoadError> {
    let points = range.scan_points();
    let total = points.len() + 8;
    let done = std::sync::atomic::AtomicUsize::new(0);
    let judge_at = |m: i64| -> Result<(bool, (Sample, Option<Overall>)), RoadError> {
        let out = sample_at(road, class, range, m, options)?;
        let n = done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
        if let Some(p) = progress {
            p(n.min(total), total, "road calculations");
        }
        Ok((out.0.pass, out))
    };
    let found = largest_passing(&points, &judge_at)?;
    let mut samples: Vec<Sample> = found.computed.iter().map(|(_, (s, _))| s.clone()).collect();
    let answer = found.answer.map(|(m, (_, o))| (m, o));
    let next_value = found.next_failing.map(|m| range.value(m));
    samples.sort_by(|a, b| a.value.total_cmp(&b.value));
    let evaluations = samples.len();
    let margins = answer
        .as_ref()
        .and_then(|(_, o)| o.as_ref())
        .map(|o| {
            class
                .verdict(o)
                .criteria
                .iter()
                .map(|c| Margin {
                    name: c.name,
                    comparison: c.comparison,
                    margin: c.margin,
                    unit: c.unit,
                })
                .collect()
        })
        .unwrap_or_default();
    let reason = answer.is_none().then(|| nothing_passes(class, range, &samples));
    Ok(Maximized {
        key: range.key,
        value: answer.map(|(m, _)| range.value(m)),
        reason,
        range: [range.start, range.end],
        step: range.step,
        resolution: RESOLUTION,
        margins,
        next_value,
        class: class.name,
        criteria: class.limits.iter().map(|l| l.name).collect(),
        required: class.limits.iter().map(|l| l.required).collect(),
        grid: None,
        samples,
        evaluations,
    })
}

/// What [`largest_passing`] found: the largest passing point and what was
/// computed there, the lattice point after it (computed, failing), and
/// every point computed.
pub struct Found<T> {
    /// The largest passing point found, with its payload.
    pub answer: Option<(i64, T)>,
    /// The next lattice point after the answer, which fails (`None`: the
    /// answer is the last scan point, or there is none).
    pub next_failing: Option<i64>,
    /// Every computed point (scan first, then bisection) with its verdict and payload.
    pub computed: Vec<(i64, T)>,
}

/// The search of [`maximize`] on integer lattice points: `judge(m)` at every
/// scan point (in parallel), then, between the largest passing scan point and
/// the scan point after it (which fails), bisection down to neighbouring
/// lattice points. No monotonicity is assumed: the answer is the largest
/// passing scan point refined towards the next failing one, and the lattice
/// point after the answer was computed and fails.
///
/// # Errors
/// The first error of `judge`.
pub fn largest_passing<T: Send + Clone, E: Send>(
    points: &[i64],
    judge: &(dyn Fn(i64) -> Result<(bool, T), E> + Sync),
) -> Result<Found<T>, E> {
    let scanned: Vec<(i64, bool, T)> = points
        .par_iter()
        .map(|&m| judge(m).map(|(pass, t)| (m, pass, t)))
        .collect::<Result<_, E>>()?;
    let mut computed: Vec<(i64, T)> = scanned.iter().map(|(m, _, t)| (*m, t.clone())).collect();
    let Some(best) = scanned.iter().rposition(|s| s.1) else {
        return Ok(Found {
            answer: None,
            next_failing: None,
            computed,
        });
    };
    if best + 1 == scanned.len() {
        let (m, _, t) = &scanned[best];
        return Ok(Found {
            answer: Some((*m, t.clone())),
            next_failing: None,
            computed,
        });
    }
    let (mut lo, mut hi) = (scanned[best].0, scanned[best + 1].0);
    let mut lo_payload = scanned[best].2.clone();
    while hi - lo > 1 {
        let mid = lo + (hi - lo) / 2;
        let (pass, t) = judge(mid)?;
        computed.push((mid, t.clone()));
        if pass {
            lo = mid;
            lo_payload = t;
        } else {
            hi = mid;
        }
    }
    Ok(Found {
        answer: Some((lo, lo_payload)),
        next_failing: Some(hi),
        computed,
    })
}

/// Why no scanned value of `range` meets `class`: the sample that fails the
/// fewest criteria and what it misses by.
fn nothing_passes(class: &LightingClass, range: &SearchRange, samples: &[Sample]) -> String {
    let unit = range.key.unit();
    let head = format!(
        "no {} in {}:{} {unit} meets {} (scanned every {} {unit})",
        range.key.as_str(),
        range.start,
        range.end,
        class.name,
        range.step
    );
    let failing = |s: &Sample| -> Vec<String> {
        class
            .limits
            .iter()
            .zip(&s.achieved)
            .filter_map(|(l, a)| {
                let a = (*a)?;
                (l.comparison.margin(a, l.required) < 0.0).then(|| {
                    format!(
                        "{} {} {} {}",
                        l.name,
                        crate::numfmt::significant(a, 3),
                        if l.comparison == Comparison::AtLeast { "<" } else { ">" },
                        l.required
                    )
                })
            })
            .collect()
    };
    let closest = samples
        .iter()
        .filter(|s| s.error.is_none())
        .map(|s| (s, failing(s)))
        .min_by_key(|(_, f)| f.len());
    match closest {
        Some((s, f)) => format!("{head}; closest at {} {unit}: {}", s.value, f.join(", ")),
        None => format!("{head}; the road could not be judged at any scanned value"),
    }
}

/// [`maximize`] for each value of `held` (`--grid KEY=A:B:STEP`): the key
/// `held.key` set to each of `values`, the answer's `grid` naming it.
///
/// # Errors
/// As [`maximize`]; [`RoadError::Invalid`] for a grid value the key cannot take.
pub fn maximize_grid(
    road: &Road,
    class: &LightingClass,
    range: &SearchRange,
    held: RoadKey,
    values: &[f64],
    options: &RoadOptions,
    progress: Option<&Progress<'_>>,
) -> Result<Vec<Maximized>, RoadError> {
    let mut out = Vec::with_capacity(values.len());
    for (k, &v) in values.iter().enumerate() {
        let at = held.set(road, v)?;
        let inner = |done: usize, total: usize, what: &str| {
            if let Some(p) = progress {
                p(
                    k * total + done,
                    values.len() * total,
                    &format!("{}={v}: {what}", held.as_str()),
                );
            }
        };
        let mut m = maximize(&at, class, range, options, Some(&inner))?;
        m.grid = Some(Held { key: held, value: v });
        out.push(m);
    }
    Ok(out)
}

/// `maximize` in the JSON: one answer, or one per `--grid` value.
#[derive(Debug, Clone, Serialize)]
#[serde(untagged)]
pub enum MaximizeAnswer {
    /// `--maximize KEY`.
    One(Box<Maximized>),
    /// `--maximize KEY --grid HELD=A:B:STEP`: one answer per value of HELD.
    Grid(Vec<Maximized>),
}

impl MaximizeAnswer {
    /// Every answer, in order.
    pub fn answers(&self) -> &[Maximized] {
        match self {
            MaximizeAnswer::One(m) => std::slice::from_ref(&**m),
            MaximizeAnswer::Grid(v) => v,
        }
    }
}

/// Everything `photosolid road` reports: the road's figures, with `--class`
/// its verdict (keys `class`, `criteria`, `pass`), with `--maximize` the answer.
#[derive(Debug, Clone, Serialize)]
pub struct RoadAnswer {
    /// The road as its file describes it.
    #[serde(flatten)]
    pub result: RoadResult,
    /// Its verdict against the class asked for.
    #[serde(flatten)]
    pub verdict: Option<ClassVerdict>,
    /// The largest value of the key asked for that meets the class.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub maximize: Option<MaximizeAnswer>,
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A verdict that passes below 30, fails from 30 to 54, passes again from
    /// 55 to 72 and fails from 73: the scan (every 10) sees the second
    /// stretch, the bisection ends on 72 with 73 computed and failing.
    #[test]
    fn the_search_finds_the_last_passing_stretch_of_a_non_monotone_verdict() {
        let pass = |m: i64| m < 30 || (55..73).contains(&m);
        let points: Vec<i64> = (0..=100).step_by(10).collect();
        let judge = |m: i64| -> Result<(bool, i64), ()> { Ok((pass(m), m)) };
        let found = largest_passing(&points, &judge).unwrap();
        assert_eq!(found.answer.map(|a| a.0), Some(72));
        assert_eq!(found.next_failing, Some(73));
        assert!(found.computed.iter().any(|c| c.0 == 73));
        assert!(found.computed.iter().any(|c| c.0 == 72));
        // every computed point's verdict is the function's
        assert!(found.computed.iter().all(|(m, t)| m == t));
    }

    #[test]
    fn the_search_reports_nothing_or_the_range_end() {
        let points: Vec<i64> = (0..=50).step_by(5).collect();
        let never = |_m: i64| -> Result<(bool, ()), ()> { Ok((false, ())) };
        let found = largest_passing(&points, &never).unwrap();
        assert!(found.answer.is_none() && found.next_failing.is_none());
        assert_eq!(found.computed.len(), points.len());
        let always = |_m: i64| -> Result<(bool, ()), ()> { Ok((true, ())) };
        let found = largest_passing(&points, &always).unwrap();
        assert_eq!(found.answer.map(|a| a.0), Some(50));
        assert!(found.next_failing.is_none());
    }

    #[test]
    fn a_range_rounds_its_step_to_the_resolution_and_ends_on_its_end() {
        let r = SearchRange::new(RoadKey::SpacingM, 10.0, 20.004, Some(0.333)).unwrap();
        assert!((r.step - 0.33).abs() < 1e-12);
        let pts = r.scan_points();
        assert_eq!(pts[0], 0);
        assert_eq!(*pts.last().unwrap(), 1000);
        assert!((r.value(1000) - 20.0).abs() < 1e-12);
        assert!(SearchRange::new(RoadKey::SpacingM, 20.0, 10.0, None).is_err());
        assert!(SearchRange::new(RoadKey::TiltDeg, 0.0, 95.0, None).is_err());
        assert!(SearchRange::new(RoadKey::SpacingM, 10.0, 11.0, Some(2.0)).is_err());
    }
}
