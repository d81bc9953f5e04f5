//! The jobs of `compare`, `tradeoff` and `engines`: a file's reconstructions
//! (or its representations, or the engines' lookups) against a reference.

use crate::compare::trade::{trade_table, TradeOptions, TradeTable};
use crate::compare::{compare_with_progress, Against, CompareOptions, Comparison, Directions, Normalize};
use crate::engines::{measure, Engine, EngineOptions, EnginesOptions, EnginesReport};
use crate::error::{Result, Warning, WarningCode};
use crate::model::Progress;
use crate::numfmt::PctOfPeak;
use crate::reconstruct::Filter;
use crate::registry::{Job, Recon, Registry};
use crate::synth::Truth;

use super::{option_error, Named};

/// The options of `compare` (the CLI's flags; defaults are the CLI's).
#[derive(Clone, Debug)]
pub struct CompareSettings {
    /// `--recon`: the reconstructions (None: [`CompareOptions`]' default list,
    /// then the default instances of `registry`'s added representations).
    pub recons: Option<Vec<Recon>>,
    /// The representations offered beyond the built-in ones (the CLI's: none).
    pub registry: Registry,
    /// `--against`: the reference (None: truth when the file records it, else
    /// withheld; with `--vs`, catmull-rom of the other file).
    pub against: Option<Against>,
    /// `--folds`: folds of the withheld reference (k ≥ 2; None: 2). Given with
    /// another reference it is an `ignored-option` warning.
    pub folds: Option<usize>,
    /// `--units`: cd, peak, klm or flux. Default cd.
    pub units: Normalize,
    /// `--align`: search the best C rotation and mirror onto the other file (needs `--vs`).
    pub align: bool,
    /// `--directions` (None: dense:20000). Given under the withheld reference,
    /// which measures at the withheld points, it is an `ignored-option` warning.
    pub directions: Option<Directions>,
    /// `--tolerance`: the Hausdorff tolerance, a percent of I_max. Default 0.1%.
    pub tolerance: PctOfPeak,
    /// `--factor`: grid solids on a fixed grid refined this many times (None: adaptive).
    pub factor: Option<usize>,
    /// `--solid-tolerance`: the adaptive solids' tolerance, a percent of I_max
    /// (None: 0.05%); excluded by `factor`.
    pub solid_tolerance: Option<PctOfPeak>,
    /// Compute the report's plot data (`--report`).
    pub plots: bool,
}

impl Default for CompareSettings {
    fn default() -> Self {
        let d = CompareOptions::default();
        Self {
            recons: None,
            registry: Registry::default(),
            against: None,
            folds: None,
            units: d.normalize,
            align: false,
            directions: None,
            tolerance: PctOfPeak(0.1),
            factor: None,
            solid_tolerance: None,
            plots: false,
        }
    }
}

impl CompareSettings {
    /// The library's options for `file` (and `vs`): the truth the file
    /// records, its lamp fluxes and its source readings decided here.
    fn options(&self, file: Named<'_>, vs: Option<Named<'_>>) -> Result<CompareOptions> {
        if self.align && vs.is_none() {
            return Err(option_error("--align", "needs --vs OTHER"));
        }
        if self.factor.is_some() && self.solid_tolerance.is_some() {
            return Err(option_error("--solid-tolerance", "cannot be used with --factor"));
        }
        let defaults = CompareOptions::default();
        Ok(CompareOptions {
            recons: match &self.recons {
                Some(r) => r.clone(),
                None => self.registry.candidates(&Job::Compare),
            },
            against: self.against,
            truth: Truth::of_luminaire(file.document),
            folds: self.folds.unwrap_or(defaults.folds),
            normalize: self.units,
            lamp_flux_lm: [
                file.document.declared().lamp_flux_lm,
                vs.and_then(|o| o.document.declared().lamp_flux_lm),
            ],
            directions: self.directions.unwrap_or(defaults.directions),
            tolerance: self.tolerance.fraction(),
            factor: self.factor.unwrap_or(defaults.factor),
            solid_tolerance: match self.factor {
                Some(_) => None,
                None => self
                    .solid_tolerance
                    .map(PctOfPeak::fraction)
                    .or(defaults.solid_tolerance),
            },
            align: self.align,
            plots: self.plots,
            source: file.source(),
            ..defaults
        })
    }

    /// An `ignored-option` warning for each option given that has no effect
    /// with the reference `against`: `--directions` under the withheld
    /// reference (it measures at the withheld points), `--folds` under another.
    fn ignored(&self, against: Against) -> Vec<Warning> {
        let mut out = Vec::new();
        match (against, self.directions, self.folds) {
            (Against::Withheld, Some(d), _) => out.push(Warning::new(
                WarningCode::IgnoredOption,
                format!(
                    "--directions {d}: the withheld reference measures each reconstruction at the withheld \
                     measurements, not at a direction set"
                ),
            )),
            (Against::Withheld, None, _) => {}
            (other, _, Some(k)) => out.push(Warning::new(
                WarningCode::IgnoredOption,
                format!("--folds {k}: folds are the withheld reference's, and the reference is {other}"),
            )),
            _ => {}
        }
        out
    }
}

/// `photosolid compare FILE [--vs OTHER]`: the comparison `compare --json` prints.
pub fn compare(
    file: Named<'_>,
    vs: Option<Named<'_>>,
    settings: &CompareSettings,
    progress: &Progress<'_>,
) -> Result<Comparison> {
    let opts = settings.options(file, vs)?;
    let mut c = compare_with_progress(
        file.document.distribution(),
        vs.map(|o| o.document.distribution()),
        &opts,
        progress,
    )?;
    c.file = file.name.to_string();
    c.warnings = file.warnings_with(vs);
    c.warnings.extend(settings.ignored(opts.reference(vs.is_some())));
    c.vs = vs.map(|o| o.name.to_string());
    c.photometry_side_by_side = vs.map(|o| crate::photometry::derived::side_by_side(file.document, o.document));
    Ok(c)
}

/// The options of `tradeoff` (the CLI's flags; defaults are the CLI's).
#[derive(Clone, Debug)]
pub struct TradeoffSettings {
    /// `--against` (None: as `compare`).
    pub against: Option<Against>,
    /// `--factors`: texture render factors. Default 1, 2, 5, 10.
    pub factors: Vec<u32>,
    /// `--factor`: grid solids on a fixed grid (None: adaptive solids, as `compare`).
    pub factor: Option<usize>,
    /// `--repeats`: timing repeats per representation (the median is reported). Default 5.
    pub repeats: usize,
    /// `--gpu`: add the GPU rows (an error when no adapter is available).
    pub gpu: bool,
    /// Compute the report's plot data (`--report`).
    pub plots: bool,
    /// The representations offered beyond the built-in ones (the CLI's: none).
    pub registry: Registry,
}

impl Default for TradeoffSettings {
    fn default() -> Self {
        Self {
            against: None,
            factors: TradeOptions::default().factors,
            factor: None,
            repeats: 5,
            gpu: false,
            plots: false,
            registry: Registry::default(),
        }
    }
}

/// `photosolid tradeoff FILE [--vs OTHER]`: the table `tradeoff --json` prints.
pub fn tradeoff(
    file: Named<'_>,
    vs: Option<Named<'_>>,
    settings: &TradeoffSettings,
    progress: &Progress<'_>,
) -> Result<TradeTable> {
    let opts = TradeOptions {
        factors: settings.factors.clone(),
        compare: CompareOptions {
            against: settings.against,
            truth: Truth::of_luminaire(file.document),
            factor: settings.factor.unwrap_or(2),
            solid_tolerance: if settings.factor.is_some() {
                None
            } else {
                CompareOptions::default().solid_tolerance
            },
            timing_repeats: settings.repeats,
            directions: Directions::default(),
            plots: settings.plots,
            source: file.source(),
            ..CompareOptions::default()
        },
        gpu: settings.gpu,
        registry: settings.registry.clone(),
    };
    let mut t = trade_table(
        file.document.distribution(),
        vs.map(|o| o.document.distribution()),
        &opts,
        progress,
    )?;
    t.file = file.name.to_string();
    t.comparison.file = t.file.clone();
    t.warnings = file.warnings_with(vs);
    t.comparison.warnings = t.warnings.clone();
    t.comparison.vs = vs.map(|o| o.name.to_string());
    Ok(t)
}

/// The options of `engines` (the CLI's flags; defaults are the CLI's).
#[derive(Clone, Debug)]
pub struct EnginesSettings {
    /// `--engines` (None: all).
    pub engines: Option<Vec<Engine>>,
    /// `--against`: truth or a reconstruction of the file (None: catmull-rom).
    pub against: Option<Against>,
    /// `--tolerance`: search each engine's smallest resolution within this percent of I_max.
    pub tolerance: Option<PctOfPeak>,
    /// `--resolution` of the engines where it is a choice.
    pub resolution: Option<usize>,
    /// `--filter` of pbrt's and godot's bakes. Default catmull-rom.
    pub filter: Filter,
    /// `--factor`: refinement of the solids' grid. Default 3.
    pub factor: usize,
    /// Compute the report's plot data (`--report`).
    pub plots: bool,
}

impl Default for EnginesSettings {
    fn default() -> Self {
        Self {
            engines: None,
            against: None,
            tolerance: None,
            resolution: None,
            filter: Filter::CatmullRom,
            factor: 3,
            plots: false,
        }
    }
}

/// `photosolid engines FILE`: the report `engines --json` prints.
pub fn engines(file: Named<'_>, settings: &EnginesSettings) -> Result<EnginesReport> {
    let opts = EnginesOptions {
        engines: settings.engines.clone().unwrap_or_else(|| Engine::ALL.to_vec()),
        reference: settings
            .against
            .unwrap_or(Against::Recon(Recon::Filter(Filter::CatmullRom))),
        truth: Truth::of_luminaire(file.document),
        layout: EngineOptions {
            resolution: settings.resolution,
            filter: settings.filter,
        },
        factor: settings.factor,
        tolerance: settings.tolerance.map(PctOfPeak::fraction),
        plots: settings.plots,
        ..Default::default()
    };
    let mut r = measure(file.document, &opts)?;
    r.file = file.name.to_string();
    let mut warnings = file.warnings_with(None);
    warnings.append(&mut r.warnings);
    r.warnings = warnings;
    Ok(r)
}
