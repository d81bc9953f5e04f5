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
    /// Files and directories (searched recursively for .ies/.ldt, TM-33 .xml and .gldf, any case, and files without such an extension by their first bytes). Exit 1 when nothing photometric is found.
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
    /// Also measure sh:{2,4,8,16}, lobes:{1,2,3,4} and c-mean against the hold-out and fill the
    /// `smallest_within_1pct` column (tens of ms a file; null without this flag).
    #[arg(long)]
    compact: bool,
    #[command(flatten)]
    read: super::ReadArgs,
}

/// A note when resumed rows were measured with another `--compact` choice
/// than this run's: the table then mixes measured and unmeasured
/// `smallest_within_1pct` columns, which a null alone would not say.
fn compact_mismatch(resumed: &[BatchRecord], compact: bool) -> Option<String> {
    let other = resumed
        .iter()
        .filter(|r| r.ok && r.errors.is_empty() && r.compact_ms.is_some() != compact)
        .count();
    (other > 0).then(|| {
        let rows = photosolid::error::count(other, "resumed row was", "resumed rows were");
        if compact {
            format!("note: {rows} measured without --compact: their smallest_within_1pct stays null (run without --resume to measure them)")
        } else {
            format!("note: {rows} measured with --compact: only they have smallest_within_1pct (add --compact to measure the new rows too)")
        }
    })
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

/// Refuse an `-o` whose extension names another format (`x.csv` would hold
/// Parquet bytes): `.parquet`, `.pq` or no extension.
fn check_table_name(out: &std::path::Path) -> anyhow::Result<()> {
    let ext = out.extension().map(|e| e.to_string_lossy().to_ascii_lowercase());
    match ext.as_deref() {
        None | Some("parquet" | "pq") => Ok(()),
        Some(e) => {
            let hint = match e {
                "jsonl" | "json" | "ndjson" => " (for JSON Lines add --jsonl OUT.jsonl next to -o OUT.parquet)",
                "csv" | "tsv" | "txt" | "xlsx" => {
                    " (pandas, DuckDB, polars and Arrow read Parquet; --jsonl OUT.jsonl gives text rows)"
                }
                _ => "",
            };
            anyhow::bail!(
                "-o {}: batch writes its table as Parquet; name it OUT.parquet{hint}",
                out.display()
            )
        }
    }
}

pub fn run(a: BatchArgs) -> anyhow::Result<i32> {
    check_table_name(&a.output)?;
    super::check_output("-o", &a.output)?;
    if let Some(j) = &a.jsonl {
        super::check_output("--jsonl", j)?;
    }
    if let Some(dir) = &a.report {
        super::check_report_dir("--report", dir)?;
    }
    let walked = photosolid::formats::collect(&a.paths)?;
    let mut notes = walked.summary();
    let files = walked.files;
    if files.is_empty() {
        // An empty table would look like a successful run.
        return Ok(super::nothing_found(&a.paths, &notes, "; no table written"));
    }
    let mut rows = previous(&a)?;
    let resumed = rows.len();
    notes.extend(compact_mismatch(&rows, a.compact));
    let seen: HashSet<String> = rows.iter().map(|r| r.path.clone()).collect();
    let todo: Vec<PathBuf> = files
        .into_iter()
        .filter(|f| !seen.contains(&f.display().to_string()))
        .collect();
    let options = BatchOptions {
        compact: a.compact,
        read: a.read.options(),
        ..Default::default()
    };
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
        "{} ({} resumed, {} analysed): {} loaded, {} failed to load, {}; table written to {}",
        photosolid::error::count(rows.len(), "file", "files"),
        resumed,
        todo.len(),
        ok,
        rows.len() - ok,
        photosolid::error::count(outliers, "outlier", "outliers"),
        a.output.display()
    );
    for n in &notes {
        outln!("{n}");
    }
    if let Some(j) = &a.jsonl {
        outln!("JSON Lines written to {}", j.display());
    }
    if let Some(dir) = &a.report {
        super::say_report_written(false, dir)?;
    }
    Ok(0)
}
