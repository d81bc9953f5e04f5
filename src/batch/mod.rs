//! Catalogue batches: one [`BatchRecord`] row per photometric file, the
//! table of `photosolid batch` and of the Python binding's `batch()`.
//!
//! Each file is loaded ([`crate::load_with`]), summarised with the numbers of
//! `photosolid info` that the columns hold ([`crate::photometry::summary`]), checked by a hold-out of its own
//! measurements ([`crate::reconstruct::holdout()`], every filter, the best one
//! kept) and fitted with OpenGL lights ([`crate::fit::fit`]). Files are
//! processed in parallel (rayon); rows come back in input order. A file
//! that cannot be read is a row with `ok = false` and its error, never a
//! failed batch. The column schema is in `docs/batch.md`; the Parquet
//! writer and reader are in [`table`] (cargo feature `parquet`), the
//! catalogue page in [`catalogue`].

pub mod catalogue;
#[cfg(feature = "parquet")]
pub mod table;

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::error::ModelError;
use crate::error::{Error, ErrorRecord};
use crate::fit::{fit, FitOptions};
use crate::formats::ReadOptions;
use crate::model::IntensityField;
use crate::model::{Distribution, Luminaire, Progress};
use crate::photometry::Summary;
use crate::reconstruct::{holdout, holdout_split, Filter, HoldoutReport, HoldoutSpec, LightTexture};
use crate::registry::{Job, Registry};

/// The hold-out of the batch: keep every 2nd stored C-plane and every 2nd γ
/// row, reconstruct the others (`photosolid holdout`'s default).
pub const HOLDOUT: HoldoutSpec = HoldoutSpec {
    c_step: 2,
    gamma_step: 2,
};

/// One row of a batch: one file. `None` (null) where the file did not load
/// or the quantity is undefined for it. Units are in the names: `_lm`
/// lumens, `_cd` candela, `_deg` degrees, `_pct` percent, `_ms`
/// milliseconds; ratios are fractions (not percent).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BatchRecord {
    /// The file, as found (the path given, or under a directory given).
    pub path: String,
    /// The file loaded (`errors` may still name a hold-out or fit that could not run).
    pub ok: bool,
    /// Error messages: the load error (`ok = false`, path:line: what was
    /// expected, what was found), or `holdout: ...` / `fit: ...` when that
    /// step could not run on a loaded file.
    pub errors: Vec<String>,
    /// Warning codes (kebab-case, [`crate::error::WarningCode`]): the
    /// reader's, then the photometric consistency checks' (`flux-mismatch`, ...).
    pub warnings: Vec<String>,
    /// `ies` or `ldt`.
    pub format: Option<String>,
    /// Format version, e.g. `LM-63-2002`.
    pub version: Option<String>,
    /// Photometric type, `A`, `B` or `C`.
    pub photometric_type: Option<String>,
    /// Symmetry the stored planes rely on (`none`, `rotational`, `c0-c180`, `c90-c270`, `quadrant`).
    pub symmetry: Option<String>,
    /// Stored C-planes.
    pub n_c: Option<u32>,
    /// C-planes on the full circle after symmetry expansion.
    pub n_c_full: Option<u32>,
    /// γ angles.
    pub n_gamma: Option<u32>,
    /// First measured γ, degrees.
    pub gamma_min_deg: Option<f64>,
    /// Last measured γ, degrees.
    pub gamma_max_deg: Option<f64>,
    /// Largest intensity, cd.
    pub max_cd: Option<f64>,
    /// Integrated luminous flux, lm.
    pub flux_lm: Option<f64>,
    /// Luminaire flux the file declares, lm.
    pub declared_flux_lm: Option<f64>,
    /// `flux_lm / declared_flux_lm`.
    pub flux_ratio: Option<f64>,
    /// Light output ratio (fraction).
    pub lor: Option<f64>,
    /// Downward light output ratio (fraction).
    pub dlor: Option<f64>,
    /// Upward light output ratio (fraction).
    pub ulor: Option<f64>,
    /// IES beam angle (50 % of I_max) in the C0-C180 plane, degrees.
    pub beam_angle_deg: Option<f64>,
    /// IES field angle (10 % of I_max) in the C0-C180 plane, degrees.
    pub field_angle_deg: Option<f64>,
    /// IES beam angle in the C90-C270 plane, degrees.
    pub beam_angle_c90_deg: Option<f64>,
    /// IES field angle in the C90-C270 plane, degrees.
    pub field_angle_c90_deg: Option<f64>,
    /// Bare-lamp flux the file declares, lm (`null` for absolute photometry; schema 2).
    pub lamp_flux_lm: Option<f64>,
    /// Manufacturer (IES `[MANUFAC]`, EULUMDAT line 1; schema 2).
    pub manufacturer: Option<String>,
    /// Catalogue number (IES `[LUMCAT]`, EULUMDAT line 10; schema 2).
    pub catalogue: Option<String>,
    /// Input power, W (IES input watts, EULUMDAT the sum over lamp sets; schema 2).
    pub input_watts: Option<f64>,
    /// `flux_lm / input_watts`, lm/W (schema 2).
    pub efficacy_lm_per_w: Option<f64>,
    /// The filter with the smallest hold-out RMS error ([`HOLDOUT`]), e.g. `catmull-rom`.
    pub best_filter: Option<String>,
    /// Its RMS error over the withheld measured samples, % of I_max.
    pub best_filter_rms_pct: Option<f64>,
    /// Its largest error over the withheld measured samples, % of I_max.
    pub best_filter_max_pct: Option<f64>,
    /// The fitted OpenGL light combination (`fit`'s chosen one, e.g. `point+spot-down`).
    pub fitted_gl: Option<String>,
    /// Its error against every measured direction: `fit`'s relative RMS
    /// error with guard 0.02 I_max (fraction, 0.05 = 5 %; `photosolid fit --json` `error`).
    pub fitted_gl_error: Option<f64>,
    /// Time to read and summarise the file, ms.
    pub parse_ms: f64,
    /// Time of the hold-out (6 filters), ms.
    pub holdout_ms: f64,
    /// Time of the OpenGL fit, ms.
    pub fit_ms: f64,
    /// With `batch --compact` ([`BatchOptions::compact`]): the representation
    /// with the fewest bytes whose largest error over the hold-out's withheld
    /// samples ([`HOLDOUT`]) is within 1 % of I_max, among the six filters on
    /// the measured grid, `sh:{2,4,8,16}`, `lobes:{1,2,3,4}` and `c-mean` (each rebuilt
    /// from the kept samples; `compare::smallest_named`, the rule of
    /// `tradeoff`'s key of the same name). Null when none is, and when not
    /// measured (then `compact_ms` is null too; schema 3).
    pub smallest_within_1pct: Option<String>,
    /// Time of the compact candidates (`--compact`), ms; null when not measured.
    pub compact_ms: Option<f64>,
    /// The luminaire's front used: the C angle, degrees in the file's frame,
    /// [0, 360), from the format's convention or `batch --front` (`info --json`
    /// `front_c_deg`; schema 4).
    #[serde(default)]
    pub front_c_deg: Option<f64>,
}

impl BatchRecord {
    /// A row for `path` with nothing measured yet.
    fn empty(path: &Path) -> Self {
        BatchRecord {
            path: path.display().to_string(),
            ok: false,
            errors: Vec::new(),
            warnings: Vec::new(),
            format: None,
            version: None,
            photometric_type: None,
            symmetry: None,
            n_c: None,
            n_c_full: None,
            n_gamma: None,
            gamma_min_deg: None,
            gamma_max_deg: None,
            max_cd: None,
            flux_lm: None,
            declared_flux_lm: None,
            flux_ratio: None,
            lor: None,
            dlor: None,
            ulor: None,
            beam_angle_deg: None,
            field_angle_deg: None,
            beam_angle_c90_deg: None,
            field_angle_c90_deg: None,
            lamp_flux_lm: None,
            manufacturer: None,
            catalogue: None,
            input_watts: None,
            efficacy_lm_per_w: None,
            best_filter: None,
            best_filter_rms_pct: None,
            best_filter_max_pct: None,
            fitted_gl: None,
            fitted_gl_error: None,
            parse_ms: 0.0,
            holdout_ms: 0.0,
            fit_ms: 0.0,
            smallest_within_1pct: None,
            compact_ms: None,
            front_c_deg: None,
        }
    }

    /// Whether the row is an outlier the catalogue lists first: not loaded,
    /// a hold-out or fit that failed, a warning, or a computed flux more than
    /// [`crate::photometry::FLUX_MISMATCH`] off the declared one.
    pub fn is_outlier(&self) -> bool {
        !self.ok || !self.errors.is_empty() || !self.warnings.is_empty() || self.flux_mismatch()
    }

    /// The computed flux is more than [`crate::photometry::FLUX_MISMATCH`] off the declared one.
    pub fn flux_mismatch(&self) -> bool {
        self.flux_ratio
            .is_some_and(|r| (r - 1.0).abs() > crate::photometry::FLUX_MISMATCH)
    }
}

/// What [`analyse`] does besides loading.
#[derive(Debug, Clone, Default)]
pub struct BatchOptions {
    /// Reader options (`batch --repair`, `--front`, ...).
    pub read: ReadOptions,
    /// Measure the compact candidates and fill `smallest_within_1pct`
    /// (`batch --compact`; off by default: tens of ms a file).
    pub compact: bool,
    /// The representations beyond the built-in ones whose default instances
    /// are compact candidates (the CLI's: none).
    pub registry: Registry,
}

/// A number only when finite (a table never holds NaN or infinity).
fn finite(x: Option<f64>) -> Option<f64> {
    x.filter(|v| v.is_finite())
}

/// A value's JSON string form (the spelling `info --json` uses).
fn json_str(v: &impl Serialize) -> Option<String> {
    match serde_json::to_value(v) {
        Ok(serde_json::Value::String(s)) => Some(s),
        _ => None,
    }
}

fn ms(t: Instant) -> f64 {
    t.elapsed().as_secs_f64() * 1e3
}

/// The row of one file (see the module docs). Never fails: a file that does
/// not load is a row with `ok = false` and the error.
pub fn analyse(path: &Path, options: &BatchOptions) -> BatchRecord {
    let mut row = BatchRecord::empty(path);
    let t = Instant::now();
    let lum = match crate::formats::load_document_with(path, &options.read) {
        Ok(l) => l,
        Err(e) => {
            row.errors.push(ErrorRecord::from(&e).message);
            row.parse_ms = ms(t);
            return row;
        }
    };
    // Only the numbers the columns hold (the photometric summary), not the
    // whole `info` report: its UGR, BUG and luminance tables, flux code and
    // zonal lumens would cost more than the parse (issue 26).
    let l = &lum.luminaire;
    let s = crate::photometry::summary(l);
    row.parse_ms = ms(t);
    row.ok = true;
    add_summary(&mut row, l, &s);
    let reports = add_holdout(&mut row, lum.distribution());
    add_fit(&mut row, lum.distribution());
    // Without a hold-out (its error is in the row) there is nothing to measure against.
    if options.compact && !reports.is_empty() {
        add_compact(&mut row, lum.distribution(), &reports, &options.registry);
    }
    row
}

/// Fills the columns of `row` that describe the luminaire `l` (its warnings,
/// format, grid and metadata) and its photometric summary `s` (cd, lm, degrees,
/// W, lm/W); a number that is not finite is left null.
fn add_summary(row: &mut BatchRecord, l: &Luminaire, s: &Summary) {
    let d = l.distribution();
    row.warnings = l
        .warnings()
        .iter()
        .chain(&s.warnings)
        .map(|w| w.code.as_str().to_string())
        .collect();
    row.format = json_str(&l.format());
    row.version = Some(l.version().to_string());
    row.photometric_type = json_str(&l.photometric_type());
    row.symmetry = json_str(&d.symmetry());
    row.n_c = u32::try_from(d.n_c()).ok();
    row.n_c_full = u32::try_from(d.full_planes().len()).ok();
    row.n_gamma = u32::try_from(d.n_gamma()).ok();
    let g = d.gamma_angles_deg();
    row.gamma_min_deg = g.first().copied();
    row.gamma_max_deg = g.last().copied();
    row.max_cd = finite(Some(s.max_cd));
    row.flux_lm = finite(Some(s.flux.total_lm));
    row.declared_flux_lm = finite(s.declared_flux_lm);
    row.flux_ratio = finite(s.flux_ratio);
    row.lor = finite(s.lor);
    row.dlor = finite(s.dlor);
    row.ulor = finite(s.ulor);
    row.beam_angle_deg = finite(s.beams.ies_beam_deg[0]);
    row.field_angle_deg = finite(s.beams.ies_field_deg[0]);
    row.beam_angle_c90_deg = finite(s.beams.ies_beam_deg[1]);
    row.field_angle_c90_deg = finite(s.beams.ies_field_deg[1]);
    let watts = crate::report::info::input_watts(l);
    row.lamp_flux_lm = finite(l.declared().lamp_flux_lm);
    row.manufacturer = Some(l.metadata().manufacturer.clone());
    row.catalogue = Some(l.metadata().catalogue.clone());
    row.input_watts = finite(watts);
    row.efficacy_lm_per_w = finite(watts.map(|w| s.flux.total_lm / w));
    row.front_c_deg = finite(Some(l.front().c_deg));
}

/// Fills the hold-out columns of `row` for `d`: the filter of the smallest RMS
/// error ([`HOLDOUT`], every filter) with its RMS and max errors (% of I_max),
/// and the time taken (`holdout_ms`); an error message when the hold-out fails.
fn add_holdout(row: &mut BatchRecord, d: &Distribution) -> Vec<HoldoutReport> {
    let t = Instant::now();
    let mut out = Vec::new();
    match holdout(d, HOLDOUT, &Filter::ALL) {
        Ok(reports) => {
            // The first of the smallest RMS errors (Filter::ALL order breaks ties).
            let best = reports
                .iter()
                .filter(|r| r.rms_percent.is_finite())
                .min_by(|a, b| a.rms_percent.total_cmp(&b.rms_percent));
            if let Some(b) = best {
                row.best_filter = Some(b.filter.to_string());
                row.best_filter_rms_pct = finite(Some(b.rms_percent));
                row.best_filter_max_pct = finite(Some(b.max_percent));
            }
            out = reports;
        }
        Err(e) => row.errors.push(format!("holdout: {}", Error::from(e))),
    }
    row.holdout_ms = ms(t);
    out
}

/// Fills `smallest_within_1pct` (and `compact_ms`) of `row` for `d`: the
/// filters' hold-out errors (`reports`), and `sh:L` and `lobes:K` rebuilt
/// from the same kept samples and measured at the same withheld ones; an
/// error message when they cannot be built (the column then stays null).
fn add_compact(row: &mut BatchRecord, d: &Distribution, reports: &[HoldoutReport], registry: &Registry) {
    let t = Instant::now();
    match compact_candidates(d, reports, registry) {
        Ok(c) => {
            row.smallest_within_1pct = crate::compare::smallest_named(
                c.iter().map(|(name, bytes, pct)| (name.as_str(), *bytes, *pct)),
                crate::compare::trade::WITHIN_PCT,
            );
        }
        Err(e) => row.errors.push(format!("compact: {}", Error::from(e))),
    }
    row.compact_ms = Some(ms(t));
}

/// (name, bytes, largest hold-out error in % of I_max) of every candidate of
/// [`BatchRecord::smallest_within_1pct`]: the filters (their hold-out
/// `reports`), then `registry`'s candidates for [`Job::Compact`] (`sh:L`,
/// `lobes:K`, then those added to it) built from the same kept samples.
fn compact_candidates(
    d: &Distribution,
    reports: &[HoldoutReport],
    registry: &Registry,
) -> Result<Vec<(String, usize, f64)>, ModelError> {
    let i_max = d.max_cd();
    let full = LightTexture::new(d)?;
    let mut out: Vec<(String, usize, f64)> = reports
        .iter()
        .map(|r| (r.filter.to_string(), full.sampler(r.filter).bytes(), r.max_percent))
        .collect();
    let split = holdout_split(d, HOLDOUT)?;
    let candidates = registry.candidates(&Job::Compact { dist: d });
    let kept = crate::registry::Reconstructions::new(split.kept.clone(), &candidates)?;
    for r in candidates {
        let field = kept.field(r)?;
        out.push((r.to_string(), field.bytes(), split.max_percent(&*field, i_max)));
    }
    Ok(out)
}

/// Fills the fit columns of `row` for `d`: the chosen combination of fitted
/// OpenGL lights and its error, and the time taken (`fit_ms`); an error
/// message when the fit fails.
fn add_fit(row: &mut BatchRecord, d: &Distribution) {
    let t = Instant::now();
    // Files run in parallel already: the fit's own parallelism would only add overhead.
    let opts = FitOptions {
        parallel: false,
        ..FitOptions::default()
    };
    match fit(d, &opts) {
        Ok(f) => {
            row.fitted_gl = Some(f.chosen().combination.name().to_string());
            row.fitted_gl_error = finite(Some(f.error()));
        }
        Err(e) => row.errors.push(format!("fit: {}", Error::from(e))),
    }
    row.fit_ms = ms(t);
}

/// The rows of `files` in input order, analysed in parallel (rayon).
/// `progress(done, total, path)` is called after each file, from the worker
/// threads.
pub fn run(files: &[PathBuf], options: &BatchOptions, progress: &Progress) -> Vec<BatchRecord> {
    let never = std::sync::atomic::AtomicBool::new(false);
    run_until(files, options, progress, &never).unwrap_or_default()
}

/// [`run`] that stops starting files once `stop` is set (a Ctrl-C in Python,
/// a caller's cancel): `None` when it stopped before the last file, within
/// the time of the files already started.
pub fn run_until(
    files: &[PathBuf],
    options: &BatchOptions,
    progress: &Progress,
    stop: &std::sync::atomic::AtomicBool,
) -> Option<Vec<BatchRecord>> {
    let done = AtomicUsize::new(0);
    files
        .par_iter()
        .map(|f| {
            if stop.load(Ordering::Relaxed) {
                return None;
            }
            let row = analyse(f, options);
            progress(done.fetch_add(1, Ordering::Relaxed) + 1, files.len(), &row.path);
            Some(row)
        })
        .collect()
}

/// Every .ies/.ldt file under `paths` (directories recursively, sorted; files as given).
///
/// # Errors
/// [`Error::Io`] when a directory cannot be listed.
pub fn collect(paths: &[PathBuf]) -> crate::Result<Vec<PathBuf>> {
    Ok(crate::formats::collect(paths)?.files)
}

/// The rows as JSON Lines, one [`BatchRecord`] object per line (keys = the field names).
pub fn to_jsonl(rows: &[BatchRecord]) -> String {
    let mut s = String::new();
    for r in rows {
        // A BatchRecord has only strings, finite numbers, booleans and lists: serialising cannot fail.
        if let Ok(line) = serde_json::to_string(r) {
            s.push_str(&line);
            s.push('\n');
        }
    }
    s
}

/// Rows read back from JSON Lines written by [`to_jsonl`] (blank lines skipped).
///
/// # Errors
/// [`Error::Parse`] naming the line that is not a batch row.
pub fn from_jsonl(text: &str, path: &Path) -> crate::Result<Vec<BatchRecord>> {
    let mut rows = Vec::new();
    for (i, line) in text.lines().enumerate() {
        if line.trim().is_empty() {
            continue;
        }
        let row = serde_json::from_str(line).map_err(|e| crate::error::ParseError {
            path: path.to_path_buf(),
            location: crate::error::Location::line(i + 1),
            kind: crate::ErrorKind::Invalid,
            expected: "a JSON object with the batch row keys (docs/batch.md)".into(),
            found: e.to_string(),
        })?;
        rows.push(row);
    }
    Ok(rows)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn synth_file(dir: &Path) -> PathBuf {
        let grid = crate::synth::GridSpec::uniform(15.0, 5.0).unwrap();
        let lum = crate::synth::Synth::Isotropic.build(&grid, 100.0).unwrap();
        let p = dir.join("iso.ldt");
        crate::save(&lum.clone().into(), &p, &Default::default()).unwrap();
        p
    }

    /// A loaded file has the info numbers; a missing one is an ok=false row with the error.
    #[test]
    fn rows_of_good_and_missing_files() {
        let dir = tempfile::tempdir().unwrap();
        let good = synth_file(dir.path());
        let missing = dir.path().join("missing.ies");
        let rows = run(&[good.clone(), missing], &BatchOptions::default(), &|_, _, _| {});
        assert_eq!(rows.len(), 2);
        let r = &rows[0];
        assert!(r.ok && r.errors.is_empty(), "{r:?}");
        // 100 cd everywhere: 400π lm, within the flux rule's discretisation.
        let flux = r.flux_lm.unwrap();
        assert!((flux - 400.0 * std::f64::consts::PI).abs() < 1e-6 * flux, "{flux}");
        // EULUMDAT stores cd/klm with a few digits: 100 cd within 1e-6.
        assert!((r.max_cd.unwrap() - 100.0).abs() < 1e-4, "{r:?}");
        // A constant is reconstructed exactly by every filter.
        assert!(r.best_filter_rms_pct.unwrap() < 1e-9, "{r:?}");
        assert!(r.fitted_gl.is_some());
        assert!(!rows[1].ok);
        assert_eq!(rows[1].errors.len(), 1);
        assert!(rows[1].errors[0].contains("missing.ies"), "{:?}", rows[1].errors);
        assert!(rows[1].flux_lm.is_none());
    }

    /// JSON Lines read back equal what was written; a bad line is named.
    #[test]
    fn jsonl_round_trip() {
        let dir = tempfile::tempdir().unwrap();
        let rows = run(&[synth_file(dir.path())], &BatchOptions::default(), &|_, _, _| {});
        let text = to_jsonl(&rows);
        assert_eq!(from_jsonl(&text, Path::new("x.jsonl")).unwrap(), rows);
        let err = from_jsonl(&format!("{text}{{\"path\": 1}}\n"), Path::new("x.jsonl")).unwrap_err();
        assert!(err.to_string().contains("x.jsonl:2"), "{err}");
    }
}
