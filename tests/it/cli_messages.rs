//! The CLI's messages and numbers: percents relative to I_max, help and errors that say what
//! and where, units, precision, one vocabulary, report folders, coded warnings.

use crate::common;
use common::cli::{fails, ok, run, write_ies};

/// Issue 27, item 2: every flag relative to I_max is a percent with its sign.
/// A bare number is a usage error (exit 2) with the hint, before any file is
/// read; outputs echo the percent and JSON gives `_pct` keys beside the old ones.
#[test]
fn tolerances_relative_to_i_max_are_percents_with_their_sign() {
    let t = tempfile::tempdir().unwrap();
    for (args, hint) in [
        (
            vec![
                "mesh",
                "missing.ies",
                "--filter",
                "bilinear",
                "--tolerance",
                "0.1",
                "-o",
                "m.ply",
            ],
            "did you mean 0.1%?",
        ),
        (
            vec!["compare", "missing.ies", "--tolerance", "0.001"],
            "did you mean 0.001%?",
        ),
        (
            vec!["compare", "missing.ies", "--solid-tolerance", "0.0005"],
            "write 0.05%",
        ),
        (vec!["engines", "missing.ies", "--tolerance", "0.01"], "write 1%"),
        (vec!["plan", "missing.toml", "--tolerance", "5"], "did you mean 5%?"),
        (vec!["fit", "missing.ies", "--guard", "0.02"], "write 2%"),
        (vec!["fit", "missing.ies", "--tolerance", "0.01"], "or 1% if"),
        (vec!["gpu-check", "missing.ies", "--tolerance", "1e-5"], "write 0.001%"),
    ] {
        let e = fails(&run(&args, t.path()), 2);
        assert!(
            e.contains(hint) && e.contains("percent") && !e.contains("missing."),
            "{args:?}: {e}"
        );
    }
    ok(&run(&["synth", "cosine-power", "--p", "5", "-o", "c.ldt"], t.path()));
    let v: serde_json::Value = serde_json::from_str(&ok(&run(
        &[
            "mesh",
            "c.ldt",
            "--filter",
            "bilinear",
            "--tolerance",
            "0.5%",
            "-o",
            "m.ply",
            "--json",
        ],
        t.path(),
    )))
    .unwrap();
    assert_eq!(v["tolerance_pct"], 0.5, "{v}");
    let text = ok(&run(
        &[
            "mesh",
            "c.ldt",
            "--filter",
            "bilinear",
            "--tolerance",
            "0.5%",
            "-o",
            "m.ply",
        ],
        t.path(),
    ));
    assert!(text.contains("tolerance 0.5% of I_max = "), "{text}");
    let v: serde_json::Value = serde_json::from_str(&ok(&run(
        &[
            "compare",
            "c.ldt",
            "--recon",
            "bilinear",
            "--tolerance",
            "1%",
            "--solid-tolerance",
            "0.5%",
            "--json",
        ],
        t.path(),
    )))
    .unwrap();
    assert_eq!(
        (v["tolerance_pct"].as_f64(), v["tolerance"].as_f64()),
        (Some(1.0), Some(0.01)),
        "{v}"
    );
    assert_eq!(v["solid_tolerance_pct"], 0.5, "{v}");
    let text = ok(&run(
        &["compare", "c.ldt", "--recon", "bilinear", "--tolerance", "1%"],
        t.path(),
    ));
    assert!(text.contains("Hausdorff tolerance 1% of I_max"), "{text}");
    let v: serde_json::Value = serde_json::from_str(&ok(&run(
        &["fit", "c.ldt", "--max-lights", "1", "--guard", "3%", "--json"],
        t.path(),
    )))
    .unwrap();
    assert_eq!(
        (v["guard_pct"].as_f64(), v["guard"].as_f64()),
        (Some(3.0), Some(0.03)),
        "{v}"
    );
    // hausdorff's tolerance is a length, and its help says so.
    let help = ok(&run(&["hausdorff", "--help"], t.path()));
    assert!(help.contains("absolute length in the meshes' unit"), "{help}");
    let help = ok(&run(&["compare", "--help"], t.path()));
    assert!(
        help.contains("[default: 0.1%]") && help.contains("percent of I_max"),
        "{help}"
    );
    // The rule, and what each percent is of, is stated in the top-level help.
    let help = ok(&run(&["--help"], t.path()));
    assert!(
        help.contains("percents written with their sign")
            && help.contains("Relative to I_max")
            && help.contains("percentage points of the fit's error"),
        "{help}"
    );
}

/// Issue 27, item 3: help and error messages a new user met.
#[test]
fn help_and_errors_say_what_is_wrong_and_where() {
    let t = tempfile::tempdir().unwrap();
    // compare --help names no option that does not exist.
    let help = ok(&run(&["compare", "--help"], t.path()));
    assert!(!help.contains("lamp_flux_lm"), "{help}");
    // A negative factor is a real message, not clap's "use '-- -3'" tip.
    for args in [
        vec![
            "mesh",
            "missing.ies",
            "--filter",
            "bilinear",
            "--factor",
            "-3",
            "-o",
            "m.ply",
        ],
        vec!["compare", "missing.ies", "--factor", "-3"],
        vec!["texture", "missing.ies", "--factor", "-3", "-o", "t.exr"],
        vec!["engines", "missing.ies", "--factor", "-3"],
    ] {
        let e = fails(&run(&args, t.path()), 2);
        assert!(
            e.contains("must be a positive integer") && !e.contains("-- -3"),
            "{args:?}: {e}"
        );
    }
    // A truncated TM-33 document is reported where it ends, not at 1:1.
    ok(&run(&["synth", "cosine-power", "--p", "5", "-o", "c.ldt"], t.path()));
    ok(&run(&["convert", "c.ldt", "c.xml"], t.path()));
    let xml = std::fs::read_to_string(t.path().join("c.xml")).unwrap();
    let cut = &xml[..xml.len() / 2];
    std::fs::write(t.path().join("cut.xml"), cut).unwrap();
    let lines = cut.lines().count();
    let e = fails(&run(&["info", "cut.xml"], t.path()), 1);
    assert!(!e.contains("cut.xml:1:1:"), "{e}");
    assert!(e.contains(&format!("cut.xml:{lines}:")), "line {lines}: {e}");
    // Outputs are checked before the work: a missing folder fails at once, naming it.
    for args in [
        vec!["mesh", "c.ldt", "--filter", "bilinear", "-o", "nowhere/m.ply"],
        vec!["texture", "c.ldt", "-o", "nowhere/t.exr"],
        vec!["convert", "c.ldt", "nowhere/c.ies"],
        vec!["synth", "isotropic", "-o", "nowhere/s.ldt"],
        vec!["export", "c.ldt", "--engine", "pbrt", "-o", "nowhere/p.exr"],
        vec!["batch", "c.ldt", "-o", "nowhere/t.parquet"],
    ] {
        let e = fails(&run(&args, t.path()), 1);
        assert!(e.contains("the folder nowhere does not exist"), "{args:?}: {e}");
    }
    // batch -o x.csv would hold Parquet: refused, with the way out.
    let e = fails(&run(&["batch", "c.ldt", "-o", "x.csv"], t.path()), 1);
    assert!(
        e.contains("writes its table as Parquet") && e.contains("--jsonl"),
        "{e}"
    );
    assert!(!t.path().join("x.csv").exists());
    // validate --json: warnings have the documented {line, column, code, message}.
    let gamma: Vec<f64> = (0..=18).map(|k| 10.0 * k as f64).collect();
    let cd: Vec<f64> = gamma.iter().map(|&g| if g == 30.0 { -1.0 } else { 100.0 }).collect();
    write_ies(t.path(), "neg.ies", 1000.0, &gamma, &cd);
    let out = ok(&run(&["validate", "neg.ies", "--json"], t.path()));
    let v: serde_json::Value = serde_json::from_str(out.lines().next().unwrap()).unwrap();
    let w = &v["warnings"][0];
    for key in ["line", "column", "code", "message"] {
        assert!(w.get(key).is_some(), "{key} missing: {v}");
    }
}

/// Issue 27, item 6: `hausdorff` refuses meshes in different units (or
/// converts both to cd with `--units cd`), prints the unit with H, and
/// accepts a mesh without a units header as "units unknown".
#[test]
fn hausdorff_refuses_mixed_units_and_names_its_unit() {
    let t = tempfile::tempdir().unwrap();
    ok(&run(&["synth", "cosine-power", "--p", "5", "-o", "c.ldt"], t.path()));
    ok(&run(&["mesh", "c.ldt", "--measured", "-o", "a_cd.ply"], t.path()));
    ok(&run(&["mesh", "c.ldt", "--measured", "-o", "a_cd.glb"], t.path()));
    ok(&run(
        &["mesh", "c.ldt", "--measured", "--units", "peak", "-o", "b_peak.ply"],
        t.path(),
    ));
    ok(&run(
        &["mesh", "c.ldt", "--measured", "--units", "peak", "-o", "b_peak.stl"],
        t.path(),
    ));
    for (a, b) in [("a_cd.ply", "b_peak.ply"), ("a_cd.glb", "b_peak.stl")] {
        let e = fails(&run(&["hausdorff", a, b], t.path()), 1);
        assert!(
            e.contains(&format!("{a} is in cd and {b} in peak")) && e.contains("--units cd"),
            "{e}"
        );
    }
    // Same units: H with its unit.
    let out = ok(&run(&["hausdorff", "a_cd.ply", "a_cd.glb"], t.path()));
    assert!(out.starts_with("H = ") && out.contains(" cd (+"), "{out}");
    let v: serde_json::Value = serde_json::from_str(&ok(&run(
        &["hausdorff", "b_peak.ply", "b_peak.stl", "--json"],
        t.path(),
    )))
    .unwrap();
    assert_eq!(v["units"], "peak", "{v}");
    // --units cd converts the peak mesh by its recorded scale: the same solid, H ~ 0 cd.
    let v: serde_json::Value = serde_json::from_str(&ok(&run(
        &["hausdorff", "a_cd.ply", "b_peak.ply", "--units", "cd", "--json"],
        t.path(),
    )))
    .unwrap();
    assert_eq!(v["units"], "cd", "{v}");
    let peak = photosolid::load(t.path().join("c.ldt"))
        .unwrap()
        .distribution()
        .max_cd();
    assert!(v["hausdorff"].as_f64().unwrap() < 1e-5 * peak, "{v}");
    // A mesh from another tool (no units header): accepted, "units unknown".
    let obj = "v 1 0 0\nv 0 1 0\nv 0 0 1\nv 0 0 0\nf 1 2 3\nf 1 4 2\nf 2 4 3\nf 3 4 1\n";
    std::fs::write(t.path().join("other.obj"), obj).unwrap();
    let out = ok(&run(&["hausdorff", "other.obj", "other.obj"], t.path()));
    assert!(out.contains("(units unknown)"), "{out}");
    let v: serde_json::Value =
        serde_json::from_str(&ok(&run(&["hausdorff", "other.obj", "other.obj", "--json"], t.path()))).unwrap();
    assert!(v["units"].is_null(), "{v}");
}

/// Issue 27, item 5: numbers in the units a reader expects, each once, plurals right.
#[test]
fn numbers_are_printed_once_with_sensible_precision() {
    let t = tempfile::tempdir().unwrap();
    ok(&run(&["synth", "cosine-power", "--p", "5", "-o", "c.ldt"], t.path()));
    let out = ok(&run(&["mesh", "c.ldt", "--measured", "-o", "m.ply"], t.path()));
    assert_eq!(out.matches("vertices").count(), 1, "{out}");
    assert_eq!(out.matches("volume").count(), 1, "{out}");
    assert!(out.contains("1 component") && !out.contains("component(s)"), "{out}");
    assert!(!out.contains("e6") && !out.contains("e3 "), "{out}");
    // compare --vs: BUG classes are integers, not 0.0000.
    let out = ok(&run(
        &["compare", "c.ldt", "--vs", "c.ldt", "--recon", "bilinear"],
        t.path(),
    ));
    let bug = out.lines().find(|l| l.starts_with("BUG B (class)")).expect(&out);
    assert!(!bug.contains('.'), "{bug}");
    let w = |n: usize| photosolid::error::count(n, "warning", "warnings");
    assert_eq!((w(1), w(2)), ("1 warning".to_string(), "2 warnings".to_string()));
    assert_eq!(photosolid::numfmt::trimmed(3153.04, 4), "3153");
    assert_eq!(photosolid::numfmt::trimmed(-0.31699200000000005, 6), "-0.316992");
    assert_eq!(photosolid::numfmt::trimmed(1.5e-7, 4), "1.5e-7");
    assert_eq!(photosolid::error::percent_of(0.001), 0.1);
}

/// One vocabulary: `--vs FILE` and `--against REF` on compare, tradeoff and engines (the old
/// `--reference` still works, with a deprecation warning); `--units` on mesh and compare
/// (`--normalize` an alias); `fit --tolerance` a percent; negative numbers as option values.
#[test]
fn one_vocabulary_across_commands() {
    let t = tempfile::tempdir().unwrap();
    // Parsed (the missing file is the error, exit 1, not a usage error).
    for args in [
        vec!["compare", "missing.ies", "--vs", "other.ies", "--against", "withheld"],
        vec!["compare", "missing.ies", "--units", "peak"],
        vec!["compare", "missing.ies", "--normalize", "peak"],
        vec!["tradeoff", "missing.ies", "--vs", "other.ies", "--against", "bilinear"],
        vec!["tradeoff", "missing.ies", "--against", "withheld"],
        vec!["engines", "missing.ies", "--against", "truth"],
        vec!["fit", "missing.ies", "--tolerance", "1%"],
        vec!["info", "missing.ies", "--tilt", "-5", "--front", "-90"],
        vec!["convert", "missing.ies", "out.ldt", "--rotate-c", "-90"],
    ] {
        let e = fails(&run(&args, t.path()), 1);
        assert!(e.contains("missing.ies") && !e.contains("deprecated"), "{args:?}: {e}");
    }
    for (args, new) in [
        (
            vec!["tradeoff", "missing.ies", "--reference", "withheld"],
            "write --against withheld",
        ),
        (
            vec!["tradeoff", "missing.ies", "--reference", "other.ies"],
            "write --vs other.ies",
        ),
        (
            vec!["engines", "missing.ies", "--reference", "truth"],
            "write --against truth",
        ),
    ] {
        let e = fails(&run(&args, t.path()), 1);
        assert!(e.contains("[deprecated-option]") && e.contains(new), "{args:?}: {e}");
    }
    // The old and the new spelling cannot be mixed.
    fails(
        &run(
            &[
                "tradeoff",
                "missing.ies",
                "--reference",
                "truth",
                "--against",
                "withheld",
            ],
            t.path(),
        ),
        2,
    );
    // Complete help lists.
    let help = ok(&run(&["--help"], t.path()));
    assert!(help.contains("gltf, godot)") && help.contains("TM-33"), "{help}");
}

/// Fail before the work: a report folder that is a file, or under a folder that cannot be
/// written, is refused before anything is computed, on every command that writes one.
#[test]
fn report_folders_are_checked_before_the_work() {
    let t = tempfile::tempdir().unwrap();
    let d = t.path();
    std::fs::write(d.join("afile"), "x").unwrap();
    ok(&run(&["synth", "cosine-power", "--p", "5", "-o", "c.ies"], d));
    let road = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("data/road_en13201.toml");
    let scene = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("data/office_scene.toml");
    let (road, scene) = (road.to_str().unwrap(), scene.to_str().unwrap());
    let commands: Vec<Vec<&str>> = vec![
        vec!["compare", "c.ies"],
        vec!["tradeoff", "c.ies"],
        vec!["engines", "c.ies"],
        vec!["road", road],
        vec!["scene", scene],
        vec!["plan", scene],
        vec!["batch", "c.ies", "-o", "t.parquet"],
    ];
    for cmd in &commands {
        let args: Vec<&str> = cmd.iter().copied().chain(["--report", "afile"]).collect();
        let e = fails(&run(&args, d), 1);
        assert!(
            e.contains("afile: is a file") && e.contains("nothing was computed"),
            "{args:?}: {e}"
        );
    }
    let e = fails(&run(&["demo", "-o", "afile"], d), 1);
    assert!(e.contains("afile: is a file"), "{e}");
    // A folder this process cannot write in: /proc refuses new files even to root.
    for cmd in &commands {
        let args: Vec<&str> = cmd
            .iter()
            .copied()
            .chain(["--report", "/proc/photosolid-report"])
            .collect();
        let e = fails(&run(&args, d), 1);
        assert!(
            e.contains("cannot write in /proc") && e.contains("nothing was computed"),
            "{args:?}: {e}"
        );
    }
    let e = fails(&run(&["convert", "c.ies", "/proc/c.ldt"], d), 1);
    assert!(e.contains("cannot write in /proc"), "{e}");
}

/// compare, tradeoff and plan carry coded warnings in their JSON: the file's reader
/// warnings (here an unknown LM-63 version line), as info has them.
#[test]
fn comparisons_carry_the_files_coded_warnings() {
    let t = tempfile::tempdir().unwrap();
    let d = t.path();
    ok(&run(&["synth", "cosine-power", "--p", "5", "-o", "c.ies"], d));
    let text = std::fs::read_to_string(d.join("c.ies")).unwrap();
    let first = text.lines().next().unwrap().to_string();
    std::fs::write(d.join("odd.ies"), text.replacen(&first, "IESNA:LM-63-2077", 1)).unwrap();
    let json = |args: &[&str]| -> serde_json::Value { serde_json::from_str(&ok(&run(args, d))).unwrap() };
    let info = json(&["info", "odd.ies", "--json"]);
    let codes = crate::common::cli::warning_codes;
    assert!(
        codes(&info).contains(&"unknown-version".to_string()),
        "{}",
        info["warnings"]
    );
    let c = json(&["compare", "odd.ies", "--recon", "bilinear", "--factor", "1", "--json"]);
    assert_eq!(codes(&c), ["unknown-version"], "{}", c["warnings"]);
    let c = json(&[
        "compare", "c.ies", "--vs", "odd.ies", "--recon", "bilinear", "--factor", "1", "--json",
    ]);
    let w = &c["warnings"][0];
    assert!(
        w["code"] == "unknown-version" && w["message"].as_str().unwrap().starts_with("odd.ies: "),
        "{w}"
    );
    let tr = json(&[
        "tradeoff",
        "odd.ies",
        "--factors",
        "1",
        "--factor",
        "1",
        "--repeats",
        "1",
        "--json",
        "--report",
        "rep",
    ]);
    assert_eq!(codes(&tr), ["unknown-version"], "{}", tr["warnings"]);
    // The report's report.json is what --json printed (the same run: timings equal too), and
    // the pages carry the command's own title.
    let written: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(d.join("rep/report.json")).unwrap()).unwrap();
    assert_eq!(written, tr);
    assert!(tr["rows"][0].get("pareto").is_some() && tr["rows"][0].get("pareto_bytes").is_some());
    let html = std::fs::read_to_string(d.join("rep/index.html")).unwrap();
    assert!(
        html.contains("<h1>Representations: bytes, time and error</h1>"),
        "title"
    );
}
