//! Helpers shared by the integration tests: the corpus (and the record of
//! each check skipped without it), `assert_close!`, the generated reader
//! fixtures (`fixtures`), the CLI runner (`cli`) and golden snapshots.
#![allow(dead_code)]

use std::path::{Path, PathBuf};

pub mod cli;
pub mod fixtures;
#[cfg(feature = "gpu")]
pub mod gpu;

/// `assert_close!(a, b, abs = TOL)` or `assert_close!(a, b, rel = TOL)`, then
/// an optional `format!`-style context: fails unless `|a - b| <= TOL`
/// (absolute) or `|a - b| <= TOL * |b|` (relative to the second value, the
/// reference). NaN never passes. The message prints both expressions and
/// values, the difference, the tolerance and the context. Values are
/// taken by value or by reference and converted with `as f64` (so f32
/// and integers work). Bring it in with
/// `#[macro_use] mod common;`.
#[allow(unused_macros)]
macro_rules! assert_close {
    (@context) => {
        String::new()
    };
    (@context $($context:tt)+) => {
        format!(": {}", format_args!($($context)+))
    };
    ($a:expr, $b:expr, abs = $tol:expr $(, $($context:tt)+)?) => {{
        // `.clone()` takes `f64` and `&f64` alike (method calls auto-dereference).
        #[allow(clippy::clone_on_copy, clippy::unnecessary_cast)]
        let (a, b, tol) = (($a).clone() as f64, ($b).clone() as f64, ($tol).clone() as f64);
        let diff = (a - b).abs();
        // A NaN difference compares false: it never passes.
        let within = diff <= tol;
        if !within {
            panic!(
                "assert_close failed: {} = {a:?}, {} = {b:?}, |difference| = {diff:?} > absolute tolerance {tol:?}{}",
                stringify!($a),
                stringify!($b),
                assert_close!(@context $($($context)+)?)
            );
        }
    }};
    ($a:expr, $b:expr, rel = $tol:expr $(, $($context:tt)+)?) => {{
        // `.clone()` takes `f64` and `&f64` alike (method calls auto-dereference).
        #[allow(clippy::clone_on_copy, clippy::unnecessary_cast)]
        let (a, b, tol) = (($a).clone() as f64, ($b).clone() as f64, ($tol).clone() as f64);
        let (diff, allowed) = ((a - b).abs(), tol * b.abs());
        let within = diff <= allowed;
        if !within {
            panic!(
                "assert_close failed: {} = {a:?}, {} = {b:?}, |difference| = {diff:?} > relative tolerance {tol:?} of |{}| = {allowed:?}{}",
                stringify!($a),
                stringify!($b),
                stringify!($b),
                assert_close!(@context $($($context)+)?)
            );
        }
    }};
}

/// A small deterministic PRNG (xorshift64*): damaged inputs and random
/// cases that reproduce from the seed.
pub struct Rng(pub u64);

impl Rng {
    /// The next 64 random bits.
    pub fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }
}

/// Where the third-party corpus is looked for: `$PHOTOSOLID_CORPUS` when set
/// (scripts/test-all.sh and tests point it at a missing folder to check the
/// skip count), else `../shared/corpus` next to the checkout.
pub fn corpus_root() -> PathBuf {
    match std::env::var_os("PHOTOSOLID_CORPUS") {
        Some(p) if !p.is_empty() => PathBuf::from(p),
        _ => Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/corpus"),
    }
}

/// Folder that collects one file per skipped corpus check:
/// `$PHOTOSOLID_SKIPPED_CORPUS_DIR` when set (scripts/test-all.sh sets it and
/// counts the files), else `target/skipped-corpus-checks`.
pub fn skipped_corpus_dir() -> PathBuf {
    match std::env::var_os("PHOTOSOLID_SKIPPED_CORPUS_DIR") {
        Some(p) if !p.is_empty() => PathBuf::from(p),
        _ => Path::new(env!("CARGO_MANIFEST_DIR")).join("target/skipped-corpus-checks"),
    }
}

/// The third-party corpus, when present. When it is missing, the calling
/// test is recorded as a skipped corpus check (see [`record_corpus_skip`]),
/// so the test command can print how many checks did not run.
#[track_caller]
pub fn corpus() -> Option<PathBuf> {
    let caller = std::panic::Location::caller();
    corpus_at(&corpus_root(), &skipped_corpus_dir(), caller.file())
}

/// [`corpus`] with explicit folders: `root` if it is a directory, else
/// `None` after recording the skip of the current test in `skipped_dir`.
/// `caller_file` (`tests/it/ies.rs`) names the test file.
pub fn corpus_at(root: &Path, skipped_dir: &Path, caller_file: &str) -> Option<PathBuf> {
    if root.is_dir() {
        return Some(root.to_path_buf());
    }
    let check = record_corpus_skip(skipped_dir, caller_file);
    eprintln!("notice: {} not found; corpus check {check} skipped", root.display());
    None
}

/// Record one skipped corpus check: the file `skipped_dir/<binary>__<test>`
/// holding the line `<binary>::<test>`. One file per test keeps parallel test
/// threads (and processes) from interleaving writes, and a test that asks for
/// the corpus twice is counted once. Returns `<binary>::<test>`.
pub fn record_corpus_skip(skipped_dir: &Path, caller_file: &str) -> String {
    let binary = Path::new(caller_file)
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "unknown".into());
    // libtest runs each test on a thread named after it.
    let test = std::thread::current()
        .name()
        .filter(|n| *n != "main")
        .unwrap_or("unnamed-test")
        .to_string();
    // In the one-binary layout (tests/it/main.rs) libtest names the thread
    // `<module>::<test>` already, the module being the test file's stem.
    let check = if test.starts_with(&format!("{binary}::")) {
        test
    } else {
        format!("{binary}::{test}")
    };
    let file: String = check
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '_' || c == '-' {
                c
            } else {
                '_'
            }
        })
        .collect();
    std::fs::create_dir_all(skipped_dir)
        .and_then(|_| std::fs::write(skipped_dir.join(file), format!("{check}\n")))
        .unwrap_or_else(|e| {
            panic!(
                "cannot record the skipped corpus check in {}: {e}",
                skipped_dir.display()
            )
        });
    check
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

/// The UGR reference tables (`../shared/ugr-reference`: 11 real luminaires
/// with the catalogue tables DIALux and Relux export for them), when present;
/// `$PHOTOSOLID_UGR_REFERENCE` overrides the folder. A missing folder is
/// recorded as a skipped corpus check, like [`corpus`].
#[track_caller]
pub fn ugr_reference() -> Option<PathBuf> {
    let root = match std::env::var_os("PHOTOSOLID_UGR_REFERENCE") {
        Some(p) if !p.is_empty() => PathBuf::from(p),
        _ => Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/ugr-reference"),
    };
    let caller = std::panic::Location::caller();
    corpus_at(&root, &skipped_corpus_dir(), caller.file())
}
