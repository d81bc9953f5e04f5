//! The `photosolid` binary, run for real in a temporary directory per test.

#[macro_use]
mod common;

use common::cli::{ok, run};
use common::corpus;
use std::path::Path;

#[test]
fn synth_then_info_json_has_the_contract_keys_and_closed_form_flux() {
    let t = tempfile::tempdir().unwrap();
    for (ext, args, exact) in [
        (
            "ldt",
            vec!["isotropic", "--intensity", "100"],
            400.0 * std::f64::consts::PI,
        ),
        (
            "ies",
            vec!["lambertian", "--gamma-step", "0.5"],
            1000.0 * std::f64::consts::PI,
        ),
        (
            "ldt",
            vec!["cosine-power", "--p", "5", "--gamma-step", "0.25"],
            2.0 * std::f64::consts::PI * 1000.0 / 6.0,
        ),
    ] {
        let file = format!("{}.{ext}", args[0]);
        let mut a = vec!["synth"];
        a.extend(args.iter().copied());
        a.extend(["-o", file.as_str()]);
        ok(&run(&a, t.path()));
        let v: serde_json::Value = serde_json::from_str(&ok(&run(&["info", &file, "--json"], t.path()))).unwrap();
        for key in [
            "format",
            "version",
            "photometric_type",
            "symmetry",
            "n_c",
            "n_gamma",
            "max_cd",
            "flux_lm",
            "declared_flux_lm",
            "lor",
            "dlor",
            "ulor",
            "beam_angle_deg",
            "field_angle_deg",
            "warnings",
        ] {
            assert!(v.get(key).is_some(), "{file}: key {key} missing in {v}");
        }
        assert_eq!(v["format"], ext);
        let flux = v["flux_lm"].as_f64().unwrap();
        // Grids of 0.25-5 degrees: the piecewise-linear integral is within 0.1 % of the closed form.
        assert_close!(flux, exact, rel = 1e-3, "{file}: {flux} vs {exact}");
        assert!(v["warnings"].is_array());
    }
}

#[test]
fn convert_keeps_physical_intensities() {
    let t = tempfile::tempdir().unwrap();
    ok(&run(
        &["synth", "roadway", "--c-step", "10", "-o", "road.ldt"],
        t.path(),
    ));
    ok(&run(&["convert", "road.ldt", "road.ies"], t.path()));
    ok(&run(
        &["convert", "road.ies", "road2019.ies", "--ies-version", "2019"],
        t.path(),
    ));
    let a = photosolid::load(t.path().join("road.ldt")).unwrap();
    let b = photosolid::load(t.path().join("road.ies")).unwrap();
    let c = photosolid::load(t.path().join("road2019.ies")).unwrap();
    let peak = a.distribution().max_cd();
    for other in [&b, &c] {
        let (x, y) = (a.distribution().expand(1), other.distribution().expand(1));
        assert_eq!(x.c_angles_deg(), y.c_angles_deg());
        assert_eq!(x.gamma_angles_deg(), y.gamma_angles_deg());
        for (p, q) in x.intensities_cd().iter().zip(y.intensities_cd()) {
            assert_close!(p, q, abs = 1e-6 * peak, "{p} vs {q}");
        }
    }
    assert!(c.version().contains("2019"));
    // Rotation by 90 degrees moves the C90-C270 mirror onto C0-C180.
    ok(&run(
        &["convert", "road.ldt", "turned.ldt", "--rotate-c", "90"],
        t.path(),
    ));
    let turned = photosolid::load(t.path().join("turned.ldt")).unwrap();
    assert_eq!(turned.distribution().symmetry(), photosolid::Symmetry::C0C180);
}

#[test]
fn validate_exit_codes_and_json_lines_in_input_order() {
    let t = tempfile::tempdir().unwrap();
    ok(&run(&["synth", "batwing", "-o", "a.ldt"], t.path()));
    ok(&run(
        &["synth", "spot", "--p", "8", "--cutoff", "40", "-o", "b.ies"],
        t.path(),
    ));
    let good = run(&["validate", "--json", "b.ies", "a.ldt"], t.path());
    let out = ok(&good);
    let lines: Vec<serde_json::Value> = out.lines().map(|l| serde_json::from_str(l).unwrap()).collect();
    assert_eq!(lines.len(), 2);
    assert_eq!(lines[0]["path"], "b.ies");
    assert_eq!(lines[1]["path"], "a.ldt");
    for l in &lines {
        assert_eq!(l["ok"], true);
        assert!(l["errors"].as_array().unwrap().is_empty());
        assert!(l["info"]["flux_lm"].as_f64().unwrap() > 0.0);
    }
    std::fs::write(
        t.path().join("broken.IES"),
        "IESNA:LM-63-2002\nTILT=NONE\n1 -1 1 3 1 1 2 0 0 0\n1 1 10\n0 45\n",
    )
    .unwrap();
    let bad = run(&["validate", "--json", "."], t.path());
    assert_eq!(bad.status.code(), Some(1));
    let s = String::from_utf8_lossy(&bad.stdout);
    let broken: Vec<serde_json::Value> = s
        .lines()
        .map(|l| serde_json::from_str::<serde_json::Value>(l).unwrap())
        .filter(|v| v["ok"] == false)
        .collect();
    assert_eq!(broken.len(), 1);
    // Errors are records like warnings: {line, column, code, message}.
    let err = &broken[0]["errors"][0];
    assert!(err["line"].as_u64().is_some_and(|l| l > 0), "{err}");
    assert!(matches!(err["code"].as_str(), Some("invalid" | "unsupported")), "{err}");
    let msg = err["message"].as_str().unwrap();
    let after = msg.split("broken.IES:").nth(1).unwrap_or("");
    assert!(
        after.starts_with(|c: char| c.is_ascii_digit()),
        "error must name file and line: {msg}"
    );
}

/// Issue 26: `validate --json` leaves out the three costly tables unless
/// `--derived` is given; every other `info --json` key is there either way,
/// with the same values, and `info` keeps the tables.
#[test]
fn validate_computes_the_derived_tables_only_when_asked() {
    let t = tempfile::tempdir().unwrap();
    ok(&run(
        &["synth", "spot", "--p", "8", "--cutoff", "40", "-o", "b.ies"],
        t.path(),
    ));
    let line = |args: &[&str]| -> serde_json::Value { serde_json::from_str(ok(&run(args, t.path())).trim()).unwrap() };
    let tables = ["ugr_table", "bug_rating", "luminance_table"];
    let info = line(&["info", "--json", "b.ies"]);
    let lean = line(&["validate", "--json", "b.ies"]);
    let full = line(&["validate", "--json", "--derived", "b.ies"]);
    let (lean, full) = (&lean["info"], &full["info"]);
    for k in tables {
        assert!(info.get(k).is_some(), "info lacks {k}");
        assert!(lean.get(k).is_none(), "validate without --derived has {k}");
        assert_eq!(full[k], info[k], "validate --derived: {k}");
    }
    let keys = |v: &serde_json::Value| v.as_object().unwrap().keys().cloned().collect::<Vec<_>>();
    let mut want = keys(&info);
    want.retain(|k| !tables.contains(&k.as_str()));
    assert_eq!(keys(lean), want);
    assert_eq!(keys(full), keys(&info));
    for k in &want {
        assert_eq!(lean[k], info[k], "{k}");
    }
}

#[test]
fn validate_whole_corpus_reports_every_file() {
    let Some(c) = corpus() else { return };
    let o = run(
        &["validate", "--json", c.to_str().unwrap()],
        Path::new(env!("CARGO_MANIFEST_DIR")),
    );
    // Some corpus files are malformed on purpose, so the exit status is 1.
    assert_eq!(o.status.code(), Some(1));
    let n = String::from_utf8_lossy(&o.stdout).lines().count();
    assert!(n >= 110, "expected every .ies/.ldt of the corpus, got {n}");
}

#[test]
fn info_on_missing_file_is_a_clear_error() {
    let t = tempfile::tempdir().unwrap();
    let o = run(&["info", "nope.ldt"], t.path());
    assert_eq!(o.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&o.stderr).contains("nope.ldt"));
}

#[test]
fn demo_runs_without_files() {
    let t = tempfile::tempdir().unwrap();
    let out = ok(&run(&["demo", "--output", "d"], t.path()));
    assert!(out.contains("flux"), "{out}");
    assert!(t.path().join("d/demo_roadway.ldt").exists());
}

#[test]
fn mesh_from_filter_texture_fitted_lights_and_measured() {
    let t = tempfile::tempdir().unwrap();
    ok(&run(
        &["synth", "isotropic", "--intensity", "100", "-o", "iso.ldt"],
        t.path(),
    ));
    let exact = 4.0 / 3.0 * std::f64::consts::PI * 1e6;
    for args in [
        vec!["--filter", "catmull-rom"],
        vec!["--filter", "bilinear", "--texture"],
        vec!["--filter", "fitted-gl"],
        vec!["--measured"],
    ] {
        let mut a = vec!["mesh", "iso.ldt", "-o", "s.ply", "--json"];
        a.extend(args.iter().copied());
        let v: serde_json::Value = serde_json::from_str(&ok(&run(&a, t.path()))).unwrap();
        let vol = v["volume"].as_f64().unwrap();
        // Inscribed polyhedra of a 100 cd sphere: within 1 % of 4/3 pi r^3 on these grids.
        assert_close!(vol, exact, rel = 0.01, "{args:?}: volume {vol} vs {exact}");
        assert_eq!(v["watertight"], true);
    }
}

#[test]
fn texture_counts_clamped_overshoot_unless_unclamped() {
    let t = tempfile::tempdir().unwrap();
    ok(&run(
        &["synth", "spot", "--p", "8", "--cutoff", "40", "-o", "spot.ldt"],
        t.path(),
    ));
    let clamped = |extra: &[&str]| -> usize {
        let mut a = vec![
            "texture",
            "spot.ldt",
            "--filter",
            "catmull-rom",
            "--backend",
            "cpu",
            "-o",
            "t.exr",
        ];
        a.extend_from_slice(extra);
        let out = ok(&run(&a, t.path()));
        let n = out.split(" texels clamped").next().unwrap().rsplit(' ').next().unwrap();
        n.parse().unwrap()
    };
    // Catmull-Rom rings below zero past the spot's cut-off: counted when clamped, kept when not.
    assert!(clamped(&[]) > 0);
    assert_eq!(clamped(&["--unclamped"]), 0);
    let (tex, meta) = photosolid::reconstruct::exr_io::read_exr(t.path().join("t.exr")).unwrap();
    assert!(
        tex.data.iter().any(|&v| v < 0.0),
        "unclamped texture keeps negative overshoot"
    );
    assert!(meta.source.unwrap().contains("spot.ldt"));
}
