//! `photosolid batch PATH... -o OUT.parquet [--jsonl OUT.jsonl] [--report DIR] [--resume]`.
//!
//! One row per .ies/.ldt file under the paths (recursive): the columns of
//! `photosolid::batch::BatchRecord` (docs/batch.md). Files run in parallel;
//! a file that does not load is a row with `ok = false`, not a failure
//! (exit 0). The outputs are rewritten atomically after every chunk of files
//! (at least 512, and a quarter of the rows so far, so rewriting stays a
//! small share of the run), so an interrupted run leaves a complete table of
//! the files done; `--resume` reads it back (OUT.parquet, else OUT.jsonl)
//! and analyses only the files whose path is not in it. Resumed rows keep
//! their place; new rows follow in input order.

use std::collections::HashSet;
use std::path::PathBuf;

use clap::Args;
use photosolid::batch::{self, catalogue, table, BatchOptions, BatchRecord};

#[derive(Args, Debug)]
pub struct BatchArgs {
    /// Files and directories (searched recursively for .ies/.ldt, any case).
    #[arg(required = true)]
    paths: Vec<PathBuf>,
    /// The table, Parquet (schema in docs/batch.md).
    #[arg(short = 'o', long = "output", value_name = "OUT.parquet")]
    output: PathBuf,
    /// The same rows as JSON Lines, one object per file.
    #[arg(long, value_name = "OUT.jsonl")]
    jsonl: Option<PathBuf>,
    /// Write a catalogue page (DIR/index.html): sortable table, polar thumbnails, outliers first.
    #[arg(long, value_name = "DIR")]
    report: Option<PathBuf>,
    /// Skip files whose path is already in the output (OUT.parquet, else OUT.jsonl), keeping their rows.
    #[arg(long)]
    resume: bool,
}

/// Rows of an earlier run, for `--resume`.
fn previous(a: &BatchArgs) -> anyhow::Result<Vec<BatchRecord>> {
    if !a.resume {
        return Ok(Vec::new());
    }
    if a.output.is_file() {
        return Ok(table::read_parquet(&a.output)?);
    }
    if let Some(j) = a.jsonl.as_ref().filter(|j| j.is_file()) {
        let bytes = std::fs::read(j).map_err(|e| photosolid::Error::io(j, e))?;
        return Ok(batch::from_jsonl(&String::from_utf8_lossy(&bytes), j)?);
    }
    Ok(Vec::new())
}

/// Write the table (and the JSON Lines) atomically.
fn write_outputs(a: &BatchArgs, rows: &[BatchRecord]) -> anyhow::Result<()> {
    table::write_parquet(&a.output, rows)?;
    if let Some(j) = &a.jsonl {
        photosolid::formats::files::write_atomic(j, batch::to_jsonl(rows).as_bytes())?;
    }
    Ok(())
}

pub fn run(a: BatchArgs) -> anyhow::Result<i32> {
    let files = batch::collect(&a.paths)?;
    let mut rows = previous(&a)?;
    let resumed = rows.len();
    let seen: HashSet<String> = rows.iter().map(|r| r.path.clone()).collect();
    let todo: Vec<PathBuf> = files
        .into_iter()
        .filter(|f| !seen.contains(&f.display().to_string()))
        .collect();
    let options = BatchOptions::default();
    let bar = super::progress_bar("files");
    bar.set_length(todo.len() as u64);
    // At least one pass, so that an empty or fully resumed run still writes its outputs.
    let mut start = 0;
    loop {
        let end = (start + 512.max(rows.len() / 4)).min(todo.len());
        let base = start as u64;
        let new = batch::run(&todo[start..end], &options, &|done, _, path| {
            bar.set_position(base + done as u64);
            bar.set_message(path.to_string());
        });
        rows.extend(new);
        write_outputs(&a, &rows)?;
        start = end;
        if start >= todo.len() {
            break;
        }
    }
    bar.finish_and_clear();
    if let Some(dir) = &a.report {
        super::with_progress("thumbnails", |p| catalogue::write(dir, &rows, &options.read, p))?;
    }
    let ok = rows.iter().filter(|r| r.ok).count();
    let outliers = rows.iter().filter(|r| r.is_outlier()).count();
    outln!(
        "{} files ({} resumed, {} analysed): {} loaded, {} failed to load, {} outliers; table written to {}",
        rows.len(),
        resumed,
        todo.len(),
        ok,
        rows.len() - ok,
        outliers,
        a.output.display()
    );
    if let Some(j) = &a.jsonl {
        outln!("JSON Lines written to {}", j.display());
    }
    if let Some(dir) = &a.report {
        super::say_report_written(false, dir)?;
    }
    Ok(0)
}
