//! Fitted OpenGL lights: approximate a luminaire by at most two fixed-function
//! OpenGL lights (Zotti, Neumann, Purgathofer 2005, §3–§5;
//! docs/domain.md §6–§7).
//!
//! - [`model`]: the light model ([`FittedLights`], the `fitted-gl`
//!   reconstruction) and its evaluation in any direction;
//! - [`objective`]: Zotti et al.'s relative error (and a solid-angle-weighted
//!   variant) and the exact cut-off profile;
//! - `optimize` (private): the search over exponents and axes;
//! - [`report`]: serde output and a GLSL / JSON snippet for renderers;
//! - [`lobes`]: mixtures of K cosine-power lobes (`lobes:K`), fitted by the same search.
//!
//! # What is tried ([`Combination`])
//! One spot down, one spot up, one point light; with `max_lights = 2` also
//! point + spot down, point + spot up, and two spots in opposite hemispheres
//! (Zotti et al. 2005, §3). A combination needing a spot in a hemisphere that holds no
//! measured direction, or only dark ones, is skipped with the reason. The spot
//! axes are vertical when the data is rotationally symmetric (the best
//! rotational model of rotational data, and what a renderer expects), and
//! free (tilt and azimuth) otherwise.
//!
//! # Model selection
//! Every combination's error is reported. The chosen one has the fewest
//! lights among those whose error is within `tolerance` of the best
//! ([`DEFAULT_TOLERANCE`] = 0.01: an extra light must buy at least one
//! percentage point of RMS relative error), then the smallest error: a scene
//! pays only for the lights it needs.
//!
//! ```
//! use photosolid_fields::fit::{fit, FitOptions, Hemisphere, Spot, Light, FittedLights};
//! let truth = FittedLights::new(vec![Light::Spot(Spot::vertical(Hemisphere::Down, 800.0, 6.0, 40.0))]);
//! let gamma: Vec<f64> = (0..=180).map(f64::from).collect();
//! let d = truth.sample(&[0.0], &gamma).unwrap();
//! let f = fit(&d, &FitOptions::default()).unwrap();
//! let Light::Spot(s) = f.model().lights[0] else { panic!() };
//! assert!((s.exponent - 6.0).abs() < 0.01 && (s.cutoff_deg - 40.0).abs() <= 0.5);
//! ```

mod fastmath;
pub mod lobes;
pub mod model;
pub mod objective;
pub(crate) mod optimize;
pub mod report;

use rayon::prelude::*;
use serde::Serialize;

pub use model::{FittedLights, Hemisphere, Light, PreparedLights, Spot, RECONSTRUCTION_NAME};
pub use objective::{ErrorMetric, DEFAULT_GUARD, MAX_RELATIVE_WEIGHT};
pub use report::FitReport;

use crate::error::ModelError;
use crate::model::Distribution;
use objective::{Other, Samples};
use optimize::{OtherSpec, Rng, SpotFit, SpotSearch};

/// Default model-selection tolerance, in units of the error (0.01 = one
/// percentage point of RMS relative error).
pub const DEFAULT_TOLERANCE: f64 = 0.01;
/// Default seed of the search's PRNG.
pub const DEFAULT_SEED: u64 = 0x2005_2005;

/// Options of [`fit`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FitOptions {
    /// At most this many lights, 1 or 2. Default: 2.
    pub max_lights: usize,
    /// The error minimised and reported. Default: [`ErrorMetric::Relative`].
    pub metric: ErrorMetric,
    /// Guard constant `C` of the error, relative to I_max. Default: [`DEFAULT_GUARD`] (0.02).
    pub guard: f64,
    /// Model-selection tolerance on the error. Default: [`DEFAULT_TOLERANCE`] (0.01).
    pub tolerance: f64,
    /// Seed of the search's PRNG (results are deterministic per seed). Default: [`DEFAULT_SEED`].
    pub seed: u64,
    /// Fit the combinations in parallel (rayon); the result does not depend on it. Default: true.
    pub parallel: bool,
}

impl Default for FitOptions {
    fn default() -> Self {
        Self {
            max_lights: 2,
            metric: ErrorMetric::Relative,
            guard: DEFAULT_GUARD,
            tolerance: DEFAULT_TOLERANCE,
            seed: DEFAULT_SEED,
            parallel: true,
        }
    }
}

/// A combination of lights tried by the fit (Zotti et al. 2005, §3).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Combination {
    /// One spot into the lower hemisphere.
    SpotDown,
    /// One spot into the upper hemisphere.
    SpotUp,
    /// One point light.
    Point,
    /// A point light and a spot down.
    PointSpotDown,
    /// A point light and a spot up.
    PointSpotUp,
    /// A spot down and a spot up.
    SpotDownSpotUp,
}

impl Combination {
    /// Every combination, in report order.
    pub const ALL: [Combination; 6] = [
        Combination::SpotDown,
        Combination::SpotUp,
        Combination::Point,
        Combination::PointSpotDown,
        Combination::PointSpotUp,
        Combination::SpotDownSpotUp,
    ];
    /// Number of lights.
    pub fn lights(self) -> usize {
        match self {
            Combination::SpotDown | Combination::SpotUp | Combination::Point => 1,
            _ => 2,
        }
    }
    /// Number of shape and weight parameters (to break exact ties).
    fn parameters(self) -> usize {
        match self {
            Combination::Point => 1,
            Combination::SpotDown | Combination::SpotUp => 5,
            Combination::PointSpotDown | Combination::PointSpotUp => 6,
            Combination::SpotDownSpotUp => 10,
        }
    }
    /// Report name, e.g. `point+spot-down`.
    pub fn name(self) -> &'static str {
        match self {
            Combination::SpotDown => "spot-down",
            Combination::SpotUp => "spot-up",
            Combination::Point => "point",
            Combination::PointSpotDown => "point+spot-down",
            Combination::PointSpotUp => "point+spot-up",
            Combination::SpotDownSpotUp => "spot-down+spot-up",
        }
    }
    /// The spot hemispheres it needs.
    fn hemispheres(self) -> &'static [Hemisphere] {
        match self {
            Combination::SpotDown | Combination::PointSpotDown => &[Hemisphere::Down],
            Combination::SpotUp | Combination::PointSpotUp => &[Hemisphere::Up],
            Combination::Point => &[],
            Combination::SpotDownSpotUp => &[Hemisphere::Down, Hemisphere::Up],
        }
    }
}

/// The outcome of one combination.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Trial {
    /// Which lights.
    pub combination: Combination,
    /// Number of lights of the combination.
    pub lights: usize,
    /// The fitted model (weights in cd); `None` when skipped.
    pub model: Option<FittedLights>,
    /// The error minimised (see [`ErrorMetric`]); `None` when skipped.
    pub error: Option<f64>,
    /// Largest |approximation − measurement| over the measured directions, relative to I_max.
    pub max_error: Option<f64>,
    /// Flux of the model sampled on the data's grid / flux of the data (`None` when the data has no flux).
    pub flux_ratio: Option<f64>,
    /// Objective evaluations spent (each tries every cut-off).
    pub evaluations: usize,
    /// Why the combination was not fitted.
    pub skipped: Option<String>,
}

/// The result of [`fit`]: every combination tried and the chosen one.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Fit {
    /// Index of the chosen trial in `trials`.
    pub chosen: usize,
    /// Every combination, in [`Combination::ALL`] order (those above `max_lights` left out).
    pub trials: Vec<Trial>,
    /// Largest measured intensity, cd (the scale of the relative weights and errors).
    pub i_max_cd: f64,
    /// The options used.
    pub options: FitOptions,
    /// Whether the spot axes were held vertical (rotationally symmetric data).
    pub axis_vertical: bool,
    /// Number of measured directions in the error sum.
    pub directions: usize,
}

impl Fit {
    /// The chosen trial.
    pub fn chosen(&self) -> &Trial {
        &self.trials[self.chosen]
    }
    /// The chosen model (weights in cd).
    #[allow(
        clippy::expect_used,
        reason = "`fit` chooses only among fitted trials (`select` skips those without a model)"
    )]
    pub fn model(&self) -> &FittedLights {
        self.chosen().model.as_ref().expect("the chosen trial is fitted")
    }
    /// The chosen model's error.
    #[allow(
        clippy::expect_used,
        reason = "`fit` chooses only among fitted trials, and a fitted trial has its error"
    )]
    pub fn error(&self) -> f64 {
        self.chosen().error.expect("the chosen trial is fitted")
    }
}

/// The error ([`ErrorMetric`], guard `guard` relative to I_max) of `model` (cd)
/// against the measured distribution `d`.
pub fn error_of(d: &Distribution, model: &FittedLights, metric: ErrorMetric, guard: f64) -> Result<f64, ModelError> {
    let mut s = Samples::new(d, metric, guard)?;
    if s.rotational && !model.is_rotational() {
        // A tilted light must be seen from every azimuth.
        s = Samples::new(&d.expand(72), metric, guard)?;
    }
    let k = 1.0 / s.i_max;
    Ok(s.error_sq(|dir| k * model.intensity_dir(dir)).sqrt())
}

/// A combination's fit in relative units.
struct Outcome {
    lights: Vec<Light>,
    evals: usize,
    spots: Vec<SpotFit>,
}

fn seed_for(seed: u64, c: Combination) -> u64 {
    seed ^ (0x9E37_79B9_7F4A_7C15u64.wrapping_mul(c as u64 + 1))
}

fn point_only(s: &Samples) -> Outcome {
    let w = if s.rho_m > 0.0 { s.rho_m / s.rho_sum } else { 0.0 };
    Outcome {
        lights: vec![Light::Point { weight_cd: w }],
        evals: 1,
        spots: vec![],
    }
}

fn one_spot(s: &Samples, thin: Option<&Samples>, hemi: Hemisphere, with_point: bool, free: bool, seed: u64) -> Outcome {
    let other = if with_point { OtherSpec::Point } else { OtherSpec::None };
    let mut search = SpotSearch::new(s, thin, hemi, other, free);
    let f = search.run(&[], &mut Rng::new(seed));
    let mut lights = vec![Light::Spot(f.spot())];
    if with_point {
        lights.insert(
            0,
            Light::Point {
                weight_cd: f.prof.w_other,
            },
        );
    }
    Outcome {
        lights,
        evals: search.evals(),
        spots: vec![f],
    }
}

/// Two spots in opposite hemispheres, starting from the single-spot fits.
fn two_spots(s: &Samples, thin: Option<&Samples>, down: SpotFit, up: SpotFit, free: bool) -> Outcome {
    let mut evals = 0;
    let (mut d, mut u) = (down, up);
    // Joint weights for the current shapes: profile the down spot with the up spot fixed.
    let joint = |d: &SpotFit, u: &SpotFit, evals: &mut usize| -> SpotFit {
        let mut p = objective::Profiler::new(s, Other::Shape(u.factors(s)));
        let r = p.profile(optimize::axis_of(d.hemi, d.x, d.y), optimize::exponent_of(d.u));
        *evals += 1;
        SpotFit { prof: r, ..*d }
    };
    let mut dj = joint(&d, &u, &mut evals);
    let bd = d.factors(s);
    let bu = u.factors(s);
    let overlap = bd.iter().zip(&bu).any(|(a, b)| *a > 0.0 && *b > 0.0);
    if overlap {
        // Alternate: each spot searched with the other's shape fixed (both weights free).
        // Cheap rounds on the thinned data while the pair moves, then one full round.
        let rounds = 3;
        for round in 0..rounds {
            let last = round + 1 == rounds;
            let before = dj.prof.e;
            let mut sd = SpotSearch::new(s, thin, Hemisphere::Down, OtherSpec::Spot(u), free);
            d = sd.refine(d, last);
            evals += sd.evals();
            let mut su = SpotSearch::new(s, thin, Hemisphere::Up, OtherSpec::Spot(d), free);
            u = su.refine(u, last);
            evals += su.evals();
            dj = joint(&d, &u, &mut evals);
            if !last && before - dj.prof.e <= 1e-12 + 1e-6 * dj.prof.e {
                // Converged on the cheap data: skip to the full round.
                let mut sd = SpotSearch::new(s, thin, Hemisphere::Down, OtherSpec::Spot(u), free);
                d = sd.refine(d, true);
                evals += sd.evals();
                let mut su = SpotSearch::new(s, thin, Hemisphere::Up, OtherSpec::Spot(d), free);
                u = su.refine(u, true);
                evals += su.evals();
                dj = joint(&d, &u, &mut evals);
                break;
            }
        }
    }
    let mut sd = dj.spot();
    sd.weight_cd = dj.prof.w_spot;
    let mut su = u.spot();
    su.weight_cd = dj.prof.w_other;
    Outcome {
        lights: vec![Light::Spot(sd), Light::Spot(su)],
        evals,
        spots: vec![dj, u],
    }
}

/// Fit at most `options.max_lights` OpenGL lights to `d` (see the module docs).
///
/// Errors: an all-zero (or all-negative) distribution ([`ModelError::AllZero`]);
/// options outside their domain ([`ModelError::Parameter`]).
pub fn fit(d: &Distribution, options: &FitOptions) -> Result<Fit, ModelError> {
    check_options(options)?;
    let s = Samples::new(d, options.metric, options.guard)?;
    let free = !s.rotational;
    let thin = s.thinned();
    let search = Search {
        s: &s,
        thin: thin.as_ref(),
        free,
    };
    let outcomes = search.outcomes(options);
    let data_flux = crate::photometry::flux(d).total_lm;
    let trials: Vec<Trial> = outcomes
        .into_iter()
        .map(|(c, o)| trial(&s, d, data_flux, c, o))
        .collect();
    let chosen = select(&trials, options.tolerance);
    Ok(Fit {
        chosen,
        trials,
        i_max_cd: s.i_max,
        options: options.clone(),
        axis_vertical: !free,
        directions: s.len(),
    })
}

/// `Ok` when the options [`fit`] cannot check by fitting are in their domain
/// (`max_lights` 1 or 2, `tolerance` finite and >= 0), else [`ModelError::Parameter`].
fn check_options(options: &FitOptions) -> Result<(), ModelError> {
    let bad = |name, value: String, reason: &str| {
        Err(ModelError::Parameter {
            name,
            value,
            reason: reason.into(),
        })
    };
    if !(1..=2).contains(&options.max_lights) {
        return bad("max-lights", options.max_lights.to_string(), "must be 1 or 2");
    }
    if !(options.tolerance.is_finite() && options.tolerance >= 0.0) {
        return bad(
            "tolerance",
            options.tolerance.to_string(),
            "must be a finite number >= 0",
        );
    }
    Ok(())
}

/// Why `c` cannot be fitted to `s` (a hemisphere it puts a spot in holds no measured
/// direction, or only dark ones), the text a skipped [`Trial`] reports; `None` when it can.
fn skip_reason(s: &Samples, c: Combination) -> Option<String> {
    for &h in c.hemispheres() {
        let (i, name) = match h {
            Hemisphere::Down => (0, "lower"),
            Hemisphere::Up => (1, "upper"),
        };
        if !s.measured[i] {
            return Some(format!("no measured direction in the {name} hemisphere"));
        }
        if !s.lit[i] {
            return Some(format!("the {name} hemisphere is dark"));
        }
    }
    None
}

/// What every combination of one [`fit`] is searched on.
struct Search<'a> {
    /// The measured directions, in units of I_max.
    s: &'a Samples,
    /// Every other direction of `s` for the cheap early rounds (`None` on small grids).
    thin: Option<&'a Samples>,
    /// Spot axes free (tilt and azimuth); held vertical for rotationally symmetric data.
    free: bool,
}

impl Search<'_> {
    /// The outcome of every combination up to `options.max_lights` lights, in
    /// [`Combination::ALL`] order, `None` for one skipped. The single-spot ones come
    /// first (in parallel when asked): two spots start from their fits.
    fn outcomes(&self, options: &FitOptions) -> Vec<(Combination, Option<Outcome>)> {
        let combos: Vec<Combination> = Combination::ALL
            .into_iter()
            .filter(|c| c.lights() <= options.max_lights)
            .collect();
        let first: Vec<Combination> = combos
            .iter()
            .copied()
            .filter(|&c| c != Combination::SpotDownSpotUp)
            .collect();
        let outcomes: Vec<Option<Outcome>> = if options.parallel {
            first.par_iter().map(|&c| self.single(c, options.seed)).collect()
        } else {
            first.iter().map(|&c| self.single(c, options.seed)).collect()
        };
        let mut all: Vec<(Combination, Option<Outcome>)> = first.into_iter().zip(outcomes).collect();
        if combos.contains(&Combination::SpotDownSpotUp) {
            let o = self.two_spots_from_singles(&all);
            all.push((Combination::SpotDownSpotUp, o));
        }
        all
    }

    /// The outcome of `c`, any combination but two spots, with the search seeded from
    /// `seed` and `c`; `None` when `c` is skipped ([`skip_reason`]).
    fn single(&self, c: Combination, seed: u64) -> Option<Outcome> {
        let (s, thin, free) = (self.s, self.thin, self.free);
        if skip_reason(s, c).is_some() {
            return None;
        }
        let seed = seed_for(seed, c);
        Some(match c {
            Combination::Point => point_only(s),
            Combination::SpotDown => one_spot(s, thin, Hemisphere::Down, false, free, seed),
            Combination::SpotUp => one_spot(s, thin, Hemisphere::Up, false, free, seed),
            Combination::PointSpotDown => one_spot(s, thin, Hemisphere::Down, true, free, seed),
            Combination::PointSpotUp => one_spot(s, thin, Hemisphere::Up, true, free, seed),
            Combination::SpotDownSpotUp => unreachable!("fitted after the single spots"),
        })
    }

    /// The outcome of two spots, started from the single spot down and the single spot
    /// up among the outcomes `singles`; `None` when it is skipped or either single one was.
    fn two_spots_from_singles(&self, singles: &[(Combination, Option<Outcome>)]) -> Option<Outcome> {
        let single = |h: Combination| {
            singles
                .iter()
                .find(|(x, _)| *x == h)
                .and_then(|(_, o)| o.as_ref())
                .map(|o| o.spots[0])
        };
        match (
            skip_reason(self.s, Combination::SpotDownSpotUp),
            single(Combination::SpotDown),
            single(Combination::SpotUp),
        ) {
            (None, Some(dn), Some(up)) => Some(two_spots(self.s, self.thin, dn, up, self.free)),
            _ => None,
        }
    }
}

/// The [`Trial`] of combination `c` on the samples `s` of `d` (whose flux is
/// `data_flux`, lm): the outcome's lights scaled to cd, with their error, largest
/// error (relative to I_max) and flux ratio; the skip reason when `o` is `None`.
fn trial(s: &Samples, d: &Distribution, data_flux: f64, c: Combination, o: Option<Outcome>) -> Trial {
    let Some(o) = o else {
        return Trial {
            combination: c,
            lights: c.lights(),
            model: None,
            error: None,
            max_error: None,
            flux_ratio: None,
            evaluations: 0,
            skipped: skip_reason(s, c),
        };
    };
    // The search works in units of I_max; the model is reported in cd.
    let model = FittedLights::new(
        o.lights
            .iter()
            .map(|l| match *l {
                Light::Spot(sp) => Light::Spot(Spot {
                    weight_cd: sp.weight_cd * s.i_max,
                    ..sp
                }),
                Light::Point { weight_cd } => Light::Point {
                    weight_cd: weight_cd * s.i_max,
                },
            })
            .collect(),
    );
    let k = 1.0 / s.i_max;
    // The samples' directions are unit vectors: the renderer's form, axes computed once.
    let prepared = model.prepare();
    let a = |dir: glam::DVec3| k * prepared.intensity_unit(dir);
    let (error_sq, max_error) = s.error_sq_and_max(a);
    let error = error_sq.sqrt();
    let flux_ratio = model
        .sample_like(d)
        .ok()
        .map(|m| crate::photometry::flux(&m).total_lm)
        .filter(|_| data_flux > 0.0)
        .map(|f| f / data_flux);
    Trial {
        combination: c,
        lights: c.lights(),
        model: Some(model),
        error: Some(error),
        max_error: Some(max_error),
        flux_ratio,
        evaluations: o.evals,
        skipped: None,
    }
}

/// Fewest lights within `tolerance` of the best error, then the smallest
/// error, then the fewest parameters (exact ties, e.g. a flat hemisphere
/// that a point light and a p = 0 spot both fit).
fn select(trials: &[Trial], tolerance: f64) -> usize {
    let best = trials.iter().filter_map(|t| t.error).fold(f64::INFINITY, f64::min);
    let tie = 1e-9;
    let mut pick: Option<usize> = None;
    for (i, t) in trials.iter().enumerate() {
        let Some(e) = t.error else { continue };
        if e > best + tolerance {
            continue;
        }
        let better = match pick {
            None => true,
            Some(j) => {
                let u = &trials[j];
                let ue = u.error.unwrap_or(f64::INFINITY);
                if t.lights != u.lights {
                    t.lights < u.lights
                } else if (e - ue).abs() > tie {
                    e < ue
                } else {
                    t.combination.parameters() < u.combination.parameters()
                }
            }
        };
        if better {
            pick = Some(i);
        }
    }
    // The point light is always fitted, so something is always there.
    pick.unwrap_or(0)
}
