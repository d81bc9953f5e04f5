//! The job of `validate`: every photometric file under some paths loaded,
//! one line each, in input order.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

use rayon::prelude::*;
use serde::Serialize;

use crate::error::{ErrorRecord, Result, WarningRecord};
use crate::formats::{Document, ReadOptions};
use crate::model::Progress;
use crate::report::info::Tables;
use crate::report::InfoReport;

/// One file's line: `validate --json` prints one per line.
#[derive(Clone, Debug, Serialize)]
pub struct ValidateLine {
    /// The file (its path as walked; `FILE.gldf#ID` for a container's photometry).
    pub path: String,
    /// Whether it loaded.
    pub ok: bool,
    /// Why it did not (one record), empty when it loaded.
    pub errors: Vec<ErrorRecord>,
    /// The reader's warnings when it loaded.
    pub warnings: Vec<WarningRecord>,
    /// The `info --json` numbers when it loaded (the derived tables only with `derived`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub info: Option<InfoReport>,
}

/// What `validate` found: a line per file and the walk's notes (files read
/// by content, files passed over).
#[derive(Clone, Debug, Default)]
pub struct Validated {
    /// One line per file, in input order.
    pub lines: Vec<ValidateLine>,
    /// The walk's notes, one sentence each.
    pub notes: Vec<String>,
}

impl Validated {
    /// How many files failed.
    pub fn failed(&self) -> usize {
        self.lines.iter().filter(|l| !l.ok).count()
    }
}

/// `photosolid validate PATH...`: load every file under `paths` in parallel
/// with `read`; `derived` adds the UGR table, BUG rating and luminance table
/// (about 95 % of the time of validating a file). `progress` is told
/// `(done, total, "files")`.
pub fn validate(paths: &[PathBuf], derived: bool, read: &ReadOptions, progress: &Progress<'_>) -> Result<Validated> {
    let walked = crate::formats::collect(paths)?;
    let notes = walked.summary();
    let files = walked.files;
    let tables = if derived { Tables::Compute } else { Tables::Skip };
    let done = AtomicUsize::new(0);
    let lines = files
        .par_iter()
        .map(|f| {
            let line = ValidateLine::of(f, crate::formats::load_document_with(f, read), tables);
            progress(done.fetch_add(1, Ordering::Relaxed) + 1, files.len(), "files");
            line
        })
        .collect();
    Ok(Validated { lines, notes })
}

impl ValidateLine {
    /// The line of file `f` from what reading it gave.
    fn of(f: &Path, read: Result<Document>, tables: Tables) -> ValidateLine {
        match read {
            Ok(lum) => {
                let mut info = InfoReport::of_document_with(&lum, tables, &Default::default());
                info.path = f.display().to_string();
                ValidateLine {
                    path: f.display().to_string(),
                    ok: true,
                    errors: vec![],
                    warnings: info.warnings.iter().map(Into::into).collect(),
                    info: Some(info),
                }
            }
            Err(e) => ValidateLine {
                path: f.display().to_string(),
                ok: false,
                errors: vec![ErrorRecord::from(&e)],
                warnings: vec![],
                info: None,
            },
        }
    }
}
