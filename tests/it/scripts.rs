//! scripts/test-all.sh reports every test group that cannot run, one line
//! each with the reason, and fails with CI=true when a required one is missing.

use std::process::Command;

use crate::common;

fn probe(ci: bool) -> (Option<i32>, String) {
    let mut c = Command::new("bash");
    c.arg(concat!(env!("CARGO_MANIFEST_DIR"), "/scripts/test-all.sh"))
        .arg("--probe")
        .env("PHOTOSOLID_BIN", env!("CARGO_BIN_EXE_photosolid"))
        .env_remove("CI");
    if ci {
        c.env("CI", "true");
    }
    let o = c.output().expect("run bash");
    (o.status.code(), String::from_utf8_lossy(&o.stdout).into_owned())
}

#[test]
fn probe_reports_each_group_and_ci_requires_gpu_chromium_notebooks() {
    let (code, out) = probe(false);
    assert_eq!(code, Some(0), "{out}");
    // Every group on one line: ok, or SKIP with a reason after the colon.
    for group in [
        "corpus",
        "HTML report rendering",
        "WGPU_BACKEND=vulkan",
        "WGPU_BACKEND=gl",
        "notebooks",
    ] {
        let lines: Vec<&str> = out
            .lines()
            .filter(|l| l.contains(group) && (l.starts_with("ok ") || l.starts_with("SKIP ")))
            .collect();
        assert!(!lines.is_empty(), "{group} not reported:\n{out}");
        for l in lines.iter().filter(|l| l.starts_with("SKIP ")) {
            let reason = l.split_once(": ").map(|(_, r)| r.trim()).unwrap_or("");
            assert!(!reason.is_empty(), "no reason: {l}");
        }
    }
    let skipped: Vec<&str> = out.lines().filter(|l| l.starts_with("SKIP ")).collect();
    let summary = format!("== skipped test groups: {}", skipped.len() / 2);
    assert!(out.contains(&summary), "{summary} missing:\n{out}");
    // With CI=true the same missing groups, except the corpus, are failures.
    let required: Vec<&&str> = skipped.iter().filter(|l| !l.starts_with("SKIP corpus")).collect();
    let (code, ci_out) = probe(true);
    if required.is_empty() {
        assert_eq!(code, Some(0), "{ci_out}");
    } else {
        assert_eq!(code, Some(1), "{ci_out}");
        assert!(
            ci_out
                .lines()
                .any(|l| l.starts_with("FAIL ") && l.contains("required with CI=true")),
            "{ci_out}"
        );
    }
}

/// A test that finds no corpus leaves one file named after itself (also when
/// many test threads skip at once, and once however often it asks), and
/// scripts/corpus-skips.sh counts the checks and the test binaries for the
/// test command's "SKIP corpus tests" line.
#[test]
fn skipped_corpus_checks_are_counted_per_test() {
    let t = tempfile::tempdir().unwrap();
    let (missing, skipped) = (t.path().join("no-corpus"), t.path().join("skipped"));
    // A present corpus is returned and records nothing.
    assert_eq!(
        common::corpus_at(t.path(), &skipped, "tests/x.rs").as_deref(),
        Some(t.path())
    );
    assert!(!skipped.exists());
    // This test itself: the file holds "<binary>::<test name>".
    assert!(common::corpus_at(&missing, &skipped, "tests/scripts.rs").is_none());
    let own = std::fs::read_to_string(skipped.join("scripts__skipped_corpus_checks_are_counted_per_test")).unwrap();
    assert_eq!(own, "scripts::skipped_corpus_checks_are_counted_per_test\n");
    // 12 threads named like tests of two binaries, each asking three times, all at once.
    let threads: Vec<_> = (0..12)
        .map(|i| {
            let (missing, skipped) = (missing.clone(), skipped.clone());
            std::thread::Builder::new()
                .name(format!("module::case_{i}"))
                .spawn(move || {
                    let file = if i < 8 { "tests/ies.rs" } else { "tests/ldt.rs" };
                    for _ in 0..3 {
                        assert!(common::corpus_at(&missing, &skipped, file).is_none());
                    }
                })
                .unwrap()
        })
        .collect();
    for th in threads {
        th.join().unwrap();
    }
    let o = Command::new("bash")
        .arg(concat!(env!("CARGO_MANIFEST_DIR"), "/scripts/corpus-skips.sh"))
        .arg(&skipped)
        .arg(&missing)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(
        String::from_utf8_lossy(&o.stdout),
        format!("13 checks in 3 test files skipped: {} not found\n", missing.display())
    );
    // No skips: no line.
    let none = Command::new("bash")
        .arg(concat!(env!("CARGO_MANIFEST_DIR"), "/scripts/corpus-skips.sh"))
        .arg(t.path().join("empty"))
        .arg(&missing)
        .output()
        .unwrap();
    assert!(none.status.success() && none.stdout.is_empty());
}

/// The panic message of `f`, which must panic.
fn panic_message(f: impl FnOnce() + std::panic::UnwindSafe) -> String {
    let e = std::panic::catch_unwind(f).expect_err("must fail");
    e.downcast_ref::<String>().cloned().unwrap_or_default()
}

#[test]
fn assert_close_passes_within_and_fails_outside_its_tolerance() {
    assert_close!(1.0, 1.0 + 1e-10, abs = 1e-9);
    assert_close!(100.0, 100.5, rel = 0.005, "exactly at the bound");
    assert_close!(&2.0f32, 2.0, abs = 0.0);
    let m = panic_message(|| assert_close!(1.0, 1.1, abs = 0.05, "case {}", 7));
    for part in [
        "1.0 = 1.0",
        "1.1 = 1.1",
        "|difference| = 0.1",
        "absolute tolerance 0.05",
        ": case 7",
    ] {
        assert!(m.contains(part), "{part:?} not in {m}");
    }
    // Relative to the second (reference) value: 0.5 % of 200 is 1.
    assert_close!(201.0, 200.0, rel = 0.005);
    let m = panic_message(|| assert_close!(202.0, 200.0, rel = 0.005));
    assert!(m.contains("relative tolerance 0.005 of |200.0| = 1.0"), "{m}");
    // NaN never passes, whatever the tolerance.
    panic_message(|| assert_close!(f64::NAN, 1.0, abs = f64::INFINITY));
    panic_message(|| assert_close!(f64::NAN, f64::NAN, rel = 1.0));
}

/// Runs scripts/check_layers.py on the tree at `root`: (exit code, stdout).
fn check_layers(root: &std::path::Path) -> (Option<i32>, String) {
    let o = Command::new("python3")
        .arg(concat!(env!("CARGO_MANIFEST_DIR"), "/scripts/check_layers.py"))
        .arg("--root")
        .arg(root)
        .output()
        .expect("python3 (the layer check of scripts/test-all.sh needs it) is not on PATH");
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
    (o.status.code(), text)
}

fn copy_tree(from: &std::path::Path, to: &std::path::Path) {
    std::fs::create_dir_all(to).unwrap();
    for e in std::fs::read_dir(from).unwrap() {
        let e = e.unwrap();
        if e.file_type().unwrap().is_dir() {
            copy_tree(&e.path(), &to.join(e.file_name()));
        } else {
            std::fs::copy(e.path(), to.join(e.file_name())).unwrap();
        }
    }
}

/// The layer check (ARCHITECTURE.md, "Layers") passes on the crate and fails,
/// naming file, line and edge, on upward paths planted in a copy of it: a
/// `use` line, a grouped import, an inline path, a root re-export and a
/// `super::` chain that climbs out of its module; test code stays exempt.
#[test]
fn layer_check_passes_here_and_catches_planted_upward_paths() {
    let here = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let (code, out) = check_layers(here);
    assert_eq!(code, Some(0), "{out}");
    assert!(out.contains("layers only point down"), "{out}");

    let t = tempfile::tempdir().unwrap();
    std::fs::copy(here.join("ARCHITECTURE.md"), t.path().join("ARCHITECTURE.md")).unwrap();
    copy_tree(&here.join("src"), &t.path().join("src"));
    copy_tree(&here.join("crates"), &t.path().join("crates"));
    // The layers live in the layer crates that hold several modules, the rest in the root package's src/.
    let file_of = |file: &str| {
        // the module's own directory: a layer crate's src/, else the root package's
        let module = std::path::Path::new(file).iter().next().unwrap();
        [
            "crates/photosolid-core/src",
            "crates/photosolid-fields/src",
            "crates/photosolid-analysis/src",
        ]
        .iter()
        .map(|c| std::path::Path::new(c).join(file))
        .find(|p| {
            let top = t.path().join(p.parent().unwrap()).join(module);
            t.path().join(p).exists() || top.exists() || top.with_extension("rs").exists()
        })
        .unwrap_or_else(|| std::path::Path::new("src").join(file))
    };
    let plant = |file: &str, text: &str| -> usize {
        let p = t.path().join(file_of(file));
        let mut s = std::fs::read_to_string(&p).unwrap();
        let line = s.lines().count() + 1;
        s.push_str(text);
        std::fs::write(&p, s).unwrap();
        line
    };
    let (code, out) = check_layers(t.path());
    assert_eq!(code, Some(0), "an unchanged copy passes:\n{out}");
    // Exempt: test code (inline, and a file a `#[cfg(test)]` module names), comments, strings.
    plant(
        "model/mod.rs",
        "#[cfg(test)]\nmod planted_tests {\n    use crate::report::significant;\n}\n\
         #[cfg(test)]\n#[path = \"planted_t.rs\"]\nmod planted_t;\n\
         // crate::cli::x in a comment\nconst _S: &str = \"crate::report::x\";\n",
    );
    std::fs::write(
        t.path()
            .join(file_of("model/mod.rs").parent().unwrap().join("planted_t.rs")),
        "use crate::report::significant;\n",
    )
    .unwrap();
    let (code, out) = check_layers(t.path());
    assert_eq!(code, Some(0), "test code, comments and strings are exempt:\n{out}");
    let use_line = plant("model/mod.rs", "use crate::report::significant;\n");
    let group_line = plant(
        "photometry/flux.rs",
        "use crate::{error::Error, compare::Progress as P};\n",
    );
    let inline_line = plant(
        "formats/angles.rs",
        "fn planted() -> String { crate::report::significant(1.0, 2) }\n",
    );
    let root_line = plant("error.rs", "type Planted = crate::Luminaire;\n");
    let allowed_line = plant("synth.rs", "type Planted = crate::Error;\n");
    let super_line = plant("reconstruct/filter.rs", "use super::super::solid::Mesh;\n");
    let (code, out) = check_layers(t.path());
    assert_eq!(code, Some(1), "{out}");
    let at = |file: &str| file_of(file).display().to_string();
    for want in [
        format!(
            "{}:{use_line}: model -> report (crate::report::significant)",
            at("model/mod.rs")
        ),
        format!("{}:{group_line}: photometry -> compare", at("photometry/flux.rs")),
        format!(
            "{}:{inline_line}: formats -> report (crate::report::significant)",
            at("formats/angles.rs")
        ),
        format!(
            "{}:{super_line}: reconstruct -> solid (super::super::solid::Mesh)",
            at("reconstruct/filter.rs")
        ),
        // The root's re-export counts as the module it re-exports.
        format!("{}:{root_line}: error -> model (crate::Luminaire)", at("error.rs")),
    ] {
        assert!(out.contains(&want), "{want} not in:\n{out}");
    }
    // `crate::Error` is the root's re-export of error, the lowest layer: allowed.
    assert!(!out.contains(&format!("{}:{allowed_line}", at("synth.rs"))), "{out}");
    assert!(out.contains("5 path(s) point up the layer order"), "{out}");
}

/// Runs scripts/check_fn_length.py on the tree at `root`: (exit code, stdout).
fn check_fn_length(root: &std::path::Path) -> (Option<i32>, String) {
    let o = Command::new("python3")
        .arg(concat!(env!("CARGO_MANIFEST_DIR"), "/scripts/check_fn_length.py"))
        .arg("--root")
        .arg(root)
        .output()
        .expect("python3 (the function-length check of scripts/test-all.sh needs it) is not on PATH");
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
    (o.status.code(), text)
}

/// A function of `body_lines` statements (its length is `body_lines + 2`).
fn function(name: &str, body_lines: usize) -> String {
    let body: String = (0..body_lines).map(|i| format!("    let _x{i} = \"}}\";\n")).collect();
    format!("fn {name}() {{\n{body}}}\n")
}

/// The function-length check (issue 28 item 4) passes on the crate with its
/// allow list, and on a planted tree fails on a new function over 80 lines,
/// on a listed one that grew, and on a listed one that is gone; test code
/// and a function of exactly 80 lines pass. Braces inside strings do not count.
#[test]
fn function_length_check_passes_here_and_catches_long_functions() {
    let here = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let (code, out) = check_fn_length(here);
    assert_eq!(code, Some(0), "{out}");

    let t = tempfile::tempdir().unwrap();
    std::fs::create_dir_all(t.path().join("src")).unwrap();
    std::fs::create_dir_all(t.path().join("scripts")).unwrap();
    let write = |lib: &str, allowed: &str| {
        std::fs::write(t.path().join("src/lib.rs"), lib).unwrap();
        std::fs::write(t.path().join("scripts/fn_length_allowed.txt"), allowed).unwrap();
    };
    let tests_mod = format!("#[cfg(test)]\nmod tests {{\n{}}}\n", function("long_test", 200));
    write(&format!("{}{}", function("exactly_80", 78), tests_mod), "");
    let (code, out) = check_fn_length(t.path());
    assert_eq!(code, Some(0), "{out}");

    write(&function("too_long", 79), "");
    let (code, out) = check_fn_length(t.path());
    assert_eq!(code, Some(1), "{out}");
    assert!(out.contains("src/lib.rs::too_long: 81 lines"), "{out}");

    write(&function("listed", 100), "src/lib.rs::listed 90\n");
    let (code, out) = check_fn_length(t.path());
    assert_eq!(code, Some(1), "{out}");
    assert!(out.contains("grew past its recorded 90"), "{out}");

    write(&function("listed", 10), "# a comment\nsrc/lib.rs::listed 90\n");
    let (code, out) = check_fn_length(t.path());
    assert_eq!(code, Some(1), "{out}");
    assert!(out.contains("take it off"), "{out}");
}
