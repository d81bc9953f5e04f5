//! Every HTML report carries the interactive 3D view (crates/photosolid-report/src/viewer), its
//! data parses, states the reference, and a typical report stays under 1 MB.
//! The browser checks (rendering, toggles, slider, offline) are in tests/browser/.

use crate::common;

use std::path::Path;
use std::process::Command;

use common::cli::{bin, ok};

fn run(cmd: &mut Command) {
    ok(&cmd.output().unwrap());
}

/// A roadway luminaire written by `synth` (so `truth` is its reference).
fn road(dir: &Path) -> std::path::PathBuf {
    let f = dir.join("road.ldt");
    run(bin()
        .args(["synth", "roadway", "--c-step", "10", "--gamma-step", "5", "-o"])
        .arg(&f));
    f
}

/// The viewer's JSON data in `index.html`, after checking the fragment is there once.
fn viewer_data(index: &Path) -> (String, serde_json::Value) {
    let html = std::fs::read_to_string(index).unwrap();
    assert_eq!(
        html.matches("<section class=\"psv\">").count(),
        1,
        "{}",
        index.display()
    );
    assert!(html.contains("<canvas class=\"psv-gl\""));
    assert!(html.contains("WebGL is not available"));
    let tag = "<script type=\"application/json\" class=\"psv-data\">";
    let start = html.find(tag).unwrap() + tag.len();
    let end = start + html[start..].find("</script>").unwrap();
    let v: serde_json::Value = serde_json::from_str(&html[start..end]).unwrap();
    // The static PNGs stay next to the view.
    assert!(html.contains("data:image/png;base64,"));
    for bad in ["http://", "https://", "<script src", "<link"] {
        assert!(!html.contains(bad), "{bad}");
    }
    (html, v)
}

fn check_solids(v: &serde_json::Value, min_recons: usize) {
    let solids = v["solids"].as_array().unwrap();
    assert_eq!(solids[0]["role"], "reference");
    assert!(solids.len() > min_recons, "{} solids", solids.len());
    let nv = v["nc"].as_u64().unwrap() * v["ng"].as_u64().unwrap();
    // base64 of nv u16 radii: 4 characters per 3 bytes.
    for s in solids {
        assert_eq!(s["radius"].as_str().unwrap().len() as u64, (2 * nv).div_ceil(3) * 4);
    }
    let step = v["c_step_deg"].as_f64().unwrap();
    assert!((2.0..=5.0).contains(&step), "{step}");
}

/// `compare` of the synthetic roadway luminaire with `extra` arguments and
/// `--report`: the report's HTML and viewer data.
fn compare_report(extra: &[&str]) -> (String, serde_json::Value) {
    let dir = tempfile::tempdir().unwrap();
    let f = road(dir.path());
    let rep = dir.path().join("rep");
    run(bin()
        .arg("compare")
        .arg(&f)
        .args(extra)
        .args(["--directions", "dense:2000", "--report"])
        .arg(&rep));
    viewer_data(&rep.join("index.html"))
}

#[test]
fn compare_report_has_the_viewer_and_stays_under_a_megabyte() {
    // The same defaults as compare_report(&[]) but 3,000 directions: the run the compare
    // contract test reads too.
    let (dir, _) = common::cli::shared_road_compare();
    let (html, v) = viewer_data(&dir.join("rep/index.html"));
    assert!(
        v["reference"].as_str().unwrap().starts_with("truth (roadway"),
        "{}",
        v["reference"]
    );
    check_solids(&v, 6);
    eprintln!("compare index.html: {} bytes", html.len());
    assert!(html.len() < 1_000_000, "{} bytes", html.len());
}

#[test]
fn withheld_compare_states_what_the_colours_are_against() {
    let (html, v) = compare_report(&["--against", "withheld"]);
    assert!(v["reference"].as_str().unwrap().starts_with("the measured solid"));
    assert!(html.contains("against the withheld measurements"));
    // The measured solid is the reference here, not one of the coloured surfaces.
    assert!(v["solids"].as_array().unwrap()[1..]
        .iter()
        .all(|s| s["name"] != "measured"));
}

#[test]
fn tradeoff_and_engines_reports_have_the_viewer() {
    let dir = tempfile::tempdir().unwrap();
    let f = road(dir.path());
    // tradeoff at a fixed grid and two texture factors: the viewer is the same, and the
    // defaults against the closed form took about 50 s of a test thread (BENCHMARKS.md).
    let quick: &[(&str, &[&str])] = &[
        ("tradeoff", &["--factor", "1", "--factors", "1,2", "--repeats", "1"]),
        ("engines", &[]),
    ];
    for &(cmd, args) in quick {
        let rep = dir.path().join(cmd);
        run(bin().arg(cmd).arg(&f).args(args).arg("--report").arg(&rep));
        let (html, v) = viewer_data(&rep.join("index.html"));
        check_solids(&v, 2);
        eprintln!(
            "{cmd} index.html: {} bytes, {} solids",
            html.len(),
            v["solids"].as_array().unwrap().len()
        );
    }
}

#[test]
fn demo_report_has_the_viewer() {
    let (dir, _) = common::cli::shared_demo();
    let (html, v) = viewer_data(&dir.join("out/demo/index.html"));
    assert!(v["reference"].as_str().unwrap().starts_with("truth"));
    check_solids(&v, 6);
    assert!(html.len() < 1_000_000, "{} bytes", html.len());
}

#[test]
fn scene_and_plan_reports_have_a_viewer_per_luminaire() {
    let dir = tempfile::tempdir().unwrap();
    let scene = concat!(env!("CARGO_MANIFEST_DIR"), "/data/road_scene.toml");
    for cmd in ["scene", "plan"] {
        let rep = dir.path().join(cmd);
        run(bin().args([cmd, scene, "--report"]).arg(&rep));
        let html = std::fs::read_to_string(rep.join("index.html")).unwrap();
        let json: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(rep.join(format!("{cmd}.json"))).unwrap()).unwrap();
        let n = json["luminaires"].as_array().unwrap().len();
        assert!(n >= 2);
        assert_eq!(html.matches("<section class=\"psv\">").count(), n, "{cmd}");
        assert!(html.contains("(the scene's reference)"), "{cmd}");
        for bad in ["http://", "https://", "<script src", "<link"] {
            assert!(!html.contains(bad), "{bad}");
        }
        if cmd == "scene" {
            assert!(html.contains("data:image/png;base64,"), "the isolux maps stay");
        }
        if cmd == "plan" {
            // A chosen representation other than the reference is drawn with its errors.
            let chosen: Vec<&str> = json["luminaires"]
                .as_array()
                .unwrap()
                .iter()
                .map(|l| l["representation"].as_str().unwrap())
                .filter(|r| *r != "catmull-rom")
                .collect();
            for r in chosen {
                assert!(
                    html.contains(&format!("\"name\":\"{r}\",\"role\":\"reconstruction\"")),
                    "{r}"
                );
            }
        }
        assert!(html.len() < 1_000_000, "{cmd}: {} bytes", html.len());
    }
}
