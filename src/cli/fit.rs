//! `photosolid fit FILE [--max-lights 1|2] [--error relative|solid-angle] [--tolerance PCT%] [--json]`.

use std::path::PathBuf;

use clap::Args;
use photosolid::fit::{fit, ErrorMetric, FitOptions, FitReport};

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
    /// Pick the fewest lights whose error is within this many percentage points of the best
    /// combination's error (a percent with its sign, `1%`; a bare number is refused).
    #[arg(long, value_name = "PCT%", default_value = "1%", value_parser = super::parse::percentage_points)]
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
        tolerance: a.tolerance / 100.0,
        ..Default::default()
    };
    let result = fit(lum.distribution(), &options)?;
    let report = FitReport::of(&result);
    super::print_report(a.json, &a.file, &report, &report.to_text())?;
    Ok(0)
}

#[cfg(test)]
mod tests {
    /// The flag's default (`1%`) is the library's default tolerance.
    #[test]
    fn the_default_tolerance_is_the_librarys() {
        use clap::CommandFactory;
        let cmd = crate::cli::Cli::command();
        let fit = cmd.find_subcommand("fit").unwrap();
        let arg = fit.get_arguments().find(|a| a.get_id() == "tolerance").unwrap();
        let default = arg.get_default_values()[0].to_str().unwrap();
        assert_eq!(
            super::super::parse::percentage_points(default).unwrap() / 100.0,
            photosolid::fit::DEFAULT_TOLERANCE
        );
    }
}
