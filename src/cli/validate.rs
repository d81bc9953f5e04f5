//! `photosolid validate PATH... [--json] [--derived]`: load every .ies/.ldt/TM-33 .xml file and every photometry of each .gldf container (any case) under the paths.
//!
//! Files are loaded in parallel (rayon) and reported in input order (paths
//! as given, directories walked in sorted order). Exit status 0 when every
//! file loaded, 1 otherwise. A progress bar goes to stderr when it is a
//! terminal and there are many files.

use std::io::{IsTerminal, Write};
use std::path::{Path, PathBuf};

use clap::Args;
use photosolid::formats::Document;
use photosolid::report::info::Tables;
use photosolid::report::InfoReport;
use rayon::prelude::*;
use serde::Serialize;

use super::ReadArgs;

#[derive(Args, Debug)]
pub struct ValidateArgs {
    /// Files and directories (searched recursively for .ies/.ldt, TM-33 .xml and .gldf, any case, and files without such an extension by their first bytes; a .gldf gives every photometry). Exit 1 when nothing photometric is found.
    #[arg(required = true)]
    paths: Vec<PathBuf>,
    /// One JSON object per line: path, ok, errors, warnings, and the info numbers when ok
    /// (the `info --json` keys except `ugr_table`, `bug_rating` and `luminance_table`: see --derived).
    #[arg(long)]
    json: bool,
    /// Also compute the UGR table, BUG rating and luminance table of every file (the JSON keys
    /// `ugr_table`, `bug_rating`, `luminance_table`, as `info --json` has them). Off by default
    /// (a change of the JSON contract, issue 26): they are about 95 % of the time of validating a file.
    #[arg(long)]
    derived: bool,
    #[command(flatten)]
    read: ReadArgs,
}

#[derive(Serialize)]
struct Line {
    path: String,
    ok: bool,
    errors: Vec<photosolid::error::ErrorRecord>,
    warnings: Vec<photosolid::error::WarningRecord>,
    #[serde(skip_serializing_if = "Option::is_none")]
    info: Option<InfoReport>,
}

pub fn run(a: ValidateArgs) -> anyhow::Result<i32> {
    let walked = photosolid::formats::collect(&a.paths)?;
    let notes = walked.summary();
    let files = walked.files;
    if files.is_empty() {
        // Nothing to check is a failure, not "0 files, 0 ok".
        return Ok(super::nothing_found(&a.paths, &notes, ""));
    }
    let opts = a.read.options();
    let tables = if a.derived { Tables::Compute } else { Tables::Skip };
    let bar = (std::io::stderr().is_terminal() && files.len() > 20).then(|| {
        let b = super::progress_bar("files");
        b.set_length(files.len() as u64);
        b
    });
    let results: Vec<Line> = files
        .par_iter()
        .map(|f| {
            let r = photosolid::formats::load_document_with(f, &opts);
            if let Some(b) = &bar {
                b.inc(1);
            }
            Line::of(f, r, tables)
        })
        .collect();
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    let mut out = std::io::BufWriter::new(std::io::stdout().lock());
    let failed = results.iter().filter(|r| !r.ok).count();
    for r in &results {
        if a.json {
            serde_json::to_writer(&mut out, r)?;
            writeln!(out)?;
        } else {
            r.write_text(&mut out)?;
        }
    }
    if !a.json {
        writeln!(
            out,
            "{}, {} ok, {} failed",
            photosolid::error::count(results.len(), "file", "files"),
            results.len() - failed,
            failed
        )?;
        for n in &notes {
            writeln!(out, "{n}")?;
        }
    } else {
        // stdout stays one JSON object per line.
        for n in &notes {
            eprintln!("{n}");
        }
    }
    out.flush()?;
    Ok(if failed == 0 { 0 } else { 1 })
}

impl Line {
    /// The line of file `f` from what reading it gave.
    fn of(f: &Path, read: Result<Document, photosolid::Error>, tables: Tables) -> Line {
        match read {
            Ok(lum) => {
                let mut info = InfoReport::of_document_with(&lum, tables, &Default::default());
                info.path = f.display().to_string();
                Line {
                    path: f.display().to_string(),
                    ok: true,
                    errors: vec![],
                    warnings: info.warnings.iter().map(Into::into).collect(),
                    info: Some(info),
                }
            }
            Err(e) => Line {
                path: f.display().to_string(),
                ok: false,
                errors: vec![photosolid::error::ErrorRecord::from(&e)],
                warnings: vec![],
                info: None,
            },
        }
    }

    /// The text form: `ok PATH (N warnings)` and each warning, or `FAIL PATH` and each error.
    fn write_text(&self, out: &mut impl Write) -> std::io::Result<()> {
        if self.ok {
            writeln!(
                out,
                "ok   {} ({})",
                self.path,
                photosolid::error::count(self.warnings.len(), "warning", "warnings")
            )?;
            for w in &self.warnings {
                writeln!(out, "       {w}")?;
            }
        } else {
            writeln!(out, "FAIL {}", self.path)?;
            for e in &self.errors {
                writeln!(out, "       {}", e.message)?;
            }
        }
        Ok(())
    }
}
