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
use photosolid::report::InfoReport;

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
    #[command(flatten)]
    read: ReadArgs,
}

pub fn run(a: InfoArgs) -> anyhow::Result<i32> {
    let files = photosolid::formats::photometries_in(&a.file);
    let mut reports = Vec::with_capacity(files.len());
    for f in &files {
        let mut doc = super::load(f, &a.read)?;
        if let Some(t) = a.tilt {
            let tilted = doc.tilted_distribution(t)?;
            doc.luminaire.set_distribution(tilted);
        }
        reports.push(InfoReport::of_document(&doc));
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
