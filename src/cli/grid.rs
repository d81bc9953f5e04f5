//! `photosolid grid FILE [--json|--csv] [--full]`: the measured grid as data,
//! for independent cross-checks (the notebooks recompute reconstructions
//! from it with numpy/scipy).
//!
//! JSON: `{"c_deg": [...], "gamma_deg": [...], "cd": [[...], ...] (one row
//! per C-plane), "symmetry", "i_max_cd", "source"}`. Without `--full` the
//! stored planes are given (as the symmetry needs); with `--full` the planes
//! of the whole circle. CSV: `c_deg,gamma_deg,cd` one line per sample.

use std::io::Write;
use std::path::PathBuf;

use clap::Args;
use serde::Serialize;

use super::ReadArgs;

#[derive(Args, Debug)]
pub struct GridArgs {
    /// A photometric file: .ies, .ldt, TM-33 .xml, or a GLDF photometry (FILE.gldf#ID; FILE.gldf when it holds one).
    file: PathBuf,
    /// CSV instead of JSON.
    #[arg(long)]
    csv: bool,
    /// Every plane of the full circle (symmetry expanded) instead of the stored ones.
    #[arg(long)]
    full: bool,
    #[command(flatten)]
    read: ReadArgs,
}

#[derive(Serialize)]
struct Grid<'a> {
    source: String,
    symmetry: photosolid::Symmetry,
    i_max_cd: f64,
    c_deg: &'a [f64],
    gamma_deg: &'a [f64],
    cd: Vec<&'a [f64]>,
}

pub fn run(a: GridArgs) -> anyhow::Result<i32> {
    let lum = super::load(&a.file, &a.read)?;
    let d = if a.full {
        lum.distribution().expand(1)
    } else {
        lum.distribution().clone()
    };
    let mut out = std::io::BufWriter::new(std::io::stdout().lock());
    if a.csv {
        writeln!(out, "c_deg,gamma_deg,cd")?;
        for (ic, &c) in d.c_angles_deg().iter().enumerate() {
            for (ig, &g) in d.gamma_angles_deg().iter().enumerate() {
                writeln!(out, "{c},{g},{}", d.value_cd(ic, ig))?;
            }
        }
    } else {
        let g = Grid {
            source: a.file.display().to_string(),
            symmetry: lum.distribution().symmetry(),
            i_max_cd: d.max_cd(),
            c_deg: d.c_angles_deg(),
            gamma_deg: d.gamma_angles_deg(),
            cd: (0..d.n_c()).map(|ic| d.plane_cd(ic)).collect(),
        };
        serde_json::to_writer(&mut out, &g)?;
        writeln!(out)?;
    }
    out.flush()?;
    Ok(0)
}
