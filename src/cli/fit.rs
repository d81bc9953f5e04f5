//! `photosolid fit FILE [--max-lights 1|2] [--error relative|solid-angle] [--tolerance T] [--json]`.

use std::path::PathBuf;

use clap::Args;
use photosolid::fit::{fit, ErrorMetric, FitOptions, FitReport, DEFAULT_TOLERANCE};

use super::ReadArgs;

#[derive(Args, Debug)]
pub struct FitArgs {
    /// A photometric file: .ies, .ldt, TM-33 .xml, or a GLDF photometry (FILE.gldf#ID; FILE.gldf when it holds one).
    file: PathBuf,
    /// At most this many OpenGL lights (1 or 2).
    #[arg(long, default_value_t = 2, value_parser = clap::value_parser!(u8).range(1..=2))]
    max_lights: u8,
    /// Error minimised: the relative error of Zotti et al. (2005) over the measured directions, or each weighted by its solid angle.
    #[arg(long, value_enum, default_value = "relative")]
    error: ErrorMetric,
    /// Pick the fewest lights whose error is within T of the best (0.01 = one percentage point).
    #[arg(long, default_value_t = DEFAULT_TOLERANCE, value_parser = super::parse::non_negative)]
    tolerance: f64,
    /// Guard constant C of the error, a percent of the peak intensity with its sign (a bare number is refused).
    #[arg(long, default_value = "2%", value_parser = super::parse::pct_of_peak, allow_hyphen_values = true)]
    guard: super::parse::PctOfPeak,
    /// Print JSON (keys documented on `photosolid::fit::FitReport`).
    #[arg(long)]
    json: bool,
    #[command(flatten)]
    read: ReadArgs,
}

pub fn run(a: FitArgs) -> anyhow::Result<i32> {
    let lum = super::load(&a.file, &a.read)?;
    let options = FitOptions {
        max_lights: a.max_lights as usize,
        metric: a.error,
        guard: a.guard.fraction(),
        tolerance: a.tolerance,
        ..Default::default()
    };
    let result = fit(lum.distribution(), &options)?;
    let report = FitReport::of(&result);
    super::print_report(a.json, &a.file, &report, &report.to_text())?;
    Ok(0)
}
