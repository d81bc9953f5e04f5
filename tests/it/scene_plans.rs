//! Scenes, continued: planned representations (cropped grids, declared openings, the panel
//! office) and receivers no luminaire lights.

use glam::DVec3;
use photosolid::scene::aim::Aim;
use photosolid::scene::illuminance::evaluate;
use photosolid::scene::near_field::lambert_disk_on_axis_lux;
use photosolid::scene::opening::Opening;
use photosolid::scene::{Receiver, Scene};
use photosolid::synth::Synth;
use std::f64::consts::PI;

use super::scene::{placed, plan_timed, root, scene, synth};

#[test]
fn a_wall_seen_through_a_small_sector_is_planned_with_the_cropped_grid() {
    // The road luminaire (72 planes, gamma every 2.5 deg) 5 m up, a wall 10 m away along C0:
    // the scene sees gamma 63-84 deg and C within about 17 deg of C0.
    let lum = placed(
        "road",
        synth(Synth::Roadway, 12_000.0),
        DVec3::new(0.0, 0.0, 5.0),
        Aim::default(),
    );
    let wall = Receiver::plane(
        "wall",
        DVec3::new(10.0, 3.0, 0.0),
        DVec3::new(0.0, -6.0, 0.0),
        DVec3::new(0.0, 0.0, 4.0),
        6,
        4,
    );
    assert!(wall.normal.x < -0.99, "faces the luminaire");
    let s = scene(vec![lum], vec![wall]);
    let p = plan_timed(&s, 256);
    let l = &p.luminaires[0];
    assert!(
        l.representation.contains("+gamma:") && l.representation.contains("+c:"),
        "{}",
        l.chosen
    );
    assert_eq!(
        l.max_error_pct, 0.0,
        "the cropped grid answers exactly what the scene looks up"
    );
    let native = photosolid::reconstruct::LightTexture::new(s.luminaires[0].luminaire.distribution()).unwrap();
    assert!(l.bytes * 10 < native.bytes(), "{} vs {}", l.bytes, native.bytes());
}

#[test]
fn the_opening_a_file_declares_drives_the_area_source() {
    // A Lambertian disk of luminance L and radius r written as IES (W = L = -2r: a disk)
    // and as EULUMDAT (luminous diameter 2r, width 0), read back through a scene file.
    let (l, r) = (4000.0, 0.25);
    let t = tempfile::tempdir().unwrap();
    let mut lum = synth(Synth::Lambertian, l * PI * r * r);
    lum.set_luminous_opening(photosolid::model::Dimensions {
        length_m: -2.0 * r,
        width_m: -2.0 * r,
        height_m: 0.0,
    });
    photosolid::save(&lum.clone().into(), &t.path().join("disk.ies"), &Default::default()).unwrap();
    lum.set_luminous_opening(photosolid::model::Dimensions {
        length_m: 2.0 * r,
        width_m: 0.0,
        height_m: 0.0,
    });
    photosolid::save(&lum.clone().into(), &t.path().join("disk.ldt"), &Default::default()).unwrap();
    for file in ["disk.ies", "disk.ldt"] {
        let text = format!(
            "[[luminaire]]\nfile = \"{file}\"\nposition = [0.0, 0.0, 2.0]\n\n[[receiver]]\nname = \"axis\"\nkind = \"point\"\n\
             position = [0.0, 0.0, 1.5]\nnormal = [0.0, 0.0, 1.0]\n"
        );
        let path = t.path().join("s.toml");
        std::fs::write(&path, text).unwrap();
        let s = Scene::load(&path).unwrap();
        match s.luminaires[0].opening {
            Opening::Ellipse { length_m, width_m } => {
                assert_close!(length_m, 2.0 * r, abs = 1e-6, "{file}");
                assert_close!(width_m, 2.0 * r, abs = 1e-6, "{file}");
            }
            o => panic!("{file}: {o:?}"),
        }
        let res = evaluate(&s, None).unwrap();
        let want = lambert_disk_on_axis_lux(l, r, 0.5);
        let got = res.receivers[0].e_avg_lux;
        assert_close!(got, want, rel = 2e-3, "{file}: {got} vs {want}");
        let point = res.receivers[0].points[0].clone();
        assert_close!(point.far_field_error_pct / 100.0, r * r / 0.25, rel = 0.2, "{point:?}");
        assert_close!(point.distance_ratio.unwrap(), 1.0, abs = 1e-9);
    }
}

/// Issue 27, item 4: a receiver that no luminaire lights is warned about by
/// name with the reason (facing away, behind the luminaire, outside every
/// beam); an empty scene is an error; a missing file names the resolved path.
#[test]
fn unlit_receivers_are_named_and_empty_scenes_refused() {
    let t = tempfile::tempdir().unwrap();
    let spot = root().join("data/spot_p8_c40.ldt");
    let lum = format!(
        "[[luminaire]]\nfile = {:?}\nposition = [0.0, 0.0, 8.0]\n",
        spot.display().to_string()
    );
    let text = format!(
        "{lum}\n[[receiver]]\nname = \"floor\"\nkind = \"plane\"\norigin = [-5.0, -5.0, 0.0]\n\
         u = [0.0, 10.0, 0.0]\nv = [10.0, 0.0, 0.0]\nspacing = [1.0, 1.0]\n\n\
         [[receiver]]\nname = \"ceiling\"\nkind = \"point\"\nposition = [0.0, 0.0, 10.0]\nnormal = [0.0, 0.0, -1.0]\n\n\
         [[receiver]]\nname = \"far\"\nkind = \"point\"\nposition = [20.0, 0.0, 0.0]\nnormal = [0.0, 0.0, 1.0]\n\n\
         [[receiver]]\nname = \"lit\"\nkind = \"point\"\nposition = [0.0, 0.0, 0.0]\nnormal = [0.0, 0.0, 1.0]\n"
    );
    let path = t.path().join("s.toml");
    std::fs::write(&path, &text).unwrap();
    let r = evaluate(&Scene::load(&path).unwrap(), None).unwrap();
    assert_eq!(r.warnings.len(), 3, "{:?}", r.warnings);
    let says = |name: &str, why: &str| {
        assert!(
            r.warnings.iter().any(|w| w.code == "receiver-unlit"
                && w.message.contains(&format!("receiver {name:?}"))
                && w.message.contains(why)),
            "{name}: {why}: {:?}",
            r.warnings
        )
    };
    says("floor", "faces away");
    says("floor", "swap u and v");
    says("ceiling", "behind");
    says("far", "outside every beam");
    // The CLI prints them on stderr and still succeeds; JSON carries them.
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_photosolid"))
        .args(["scene", path.to_str().unwrap(), "--json"])
        .output()
        .unwrap();
    assert!(o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("warning: [receiver-unlit] receiver \"floor\" gets no light"),
        "{err}"
    );
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let warnings = v["warnings"].as_array().unwrap();
    assert_eq!(warnings.len(), 3);
    assert!(warnings.iter().all(|w| w["code"] == "receiver-unlit"), "{warnings:?}");

    // No receivers, no luminaires: errors (exit 1), not 0 lx.
    for (text, word) in [
        (lum.clone(), "no receivers"),
        (
            "[[receiver]]\nname = \"r\"\nkind = \"point\"\nposition = [0.0, 0.0, 0.0]\nnormal = [0.0, 0.0, 1.0]\n"
                .into(),
            "no luminaires",
        ),
        (String::new(), "no luminaires"),
    ] {
        std::fs::write(&path, &text).unwrap();
        let e = Scene::load(&path).unwrap_err().to_string();
        assert!(e.contains(word), "{e}");
        let o = std::process::Command::new(env!("CARGO_BIN_EXE_photosolid"))
            .args(["scene", path.to_str().unwrap()])
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(1), "{word}");
    }
    // A missing file: the line of `file`, the resolved path, the reason once.
    std::fs::write(
        &path,
        "[[luminaire]]\nposition = [0.0, 0.0, 8.0]\nfile = \"nothere.ldt\"\n",
    )
    .unwrap();
    let e = Scene::load(&path).unwrap_err().to_string();
    let resolved = t.path().join("nothere.ldt");
    assert!(
        e.contains("s.toml:3:") && e.contains(&resolved.display().to_string()),
        "{e}"
    );
    assert_eq!(e.matches("nothere.ldt").count(), 2, "{e}");
}

/// The panel office at working scale (data/office_panels.toml: six 600 x 600 mm panels as area
/// sources, 343 points): `scene` names the patches of area sources only, and `plan` measures
/// candidates cheapest first up to the first within the tolerance (timed in BENCHMARKS.md).
#[test]
fn the_panel_office_is_planned_cheapest_first() {
    use crate::common::cli::{ok, run};
    let t = tempfile::tempdir().unwrap();
    let d = t.path();
    for f in ["office_panels.toml", "batwing.ldt"] {
        std::fs::copy(root().join("data").join(f), d.join(f)).unwrap();
    }
    let text = ok(&run(&["scene", "office_panels.toml"], d));
    assert!(
        text.contains("area source (4096 patches)") && text.contains("343"),
        "{text}"
    );
    let toml = std::fs::read_to_string(d.join("office_panels.toml")).unwrap();
    std::fs::write(
        d.join("points.toml"),
        toml.replace("source = \"area\"", "source = \"point\""),
    )
    .unwrap();
    let text = ok(&run(&["scene", "points.toml"], d));
    assert!(text.contains("point source, ") && !text.contains("patches"), "{text}");
    let v: serde_json::Value = serde_json::from_str(&ok(&run(&["plan", "office_panels.toml", "--json"], d))).unwrap();
    let lums = v["luminaires"].as_array().unwrap();
    assert_eq!(lums.len(), 6);
    for l in lums {
        let (bytes, max) = (l["bytes"].as_u64().unwrap(), l["max_error_pct"].as_f64().unwrap());
        assert!(max <= 1.0, "{l}");
        // Every candidate measured before the chosen one is over the tolerance and no dearer.
        let rejected = l["rejected"].as_array().unwrap();
        assert_eq!(rejected.len() + 1, l["candidates"].as_u64().unwrap() as usize);
        for c in rejected {
            assert!(
                c["max_error_pct"].as_f64().unwrap() > 1.0 && c["bytes"].as_u64().unwrap() <= bytes,
                "{c}"
            );
        }
        assert!(l["candidates_not_measured"].as_u64().unwrap() > 0, "{l}");
    }
    assert!(v["warnings"].as_array().unwrap().is_empty());
}
