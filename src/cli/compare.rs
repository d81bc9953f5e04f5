//! `photosolid compare FILE [--vs OTHER] [--recon ...] [--against ...] [--normalize cd|peak|klm|flux]
//! [--align] [--directions measured|dense[:N]] [--tolerance T] [--factor K] [--json] [--report DIR]`.
//!
//! Without `--vs`: each reconstruction of FILE against FILE's reference
//! (`--against`, default its measured solid). With `--vs OTHER`: each
//! reconstruction of FILE (default list starts with `measured`) against
//! OTHER's reference, FILE first aligned onto OTHER with `--align`.
//! Metrics: see `photosolid::compare`; JSON keys: `photosolid::compare::Comparison`.

use std::io::Write;
use std::path::PathBuf;

use clap::Args;
use photosolid::compare::{compare, CompareOptions, Directions, Normalize, Recon};
use photosolid::report::compare_report;

use super::ReadArgs;

#[derive(Args, Debug)]
pub struct CompareArgs {
    /// An .ies or .ldt file.
    file: PathBuf,
    /// Compare FILE's reconstructions with this file's reference instead of FILE's own.
    #[arg(long)]
    vs: Option<PathBuf>,
    /// Reconstructions of FILE (comma separated): measured, fitted-gl, or filters.
    #[arg(long, value_delimiter = ',')]
    recon: Option<Vec<Recon>>,
    /// The reference: measured, fitted-gl or a filter.
    #[arg(long, default_value = "measured")]
    against: Recon,
    /// Normalisation: cd (absolute), peak (I_max = 1), klm (cd per 1000 lm of the file's lamp flux,
    /// as in EULUMDAT; not for absolute photometry), flux (equal luminaire flux: cd per 1000 lm of
    /// the computed flux).
    #[arg(long, default_value = "cd")]
    normalize: Normalize,
    /// Search the best C rotation and mirror of FILE onto OTHER (with --vs).
    #[arg(long)]
    align: bool,
    /// Direction set of the radial metrics: measured, dense, dense:N.
    #[arg(long, default_value = "dense:20000")]
    directions: Directions,
    /// Hausdorff tolerance, fraction of I_max.
    #[arg(long, default_value_t = 1e-3, value_parser = super::parse::positive)]
    tolerance: f64,
    /// Refinement factor of the grid solids.
    #[arg(long, default_value_t = 3, value_parser = super::parse::at_least_one)]
    factor: usize,
    /// Print JSON.
    #[arg(long)]
    json: bool,
    /// Write index.html, report.md, report.json and PNGs into DIR.
    #[arg(long)]
    report: Option<PathBuf>,
    #[command(flatten)]
    read: ReadArgs,
}

pub fn run(a: CompareArgs) -> anyhow::Result<i32> {
    let lum = super::load(&a.file, &a.read)?;
    let other = a.vs.as_ref().map(|p| super::load(p, &a.read)).transpose()?;
    if a.align && other.is_none() {
        anyhow::bail!("--align needs --vs OTHER");
    }
    let recons = a.recon.clone().unwrap_or_else(|| {
        let mut v = photosolid::compare::DEFAULT_RECONS.to_vec();
        if other.is_some() {
            v.insert(0, Recon::Measured);
        }
        v
    });
    let opts = CompareOptions {
        recons,
        against: a.against,
        normalize: a.normalize,
        lamp_flux_lm: [
            lum.declared.lamp_flux_lm,
            other.as_ref().and_then(|o| o.declared.lamp_flux_lm),
        ],
        directions: a.directions,
        tolerance: a.tolerance,
        factor: a.factor,
        align: a.align,
        plots: a.report.is_some(),
        ..Default::default()
    };
    let mut c = compare(&lum.distribution, other.as_ref().map(|o| &o.distribution), &opts)?;
    c.file = a.file.display().to_string();
    c.vs = a.vs.as_ref().map(|p| p.display().to_string());
    let mut out = std::io::stdout().lock();
    if a.json {
        serde_json::to_writer_pretty(&mut out, &c)?;
        writeln!(out)?;
    } else {
        write!(out, "{}", compare_report::to_text(&c))?;
    }
    if let Some(dir) = &a.report {
        compare_report::write_report(&c, dir)?;
        let msg = format!("report written to {}", dir.join("index.html").display());
        if a.json {
            eprintln!("{msg}");
        } else {
            writeln!(out, "{msg}")?;
        }
    }
    Ok(0)
}
