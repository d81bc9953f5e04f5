//! `photosolid tradeoff FILE [--against truth|withheld|RECON] [--vs FILE] [--gpu] [--json] [--report DIR]`:
//! every representation a renderer could hold (filters on the native grid,
//! rendered textures at several factors with each lookup, f16 and
//! symmetry-reduced storage, the fitted lights, spherical harmonics `sh:L`,
//! the measured solid), its bytes and time per lookup, and its error against the reference
//! (`photosolid::compare::trade`). JSON keys: `photosolid::compare::trade::TradeTable`.

use std::path::PathBuf;

use clap::Args;
use photosolid::compare::trade::TradeTable;
use photosolid::compare::Against;
use photosolid::jobs::{self, Loaded, TradeoffSettings};
use photosolid::report::compare_report;

use super::{ReadArgs, ReportArgs};

#[derive(Args, Debug)]
pub struct TradeoffArgs {
    /// A photometric file: .ies, .ldt, TM-33 .xml, or a GLDF photometry (FILE.gldf#ID; FILE.gldf when it holds one).
    file: PathBuf,
    /// A denser measurement of the same luminaire: the reference is its
    /// catmull-rom reconstruction unless --against names another (as `compare --vs`).
    #[arg(long, value_name = "FILE")]
    vs: Option<PathBuf>,
    /// What errors are measured against: truth (the closed form a synth file
    /// records), withheld (k-fold hold-out of FILE's measurements), or a
    /// reconstruction (of the --vs file, else of FILE). Default: truth when FILE
    /// records it, else withheld; with --vs, catmull-rom of that file.
    #[arg(long)]
    against: Option<Against>,
    /// Deprecated spelling: `--reference FILE` is `--vs FILE`, `--reference truth|withheld`
    /// is `--against truth|withheld`.
    #[arg(long, hide = true, conflicts_with_all = ["vs", "against"])]
    reference: Option<Reference>,
    /// Texture render factors (comma separated).
    #[arg(long, value_delimiter = ',', default_value = "1,2,5,10", value_parser = super::parse::texture_factor, allow_negative_numbers = true)]
    factors: Vec<u32>,
    /// Grid refinement of the solids the Hausdorff distance is measured on (a fixed grid;
    /// default: adaptive solids, as `compare`).
    #[arg(long, value_parser = super::parse::at_least_one, allow_negative_numbers = true)]
    factor: Option<usize>,
    /// Timing repeats per representation (the median is reported).
    #[arg(long, default_value_t = 5, value_parser = super::parse::at_least_one, allow_negative_numbers = true)]
    repeats: usize,
    /// Add rows for the k = 5 texture read by the GPU's texture hardware
    /// (bilinear, and Catmull-Rom from linear fetches) and for sh:16 and
    /// lobes:4 evaluated by a compute shader in f32 (`+gpu`): their errors,
    /// GPU dispatch time, adapter, texture format and sub-texel precision
    /// (textures), difference from the CPU evaluation. An error when no GPU
    /// adapter is available.
    #[arg(long)]
    gpu: bool,
    #[command(flatten)]
    out: ReportArgs,
    #[command(flatten)]
    read: ReadArgs,
}

/// The deprecated `--reference truth|withheld|FILE`.
#[derive(Clone, Debug, PartialEq)]
enum Reference {
    /// The closed form the file records.
    Truth,
    /// K-fold hold-out of the file's measurements.
    Withheld,
    /// A denser measurement of the same luminaire.
    File(PathBuf),
}

impl std::str::FromStr for Reference {
    type Err = std::convert::Infallible;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Ok(match s {
            "truth" => Reference::Truth,
            "withheld" => Reference::Withheld,
            path => Reference::File(PathBuf::from(path)),
        })
    }
}

/// `--vs` and `--against`, from the deprecated `--reference` when that was given
/// (with a warning naming the new spelling).
fn reference_of(a: &TradeoffArgs) -> (Option<PathBuf>, Option<Against>) {
    match &a.reference {
        None => (a.vs.clone(), a.against),
        Some(r) => {
            let (vs, against, new) = match r {
                Reference::Truth => (None, Some(Against::Truth), "--against truth".to_string()),
                Reference::Withheld => (None, Some(Against::Withheld), "--against withheld".to_string()),
                Reference::File(p) => (Some(p.clone()), None, format!("--vs {}", p.display())),
            };
            eprintln!("warning: [deprecated-option] tradeoff --reference is deprecated: write {new}");
            (vs, against)
        }
    }
}

pub fn run(a: TradeoffArgs) -> anyhow::Result<i32> {
    a.out.check()?;
    let (vs, against) = reference_of(&a);
    let file = Loaded::load(&a.file, &a.read.options())?;
    let vs = vs.as_ref().map(|p| Loaded::load(p, &a.read.options())).transpose()?;
    let settings = TradeoffSettings {
        against,
        factors: a.factors.clone(),
        factor: a.factor,
        repeats: a.repeats,
        gpu: a.gpu,
        plots: a.out.report.is_some(),
        // The command line offers the built-in representations.
        registry: photosolid::registry::Registry::builtin(),
    };
    let t = super::with_progress("representations", |progress| {
        jobs::tradeoff(file.named(), vs.as_ref().map(Loaded::named), &settings, progress)
    })?;
    a.out.emit(&t, &to_text(&t), compare_report::write_trade_report)?;
    Ok(0)
}

/// The table as text: one row per representation, Pareto rows starred.
fn to_text(t: &TradeTable) -> String {
    use std::fmt::Write;
    let mut s = format!(
        "{}\nreference: {}\ndirections: {}; radial max: {}\n{:<36} {:>10} {:>9} {:>10} {:>9} {:>9} {:>9} {:>9}  pareto bytes-front\n",
        t.file,
        t.reference,
        t.directions,
        t.radial_max_method,
        "representation",
        "bytes",
        "ns/sample",
        "H %",
        "+bound %",
        "max %",
        "rms %",
        "flux %"
    );
    for r in &t.rows {
        let _ = writeln!(
            s,
            "{:<36} {:>10} {:>9.1} {:>10.4} {:>9.4} {:>9.4} {:>9.4} {:>+9.4}  {:<6} {}",
            match &r.form {
                Some(f) => format!("{} ({f})", r.representation),
                None => r.representation.clone(),
            },
            r.bytes,
            r.ns_per_sample,
            r.hausdorff_pct,
            r.hausdorff_bound_pct,
            r.radial_max_pct,
            r.radial_rms_pct,
            r.flux_error_pct,
            if r.pareto { "*" } else { "" },
            if r.pareto_bytes { "*" } else { "" }
        );
    }
    let _ = writeln!(
        s,
        "smallest within 1 % radial max: {}",
        t.smallest_within_1pct.as_deref().unwrap_or("none")
    );
    if let Some(w) = t.rows.iter().find_map(|r| r.window.as_deref()) {
        let _ = writeln!(
            s,
            "sh:L rows: spherical harmonics of catmull-rom, {w} window, clamped at 0"
        );
    }
    let f32_rows: Vec<_> = t.rows.iter().filter(|r| r.ns_per_sample_f32.is_some()).collect();
    if !f32_rows.is_empty() {
        let _ = writeln!(s, "stored textures computed in f32 (as a shader does):");
        for r in f32_rows {
            let _ = writeln!(
                s,
                "  {:<36} {:>9.1} ns/sample; max |f32 - f64 lookup| {:.2e} % of I_max",
                r.representation,
                r.ns_per_sample_f32.unwrap_or(f64::NAN),
                r.f32_vs_f64_max_pct.unwrap_or(f64::NAN),
            );
        }
    }
    gpu_rows_text(t, &mut s);
    s
}

/// The `+gpu` rows' lines: what ran where and how far it is from the CPU.
fn gpu_rows_text(t: &TradeTable, out: &mut String) {
    use std::fmt::Write as _;
    for r in t.rows.iter().filter(|r| r.adapter.is_some()) {
        let adapter = r.adapter.as_deref().unwrap_or("?");
        let vs_cpu = r.hardware_vs_exact_max_pct.unwrap_or(f64::NAN);
        let Some(dispatch) = r.ns_per_sample_gpu else {
            // A representation on the open trait, evaluated by its own `build_gpu`.
            let _ = writeln!(
                out,
                "{}: evaluated on {adapter} by the representation's own GPU path (ns/sample above: batch upload + evaluation + read-back); max |GPU - CPU evaluation| {vs_cpu:.2e} % of I_max",
                r.representation,
            );
            continue;
        };
        // A texture row is read through the sampler; a series (sh:L, lobes:K) is evaluated in the shader.
        let how = match r.texture_format.as_deref() {
            Some(format) => format!(
                "{format} on {adapter}; sub-texel weights {}; max |hardware - exact lookup, same texels|",
                r.subtexel_bits
                    .map_or("not probed".into(), |bits| format!("{bits:.1} bits"))
            ),
            None => format!("evaluated in a compute shader on {adapter}, no texture; max |GPU - CPU evaluation|"),
        };
        let _ = writeln!(
            out,
            "{}: GPU dispatch {dispatch:.2} ns/sample (ns/sample above: batch upload + dispatch + read-back); {how} {vs_cpu:.2e} % of I_max",
            r.representation,
        );
    }
}
