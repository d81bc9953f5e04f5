//! `photosolid info FILE [--json]`.

use std::io::Write;
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
    let mut out = std::io::stdout().lock();
    if a.json {
        serde_json::to_writer_pretty(&mut out, &report)?;
        writeln!(out)?;
    } else {
        writeln!(out, "{}", a.file.display())?;
        write!(out, "{}", report.to_text())?;
    }
    Ok(0)
}
