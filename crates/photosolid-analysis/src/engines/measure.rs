//! How far each engine's lookup is from the file: the trade-table metrics
//! ([`crate::compare::ReconResult`]) of every emulation against one
//! reference, one row per engine layout and one per documented defect.
//!
//! - Reference: a reconstruction of the file on its native grid (default
//!   Catmull–Rom) or the closed-form truth of a `photosolid synth` file.
//! - Certified Hausdorff distance between grid solids on
//!   [`SolidGrid::refined`]`(file, factor)` (the same grid for every field),
//!   radial max/RMS, flux error and misplaced flux over a Fibonacci set.
//! - A defect row measures the engine with the defect against the same
//!   engine without it (`against` says so): the error the defect adds.
//! - With a tolerance (fraction of I_max), each engine whose resolution is a
//!   choice gets the smallest power-of-two resolution whose certified
//!   Hausdorff distance to the reference is within it.

use serde::Serialize;

use super::defects::{self, Defect};
use super::{emulate, Emulation, Engine, EngineOptions};
use crate::compare::ReferenceKind;
use crate::compare::{
    mark_pareto, measure_field, solid_hausdorff, Against, ErrorMap, FieldTarget, PlotData, ReconResult,
};
use crate::error::ModelError;
use crate::metrics::{random_directions, DirectionSet, ZOTTI_C};
use crate::model::{IntensityField, Luminaire};
use crate::reconstruct::{eval_all, Filter};
use crate::registry::{Recon, Reconstructions};
use crate::solid::{grid_solid, Mesh, RadialMesh, SolidGrid, Units};
use crate::synth::Truth;

/// Options of [`measure`].
#[derive(Debug, Clone, PartialEq)]
pub struct EnginesOptions {
    /// Engines to emulate. Default: all.
    pub engines: Vec<Engine>,
    /// The reference: `truth` or a reconstruction of the file. Default: Catmull–Rom.
    pub reference: Against,
    /// The file's closed form, when it records one ([`Truth::of_luminaire`]).
    pub truth: Option<Truth>,
    /// Layout choices (resolution, pbrt's bake filter).
    pub layout: EngineOptions,
    /// Refinement factor of the solids' grid. Default: 3.
    pub factor: usize,
    /// Fibonacci directions of the radial metrics. Default: 20000.
    pub directions: usize,
    /// Hausdorff certification tolerance, fraction of I_max. Default: 0.001.
    pub hausdorff_tolerance: f64,
    /// Resolution search: the largest Hausdorff distance allowed, fraction of I_max.
    pub tolerance: Option<f64>,
    /// Unit directions timed per lookup. Default: 20000.
    pub timing_samples: usize,
    /// Compute the report's plot data.
    pub plots: bool,
}

impl Default for EnginesOptions {
    fn default() -> Self {
        Self {
            engines: Engine::ALL.to_vec(),
            reference: Against::Recon(Recon::Filter(Filter::CatmullRom)),
            truth: None,
            layout: EngineOptions::default(),
            factor: 3,
            directions: 20_000,
            hausdorff_tolerance: 1e-3,
            tolerance: None,
            timing_samples: 20_000,
            plots: false,
        }
    }
}

/// One row of the engines table.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct EngineRow {
    /// The engine.
    pub engine: Engine,
    /// `layout` (the engine's lookup) or `defect` (the error one loader defect adds).
    pub kind: String,
    /// Row name: the engine, or `engine: defect`.
    pub name: String,
    /// The layout in words, or the defect.
    pub layout: String,
    /// Resolution used, for engines with a choice.
    pub resolution: Option<usize>,
    /// What the row is measured against: `reference`, or `<engine> without the defect`.
    pub against: String,
    /// The source line of a defect (file, function, statement).
    pub source: Option<String>,
    /// Steps of the emulation that follow no source photosolid could read
    /// (stand-ins, parts not modelled); empty when every step is from source.
    pub stand_ins: Vec<String>,
    /// What the row emulates: the engine release (npm for three.js and Babylon.js) or the
    /// commit of the source read; for a defect row, the versions that have the defect.
    pub engine_version: String,
    /// The metrics (lengths in cd). `metrics.pareto` is computed over the layout rows only:
    /// a defect row is measured against another baseline and is never on the front.
    pub metrics: ReconResult,
}

/// One resolution tried by the search.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ResolutionTrial {
    /// The resolution.
    pub resolution: usize,
    /// Certified Hausdorff distance, % of I_max.
    pub hausdorff_pct: f64,
    /// Its certification gap, % of I_max.
    pub hausdorff_bound_pct: f64,
}

/// The smallest resolution of one engine within the tolerance.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ResolutionSearch {
    /// The engine.
    pub engine: Engine,
    /// The tolerance, fraction of I_max (H + its bound must not exceed it).
    pub tolerance: f64,
    /// The same in percent of I_max (`--tolerance 1%` is 1).
    pub tolerance_pct: f64,
    /// The smallest power-of-two resolution within it; `null` when none up to the engine's largest.
    pub resolution: Option<usize>,
    /// Every resolution tried, ascending.
    pub tried: Vec<ResolutionTrial>,
}

/// An engine left out of the table.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SkippedEngine {
    /// The engine.
    pub engine: Engine,
    /// Why.
    pub reason: String,
}

/// The result of [`measure`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct EnginesReport {
    /// The file (set by the caller).
    pub file: String,
    /// The reference in words.
    pub reference: String,
    /// `truth` or `reconstruction`.
    pub reference_kind: ReferenceKind,
    /// Unit of every `*_cd` value.
    pub units: String,
    /// The reference's maximum, cd.
    pub i_max_cd: f64,
    /// Direction set of the radial metrics.
    pub directions: String,
    /// Its size.
    pub n_directions: usize,
    /// What each row's `radial_max_cd` is, in words (as in `compare`: the
    /// max over the set, refined locally around its largest samples).
    pub radial_max_method: String,
    /// Grid refinement factor of the solids.
    pub factor: usize,
    /// Hausdorff certification tolerance, fraction of I_max.
    pub hausdorff_tolerance: f64,
    /// Layout rows, then defect rows.
    pub rows: Vec<EngineRow>,
    /// The resolution searches (with a tolerance).
    pub resolutions: Vec<ResolutionSearch>,
    /// Engines that cannot take this file, with the reason (e.g. a grid Cycles refuses).
    pub skipped: Vec<SkippedEngine>,
    /// Plot data (with `plots`), not in the JSON.
    #[serde(skip)]
    pub plots: Option<PlotData>,
    /// The reference itself over the error maps' C x γ cells, % of I_max (with `plots`), not in the JSON.
    #[serde(skip)]
    pub reference_map: Option<ErrorMap>,
    /// Coded warnings: the file's reader warnings (set by the caller) and a
    /// `layout-limit` per engine whose layout cannot hold the file within 5 %
    /// radial max (docs/warnings.md).
    pub warnings: Vec<crate::error::Warning>,
}

/// A field reference with what every row's metrics need.
struct Reference<'f> {
    field: &'f dyn IntensityField,
    solid: Mesh,
    radial: RadialMesh,
    /// The solid's BVH, built by the first row and kept for the others.
    bvh: std::sync::OnceLock<crate::metrics::Bvh>,
    values: Vec<f64>,
    i_max: f64,
}

struct Setup<'a> {
    grid: &'a SolidGrid,
    set: &'a DirectionSet,
    timing: &'a [glam::DVec3],
    tol_cd: f64,
}

impl<'f> Reference<'f> {
    fn new(field: &'f dyn IntensityField, s: &Setup<'_>, i_max: f64) -> Result<Self, ModelError> {
        let solid = grid_solid(field, s.grid, Units::Candela)?;
        Ok(Self {
            field,
            radial: RadialMesh::new(&solid),
            bvh: std::sync::OnceLock::new(),
            values: eval_all(field, &s.set.directions),
            solid,
            i_max,
        })
    }
}

/// The metrics of `field` against `r` (lengths in cd, percentages of `r.i_max`).
fn metrics(
    name: &str,
    field: &dyn IntensityField,
    r: &Reference<'_>,
    s: &Setup<'_>,
) -> Result<ReconResult, ModelError> {
    let solid = grid_solid(field, s.grid, Units::Candela)?;
    Ok(measure_field(
        name,
        field,
        &solid,
        &FieldTarget {
            field: r.field,
            solid: &r.solid,
            radial: &r.radial,
            bvh: &r.bvh,
            set: s.set,
            values: &r.values,
            i_max: r.i_max,
            tol_cd: s.tol_cd,
            zotti_c: ZOTTI_C,
            timing: s.timing,
            repeats: 3,
            // The engines' tables show H, never the mean surface distance:
            // only the triangles that can set H are searched.
            hausdorff_only: true,
        },
    ))
}

/// What [`measure_engines`] measured.
struct Measured {
    /// Layout rows (Pareto front marked among them), then defect rows.
    rows: Vec<EngineRow>,
    /// Each row's field with its name, for the plots.
    fields: Vec<(String, Box<dyn IntensityField>)>,
    /// Engines that cannot take the file.
    skipped: Vec<SkippedEngine>,
}

/// Emulate every engine of `opts` on `lum` and measure it: a layout row per
/// engine against `reference`, then a row per defect.
///
/// # Errors
/// A bad layout option (resolution), a solid that cannot be built.
fn measure_engines(
    lum: &Luminaire,
    opts: &EnginesOptions,
    reference: &Reference<'_>,
    setup: &Setup<'_>,
) -> Result<Measured, ModelError> {
    let mut rows = Vec::new();
    let mut fields: Vec<(String, Box<dyn IntensityField>)> = Vec::new();
    let mut defect_rows = Vec::new();
    let mut skipped = Vec::new();
    for &engine in &opts.engines {
        // A file an engine refuses (or a fit that fails) leaves that engine out, with the reason;
        // a bad option (resolution) is the caller's error.
        super::resolution(engine, &opts.layout)?;
        let (em, found) = match emulate(engine, lum.distribution(), &opts.layout)
            .and_then(|em| Ok((em, defects::defects(engine, lum)?)))
        {
            Ok(x) => x,
            Err(e) => {
                skipped.push(SkippedEngine {
                    engine,
                    reason: e.to_string(),
                });
                continue;
            }
        };
        rows.push(layout_row(&em, reference, setup)?);
        fields.push((engine.name().into(), em.field));
        for d in found {
            let row = defect_row(engine, em.resolution, &em.stand_ins, &d, reference.i_max, setup)?;
            fields.push((row.name.clone(), d.with));
            defect_rows.push(row);
        }
    }
    // The Pareto front is over the layout rows: a defect row measures the engine with the
    // defect against the engine without it, not against the reference.
    let mut metrics_rows: Vec<ReconResult> = rows.iter().map(|r| r.metrics.clone()).collect();
    mark_pareto(&mut metrics_rows);
    for (r, m) in rows.iter_mut().zip(metrics_rows) {
        r.metrics.pareto = m.pareto;
    }
    for r in &mut defect_rows {
        r.metrics.pareto = false;
    }
    rows.extend(defect_rows);
    Ok(Measured { rows, fields, skipped })
}

/// The layout row of emulation `em`: its lookup against `reference`.
fn layout_row(em: &Emulation, reference: &Reference<'_>, setup: &Setup<'_>) -> Result<EngineRow, ModelError> {
    let engine = em.engine;
    Ok(EngineRow {
        engine,
        kind: "layout".into(),
        name: engine.name().into(),
        layout: em.layout.clone(),
        resolution: em.resolution,
        against: "reference".into(),
        source: None,
        stand_ins: em.stand_ins.iter().map(|s| s.to_string()).collect(),
        engine_version: engine.version().into(),
        metrics: metrics(engine.name(), &*em.field, reference, setup)?,
    })
}

/// The row of defect `d` of `engine` (emulated at `resolution` with
/// `stand_ins`): the engine with the defect against the same engine without
/// it, percentages of `i_max` (cd, the reference's maximum).
fn defect_row(
    engine: Engine,
    resolution: Option<usize>,
    stand_ins: &[&str],
    d: &Defect,
    i_max: f64,
    setup: &Setup<'_>,
) -> Result<EngineRow, ModelError> {
    let name = format!("{engine}: {}", d.name);
    let own = Reference::new(&*d.without, setup, i_max)?;
    Ok(EngineRow {
        engine,
        kind: "defect".into(),
        name: name.clone(),
        layout: d.name.clone(),
        resolution,
        against: format!("{engine} without the defect"),
        source: Some(d.source.to_string()),
        stand_ins: stand_ins.iter().map(|s| s.to_string()).collect(),
        engine_version: d.versions.into(),
        metrics: metrics(&name, &*d.with, &own, setup)?,
    })
}

/// The closed-form truth of the file, which `opts` must record to measure against it.
fn recorded_truth(opts: &EnginesOptions) -> Result<Truth, ModelError> {
    opts.truth.ok_or_else(|| ModelError::Parameter {
        name: "reference",
        value: "truth".into(),
        reason: "this file records no closed-form truth (only files written by `photosolid synth` do)".into(),
    })
}

/// The reference over the error maps' C x γ cells of `plots`, % of `i_max`
/// (cd); `None` without error maps.
fn reference_over_cells(plots: &PlotData, label: &str, field: &dyn IntensityField, i_max: f64) -> Option<ErrorMap> {
    plots.error_maps.first().map(|m| {
        let dirs: Vec<(f64, f64)> = m.ys.iter().flat_map(|&g| m.xs.iter().map(move |&c| (c, g))).collect();
        ErrorMap {
            name: label.to_string(),
            xs: m.xs.clone(),
            ys: m.ys.clone(),
            values: eval_all(field, &dirs).iter().map(|v| 100.0 * v / i_max).collect(),
        }
    })
}

/// Emulate every engine of `opts` on `lum` and measure it against the reference.
///
/// # Errors
/// `withheld` as the reference (it is not a field), `truth` without a
/// recorded truth, all-zero data, a failed emulation.
pub fn measure(lum: &Luminaire, opts: &EnginesOptions) -> Result<EnginesReport, ModelError> {
    let dist = lum.distribution();
    let grid = SolidGrid::refined(dist, opts.factor)?;
    let set = DirectionSet::fibonacci(opts.directions.max(100));
    let timing = random_directions(opts.timing_samples, 0x5eed);
    let recon_holder: Reconstructions;
    let recon_field: Box<dyn IntensityField + '_>;
    let truth_holder: Truth;
    let (ref_field, label, kind): (&dyn IntensityField, String, ReferenceKind) = match opts.reference {
        Against::Truth => {
            truth_holder = recorded_truth(opts)?;
            (&truth_holder, format!("truth ({truth_holder})"), ReferenceKind::Truth)
        }
        Against::Withheld => {
            return Err(ModelError::Parameter {
                name: "reference",
                value: "withheld".into(),
                reason: "engines are measured against a field: truth or a reconstruction (e.g. catmull-rom)".into(),
            })
        }
        Against::Recon(r) => {
            recon_holder = Reconstructions::new((*dist).clone(), &[r])?;
            recon_field = recon_holder.field(r)?;
            (
                &*recon_field,
                format!("{r} of FILE on its native grid (a reconstruction, not the truth)"),
                ReferenceKind::Reconstruction,
            )
        }
    };
    let i_max = dist.max_cd();
    let setup = Setup {
        grid: &grid,
        set: &set,
        timing: &timing,
        tol_cd: opts.hausdorff_tolerance.max(0.0) * i_max,
    };
    let reference = Reference::new(ref_field, &setup, i_max)?;
    let Measured { rows, fields, skipped } = measure_engines(lum, opts, &reference, &setup)?;
    let resolutions = resolution_searches(lum, opts, &skipped, &reference, &setup)?;
    let plots = opts.plots.then(|| {
        let named: Vec<(String, &dyn IntensityField)> = fields.iter().map(|(n, f)| (n.clone(), &**f)).collect();
        crate::compare::plot_data(&named, Some((label.as_str(), ref_field)), dist, None, i_max)
    });
    let reference_map = plots
        .as_ref()
        .and_then(|p| reference_over_cells(p, &label, ref_field, i_max));
    let mut report = EnginesReport {
        file: String::new(),
        reference: label,
        reference_kind: kind,
        units: "cd".into(),
        i_max_cd: i_max,
        directions: set.label.clone(),
        n_directions: set.len(),
        radial_max_method: crate::metrics::MAX_REFINEMENT.describe(&set),
        factor: opts.factor,
        hausdorff_tolerance: opts.hausdorff_tolerance,
        rows,
        resolutions,
        skipped,
        plots,
        reference_map,
        warnings: Vec::new(),
    };
    report.warnings = layout_limits(&report);
    Ok(report)
}

/// With a tolerance in `opts`, the resolution search of each of its engines
/// that has a choice of resolution and was not `skipped`; none without.
fn resolution_searches(
    lum: &Luminaire,
    opts: &EnginesOptions,
    skipped: &[SkippedEngine],
    reference: &Reference<'_>,
    setup: &Setup<'_>,
) -> Result<Vec<ResolutionSearch>, ModelError> {
    Ok(match opts.tolerance {
        Some(tol) => opts
            .engines
            .iter()
            .filter(|e| e.resolution_range().is_some() && !skipped.iter().any(|s| s.engine == **e))
            .map(|&e| search(e, lum, tol, reference, setup, &opts.layout))
            .collect::<Result<Vec<_>, _>>()?,
        None => Vec::new(),
    })
}

/// The smallest power-of-two resolution of `engine` within `tol` (fraction of I_max).
fn search(
    engine: Engine,
    lum: &Luminaire,
    tol: f64,
    reference: &Reference<'_>,
    setup: &Setup<'_>,
    layout: &EngineOptions,
) -> Result<ResolutionSearch, ModelError> {
    let Some((_, lo, hi)) = engine.resolution_range() else {
        return Err(ModelError::Parameter {
            name: "resolution",
            value: "search".into(),
            reason: format!("{engine}'s layout has a fixed size"),
        });
    };
    let mut tried = Vec::new();
    let mut found = None;
    let mut n = lo.next_power_of_two();
    while n <= hi {
        let em = emulate(
            engine,
            lum.distribution(),
            &EngineOptions {
                resolution: Some(n),
                ..*layout
            },
        )?;
        let solid = grid_solid(&*em.field, setup.grid, Units::Candela)?;
        let h = solid_hausdorff(&solid, &reference.solid, setup.tol_cd);
        let pct = |x: f64| 100.0 * x / reference.i_max;
        tried.push(ResolutionTrial {
            resolution: n,
            hausdorff_pct: pct(h.value),
            hausdorff_bound_pct: pct(h.bound),
        });
        if h.value + h.bound <= tol * reference.i_max {
            found = Some(n);
            break;
        }
        n *= 2;
    }
    Ok(ResolutionSearch {
        engine,
        tolerance: tol,
        tolerance_pct: crate::error::percent_of(tol),
        resolution: found,
        tried,
    })
}

/// The largest radial error an engine's layout may add before `engines` and
/// `export` warn `layout-limit`, % of I_max.
pub const LAYOUT_LIMIT_PCT: f64 = 5.0;

/// One `layout-limit` warning per layout row of `r` whose radial max error
/// is above [`LAYOUT_LIMIT_PCT`]: the figure, the resolution, whether a
/// finer resolution can help (not for Godot, whose layout puts the nadir on
/// a seam, `docs/engines.md`; not where the resolution search found none),
/// and the way out (the engines of this table within the limit, or
/// `photosolid engines` when only one engine was measured, as `export` does).
pub fn layout_limits(r: &EnginesReport) -> Vec<crate::error::Warning> {
    let layouts: Vec<&EngineRow> = r.rows.iter().filter(|row| row.kind == "layout").collect();
    let within: Vec<String> = layouts
        .iter()
        .filter(|row| row.metrics.radial_max_pct <= LAYOUT_LIMIT_PCT)
        .map(|row| row.engine.to_string())
        .collect();
    let way_out = match (layouts.len(), within.is_empty()) {
        (0 | 1, _) => "photosolid engines FILE measures every engine's layout on this file".to_string(),
        (_, true) => "no engine measured here holds it; photosolid tradeoff FILE measures the file's own \
                      representations"
            .to_string(),
        (_, false) => format!("engines within {LAYOUT_LIMIT_PCT} % here: {}", within.join(", ")),
    };
    layouts
        .iter()
        .filter(|row| row.metrics.radial_max_pct > LAYOUT_LIMIT_PCT)
        .map(|row| {
            let at = row.resolution.map_or(String::new(), |n| format!(" at resolution {n}"));
            let search = r.resolutions.iter().find(|s| s.engine == row.engine);
            let why = match (row.engine, row.engine.resolution_range(), search) {
                (super::Engine::Godot, ..) => "the layout cannot hold this file: Godot's dual paraboloid puts the \
                                               nadir on the seam of its two halves, where the lookup mixes in the \
                                               zenith, which a finer resolution does not remove"
                    .to_string(),
                (_, _, Some(s)) if s.resolution.is_none() => format!(
                    "no resolution up to {} holds it within {} %",
                    s.tried.last().map_or(0, |t| t.resolution),
                    crate::error::Num(s.tolerance_pct)
                ),
                (_, Some((_, _, max)), _) => format!(
                    "a finer --resolution (up to {max}) may hold it: engines --tolerance {LAYOUT_LIMIT_PCT}% finds \
                     the smallest that does"
                ),
                _ => "the layout cannot hold this file".to_string(),
            };
            crate::error::Warning::new(
                crate::error::WarningCode::LayoutLimit,
                format!(
                    "{}{at}: radial max {:.1} % of I_max, above {LAYOUT_LIMIT_PCT} %: {why}; {way_out}",
                    row.engine, row.metrics.radial_max_pct
                ),
            )
        })
        .collect()
}
