//! One luminaire, one answer: the luminaire's front (`model::front`) through
//! every format, conversion and rotation; BUG, `road` and `convert` read it.

use std::path::{Path, PathBuf};

use photosolid::formats::{Document, ReadOptions, WriteOptions};
use photosolid::model::{Format, FrontSource, Luminaire};
use photosolid::photometry::bug::bug_rating;
use photosolid::scene::road::layout::Road;
use photosolid::scene::road::quantities::{evaluate, RoadOptions, RoadResult};
use photosolid::synth::{GridSpec, Synth};

use crate::common::cli::{ok, run};
use crate::common::corpus;

/// The synthetic road luminaire as a EULUMDAT luminaire (street side C90, its format's front).
fn roadway() -> Luminaire {
    Synth::Roadway
        .build_for(Format::Ldt, &GridSpec::uniform(5.0, 2.5).unwrap(), 12_000.0)
        .unwrap()
}

/// Write `lum` to `dir/name` (format from the extension) and read it back,
/// with `front` given as `--front` would give it.
fn through(lum: &Luminaire, dir: &Path, name: &str, front: Option<f64>) -> Luminaire {
    let path = dir.join(name);
    let doc: Document = lum.clone().into();
    photosolid::save(&doc, &path, &WriteOptions::default()).unwrap();
    let opts = ReadOptions {
        front_c_deg: front,
        ..ReadOptions::default()
    };
    photosolid::formats::load_with(&path, &opts).unwrap()
}

/// `lum` with its planes turned by `deg` (as `convert --rotate-c` does), its front turned along.
fn rotated(lum: &Luminaire, deg: f64) -> Luminaire {
    let mut out = lum.clone();
    out.set_distribution(lum.distribution().reoriented(deg, false).unwrap());
    out.set_front(lum.front().reoriented(deg, false));
    out
}

const ARRANGEMENTS: [&str; 4] = ["single-sided", "opposite", "staggered", "twin-central"];

/// A `[road]` scene next to `file`, as `data/road_en13201.toml` lays it out.
fn road_scene(dir: &Path, file: &str, arrangement: &str, street_side: Option<f64>) -> PathBuf {
    let key = street_side.map_or(String::new(), |c| format!("street_side_c_deg = {c}\n"));
    let text = format!(
        "[road]\nfile = \"{file}\"\nlanes = 2\nlane_width_m = 3.5\nsurface = \"R3\"\narrangement = \
         \"{arrangement}\"\nspacing_m = 36.0\nmounting_height_m = 10.0\noverhang_m = 1.0\ntilt_deg = 5.0\n\
         setback_m = 1.0\n{key}"
    );
    let path = dir.join(format!("{arrangement}-{}.toml", file.replace('.', "_")));
    std::fs::write(&path, text).unwrap();
    path
}

fn road(dir: &Path, file: &str, arrangement: &str, street_side: Option<f64>) -> RoadResult {
    let r = Road::load(&road_scene(dir, file, arrangement, street_side)).unwrap();
    evaluate(&r, &RoadOptions::default()).unwrap()
}

/// Every overall and per-lane figure, for comparison.
fn figures(r: &RoadResult) -> Vec<f64> {
    let o = &r.overall;
    let mut v = vec![
        o.l_av_cd_m2,
        o.u_o,
        o.u_l,
        o.ti_pct,
        o.r_ei,
        o.e_av_lux,
        o.e_min_lux,
        o.e_hs_av_lux,
    ];
    for l in &r.lanes {
        v.extend([l.l_av_cd_m2, l.u_o, l.u_l, l.ti_pct]);
    }
    v
}

/// Equal to 1e-9 (relative) when both files hold the same numbers; a
/// EULUMDAT file written from other numbers rounds them to 8 significant
/// digits (`formats::ldt::write`), which moves the figures by up to 1e-8:
/// those comparisons use [`LDT_ROUNDING`].
fn assert_same(a: &[f64], b: &[f64], what: &str) {
    assert_close_to(a, b, 1e-9, what)
}

/// The tolerance of a comparison across a EULUMDAT write of other numbers (see [`assert_same`]).
const LDT_ROUNDING: f64 = 1e-7;

fn assert_close_to(a: &[f64], b: &[f64], rel: f64, what: &str) {
    assert_eq!(a.len(), b.len());
    for (x, y) in a.iter().zip(b) {
        assert!(
            (x - y).abs() <= rel * x.abs().max(y.abs()).max(1e-12),
            "{what}: {x} vs {y}\n{a:?}\n{b:?}"
        );
    }
}

/// With the front given, the road is the same after every conversion (IES
/// 2002, TM-33, EULUMDAT) and after turning the file by 90° with
/// `street_side_c_deg` turned to match, for every arrangement; BUG too.
#[test]
fn road_and_bug_are_the_same_through_every_format_and_rotation() {
    let dir = tempfile::tempdir().unwrap();
    let lum = through(&roadway(), dir.path(), "orig.ldt", None);
    let front = lum.front().c_deg;
    assert_eq!(front, 90.0);
    let ies = through(&lum, dir.path(), "conv.ies", Some(front));
    let tm33 = through(&lum, dir.path(), "conv.xml", Some(front));
    let turned = rotated(&lum, 90.0);
    through(&turned, dir.path(), "turned.ldt", None);
    let bug = bug_rating(lum.distribution(), lum.front());
    for (name, other) in [("ies", &ies), ("tm33", &tm33)] {
        assert_eq!(other.front().source, FrontSource::Flag);
        let b = bug_rating(other.distribution(), other.front());
        assert_eq!(b.rating, bug.rating, "{name}");
        assert_same(
            &[b.zones.fl, b.zones.bh, b.zones.fh, b.zones.bm],
            &[bug.zones.fl, bug.zones.bh, bug.zones.fh, bug.zones.bm],
            name,
        );
    }
    let b = bug_rating(turned.distribution(), turned.front());
    assert_eq!(b.rating, bug.rating, "turned");
    for arrangement in ARRANGEMENTS {
        let base = figures(&road(dir.path(), "orig.ldt", arrangement, None));
        assert!(base[0] > 0.0, "{arrangement}: {base:?}");
        let ies = figures(&road(dir.path(), "conv.ies", arrangement, Some(front)));
        assert_same(&base, &ies, &format!("{arrangement} ies"));
        let tm33 = figures(&road(dir.path(), "conv.xml", arrangement, Some(front)));
        assert_same(&base, &tm33, &format!("{arrangement} tm33"));
        let turned = figures(&road(dir.path(), "turned.ldt", arrangement, Some(front + 90.0)));
        assert_same(&base, &turned, &format!("{arrangement} turned"));
    }
}

/// `synth roadway` puts its street side at each format's front: both files
/// give the same road with no key, and each still carries its closed form.
#[test]
fn synth_roadway_reads_its_front_where_its_light_goes_in_both_formats() {
    let dir = tempfile::tempdir().unwrap();
    for ext in ["ldt", "ies"] {
        ok(&run(
            &[
                "synth",
                "roadway",
                "--intensity",
                "12000",
                "--c-step",
                "5",
                "--gamma-step",
                "2.5",
                "-o",
                &format!("road.{ext}"),
            ],
            dir.path(),
        ));
    }
    let ldt = photosolid::load(dir.path().join("road.ldt")).unwrap();
    let ies = photosolid::load(dir.path().join("road.ies")).unwrap();
    assert_eq!((ldt.front().c_deg, ies.front().c_deg), (90.0, 0.0));
    for lum in [&ldt, &ies] {
        let throw = photosolid::photometry::throw::downward_throw(lum.distribution()).unwrap();
        assert!(
            photosolid::model::front::c_separation_deg(throw.azimuth_c_deg, lum.front().c_deg) < 1e-6,
            "{throw:?}"
        );
        // The recorded truth equals the file at its grid points.
        let truth = photosolid::synth::Truth::of_luminaire(lum).unwrap();
        let d = lum.distribution();
        for (c, ic) in d.full_planes() {
            for (ig, &g) in d.gamma_angles_deg().iter().enumerate() {
                use photosolid::model::IntensityField;
                let (t, v) = (truth.intensity_cd(c, g), d.value_cd(ic, ig));
                assert!((t - v).abs() <= 1e-6 * 12_000.0, "C{c} g{g}: truth {t} file {v}");
            }
        }
    }
    assert_eq!(
        bug_rating(ldt.distribution(), ldt.front()).rating,
        bug_rating(ies.distribution(), ies.front()).rating
    );
    for arrangement in ["single-sided", "twin-central"] {
        let a = road(dir.path(), "road.ldt", arrangement, None);
        let b = road(dir.path(), "road.ies", arrangement, None);
        assert_close_to(&figures(&a), &figures(&b), LDT_ROUNDING, arrangement);
        assert!(
            a.warnings.iter().all(|w| w.code != "street-side-mismatch"),
            "{:?}",
            a.warnings
        );
        assert_eq!((a.street_side_c_deg, b.street_side_c_deg), (90.0, 0.0));
    }
}

/// A luminaire installed sideways is said so, with the angle to set.
#[test]
fn a_sideways_street_side_is_warned_with_the_angle_to_set() {
    let dir = tempfile::tempdir().unwrap();
    through(&roadway(), dir.path(), "road.ldt", None);
    let r = road(dir.path(), "road.ldt", "single-sided", Some(0.0));
    let w = r
        .warnings
        .iter()
        .find(|w| w.code == "street-side-mismatch")
        .expect("a warning");
    assert!(w.message.contains("street_side_c_deg = 90"), "{w}");
    // Installed sideways, its lobes throw along the road: another road altogether.
    let right = road(dir.path(), "road.ldt", "single-sided", None);
    assert!(
        (right.overall.ti_pct - r.overall.ti_pct).abs() > 1.0,
        "{:?} vs {:?}",
        right.overall,
        r.overall
    );
}

/// `info --json` reports the front and where it came from; `--front` (negative too)
/// overrides it; BUG turns with it and a front away from the light is warned.
#[test]
fn info_reports_the_front_and_warns_when_the_light_goes_elsewhere() {
    let dir = tempfile::tempdir().unwrap();
    through(&roadway(), dir.path(), "road.ldt", None);
    let json = |args: &[&str]| -> serde_json::Value {
        let mut all = vec!["info", "road.ldt", "--json"];
        all.extend_from_slice(args);
        serde_json::from_str(&ok(&run(&all, dir.path()))).unwrap()
    };
    let base = json(&[]);
    assert_eq!(base["front_c_deg"], 90.0);
    assert_eq!(base["front_source"], "format");
    let codes = crate::common::cli::warning_codes;
    assert!(
        !codes(&base).contains(&"front-mismatch".to_string()),
        "{:?}",
        codes(&base)
    );
    let flagged = json(&["--front", "-90"]);
    assert_eq!(flagged["front_c_deg"], 270.0);
    assert_eq!(flagged["front_source"], "flag");
    assert!(
        codes(&flagged).contains(&"front-mismatch".to_string()),
        "{:?}",
        codes(&flagged)
    );
    let msg = flagged["warnings"]
        .as_array()
        .unwrap()
        .iter()
        .find(|w| w["code"] == "front-mismatch")
        .unwrap();
    assert!(msg["message"].as_str().unwrap().contains("--front 90"), "{msg}");
    // Forward and back swap when the front does.
    let z = |v: &serde_json::Value, k: &str| v["bug_rating"]["zones"][k].as_f64().unwrap();
    assert!((z(&base, "fh") - z(&flagged, "bh")).abs() <= 1e-9 * z(&base, "fh").max(1.0));
    assert!((z(&base, "bl") - z(&flagged, "fl")).abs() <= 1e-9 * z(&base, "bl").max(1.0));
}

/// `convert` keeps C angles and says when the target's convention moves the front.
#[test]
fn convert_warns_front_differs_and_rotation_turns_the_front() {
    let dir = tempfile::tempdir().unwrap();
    through(&roadway(), dir.path(), "road.ldt", None);
    let o = run(&["convert", "road.ldt", "road.ies"], dir.path());
    ok(&o);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("front-differs") && err.contains("--front 90"), "{err}");
    // Turned by -90 degrees the street side lands on IES's C0: nothing to say.
    let o = run(&["convert", "road.ldt", "turned.ies", "--rotate-c", "-90"], dir.path());
    ok(&o);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!err.contains("front-differs"), "{err}");
    let a = photosolid::load(dir.path().join("road.ldt")).unwrap();
    let b = photosolid::load(dir.path().join("turned.ies")).unwrap();
    assert_eq!(
        bug_rating(a.distribution(), a.front()).rating,
        bug_rating(b.distribution(), b.front()).rating
    );
}

/// The real file: a Type II roadway IES file (symmetric about
/// C0-C180, throwing towards C0, declared B2 U0 G2) is installed with its
/// front across the road by default, and equals itself turned into a
/// EULUMDAT file's convention.
#[test]
fn a_real_ies_road_luminaire_lights_the_road_the_right_way_round() {
    let Some(root) = corpus() else { return };
    let dir = tempfile::tempdir().unwrap();
    let src = root.join("luxcore/ASA_15M_R2.ies");
    std::fs::copy(&src, dir.path().join("asa.ies")).unwrap();
    let lum = photosolid::load(dir.path().join("asa.ies")).unwrap();
    assert_eq!(lum.front().c_deg, 0.0);
    through(&rotated(&lum, 90.0), dir.path(), "asa_turned.ldt", None);
    let default = road(dir.path(), "asa.ies", "single-sided", None);
    assert!(
        default.warnings.iter().all(|w| w.code != "street-side-mismatch"),
        "{:?}",
        default.warnings
    );
    let turned = road(dir.path(), "asa_turned.ldt", "single-sided", None);
    assert_close_to(
        &figures(&default),
        &figures(&turned),
        LDT_ROUNDING,
        "ASA turned into EULUMDAT",
    );
    let sideways = road(dir.path(), "asa.ies", "single-sided", Some(90.0));
    assert!(
        sideways.warnings.iter().any(|w| w.code == "street-side-mismatch"),
        "{:?}",
        sideways.warnings
    );
}
