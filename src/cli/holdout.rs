//! `photosolid holdout FILE [--drop-c K] [--drop-gamma K] [--filters ...] [--json]`.
//!
//! `--drop-c K` keeps every K-th stored C-plane (and the range ends) and
//! drops the others; `--drop-gamma K` does the same with γ rows, never
//! dropping the poles or the ends of the measured range. K = 1 drops
//! nothing on that axis. This is the convention of the reference numbers in
//! docs/domain.md §11 ("drop 4/8" has far larger errors than "drop 2/2").

use std::io::Write;
use std::path::PathBuf;

use clap::Args;
use photosolid::reconstruct::{holdout, Filter, HoldoutReport, HoldoutSpec};

use super::ReadArgs;

#[derive(Args, Debug)]
pub struct HoldoutArgs {
    /// A photometric file: .ies, .ldt, TM-33 .xml, or a GLDF photometry (FILE.gldf#ID; FILE.gldf when it holds one).
    file: PathBuf,
    /// Keep every K-th C-plane, reconstruct the others.
    #[arg(long, default_value_t = 2, value_parser = super::parse::at_least_one, allow_negative_numbers = true)]
    drop_c: usize,
    /// Keep every K-th gamma row, reconstruct the others.
    #[arg(long, default_value_t = 2, value_parser = super::parse::at_least_one, allow_negative_numbers = true)]
    drop_gamma: usize,
    /// Filters to compare (comma separated).
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "nearest,bilinear,catmull-rom,mitchell,bspline,pchip"
    )]
    filters: Vec<Filter>,
    /// Print JSON.
    #[arg(long)]
    json: bool,
    #[command(flatten)]
    read: ReadArgs,
}

pub fn run(a: HoldoutArgs) -> anyhow::Result<i32> {
    let lum = super::load(&a.file, &a.read)?;
    let spec = HoldoutSpec {
        c_step: a.drop_c,
        gamma_step: a.drop_gamma,
    };
    let reports = holdout(lum.distribution(), spec, &a.filters)?;
    let mut out = std::io::stdout().lock();
    if a.json {
        serde_json::to_writer_pretty(&mut out, &reports)?;
        writeln!(out)?;
        return Ok(0);
    }
    writeln!(
        out,
        "{}: keep every {} C-plane(s) and every {} gamma row(s); errors in % of I_max",
        a.file.display(),
        a.drop_c,
        a.drop_gamma
    )?;
    writeln!(out, "{}", HoldoutReport::table(&reports))?;
    Ok(0)
}
