//! Helpers shared by the integration tests: the corpus and golden snapshots.
#![allow(dead_code)]

use std::path::{Path, PathBuf};

pub mod cli;
#[cfg(feature = "gpu")]
pub mod gpu;

/// The third-party corpus next to the checkout, when present.
pub fn corpus() -> Option<PathBuf> {
    let p = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/corpus");
    if p.is_dir() {
        Some(p)
    } else {
        eprintln!("notice: ../shared/corpus not found; corpus checks skipped");
        None
    }
}

/// One row of the corpus MANIFEST.tsv.
#[derive(Debug, Clone)]
pub struct Entry {
    /// Path relative to the corpus root.
    pub rel: String,
    /// Absolute path.
    pub path: PathBuf,
    /// `ies`, `ldt`, `tilt-data`, ...
    pub format: String,
    /// The free-text notes column.
    pub notes: String,
}

impl Entry {
    /// Marked malformed on purpose by the manifest, or broken by design
    /// (a TILT=<file> naming a file that does not exist must be an error).
    pub fn malformed(&self) -> bool {
        self.notes.contains("MALFORMED") || self.notes.contains("does not exist")
    }
    /// A photometric file (not a tilt table).
    pub fn photometric(&self) -> bool {
        self.format == "ies" || self.format == "ldt"
    }
}

/// All manifest rows.
pub fn manifest(root: &Path) -> Vec<Entry> {
    let text = std::fs::read_to_string(root.join("MANIFEST.tsv")).expect("MANIFEST.tsv");
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split('\t').collect();
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let (ip, ifmt, inotes) = (col("local_path"), col("format"), col("notes"));
    lines
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            let f: Vec<&str> = l.split('\t').collect();
            Entry {
                rel: f[ip].to_string(),
                path: root.join(f[ip]),
                format: f[ifmt].to_string(),
                notes: f.get(inotes).unwrap_or(&"").to_string(),
            }
        })
        .collect()
}

/// Compare `actual` with the golden file `tests/snapshots/<name>`; with
/// `UPDATE_SNAPSHOTS=1` rewrite it instead. Fails with a line diff.
pub fn snapshot(name: &str, actual: &str) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/snapshots").join(name);
    if std::env::var_os("UPDATE_SNAPSHOTS").is_some() {
        std::fs::write(&path, actual).unwrap();
        return;
    }
    let expected = std::fs::read_to_string(&path).unwrap_or_default();
    if expected != actual {
        let mut diff = String::new();
        for (i, (e, a)) in expected.lines().zip(actual.lines()).enumerate() {
            if e != a {
                diff.push_str(&format!("line {}:\n  expected: {e}\n  actual:   {a}\n", i + 1));
            }
        }
        panic!(
            "snapshot {name} differs ({} vs {} lines); rerun with UPDATE_SNAPSHOTS=1 after checking.\n{diff}",
            expected.lines().count(),
            actual.lines().count()
        );
    }
}
