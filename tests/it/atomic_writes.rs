//! Every file the CLI writes goes through the one atomic writer: a directory
//! the process cannot write into and a full device (`/dev/full`) give a
//! clear error naming the path, a non-zero exit and no partial file; a
//! successful write leaves no temporary file behind.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn run(args: &[&str], dir: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_photosolid"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("run photosolid")
}

fn data(name: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("data")
        .join(name)
        .display()
        .to_string()
}

/// A directory this process cannot create files in. A mode-0555 directory
/// does that for a normal user; root ignores modes, so for root it is
/// `/proc`, where nobody can create files.
fn unwritable_dir(tmp: &Path) -> PathBuf {
    let ro = tmp.join("ro");
    std::fs::create_dir(&ro).unwrap();
    use std::os::unix::fs::PermissionsExt;
    std::fs::set_permissions(&ro, std::fs::Permissions::from_mode(0o555)).unwrap();
    if std::fs::write(ro.join("probe"), b"x").is_ok() {
        PathBuf::from("/proc")
    } else {
        ro
    }
}

/// The CLI commands that write a file, with `OUT` standing for the output path.
fn writers(name: &str) -> Vec<Vec<String>> {
    let ies = data("batwing.ies");
    let ldt = data("cosine_p5.ldt");
    let cmd = |v: &[&str]| -> Vec<String> { v.iter().map(|s| s.replace("OUT", name)).collect() };
    let texture = [
        "texture",
        &ldt,
        "--filter",
        "bilinear",
        "--factor",
        "1",
        "--backend",
        "cpu",
    ];
    vec![
        cmd(&["convert", &ies, "OUT.ldt"]),
        cmd(&["convert", &ldt, "OUT.ies"]),
        cmd(&["synth", "batwing", "-o", "OUT.ldt"]),
        cmd(&["mesh", &ldt, "--filter", "bilinear", "--factor", "1", "-o", "OUT.ply"]),
        cmd(&["mesh", &ldt, "--measured", "-o", "OUT.glb"]),
        cmd(&[texture.as_slice(), &["-o", "OUT.exr"]].concat()),
        cmd(&[texture.as_slice(), &["--png", "OUT.png"]].concat()),
    ]
}

fn expect_failure(out: &Output, path: &str, what: &[String]) {
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "{what:?} succeeded");
    assert_ne!(out.status.code(), Some(101), "{what:?} panicked: {err}");
    assert!(err.contains(path), "{what:?}: the error names {path}: {err}");
}

#[test]
fn unwritable_directory_gives_a_clear_error_and_no_file() {
    let t = tempfile::tempdir().unwrap();
    let ro = unwritable_dir(t.path());
    let base = ro.join("out").display().to_string();
    for args in writers(&base) {
        let argv: Vec<&str> = args.iter().map(|s| s.as_str()).collect();
        let out = run(&argv, t.path());
        expect_failure(&out, &base, &args);
    }
    if ro != Path::new("/proc") {
        assert_eq!(
            std::fs::read_dir(&ro).unwrap().count(),
            0,
            "nothing left in {}",
            ro.display()
        );
    }
}

#[test]
fn full_device_gives_a_clear_error() {
    let t = tempfile::tempdir().unwrap();
    // `/dev/full` accepts the open and fails every write with ENOSPC, as a full disk does.
    // A link with the extension the commands need points at it.
    for ext in ["ldt", "ies", "ply", "glb", "exr", "png"] {
        std::os::unix::fs::symlink("/dev/full", t.path().join(format!("full.{ext}"))).unwrap();
    }
    let base = t.path().join("full").display().to_string();
    for args in writers(&base) {
        let argv: Vec<&str> = args.iter().map(|s| s.as_str()).collect();
        let out = run(&argv, t.path());
        expect_failure(&out, &base, &args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains("No space left"), "{args:?}: {err}");
    }
    // The device is still a device: nothing was renamed over it.
    use std::os::unix::fs::FileTypeExt;
    assert!(std::fs::metadata("/dev/full").unwrap().file_type().is_char_device());
}

#[test]
fn successful_writes_leave_only_the_target() {
    let t = tempfile::tempdir().unwrap();
    let base = t.path().join("ok").display().to_string();
    for args in writers(&base) {
        let argv: Vec<&str> = args.iter().map(|s| s.as_str()).collect();
        let out = run(&argv, t.path());
        assert!(
            out.status.success(),
            "{args:?}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
    let mut names: Vec<String> = std::fs::read_dir(t.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(names, ["ok.exr", "ok.glb", "ok.ies", "ok.ldt", "ok.ply", "ok.png"]);
}
