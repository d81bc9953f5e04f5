//! Running the real `photosolid` binary in a test directory.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::OnceLock;

/// The binary under test.
pub fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_photosolid"))
}

/// Run `photosolid ARGS` in `dir`.
pub fn run(args: &[&str], dir: &Path) -> Output {
    bin().args(args).current_dir(dir).output().expect("run photosolid")
}

/// Stdout of a run that must have succeeded (panics with both streams otherwise).
pub fn ok(o: &Output) -> String {
    assert!(
        o.status.success(),
        "exit {:?}\nstdout:\n{}\nstderr:\n{}",
        o.status.code(),
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// An empty directory `NAME-PID` under `CARGO_TARGET_TMPDIR` for a shared
/// run: one per test process, so two test processes at once do not remove
/// each other's.
fn fresh_dir(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// One `photosolid demo` run, with the default output directory, shared by
/// the tests that only read what it wrote (a demo run takes about 25 s of a
/// test thread; three tests each ran their own). Runs once per test process
/// in a fresh directory under `CARGO_TARGET_TMPDIR`; returns (that
/// directory, the run's stdout). Its output is in `dir/out/demo`, where the
/// README says `demo` writes.
pub fn shared_demo() -> &'static (PathBuf, String) {
    static DEMO: OnceLock<(PathBuf, String)> = OnceLock::new();
    DEMO.get_or_init(|| {
        let dir = fresh_dir("shared-demo");
        let out = ok(&run(&["demo"], &dir));
        (dir, out)
    })
}

/// One `photosolid compare road.ldt --json --directions dense:3000 --report rep`
/// run on a synthetic roadway (10° x 5° grid, 9,000 cd peak, written by the
/// library, so its reference is the closed form), shared by the tests that
/// only read its JSON and report (about 25 s of a test thread each).
/// Returns (the directory holding `road.ldt` and `rep/`, the run's stdout).
pub fn shared_road_compare() -> &'static (PathBuf, String) {
    static RUN: OnceLock<(PathBuf, String)> = OnceLock::new();
    RUN.get_or_init(|| {
        use photosolid::synth::{GridSpec, Synth};
        let dir = fresh_dir("shared-compare");
        let road = Synth::Roadway
            .build(&GridSpec::uniform(10.0, 5.0).unwrap(), 9000.0)
            .unwrap();
        photosolid::save(&road.into(), &dir.join("road.ldt"), &Default::default()).unwrap();
        let out = ok(&run(
            &[
                "compare",
                "road.ldt",
                "--json",
                "--directions",
                "dense:3000",
                "--report",
                "rep",
            ],
            &dir,
        ));
        (dir, out)
    })
}

/// Stderr of a run that must have failed with exit code `code`.
pub fn fails(o: &Output, code: i32) -> String {
    assert_eq!(
        o.status.code(),
        Some(code),
        "stdout:\n{}\nstderr:\n{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// A one-plane Type C IES file (1 lamp, `lumens` lm, metres) with these
/// gamma angles and intensities (cd), written to `dir/name`.
pub fn write_ies(dir: &Path, name: &str, lumens: f64, gamma: &[f64], cd: &[f64]) {
    let list = |v: &[f64]| v.iter().map(|x| x.to_string()).collect::<Vec<_>>().join(" ");
    let text = format!(
        "IESNA:LM-63-2002\n[TEST] photosolid test file\nTILT=NONE\n1 {lumens} 1 {} 1 1 2 0 0 0\n1 1 0\n{}\n0\n{}\n",
        gamma.len(),
        list(gamma),
        list(cd)
    );
    std::fs::write(dir.join(name), text).unwrap();
}

/// The `code` of every warning of a command's JSON (`{line, code, message}`, docs/warnings.md).
pub fn warning_codes(v: &serde_json::Value) -> Vec<String> {
    v["warnings"]
        .as_array()
        .unwrap()
        .iter()
        .map(|w| w["code"].as_str().unwrap().to_string())
        .collect()
}
