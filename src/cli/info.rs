//! `photosolid info FILE [--json]`.
//!
//! A GLDF container given without an id (`FILE.gldf`) reports every
//! photometry in it, in document order, each named `FILE.gldf#ID`: text
//! blocks one after the other, or with `--json` one object when it holds a
//! single photometry and an array of objects when it holds several. A TM-33
//! document with several emitters reports each the same way, named
//! `FILE.xml#ID`.

use std::path::PathBuf;

use clap::Args;
use photosolid::jobs::{self, InfoSettings, Loaded};

use super::ReadArgs;

#[derive(Args, Debug)]
pub struct InfoArgs {
    /// A photometric file (.ies, .ldt, TM-33 .xml: every emitter), a GLDF container (FILE.gldf: every
    /// photometry), one photometry of it (FILE.gldf#ID) or one emitter of a TM-33 document (FILE.xml#ID).
    file: PathBuf,
    /// Print JSON (keys documented in `photosolid::report::info`).
    #[arg(long)]
    json: bool,
    /// Report the distribution at this installed tilt angle (degrees), using the file's tilt table.
    #[arg(long, value_parser = super::parse::finite)]
    tilt: Option<f64>,
    /// Spacing of the UGR table's luminaire array, in units of H (the luminaires' height above the
    /// eye): 0.25, the catalogue spacing DIALux and Relux tabulate, by default; 1.0 for CIE 190's
    /// example table; any 1/n of H from 0.1 to 1. JSON: `ugr_table.spacing_h`.
    #[arg(long, default_value_t = photosolid::photometry::ugr::CATALOGUE_SPACING_H, value_parser = ugr_spacing)]
    ugr_spacing: f64,
    #[command(flatten)]
    read: ReadArgs,
}

pub fn run(a: InfoArgs) -> anyhow::Result<i32> {
    let files = photosolid::formats::photometries_in(&a.file);
    let mut reports = Vec::with_capacity(files.len());
    let settings = InfoSettings {
        tilt_deg: a.tilt,
        ugr_spacing_h: a.ugr_spacing,
    };
    for f in &files {
        let file = Loaded::load(f, &a.read.options())?;
        reports.push(jobs::info(file.named(), &settings)?);
    }
    match reports.as_slice() {
        [one] => super::print_report(a.json, &files[0], one, &one.to_text())?,
        _ if a.json => super::emit(true, &reports, "")?,
        _ => {
            for (f, r) in files.iter().zip(&reports) {
                super::print_report(false, f, r, &r.to_text())?;
            }
        }
    }
    Ok(0)
}

/// `--ugr-spacing`: a finite number that [`photosolid::photometry::ugr::check_spacing_h`] accepts.
fn ugr_spacing(s: &str) -> Result<f64, String> {
    let v = super::parse::finite(s)?;
    photosolid::photometry::ugr::check_spacing_h(v).map_err(|e| e.to_string())?;
    Ok(v)
}
