//! `photosolid validate PATH... [--json] [--derived]`: load every .ies/.ldt/TM-33 .xml file and every photometry of each .gldf container (any case) under the paths.
//!
//! Files are loaded in parallel (rayon) and reported in input order (paths
//! as given, directories walked in sorted order). Exit status 0 when every
//! file loaded, 1 otherwise. A progress bar goes to stderr when it is a
//! terminal and there are many files.

use std::io::{IsTerminal, Write};
use std::path::PathBuf;

use clap::Args;
use photosolid::jobs::{self, ValidateLine};

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

pub fn run(a: ValidateArgs) -> anyhow::Result<i32> {
    // A bar for many files only; it draws from its first update.
    let bar = std::io::stderr().is_terminal().then(|| super::progress_bar("files"));
    let show = |done: usize, total: usize, _: &str| {
        if let Some(b) = bar.as_ref().filter(|_| total > 20) {
            b.set_length(total as u64);
            b.set_position(done as u64);
        }
    };
    let validated = jobs::validate(&a.paths, a.derived, &a.read.options(), &show)?;
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    if validated.lines.is_empty() {
        // Nothing to check is a failure, not "0 files, 0 ok".
        return Ok(super::nothing_found(&a.paths, &validated.notes, ""));
    }
    let mut out = std::io::BufWriter::new(std::io::stdout().lock());
    let failed = validated.failed();
    let lines = &validated.lines;
    for r in lines {
        if a.json {
            serde_json::to_writer(&mut out, r)?;
            writeln!(out)?;
        } else {
            write_text(r, &mut out)?;
        }
    }
    if !a.json {
        writeln!(
            out,
            "{}, {} ok, {} failed",
            photosolid::error::count(lines.len(), "file", "files"),
            lines.len() - failed,
            failed
        )?;
        for n in &validated.notes {
            writeln!(out, "{n}")?;
        }
    } else {
        // stdout stays one JSON object per line.
        for n in &validated.notes {
            eprintln!("{n}");
        }
    }
    out.flush()?;
    Ok(if failed == 0 { 0 } else { 1 })
}

/// The text form: `ok PATH (N warnings)` and each warning, or `FAIL PATH` and each error.
fn write_text(line: &ValidateLine, out: &mut impl Write) -> std::io::Result<()> {
    if line.ok {
        writeln!(
            out,
            "ok   {} ({})",
            line.path,
            photosolid::error::count(line.warnings.len(), "warning", "warnings")
        )?;
        for w in &line.warnings {
            writeln!(out, "       {w}")?;
        }
    } else {
        writeln!(out, "FAIL {}", line.path)?;
        for e in &line.errors {
            writeln!(out, "       {}", e.message)?;
        }
    }
    Ok(())
}
