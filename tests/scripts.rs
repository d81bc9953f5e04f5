//! scripts/test-all.sh reports every test group that cannot run, one line
//! each with the reason, and fails with CI=true when a required one is missing.

use std::process::Command;

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
