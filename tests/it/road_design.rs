//! Road design (issue 61): EN 13201-2 class verdicts, the largest spacing
//! that meets a class, the choices that move the answer, and their CLI.

use std::path::{Path, PathBuf};

use photosolid::scene::representation::parse_representation;
use photosolid::scene::road::classes::{class_names, lighting_class, Comparison};
use photosolid::scene::road::design::{judge, maximize, SearchRange};
use photosolid::scene::road::layout::{Road, RoadKey, TiScreening};
use photosolid::scene::road::quantities::{evaluate, screening_counts, RoadOptions, RoadResult};
use photosolid::scene::road::surface::RInterpolation;

use crate::common::cli::{fails, ok, run};

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn example() -> Road {
    Road::load(&root().join("data/road_en13201.toml")).unwrap()
}

fn json(out: &str) -> serde_json::Value {
    serde_json::from_str(out).unwrap()
}

/// Every class judges the example: each criterion's `achieved` is the value
/// `overall` holds, `pass` is whether it meets `required` the way
/// `comparison` says, and the class passes exactly when every criterion does.
#[test]
fn class_verdicts_hold_the_overall_figures_against_the_table() {
    let t = tempfile::tempdir().unwrap();
    let scene = root().join("data/road_en13201.toml");
    let plain = json(&ok(&run(&["road", scene.to_str().unwrap(), "--json"], t.path())));
    for key in ["class", "criteria", "pass", "maximize"] {
        assert!(plain.get(key).is_none(), "{key} present without --class");
    }
    assert_eq!(plain["r_interpolation"], "quadratic");
    assert_eq!(plain["ti_screening"], "horizontal");
    let (mut passed, mut failed) = (0, 0);
    for class in class_names() {
        let v = json(&ok(&run(
            &["road", scene.to_str().unwrap(), "--class", class, "--json"],
            t.path(),
        )));
        assert_eq!(v["class"], class);
        let criteria = v["criteria"].as_array().unwrap();
        assert!(!criteria.is_empty());
        let mut all = true;
        for c in criteria {
            let name = c["name"].as_str().unwrap();
            let achieved = c["achieved"].as_f64().unwrap();
            assert_eq!(Some(achieved), v["overall"][name].as_f64(), "{class} {name}");
            let required = c["required"].as_f64().unwrap();
            let pass = match c["comparison"].as_str().unwrap() {
                ">=" => achieved >= required,
                "<=" => achieved <= required,
                other => panic!("comparison {other}"),
            };
            assert_eq!(c["pass"].as_bool(), Some(pass), "{class} {name}");
            for key in ["unit", "required"] {
                assert!(c.get(key).is_some(), "{class} {name} lacks {key}");
            }
            all &= pass;
        }
        assert_eq!(v["pass"].as_bool(), Some(all), "{class}");
        if all {
            passed += 1;
        } else {
            failed += 1;
        }
    }
    // the example passes some classes and fails others: both verdicts are exercised
    assert!(passed > 0 && failed > 0, "passed {passed}, failed {failed}");
}

/// The published limits of the classes the tests name (EN 13201-2:2015 Tables 1-3).
#[test]
fn the_class_tables_hold_the_standards_values() {
    let m3 = lighting_class("M3").unwrap();
    let req: Vec<(&str, f64, Comparison)> = m3.limits.iter().map(|l| (l.name, l.required, l.comparison)).collect();
    assert_eq!(
        req,
        [
            ("l_av_cd_m2", 1.0, Comparison::AtLeast),
            ("u_o", 0.40, Comparison::AtLeast),
            ("u_l", 0.60, Comparison::AtLeast),
            ("ti_pct", 15.0, Comparison::AtMost),
            ("r_ei", 0.30, Comparison::AtLeast),
        ]
    );
    let m6 = lighting_class("m6").unwrap();
    assert_eq!(m6.limits[3].required, 20.0);
    let c2 = lighting_class("C2").unwrap();
    assert_eq!((c2.limits[0].required, c2.limits[1].required), (20.0, 0.40));
    let p4 = lighting_class("P4").unwrap();
    assert_eq!((p4.limits[0].required, p4.limits[1].required), (5.0, 1.0));
    // conditional criteria say so
    assert!(m3.limits[3].condition.is_some() && m3.limits[4].condition.is_some());
    assert!(!m3.not_assessed.is_empty() && !p4.not_assessed.is_empty());
}

/// The largest spacing of the example that meets M6: the road at the answer
/// passes, one resolution step beyond it fails, the margins are the
/// answer's, and a spacing scanned above it fails too.
#[test]
fn the_largest_spacing_passes_and_one_step_beyond_fails() {
    let road = example();
    let class = lighting_class("M6").unwrap();
    let (a, b) = SearchRange::default_for(RoadKey::SpacingM, &road).unwrap();
    assert_eq!((a, b), (10.0, 60.0));
    let range = SearchRange::new(RoadKey::SpacingM, a, b, None).unwrap();
    assert!((range.step - 0.5).abs() < 1e-12);
    let m = maximize(&road, &class, &range, &RoadOptions::default(), None).unwrap();
    let value = m.value.expect("M6 is met at some spacing of the example");
    let at = |s: f64| {
        judge(
            &RoadKey::SpacingM.set(&road, s).unwrap(),
            &class,
            &RoadOptions::default(),
        )
        .unwrap()
    };
    let there = at(value);
    assert!(there.verdict.pass, "{value}: {:?}", there.verdict);
    let next = m.next_value.unwrap();
    assert!((next - value - 0.01).abs() < 1e-9, "{value} {next}");
    assert!(!at(next).verdict.pass);
    for (g, c) in m.margins.iter().zip(&there.verdict.criteria) {
        assert_eq!(g.name, c.name);
        assert!(g.margin >= 0.0 && (g.margin - c.margin).abs() < 1e-12);
    }
    assert!(m
        .samples
        .iter()
        .filter(|s| s.value > next)
        .all(|s| !s.pass || s.value <= value));
    assert!(m.evaluations < 130, "{} calculations", m.evaluations);
}

/// Nothing in the range passes: `value` is null with a reason naming the
/// failing criteria, and the command still exits 0 (a result, not an error).
#[test]
fn a_range_where_nothing_passes_gives_null_and_a_reason() {
    let t = tempfile::tempdir().unwrap();
    let scene = root().join("data/road_en13201.toml");
    let out = run(
        &[
            "road",
            scene.to_str().unwrap(),
            "--class",
            "M1",
            "--maximize",
            "spacing_m",
            "--range",
            "20:30",
            "--json",
        ],
        t.path(),
    );
    let v = json(&ok(&out));
    let m = &v["maximize"];
    assert!(m["value"].is_null());
    let reason = m["reason"].as_str().unwrap();
    assert!(reason.contains("l_av_cd_m2") && reason.contains("M1"), "{reason}");
    assert_eq!(m["key"], "spacing_m");
    assert_eq!(m["range"], serde_json::json!([20.0, 30.0]));
    assert!(m["margins"].as_array().unwrap().is_empty());
}

/// `--grid mounting_height_m=A:B:STEP` gives one answer per height, each
/// naming it; a higher mounting (a wider spread on the road) allows a
/// spacing no shorter for the luminance criteria of M5... only checked as
/// what each answer says of itself: it passes there.
#[test]
fn a_grid_gives_one_answer_per_value() {
    let t = tempfile::tempdir().unwrap();
    let scene = root().join("data/road_en13201.toml");
    let report = t.path().join("report");
    let out = run(
        &[
            "road",
            scene.to_str().unwrap(),
            "--class",
            "M5",
            "--maximize",
            "spacing_m",
            "--grid",
            "mounting_height_m=8:12:2",
            "--json",
            "--report",
            report.to_str().unwrap(),
        ],
        t.path(),
    );
    let v = json(&ok(&out));
    let answers = v["maximize"].as_array().unwrap();
    assert_eq!(answers.len(), 3);
    for (a, h) in answers.iter().zip([8.0, 10.0, 12.0]) {
        assert_eq!(a["grid"]["key"], "mounting_height_m");
        assert_eq!(a["grid"]["value"].as_f64(), Some(h));
        let value = a["value"].as_f64().unwrap();
        let road = RoadKey::MountingHeightM.set(&example(), h).unwrap();
        let road = RoadKey::SpacingM.set(&road, value).unwrap();
        let j = judge(&road, &lighting_class("M5").unwrap(), &RoadOptions::default()).unwrap();
        assert!(j.verdict.pass, "h {h}, spacing {value}");
    }
    for name in [
        "maximize_l_av_cd_m2.png",
        "maximize_u_l.png",
        "maximize_ti_pct.png",
        "index.html",
        "road.json",
    ] {
        assert!(report.join(name).is_file(), "{name}");
    }
    let html = std::fs::read_to_string(report.join("index.html")).unwrap();
    assert!(html.contains("class M5") && html.contains("largest spacing_m meeting M5"));
}

/// Usage errors exit 2 and name the flag or key; a road that cannot be
/// judged exits 1.
#[test]
fn bad_arguments_exit_2_and_an_unlit_road_exits_1() {
    let t = tempfile::tempdir().unwrap();
    let scene = root().join("data/road_en13201.toml");
    let s = scene.to_str().unwrap();
    let cases: [(&[&str], &str); 10] = [
        (&["--class", "M7"], "M7"),
        (&["--class", "M3", "--maximize", "lanes"], "lanes"),
        (
            &["--class", "M3", "--maximize", "spacing_m", "--range", "40:30"],
            "empty",
        ),
        (
            &["--class", "M3", "--maximize", "spacing_m", "--range", "a:30"],
            "START",
        ),
        (
            &["--class", "M3", "--maximize", "spacing_m", "--range", "30"],
            "START:END",
        ),
        (
            &["--class", "M3", "--maximize", "spacing_m", "--range", "0:30"],
            "spacing_m",
        ),
        (
            &["--class", "M3", "--maximize", "tilt_deg", "--range", "0:95"],
            "tilt_deg",
        ),
        (&["--class", "M3", "--maximize", "tilt_deg"], "--range"),
        (&["--maximize", "spacing_m"], "--class"),
        (
            &[
                "--class",
                "M3",
                "--maximize",
                "spacing_m",
                "--grid",
                "spacing_m=10:20:5",
            ],
            "--grid",
        ),
    ];
    for (args, says) in cases {
        let mut all = vec!["road", s];
        all.extend_from_slice(args);
        let err = fails(&run(&all, t.path()), 2);
        assert!(err.contains(says), "{args:?}: {err}");
    }
    // a luminaire that lights only upwards: nothing to judge
    let dir = t.path();
    crate::common::cli::write_ies(
        dir,
        "up.ies",
        1000.0,
        &[0.0, 45.0, 90.0, 135.0, 180.0],
        &[0.0, 0.0, 0.0, 50.0, 100.0],
    );
    std::fs::write(
        dir.join("up.toml"),
        "[road]\nfile = \"up.ies\"\nlanes = 2\nlane_width_m = 3.5\nsurface = \"R3\"\narrangement = \"single-sided\"\n\
         spacing_m = 30.0\nmounting_height_m = 10.0\n",
    )
    .unwrap();
    let err = fails(&run(&["road", "up.toml", "--class", "M3"], dir), 1);
    assert!(err.contains("no luminaire puts light"), "{err}");
}

/// The screening angle counts a luminaire on it (20° + 1e-9°), not one a
/// hair above; line-of-sight screening stops at 19°.
#[test]
fn a_luminaire_on_the_screening_angle_is_counted() {
    let h = 10.0 - 1.5;
    let dx = h / 20f64.to_radians().tan();
    let elevation = h.atan2(dx).to_degrees();
    assert!((elevation - 20.0).abs() < 1e-12);
    assert!(screening_counts(TiScreening::Horizontal, elevation));
    assert!(screening_counts(TiScreening::Horizontal, 20.0 + 0.9e-9));
    assert!(!screening_counts(TiScreening::Horizontal, 20.0 + 1e-8));
    assert!(!screening_counts(TiScreening::LineOfSight, elevation));
    assert!(screening_counts(TiScreening::LineOfSight, 19.0));
}

/// How far `with` moves each lane's figures from `base`: the largest
/// relative change (%) over the lanes of L_av, U_o, U_l and TI.
fn effect(base: &RoadResult, with: &RoadResult) -> [f64; 4] {
    let rel = |a: f64, b: f64| if b != 0.0 { 100.0 * (a - b) / b } else { 0.0 };
    let mut out = [0.0f64; 4];
    for (w, b) in with.lanes.iter().zip(&base.lanes) {
        let ch = [
            rel(w.l_av_cd_m2, b.l_av_cd_m2),
            rel(w.u_o, b.u_o),
            rel(w.u_l, b.u_l),
            rel(w.ti_pct, b.ti_pct),
        ];
        for (o, c) in out.iter_mut().zip(ch) {
            if c.abs() > o.abs() {
                *o = c;
            }
        }
    }
    out
}

/// The table of `docs/road.md` ("The choices that move the answer"),
/// measured here on the example road: each row is recomputed and must be in
/// the docs as printed, so the docs say what the code does.
#[test]
fn the_choices_table_in_the_docs_is_what_the_example_gives() {
    let road = example();
    let opts = RoadOptions::default();
    let base = evaluate(&road, &opts).unwrap();
    let mut bilinear = road.clone();
    bilinear.representation = Some(parse_representation("bilinear").unwrap().0);
    let mut r_bilinear = road.clone();
    r_bilinear.r_interpolation = RInterpolation::Bilinear;
    let mut sight = road.clone();
    sight.ti_screening = TiScreening::LineOfSight;
    let rows = [
        ("intensities", "`representation`", "catmull-rom", "bilinear", &bilinear),
        (
            "r-table interpolation",
            "`r_interpolation`",
            "quadratic",
            "bilinear",
            &r_bilinear,
        ),
        ("TI screening", "`ti_screening`", "horizontal", "line-of-sight", &sight),
    ];
    let docs = std::fs::read_to_string(root().join("docs/road.md")).unwrap();
    let mut missing = Vec::new();
    for (choice, key, default, alternative, with) in rows {
        let e = effect(&base, &evaluate(with, &opts).unwrap());
        let row = format!(
            "| {choice} | {key} | {default} | {alternative} | {:+.2} % | {:+.2} % | {:+.2} % | {:+.2} % |",
            e[0], e[1], e[2], e[3]
        );
        println!("{row}");
        if !docs.contains(&row) {
            missing.push(row);
        }
    }
    assert!(
        missing.is_empty(),
        "docs/road.md lacks these rows (measured now):\n{}",
        missing.join("\n")
    );
}

/// `plan --class` keeps every criterion's verdict: the chosen candidate's
/// verdicts are the reference's, and a candidate whose verdict differs is
/// not within.
#[test]
fn plan_with_a_class_keeps_every_verdict() {
    let t = tempfile::tempdir().unwrap();
    let scene: PathBuf = root().join("data/road_en13201.toml");
    let v = json(&ok(&run(
        &["plan", scene.to_str().unwrap(), "--class", "M6", "--json"],
        t.path(),
    )));
    assert_eq!(v["class"], "M6");
    let reference_pass = v["reference_verdict"]["pass"].as_bool().unwrap();
    let candidates = v["candidates"].as_array().unwrap();
    let chosen = candidates.iter().find(|c| c["representation"] == v["chosen"]).unwrap();
    assert_eq!(chosen["verdicts_match"].as_bool(), Some(true));
    assert_eq!(chosen["class_pass"].as_bool(), Some(reference_pass));
    let mut differing = 0;
    for c in candidates {
        if c["verdicts_match"].as_bool() == Some(false) {
            differing += 1;
            assert_eq!(c["within"].as_bool(), Some(false), "{}", c["representation"]);
        }
    }
    assert!(
        differing > 0,
        "no candidate changed a verdict: the check was not exercised"
    );
    // a scene without [road] refuses --class as a usage error
    let err = fails(
        &run(
            &[
                "plan",
                root().join("data/office_scene.toml").to_str().unwrap(),
                "--class",
                "M3",
            ],
            t.path(),
        ),
        2,
    );
    assert!(err.contains("--class"), "{err}");
}
