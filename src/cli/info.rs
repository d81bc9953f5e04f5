//! `photosolid info FILE [--json]`.

use std::path::PathBuf;

use clap::Args;
use photosolid::report::InfoReport;

use super::ReadArgs;

#[derive(Args, Debug)]
pub struct InfoArgs {
    /// An .ies or .ldt file.
    file: PathBuf,
    /// Print JSON (keys documented in `photosolid::report::info`).
    #[arg(long)]
    json: bool,
    /// Report the distribution at this installed tilt angle (degrees), using the file's tilt table.
    #[arg(long, value_parser = super::parse::finite)]
    tilt: Option<f64>,
    #[command(flatten)]
    read: ReadArgs,
}

pub fn run(a: InfoArgs) -> anyhow::Result<i32> {
    let mut lum = super::load(&a.file, &a.read)?;
    if let Some(t) = a.tilt {
        lum.distribution = lum.tilted_distribution(t)?;
    }
    let report = InfoReport::of(&lum);
    super::print_report(a.json, &a.file, &report, &report.to_text())?;
    Ok(0)
}
