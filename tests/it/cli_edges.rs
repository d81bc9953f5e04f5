//! The CLI where a new user hit wrong outputs and rough edges (issue 12):
//! the real binary, run in a temporary directory per test.

use crate::common;

use common::cli::{bin, fails, ok, run, write_ies};
use photosolid::solid::{export, topology};

/// A downlight dark at nadir and above the horizontal: two sheets meet at the
/// origin (a dimple under a flat top). Every written format must read back
/// watertight and manifold, and `--json` must say so from a real check.
#[test]
fn mesh_json_reports_the_written_files_topology() {
    let t = tempfile::tempdir().unwrap();
    let gamma: Vec<f64> = (0..=18).map(|k| 10.0 * k as f64).collect();
    let cd: Vec<f64> = gamma
        .iter()
        .map(|&g| if g > 0.0 && g <= 90.0 { 100.0 } else { 0.0 })
        .collect();
    write_ies(t.path(), "dimple.ies", 1000.0, &gamma, &cd);
    for ext in ["ply", "obj", "stl", "glb"] {
        let out = format!("s.{ext}");
        let v: serde_json::Value = serde_json::from_str(&ok(&run(
            &["mesh", "dimple.ies", "--measured", "-o", &out, "--json"],
            t.path(),
        )))
        .unwrap();
        assert_eq!(v["origin_sheets"], 2, "{ext}: {v}");
        assert_eq!(
            (&v["watertight"], &v["manifold"], &v["components"]),
            (&true.into(), &true.into(), &1.into()),
            "{ext}: {v}"
        );
        let back = export::read(&t.path().join(&out)).unwrap();
        let topo = topology(back.positions(), back.triangles());
        assert!(
            topo.watertight && topo.manifold && topo.components == 1,
            "{ext}: {topo:?}"
        );
        assert_eq!(v["vertices"], back.positions().len(), "{ext}");
    }
}

/// `texture`: the encoder follows the extension (PNG bytes in .png, EXR in .exr),
/// a flag/extension mismatch or no output at all is refused before rendering.
#[test]
fn texture_encoder_follows_the_extension_or_refuses() {
    let t = tempfile::tempdir().unwrap();
    ok(&run(&["synth", "isotropic", "-o", "iso.ldt"], t.path()));
    let tex = |extra: &[&str]| {
        let mut a = vec!["texture", "iso.ldt", "--backend", "cpu"];
        a.extend_from_slice(extra);
        run(&a, t.path())
    };
    ok(&tex(&["-o", "a.png"]));
    assert_eq!(
        &std::fs::read(t.path().join("a.png")).unwrap()[..8],
        b"\x89PNG\r\n\x1a\n"
    );
    ok(&tex(&["-o", "a.exr", "--png", "b.png"]));
    assert_eq!(
        &std::fs::read(t.path().join("a.exr")).unwrap()[..4],
        &[0x76, 0x2f, 0x31, 0x01]
    );
    assert_eq!(&std::fs::read(t.path().join("b.png")).unwrap()[..4], b"\x89PNG");
    let e = fails(&tex(&["--png", "c.exr"]), 1);
    assert!(e.contains("c.exr") && e.contains(".png"), "{e}");
    let e = fails(&tex(&["-o", "c.tif"]), 1);
    assert!(e.contains("c.tif") && e.contains(".exr"), "{e}");
    let e = fails(&tex(&[]), 1);
    assert!(e.contains("nothing to write"), "{e}");
    assert!(!t.path().join("c.exr").exists() && !t.path().join("c.tif").exists());
}

/// `gpu-check` that would check nothing fails, naming why, before looking for a GPU.
#[test]
fn gpu_check_that_checks_nothing_fails() {
    // Work one level down in a temporary directory the test owns, so that the
    // default corpus `../shared/corpus` is inside it and known to be absent,
    // wherever the repository and the system's temporary directory are.
    let t = tempfile::tempdir().unwrap();
    let work = t.path().join("work");
    std::fs::create_dir(&work).unwrap();
    assert!(!t.path().join("shared").exists());
    ok(&run(&["synth", "isotropic", "-o", "iso.ldt"], &work));
    ok(&run(&["mesh", "iso.ldt", "--measured", "-o", "m.ply"], &work));
    let e = fails(&run(&["gpu-check", "/nonexistent"], &work), 1);
    assert!(e.contains("/nonexistent") && e.contains("nothing to check"), "{e}");
    let e = fails(&run(&["gpu-check", "m.ply"], &work), 1);
    assert!(e.contains("checked nothing"), "{e}");
    // No argument: the default ../shared/corpus, which does not exist.
    let e = fails(&run(&["gpu-check"], &work), 1);
    assert!(e.contains("corpus") && e.contains("nothing to check"), "{e}");
}

/// Zero factors, zero steps and negative tolerances are usage errors (exit 2)
/// naming the flag, found before any file is read (the file does not exist).
#[test]
fn bad_numeric_arguments_are_refused_before_loading() {
    let t = tempfile::tempdir().unwrap();
    for args in [
        vec!["holdout", "missing.ies", "--drop-c", "0"],
        vec!["holdout", "missing.ies", "--drop-gamma", "0"],
        vec!["mesh", "missing.ies", "--measured", "--factor", "0", "-o", "m.ply"],
        vec!["texture", "missing.ies", "--factor", "0", "-o", "t.exr"],
        vec!["texture", "missing.ies", "--factor", "33", "-o", "t.exr"],
        vec!["texture", "missing.ies", "-o", "t.exr", "--exposure=-1"],
        vec!["gpu-check", "missing.ies", "--tolerance=-1e-5%"],
        vec!["compare", "missing.ies", "--tolerance=-0.1%"],
        vec!["compare", "missing.ies", "--factor", "0"],
        vec!["tradeoff", "missing.ies", "--factors", "1,0"],
        vec!["tradeoff", "missing.ies", "--repeats", "0"],
        vec!["fit", "missing.ies", "--tolerance=-1"],
        vec!["fit", "missing.ies", "--guard", "0%"],
        vec!["hausdorff", "a.ply", "b.ply", "--tolerance", "0"],
        vec!["synth", "isotropic", "--c-step", "0", "-o", "s.ldt"],
        vec!["synth", "isotropic", "-o", "s.ldt", "--gamma-step=-5"],
        vec!["synth", "isotropic", "--intensity", "nan", "-o", "s.ldt"],
        vec!["info", "missing.ies", "--tilt", "inf"],
    ] {
        let last = args
            .iter()
            .rev()
            .find(|a| a.starts_with("--") && **a != "--measured")
            .unwrap();
        let flag = last.split('=').next().unwrap();
        let e = fails(&run(&args, t.path()), 2);
        assert!(e.contains(flag) && !e.contains("missing.ies"), "{args:?}: {e}");
    }
    // Missing outputs and choices too: before the (missing) file is read.
    let e = fails(&run(&["mesh", "missing.ies", "-o", "m.ply"], t.path()), 1);
    assert!(e.contains("--measured") && !e.contains("missing.ies"), "{e}");
    let e = fails(&run(&["mesh", "missing.ies", "--measured", "-o", "m.xyz"], t.path()), 1);
    assert!(e.contains("m.xyz") && !e.contains("missing.ies"), "{e}");
}

/// Every command stops quietly with status 0 when its stdout is closed
/// before it writes (`| head -c1`), never with an error or a panic (101).
#[test]
fn closed_stdout_is_a_quiet_success() {
    let t = tempfile::tempdir().unwrap();
    ok(&run(&["synth", "batwing", "-o", "b.ldt"], t.path()));
    ok(&run(&["mesh", "b.ldt", "--measured", "-o", "b.ply"], t.path()));
    for args in [
        vec!["validate", "--json", "b.ldt"],
        vec!["validate", "b.ldt"],
        vec!["info", "b.ldt", "--json"],
        vec!["fit", "b.ldt", "--json", "--max-lights", "1"],
        vec!["texture", "b.ldt", "--backend", "cpu", "-o", "t.exr"],
        vec!["mesh", "b.ldt", "--measured", "-o", "m.ply", "--json"],
        vec!["grid", "b.ldt", "--csv"],
        vec!["holdout", "b.ldt", "--filters", "bilinear"],
        vec!["hausdorff", "b.ply", "b.ply"],
        vec!["synth", "isotropic", "-o", "i.ldt"],
        vec!["convert", "b.ldt", "b2.ies"],
    ] {
        let mut child = bin()
            .args(&args)
            .current_dir(t.path())
            .stdout(std::process::Stdio::piped())
            .stderr(std::process::Stdio::piped())
            .spawn()
            .unwrap();
        drop(child.stdout.take()); // the reader is gone before anything is written
        let o = child.wait_with_output().unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(0), "{args:?}: {err}");
        assert!(
            !err.contains("Broken pipe") && !err.contains("panicked"),
            "{args:?}: {err}"
        );
    }
}

/// I/O errors name the path once; the OS message is not repeated.
#[test]
fn io_errors_name_the_path_once() {
    let t = tempfile::tempdir().unwrap();
    let e = fails(&run(&["info", "nope.ies"], t.path()), 1);
    assert!(e.contains("nope.ies"), "{e}");
    let os = "No such file or directory";
    assert_eq!(e.matches(os).count(), 1, "{e}");
    // An output directory that cannot be created: under a regular file.
    std::fs::write(t.path().join("file"), "x").unwrap();
    let e = fails(&run(&["demo", "-o", "file/demo"], t.path()), 1);
    assert!(e.contains("file/demo"), "{e}");
    let o = run(&["validate", "no-dir"], t.path());
    let out = String::from_utf8_lossy(&o.stdout);
    assert_eq!(o.status.code(), Some(1));
    assert_eq!(out.matches(os).count(), 1, "{out}");
}

/// Mesa's "XDG_RUNTIME_DIR is invalid or not set" must not reach the user
/// when the variable is unset (the CLI gives the drivers a private directory).
#[test]
fn gpu_runs_without_xdg_runtime_dir_print_no_driver_noise() {
    let t = tempfile::tempdir().unwrap();
    ok(&run(&["synth", "isotropic", "-o", "iso.ldt"], t.path()));
    let o = bin()
        .args(["texture", "iso.ldt", "--backend", "auto", "-o", "t.exr"])
        .env_remove("XDG_RUNTIME_DIR")
        .current_dir(t.path())
        .output()
        .unwrap();
    ok(&o);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!err.contains("XDG_RUNTIME_DIR"), "{err}");
}

/// `hausdorff` reads every format `mesh` writes: the same solid in PLY, STL
/// and GLB is at distance 0 from itself across formats.
#[test]
fn hausdorff_reads_every_written_format() {
    let t = tempfile::tempdir().unwrap();
    ok(&run(&["synth", "batwing", "-o", "b.ldt"], t.path()));
    for ext in ["ply", "obj", "stl", "glb"] {
        ok(&run(
            &[
                "mesh",
                "b.ldt",
                "--filter",
                "bilinear",
                "--factor",
                "2",
                "-o",
                &format!("b.{ext}"),
            ],
            t.path(),
        ));
    }
    for (a, b) in [("b.ply", "b.stl"), ("b.stl", "b.glb"), ("b.glb", "b.obj")] {
        let v: serde_json::Value = serde_json::from_str(&ok(&run(&["hausdorff", a, b, "--json"], t.path()))).unwrap();
        // OBJ stores text: allow its rounding, relative to the solid's size.
        assert!(v["hausdorff"].as_f64().unwrap() < 1e-3, "{a} {b}: {v}");
        assert_eq!(v["triangles"][0], v["triangles"][1], "{a} {b}");
    }
}

/// A file renamed to the other format's extension: the error says what the content looks like.
#[test]
fn extension_and_content_disagreeing_is_named() {
    let t = tempfile::tempdir().unwrap();
    ok(&run(&["synth", "batwing", "-o", "b.ldt"], t.path()));
    ok(&run(&["synth", "batwing", "-o", "b.ies"], t.path()));
    std::fs::copy(t.path().join("b.ldt"), t.path().join("ldt-renamed.ies")).unwrap();
    std::fs::copy(t.path().join("b.ies"), t.path().join("ies-renamed.ldt")).unwrap();
    let e = fails(&run(&["info", "ldt-renamed.ies"], t.path()), 1);
    assert!(
        e.contains("looks like EULUMDAT") && e.contains("rename it to .ldt"),
        "{e}"
    );
    let e = fails(&run(&["info", "ies-renamed.ldt"], t.path()), 1);
    assert!(e.contains("looks like IES") && e.contains("rename it to .ies"), "{e}");
}

/// cd/klm is per 1000 lm of *lamp* flux (EULUMDAT practice); `flux` is the
/// equal-luminaire-flux scaling; absolute files refuse klm with a reason.
#[test]
fn klm_is_lamp_flux_and_flux_is_equal_flux() {
    let t = tempfile::tempdir().unwrap();
    let gamma: Vec<f64> = (0..=36).map(|k| 5.0 * k as f64).collect();
    let cd = vec![100.0; gamma.len()];
    write_ies(t.path(), "iso.ies", 2000.0, &gamma, &cd);
    write_ies(t.path(), "abs.ies", -1.0, &gamma, &cd);
    let volume = |file: &str, units: &str| -> f64 {
        let v: serde_json::Value = serde_json::from_str(&ok(&run(
            &["mesh", file, "--measured", "--units", units, "-o", "m.ply", "--json"],
            t.path(),
        )))
        .unwrap();
        v["volume"].as_f64().unwrap()
    };
    let sphere = |r: f64| 4.0 / 3.0 * std::f64::consts::PI * r.powi(3);
    // 100 cd per 2000 lm of lamp flux = 50 cd/klm.
    let v = volume("iso.ies", "klm");
    assert_close!(v, sphere(50.0), rel = 0.01, "klm: {v}");
    // Equal flux: the 100 cd sphere emits 400 pi lm: 1000 * 100 / (400 pi) cd/klm.
    let v = volume("iso.ies", "flux");
    assert_close!(v, sphere(250.0 / std::f64::consts::PI), rel = 0.01, "flux: {v}");
    let e = fails(
        &run(
            &["mesh", "abs.ies", "--measured", "--units", "klm", "-o", "m.ply"],
            t.path(),
        ),
        1,
    );
    assert!(e.contains("absolute photometry") && e.contains("--units flux"), "{e}");
    let e = fails(
        &run(
            &["compare", "abs.ies", "--normalize", "klm", "--recon", "bilinear"],
            t.path(),
        ),
        1,
    );
    assert!(e.contains("absolute photometry"), "{e}");
    let o = ok(&run(
        &[
            "compare",
            "iso.ies",
            "--normalize",
            "flux",
            "--recon",
            "bilinear",
            "--json",
        ],
        t.path(),
    ));
    assert!(o.contains("luminaire flux"), "{o}");
}

/// Numbers: a written IES file carries no arithmetic noise (0.1 x 3 is
/// written 0.3, not 0.30000000000000004); the compare table prints every
/// number with the same 4 significant digits (no 7.5821e-1 next to 6.427).
#[test]
fn numbers_are_written_without_noise_and_tables_with_one_precision() {
    use photosolid::formats::ies::{write, IesWriteVersion};
    use photosolid::synth::{GridSpec, Synth};
    let mut lum = Synth::Isotropic
        .build(&GridSpec::uniform(90.0, 45.0).unwrap(), 0.1)
        .unwrap();
    let scaled = lum.distribution().scaled(3.0).unwrap();
    lum.set_distribution(scaled);
    assert_eq!(lum.distribution().max_cd(), 0.30000000000000004);
    let text = write(&lum.clone().into(), IesWriteVersion::Lm63_2002);
    assert!(!text.contains("0.30000000000000004"), "{text}");
    assert!(
        text.lines().last().unwrap().split_whitespace().all(|v| v == "0.3"),
        "{text}"
    );

    let t = tempfile::tempdir().unwrap();
    ok(&run(&["synth", "batwing", "-o", "b.ldt"], t.path()));
    let out = ok(&run(
        &["compare", "b.ldt", "--recon", "nearest,bilinear,catmull-rom"],
        t.path(),
    ));
    let rows: Vec<Vec<&str>> = out
        .lines()
        .skip_while(|l| !l.starts_with("reconstruction"))
        .skip(1)
        .take(3)
        .map(|l| l.split_whitespace().collect())
        .collect();
    assert_eq!(rows.len(), 3, "{out}");
    let significant = |cell: &str| -> Option<usize> {
        let v: f64 = cell.parse().ok()?;
        if v == 0.0 {
            return Some(0);
        }
        let mantissa = cell.trim_start_matches(['+', '-']).split('e').next().unwrap();
        let digits: String = mantissa.chars().filter(char::is_ascii_digit).collect();
        let digits = digits.trim_start_matches('0');
        Some(if mantissa.contains('.') {
            digits.len()
        } else {
            digits.trim_end_matches('0').len()
        })
    };
    for row in &rows {
        for cell in row.iter().skip(1).filter(|c| **c != "*") {
            if let Some(n) = significant(cell) {
                assert!(n <= 4, "{cell} in\n{out}");
                if n > 0 && cell.contains('.') && !cell.contains('e') {
                    assert_eq!(n, 4, "{cell} in\n{out}");
                }
            }
        }
    }
}

/// `info` names the definition of each beam angle row and shows the declared
/// lamp flux that LOR and cd/klm refer to (JSON `lamp_flux_lm`).
#[test]
fn info_names_beam_definitions_and_lamp_flux() {
    let t = tempfile::tempdir().unwrap();
    let gamma: Vec<f64> = (0..=18).map(|k| 10.0 * k as f64).collect();
    let cd: Vec<f64> = gamma
        .iter()
        .map(|&g| if g <= 90.0 { 100.0 * g.to_radians().cos() } else { 0.0 })
        .collect();
    write_ies(t.path(), "lamb.ies", 2000.0, &gamma, &cd);
    write_ies(t.path(), "abs.ies", -1.0, &gamma, &cd);
    let text = ok(&run(&["info", "lamb.ies"], t.path()));
    for want in [
        "50 % of I_max",
        "10 % of I_max",
        "50 % of centre I",
        "10 % of centre I",
        "C0-C180",
        "C90-C270",
    ] {
        assert!(text.contains(want), "{want} missing:\n{text}");
    }
    let lamp = text
        .lines()
        .find(|l| l.starts_with("lamp flux"))
        .unwrap_or_else(|| panic!("{text}"));
    assert!(lamp.contains("2000.00 lm"), "{lamp}");
    let v: serde_json::Value = serde_json::from_str(&ok(&run(&["info", "lamb.ies", "--json"], t.path()))).unwrap();
    assert_eq!(v["lamp_flux_lm"], 2000.0);
    // LOR is the computed flux over that lamp flux.
    let lor = v["lor"].as_f64().unwrap();
    assert_close!(lor, v["flux_lm"].as_f64().unwrap() / 2000.0, abs = 1e-9, "{v}");
    let v: serde_json::Value = serde_json::from_str(&ok(&run(&["info", "abs.ies", "--json"], t.path()))).unwrap();
    assert!(v["lamp_flux_lm"].is_null(), "{v}");
}

/// The README tells a new user where `demo` writes (checked against what it
/// does), how to put `photosolid` on the PATH, and what the test command costs.
#[test]
fn readme_says_where_demo_writes_and_how_to_install() {
    let readme = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/README.md")).unwrap();
    assert!(readme.contains("cargo install --path ."), "install line missing");
    assert!(
        readme.contains("SKIP group: reason") && readme.contains("GB"),
        "test command cost missing"
    );
    assert!(readme.contains("`out/demo/`"), "demo output directory missing");
    // The demo run the README tests share runs without --output.
    let (dir, _) = crate::common::cli::shared_demo();
    assert!(
        dir.join("out/demo/index.html").is_file(),
        "demo did not write out/demo/"
    );
}

/// Issue 27, item 1: in a directory, files whose names lost their extension
/// are read by their content, other files are skipped and counted, plurals
/// right; a walk that finds nothing photometric is exit 1 for validate and
/// batch (no empty table written).
#[test]
fn directories_read_files_without_extension_by_content_and_count_skips() {
    let t = tempfile::tempdir().unwrap();
    let data = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("data");
    let cat = t.path().join("cat");
    std::fs::create_dir(&cat).unwrap();
    std::fs::copy(data.join("cosine_p5.ies"), cat.join("TH_400MP_A15_SCWA_(LEG_12,_SC")).unwrap();
    std::fs::copy(data.join("batwing.ldt"), cat.join("BATWING_LDT")).unwrap();
    std::fs::copy(data.join("spot_p8_c40.ies"), cat.join("spot.ies")).unwrap();
    std::fs::write(cat.join("catalogue.pdf"), b"%PDF-1.4\n%\xe2\xe3\xcf\xd3\n1 0 obj\n").unwrap();
    std::fs::write(cat.join("photo.png"), b"\x89PNG\r\n\x1a\n\0\0\0\rIHDR").unwrap();
    std::fs::write(cat.join("README"), "Lamps: see the datasheets.\nTILT is none.\n").unwrap();

    let out = ok(&run(&["validate", "cat"], t.path()));
    assert!(out.contains("3 files, 3 ok, 0 failed"), "{out}");
    assert!(out.contains("TH_400MP_A15_SCWA_(LEG_12,_SC"), "{out}");
    assert!(
        out.contains("2 files without a photometric extension read by content"),
        "{out}"
    );
    assert!(out.contains("3 files skipped: not photometric"), "{out}");

    let out = ok(&run(&["batch", "cat", "-o", "t.parquet"], t.path()));
    assert!(out.contains("3 files (0 resumed, 3 analysed): 3 loaded"), "{out}");
    assert!(
        out.contains("2 files without a photometric extension read by content"),
        "{out}"
    );

    // One of each: singular.
    let one = t.path().join("one");
    std::fs::create_dir(&one).unwrap();
    std::fs::copy(data.join("batwing.ldt"), one.join("x")).unwrap();
    std::fs::write(one.join("y.pdf"), b"%PDF-1.4\n").unwrap();
    let out = ok(&run(&["validate", "one"], t.path()));
    assert!(out.contains("1 file, 1 ok, 0 failed"), "{out}");
    assert!(
        out.contains("1 file without a photometric extension read by content"),
        "{out}"
    );
    assert!(out.contains("1 file skipped: not photometric (one/y.pdf)"), "{out}");

    // Nothing photometric: an empty folder, a folder of other files.
    let empty = t.path().join("empty");
    std::fs::create_dir(&empty).unwrap();
    let err = fails(&run(&["validate", "empty"], t.path()), 1);
    assert!(err.contains("nothing photometric found in empty"), "{err}");
    let pdfs = t.path().join("pdfs");
    std::fs::create_dir(&pdfs).unwrap();
    std::fs::write(pdfs.join("a.pdf"), b"%PDF-1.4\n").unwrap();
    let err = fails(&run(&["validate", "pdfs"], t.path()), 1);
    assert!(err.contains("1 file skipped: not photometric"), "{err}");
    let err = fails(&run(&["batch", "pdfs", "-o", "none.parquet"], t.path()), 1);
    assert!(
        err.contains("nothing photometric found in pdfs; no table written"),
        "{err}"
    );
    assert!(!t.path().join("none.parquet").exists());
}
