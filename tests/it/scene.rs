//! Scenes: illuminance against closed forms, near-field sources, plans, extremes, the CLI.

use std::f64::consts::PI;
use std::path::Path;

use glam::DVec3;
use photosolid::model::{Distribution, IntensityField, Luminaire, Symmetry};
use photosolid::scene::aim::{Aim, Pose};
use photosolid::scene::illuminance::{evaluate, SceneResult, Source};
use photosolid::scene::near_field::{corner_rectangle_form_factor, lambert_disk_on_axis_lux, lambert_polygon_lux};
use photosolid::scene::opening::Opening;
use photosolid::scene::plan::{plan, PlanOptions};
use photosolid::scene::{Receiver, Scene, SceneError, SceneLuminaire, ScenePoint, SourceKind};
use photosolid::synth::{GridSpec, Synth};

pub(crate) fn synth(kind: Synth, peak: f64) -> Luminaire {
    kind.build(&GridSpec::uniform(15.0, 2.5).unwrap(), peak).unwrap()
}

pub(crate) fn placed(name: &str, lum: Luminaire, at: DVec3, aim: Aim) -> SceneLuminaire {
    SceneLuminaire::new(name, lum, Pose::new(at, aim)).unwrap()
}

/// A cosine-power (p = 5, 2000 cd) luminaire `height_m` above the origin,
/// aimed down, with a square luminous opening of side `side_m`.
fn cos5_square_opening(height_m: f64, side_m: f64) -> SceneLuminaire {
    let mut lum = placed(
        "cos5",
        synth(Synth::CosinePower { p: 5.0 }, 2000.0),
        DVec3::new(0.0, 0.0, height_m),
        Aim::default(),
    );
    lum.opening = Opening::Rectangle {
        length_m: side_m,
        width_m: side_m,
    };
    lum
}

/// The lighting plan of `s`, timing each candidate on `timing_directions` directions.
pub(crate) fn plan_timed(s: &Scene, timing_directions: usize) -> photosolid::scene::plan::PlanResult {
    plan(
        s,
        &PlanOptions {
            timing_directions,
            ..PlanOptions::default()
        },
        None,
    )
    .unwrap()
}

pub(crate) fn scene(luminaires: Vec<SceneLuminaire>, receivers: Vec<Receiver>) -> Scene {
    Scene {
        warnings: Vec::new(),
        path: None,
        luminaires,
        receivers,
        occluders: Vec::new(),
    }
}

fn all_finite(r: &SceneResult) -> bool {
    r.receivers.iter().all(|rc| {
        [rc.e_avg_lux, rc.e_min_lux, rc.e_max_lux].iter().all(|v| v.is_finite())
            && rc
                .points
                .iter()
                .all(|p| p.e_lux.is_finite() && p.e_lux >= 0.0 && p.far_field_error_pct.is_finite())
    }) && !serde_json::to_string(r).unwrap().contains("NaN")
}

#[test]
fn isotropic_point_over_a_plane_is_i_cos3_over_h2_at_every_grid_point() {
    let (i0, h) = (1000.0, 3.0);
    let lum = placed(
        "iso",
        synth(Synth::Isotropic, i0),
        DVec3::new(1.0, -2.0, h),
        Aim::default(),
    );
    let plane = Receiver::plane(
        "floor",
        DVec3::new(-9.0, -12.0, 0.0),
        DVec3::new(20.0, 0.0, 0.0),
        DVec3::new(0.0, 20.0, 0.0),
        9,
        7,
    );
    let s = scene(vec![lum], vec![plane]);
    let r = evaluate(&s, None).unwrap();
    assert_eq!(r.receivers[0].points.len(), 63);
    for p in &r.receivers[0].points {
        let d = DVec3::from_array(p.position) - DVec3::new(1.0, -2.0, h);
        let cos = h / d.length();
        let want = i0 * cos.powi(3) / (h * h);
        assert_close!(p.e_lux, want, rel = 1e-12, "{:?}: {} vs {want}", p.position, p.e_lux);
    }
    let rc = &r.receivers[0];
    let mean = rc.points.iter().map(|p| p.e_lux).sum::<f64>() / 63.0;
    assert_close!(rc.e_avg_lux, mean, rel = 1e-12);
    assert_close!(rc.u0.unwrap(), rc.e_min_lux / rc.e_avg_lux, abs = 1e-15);
    assert_close!(rc.emin_emax.unwrap(), rc.e_min_lux / rc.e_max_lux, abs = 1e-15);
    // The aim is undone: the same lamp turned any way gives the same light.
    let mut turned = s.clone();
    turned.luminaires[0].pose = Pose::new(
        DVec3::new(1.0, -2.0, h),
        Aim {
            orient: 33.0,
            tilt: 71.0,
            roll: -20.0,
            spin: 5.0,
        },
    );
    let r2 = evaluate(&turned, None).unwrap();
    for (a, b) in r.receivers[0].points.iter().zip(&r2.receivers[0].points) {
        assert_close!(b.e_lux, a.e_lux, rel = 1e-12);
    }
}

#[test]
fn ten_thousand_lumen_isotropic_source_three_metres_above_a_point_gives_88_42_lux() {
    let i0 = 10_000.0 / (4.0 * PI);
    let lum = synth(Synth::Isotropic, i0);
    let flux = photosolid::photometry::flux(lum.distribution()).total_lm;
    assert_close!(flux, 10_000.0, abs = 1e-6, "{flux}");
    let s = scene(
        vec![placed("iso", lum, DVec3::new(0.0, 0.0, 3.0), Aim::default())],
        vec![Receiver::point("p", DVec3::ZERO, DVec3::Z)],
    );
    let r = evaluate(&s, None).unwrap();
    let e = r.receivers[0].e_avg_lux;
    assert_close!(e, 88.42, abs = 0.005, "{e}");
    assert_eq!(r.receivers[0].e_min_lux, e);
    assert_eq!(r.receivers[0].e_max_lux, e);
    // Maintenance factor scales linearly.
    let mut m = s.clone();
    m.luminaires[0].maintenance_factor = 0.8;
    assert_close!(
        evaluate(&m, None).unwrap().receivers[0].e_avg_lux,
        0.8 * e,
        abs = 1e-12 * e
    );
}

/// A Lambertian opening of luminance `l` as a luminaire: I = L·A·cos γ, closed form.
fn lambertian_opening(l: f64, opening: Opening, area: f64) -> SceneLuminaire {
    let mut lum = placed(
        "lambert",
        synth(Synth::Lambertian, l * area),
        DVec3::new(0.0, 0.0, 0.0),
        Aim::default(),
    );
    lum.opening = opening;
    lum
}

fn at(position: DVec3, normal: DVec3) -> ScenePoint {
    ScenePoint {
        position,
        normal,
        receiver: 0,
        index: 0,
    }
}

#[test]
fn lambertian_disk_on_axis_closed_form_and_the_subdivided_source_converges_to_it() {
    let (l, r) = (5000.0, 0.3);
    let truth = Synth::Lambertian.truth(l * PI * r * r);
    let disk = Opening::Ellipse {
        length_m: 2.0 * r,
        width_m: 2.0 * r,
    };
    for z in [0.15, 0.3, 0.6, 1.5] {
        let want = lambert_disk_on_axis_lux(l, r, z);
        assert_close!(PI * l * r * r / (r * r + z * z), want, rel = 1e-9);
        let p = at(DVec3::new(0.0, 0.0, -z), DVec3::Z);
        let mut last = f64::INFINITY;
        for n in [1, 2, 4, 8, 16, 32, 64] {
            let src = Source {
                field: &truth,
                pose: Pose::new(DVec3::ZERO, Aim::default()),
                maintenance_factor: 1.0,
                patches: disk.patches(n),
            };
            let err = (src.lux(&p, &[]) - want).abs() / want;
            assert!(err <= last * 1.0001, "z {z} n {n}: {err} after {last}");
            last = err;
        }
        assert!(last < 1e-3, "z {z}: {last}");
        // The point source is off by r²/z² relatively (the 1/(z² + r²) falloff).
        let point = truth.intensity_dir_cd(DVec3::new(0.0, 0.0, -1.0)) / (z * z);
        assert_close!((point - want) / want, r * r / (z * z), abs = 1e-9);
    }
    // Through the scene (measured grid, Catmull-Rom, refined to convergence).
    let lum = lambertian_opening(l, disk, PI * r * r);
    let s = scene(
        vec![lum],
        vec![Receiver::point("axis", DVec3::new(0.0, 0.0, -0.6), DVec3::Z)],
    );
    let res = evaluate(&s, None).unwrap();
    let want = lambert_disk_on_axis_lux(l, r, 0.6);
    assert_close!(
        res.receivers[0].e_avg_lux,
        want,
        rel = 1e-3,
        "{} vs {want}",
        res.receivers[0].e_avg_lux
    );
    assert!(res.luminaires[0].area.converged);
    assert_eq!(res.luminaires[0].source, SourceKind::Area);
}

#[test]
fn rectangle_against_the_closed_form_form_factor_lambert_and_subdivision() {
    let (l, a, b) = (2000.0, 0.8, 0.5);
    let verts = [
        DVec3::new(-a / 2.0, -b / 2.0, 0.0),
        DVec3::new(-a / 2.0, b / 2.0, 0.0),
        DVec3::new(a / 2.0, b / 2.0, 0.0),
        DVec3::new(a / 2.0, -b / 2.0, 0.0),
    ];
    let truth = Synth::Lambertian.truth(l * a * b);
    let rect = Opening::Rectangle {
        length_m: a,
        width_m: b,
    };
    // Receivers below the rectangle, parallel: split at the foot point into corner rectangles.
    for (x, y, z) in [(0.0, 0.0, 0.4), (0.1, -0.05, 0.3), (0.4, 0.25, 1.0), (0.2, 0.1, 3.0)] {
        let (x0, x1, y0, y1) = (x + a / 2.0, a / 2.0 - x, y + b / 2.0, b / 2.0 - y);
        let f: f64 = [(x0, y0), (x0, y1), (x1, y0), (x1, y1)]
            .iter()
            .map(|&(u, v)| corner_rectangle_form_factor(u, v, z))
            .sum();
        let want = PI * l * f;
        let p = DVec3::new(x, y, -z);
        let lam = lambert_polygon_lux(&verts, l, p, DVec3::Z);
        assert_close!(lam, want, rel = 1e-12, "({x}, {y}, {z}): {lam} vs {want}");
        let mut last = f64::INFINITY;
        for n in [1, 2, 4, 8, 16, 32, 64, 128] {
            let src = Source {
                field: &truth,
                pose: Pose::new(DVec3::ZERO, Aim::default()),
                maintenance_factor: 1.0,
                patches: rect.patches(n),
            };
            let err = (src.lux(&at(p, DVec3::Z), &[]) - want).abs() / want;
            assert!(err <= last * 1.0001 + 1e-13, "n {n}: {err} after {last}");
            last = err;
        }
        assert!(last < 1e-4, "({x}, {y}, {z}): {last}");
    }
}

#[test]
fn far_receivers_let_the_plan_pick_a_compact_model_or_a_coarse_texture() {
    let lum = cos5_square_opening(60.0, 0.5);
    let plane = Receiver::plane(
        "field",
        DVec3::new(-30.0, -30.0, 0.0),
        DVec3::new(60.0, 0.0, 0.0),
        DVec3::new(0.0, 60.0, 0.0),
        8,
        8,
    );
    let s = scene(vec![lum], vec![plane]);
    let p = plan_timed(&s, 512);
    let l = &p.luminaires[0];
    assert!(l.far_field_ok && l.far_field.five_times_rule_holds);
    assert_eq!(l.source, SourceKind::Point, "{}", l.chosen);
    // A cos^5 lobe seen from afar: a compact model (fitted lights, a lobe
    // mixture, low-order harmonics) or the coarsest texture suffices.
    let coarse = l.representation == "fitted-gl"
        || l.representation.starts_with("lobes:")
        || l.representation.starts_with("sh:")
        || l.representation.starts_with("catmull-rom@x1/");
    assert!(l.bytes <= 2048, "chose {} ({} bytes)", l.chosen, l.bytes);
    assert!(coarse, "chose {}", l.chosen);
    assert!(l.max_error_pct <= 1.0 && l.max_error_pct >= l.mean_error_pct);
    // The achieved error is measured: evaluating the chosen representation on the scene gives it again.
    let mut chosen = s.clone();
    chosen.luminaires[0].representation = Some(l.representation.parse().unwrap());
    chosen.luminaires[0].source = Some(SourceKind::Point);
    let reference = evaluate(&s, None).unwrap();
    let got = evaluate(&chosen, None).unwrap();
    let max = reference.receivers[0]
        .points
        .iter()
        .zip(&got.receivers[0].points)
        .map(|(a, b)| (a.e_lux - b.e_lux).abs() / a.e_lux)
        .fold(0.0, f64::max);
    assert_close!(
        100.0 * max,
        l.max_error_pct,
        abs = 1e-9 + 1e-6 * l.max_error_pct,
        "{} vs {}",
        100.0 * max,
        l.max_error_pct
    );
    // Everything cheaper than the choice was rejected with an error over the tolerance.
    assert!(l.rejected.iter().all(|c| c.max_error_pct > 1.0));
}

#[test]
fn a_receiver_at_one_luminaire_size_forces_the_area_source() {
    let lum = cos5_square_opening(3.0, 0.6);
    let size = lum.opening.largest_dimension_m();
    let s = scene(
        vec![lum],
        vec![
            Receiver::point("close", DVec3::new(0.0, 0.0, 3.0 - size), DVec3::Z),
            Receiver::plane(
                "floor",
                DVec3::new(-3.0, -3.0, -3.0),
                DVec3::new(6.0, 0.0, 0.0),
                DVec3::new(0.0, 6.0, 0.0),
                4,
                4,
            ),
        ],
    );
    let p = plan_timed(&s, 512);
    let l = &p.luminaires[0];
    assert_eq!(l.source, SourceKind::Area, "{}", l.chosen);
    assert!(!l.far_field_ok);
    assert!(l.far_field.max_error_pct > 1.0, "{}", l.far_field.max_error_pct);
    assert!(l
        .rejected
        .iter()
        .any(|c| c.source == SourceKind::Point && c.representation == "catmull-rom"));
    // The five-times rule measured: the floor (about 7 sizes away) is under 1 %, the close point is not.
    let ratio = l.far_field.ratio_under_1pct.unwrap();
    assert!(ratio > 1.0 && ratio <= 8.0, "{ratio}");
    assert!(l.far_field.five_times_rule_holds);
}

/// `source = "point"` is honoured by `plan` as by `scene`: the same close receiver that
/// forces the area source above is measured against the point source, and only point
/// sources are candidates.
#[test]
fn plan_honours_a_point_source_the_scene_asks_for() {
    let mut lum = cos5_square_opening(3.0, 0.6);
    lum.source = Some(SourceKind::Point);
    let size = lum.opening.largest_dimension_m();
    let s = scene(
        vec![lum],
        vec![Receiver::point("close", DVec3::new(0.0, 0.0, 3.0 - size), DVec3::Z)],
    );
    let p = plan_timed(&s, 512);
    let l = &p.luminaires[0];
    assert!(l.reference.ends_with("point source"), "{}", l.reference);
    assert_eq!(l.source, SourceKind::Point, "{}", l.chosen);
    assert!(
        l.rejected.iter().all(|c| c.source == SourceKind::Point),
        "{:?}",
        l.rejected
    );
    // The scene's own result with the chosen representation is what plan measured.
    assert!(l.max_error_pct <= 1.0, "{}", l.max_error_pct);
    let e = evaluate(&s, None).unwrap();
    assert_eq!(e.luminaires[0].source, SourceKind::Point);
}

#[test]
fn extremes_never_give_nan() {
    let iso = || synth(Synth::Isotropic, 1000.0);
    let h = 3.0;
    // A receiver on the source's plane, facing up: 0; facing the source: I/r².
    let on_plane = vec![
        Receiver::point("up", DVec3::new(5.0, 0.0, h), DVec3::Z),
        Receiver::point("facing", DVec3::new(5.0, 0.0, h), -DVec3::X),
        Receiver::point("grazing", DVec3::new(1e5, 0.0, 0.0), DVec3::Z),
    ];
    let mut area = placed("iso", iso(), DVec3::new(0.0, 0.0, h), Aim::default());
    area.opening = Opening::Rectangle {
        length_m: 1.0,
        width_m: 1.0,
    };
    for lum in [placed("iso", iso(), DVec3::new(0.0, 0.0, h), Aim::default()), area] {
        let r = evaluate(&scene(vec![lum], on_plane.clone()), None).unwrap();
        assert!(all_finite(&r));
        assert_eq!(r.receivers[0].e_avg_lux, 0.0);
        assert_eq!(r.receivers[0].u0, None);
        assert_close!(r.receivers[1].e_avg_lux, 1000.0 / 25.0, abs = 0.02 * 40.0);
        let g = r.receivers[2].e_avg_lux;
        let want = 1000.0 * h / (1e10 + h * h).powf(1.5);
        assert!(g > 0.0, "{g} vs {want}");
        assert_close!(g, want, rel = 1e-6, "{g} vs {want}");
    }
    // A point inside the opening: a clear error naming the receiver.
    let mut lum = placed("lamp", iso(), DVec3::new(0.0, 0.0, h), Aim::default());
    lum.opening = Opening::Rectangle {
        length_m: 1.0,
        width_m: 0.5,
    };
    let bad = scene(
        vec![lum],
        vec![Receiver::point("in", DVec3::new(0.2, 0.1, h), DVec3::Z)],
    );
    let e = evaluate(&bad, None).unwrap_err();
    assert!(matches!(e, SceneError::InsideOpening { .. }));
    assert!(
        e.to_string().contains("\"in\"") && e.to_string().contains("\"lamp\""),
        "{e}"
    );
    assert!(plan(&bad, &PlanOptions::default(), None).is_err());
    let centre = scene(
        vec![placed("lamp", iso(), DVec3::new(0.0, 0.0, h), Aim::default())],
        vec![Receiver::point("at", DVec3::new(0.0, 0.0, h), DVec3::Z)],
    );
    assert!(matches!(evaluate(&centre, None), Err(SceneError::InsideOpening { .. })));
    // An all-zero luminaire and one aimed away from every receiver: 0 lx, plans still made.
    let gamma: Vec<f64> = (0..=36).map(|k| k as f64 * 5.0).collect();
    let zero = Distribution::new(vec![0.0], gamma.clone(), vec![0.0; gamma.len()], Symmetry::Rotational).unwrap();
    let dark = placed(
        "dark",
        Luminaire::from_distribution(zero),
        DVec3::new(0.0, 0.0, h),
        Aim::default(),
    );
    let away = placed(
        "away",
        synth(Synth::CosinePower { p: 5.0 }, 1000.0),
        DVec3::new(2.0, 0.0, h),
        Aim {
            tilt: 180.0,
            ..Default::default()
        },
    );
    let floor = Receiver::plane(
        "floor",
        DVec3::new(-5.0, -5.0, 0.0),
        DVec3::new(10.0, 0.0, 0.0),
        DVec3::new(0.0, 10.0, 0.0),
        5,
        5,
    );
    for lum in [dark, away] {
        let s = scene(vec![lum], vec![floor.clone()]);
        let r = evaluate(&s, None).unwrap();
        assert!(all_finite(&r));
        assert_eq!(r.receivers[0].e_max_lux, 0.0);
        assert_eq!(r.receivers[0].emin_emax, None);
        let p = plan_timed(&s, 256);
        assert!(p.luminaires[0].max_error_pct == 0.0 && p.combined_max_error_pct == 0.0);
        assert!(!serde_json::to_string(&p).unwrap().contains("NaN"));
    }
}

#[test]
fn an_occluder_casts_a_shadow() {
    let lum = placed(
        "iso",
        synth(Synth::Isotropic, 1000.0),
        DVec3::new(0.0, 0.0, 4.0),
        Aim::default(),
    );
    let mut s = scene(
        vec![lum],
        vec![
            Receiver::point("shadowed", DVec3::new(0.0, 0.0, 0.0), DVec3::Z),
            Receiver::point("lit", DVec3::new(3.0, 0.0, 0.0), DVec3::Z),
        ],
    );
    s.occluders.push(
        photosolid::scene::Occluder::new(vec![
            DVec3::new(-0.5, -0.5, 2.0),
            DVec3::new(0.5, -0.5, 2.0),
            DVec3::new(0.5, 0.5, 2.0),
            DVec3::new(-0.5, 0.5, 2.0),
        ])
        .unwrap(),
    );
    let r = evaluate(&s, None).unwrap();
    assert_eq!(r.receivers[0].e_avg_lux, 0.0);
    assert_close!(r.receivers[1].e_avg_lux, 1000.0 * 4.0 / 125.0, abs = 1e-9);
}

pub(crate) fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

#[test]
fn the_example_scene_loads_and_bad_files_name_the_line() {
    let s = Scene::load(&root().join("data/road_scene.toml")).unwrap();
    assert_eq!(s.luminaires.len(), 2);
    assert_eq!(
        s.receivers[0].points.len(),
        16 * 3,
        "EN 12464-1 spacing on 40 m: 2.62 m"
    );
    assert_close!(s.luminaires[0].maintenance_factor, 0.8, abs = 1e-15);
    // aim_at points the nadir at the target.
    let nadir = s.luminaires[1].pose.nadir();
    assert!((nadir - (DVec3::new(15.0, 2.5, 0.0) - DVec3::new(15.0, -1.0, 8.0)).normalize()).length() < 1e-12);
    let r = evaluate(&s, None).unwrap();
    assert!(all_finite(&r));
    let dir = root().join("data");
    let cases = [
        ("[[luminaire]]\nfile = \"roadway.ldt\"\nposition = [0, 0]\n", 3, "position"),
        ("\n[[luminaire]]\nfile = \"roadway.ldt\"\nposition = [0.0, 0.0, 8.0]\nmaintenance_factor = 1.5\n", 5, "maintenance_factor"),
        ("[[receiver]]\nname = \"r\"\nkind = \"plane\"\norigin = [0.0, 0.0, 0.0]\nu = [1.0, 0.0, 0.0]\nv = [2.0, 0.0, 0.0]\nspacing = \"en12464\"\n", 1, "non-parallel"),
        ("[[receiver]]\nname = \"r\"\nkind = \"plane\"\norigin = [0.0, 0.0, 0.0]\nu = [1e6, 0.0, 0.0]\nv = [0.0, 1e6, 0.0]\nspacing = [0.001, 0.001]\n", 1, "coarser"),
        ("[[luminaire]]\nfile = \"missing.ldt\"\nposition = [0.0, 0.0, 8.0]\n", 2, "missing.ldt"),
        ("[[luminaire]]\nfile = \"roadway.ldt\"\nposition = [0.0, 0.0, 8.0]\ncolour = 3\n", 4, "colour"),
        ("[[luminaire]]\nfile = \"roadway.ldt\"\nposition = [0.0, 0.0, 8.0]\nrepresentation = \"cubic\"\n", 4, "representation"),
    ];
    for (text, line, word) in cases {
        let e = Scene::from_toml(text, &dir.join("bad.toml")).unwrap_err().to_string();
        assert!(
            e.contains(&format!("bad.toml:{line}:")) && e.contains(word),
            "{text:?}: {e}"
        );
    }
    // A key's error names its column too (here an indented key).
    let e = Scene::from_toml(
        "[[luminaire]]\nfile = \"roadway.ldt\"\nposition = [0.0, 0.0, 8.0]\n  maintenance_factor = 1.5\n",
        &dir.join("bad.toml"),
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("bad.toml:4:3: luminaire #1: maintenance_factor"), "{e}");
}

#[test]
fn the_cli_writes_the_contract_keys_and_isolux_maps() {
    let t = tempfile::tempdir().unwrap();
    let scene_path = root().join("data/road_scene.toml");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_photosolid"))
        .args(["scene", scene_path.to_str().unwrap(), "--json", "--report"])
        .arg(t.path())
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let receivers = v["receivers"].as_array().unwrap();
    for r in receivers {
        for key in [
            "name",
            "e_avg_lux",
            "e_min_lux",
            "e_max_lux",
            "u0",
            "emin_emax",
            "points",
        ] {
            assert!(r.get(key).is_some(), "{key}");
        }
        let p = &r["points"][0];
        assert!(p["position"].as_array().unwrap().len() == 3 && p["e_lux"].as_f64().unwrap().is_finite());
    }
    let sensor = receivers.iter().find(|r| r["name"] == "sensor").unwrap();
    assert_eq!(sensor["e_avg_lux"], sensor["e_min_lux"]);
    // The isolux maps: the size we draw; pole 1 (x = -15, y = -1) lies on the sidewalk's far edge
    // (s = 5/40, t = 1): a black dot there.
    use photosolid::report::plot::isolux::{MAP_LEFT, MAP_PIXELS as map_w, MAP_TOP};
    let road = tiny_skia::Pixmap::decode_png(&std::fs::read(t.path().join("isolux_1_road.png")).unwrap()).unwrap();
    assert_eq!(
        (road.width(), road.height()),
        (MAP_LEFT + map_w + 150, MAP_TOP + 160 + 88)
    );
    let walk = tiny_skia::Pixmap::decode_png(&std::fs::read(t.path().join("isolux_2_sidewalk.png")).unwrap()).unwrap();
    // A map shorter than its vertical axis title is centred in a band as tall as the title:
    // its top is the first coloured row under MAP_TOP.
    let top = (MAP_TOP..walk.height())
        .find(|&y| {
            let p = walk.pixel(MAP_LEFT + map_w / 2, y).unwrap();
            (p.red(), p.green(), p.blue()) != (255, 255, 255)
        })
        .unwrap()
        + 1;
    let (x, y) = (MAP_LEFT + map_w / 8, top);
    let px = walk.pixel(x, y).unwrap();
    assert!(
        px.red() < 30 && px.green() < 30 && px.blue() < 30,
        "{px:?} at ({x}, {y})"
    );
    // Away from the marks the map is false colour (viridis has no grey).
    let px = walk.pixel(MAP_LEFT + map_w / 2, top + 20).unwrap();
    assert!(px.red() != px.green() || px.green() != px.blue(), "{px:?}");
    assert!(t.path().join("scene.json").is_file());
    // plan --tolerance 1% --json: the contract keys.
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_photosolid"))
        .args(["plan", scene_path.to_str().unwrap(), "--tolerance", "1%", "--json"])
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["tolerance_pct"], 1.0);
    for l in v["luminaires"].as_array().unwrap() {
        for key in [
            "chosen",
            "bytes",
            "ns_per_eval",
            "max_error_pct",
            "mean_error_pct",
            "far_field_ok",
            "rejected",
        ] {
            assert!(l.get(key).is_some(), "{key}");
        }
        assert!(l["max_error_pct"].as_f64().unwrap() <= 1.0);
        for c in l["rejected"].as_array().unwrap() {
            assert!(c["max_error_pct"].as_f64().unwrap() > 1.0);
        }
    }
    let bad = std::process::Command::new(env!("CARGO_BIN_EXE_photosolid"))
        .args(["plan", scene_path.to_str().unwrap(), "--tolerance", "abc"])
        .output()
        .unwrap();
    assert!(!bad.status.success());
}
