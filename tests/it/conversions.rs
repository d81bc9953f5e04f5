//! Conversions keep what the file says: opening shapes both ways (LM-63's
//! signs <-> EULUMDAT's disk and rectangle), lamp colour, and a warning for
//! what the target cannot hold.

use crate::common::cli::{ok, run};

/// A 2002 IES downlight (cos γ, 1000 cd, 5 planes x 19 γ) with this luminous
/// opening line `W L H` (metres) and `[COLORTEMP]`.
fn ies_with_opening(dir: &std::path::Path, name: &str, w: f64, l: f64, h: f64) {
    let g: Vec<f64> = (0..=18).map(|i| 5.0 * i as f64).collect();
    let c = [0.0, 22.5, 45.0, 67.5, 90.0];
    let plane: Vec<String> = g
        .iter()
        .map(|x| format!("{:.3}", 1000.0 * x.to_radians().cos()))
        .collect();
    let list = |v: &[f64]| v.iter().map(|x| x.to_string()).collect::<Vec<_>>().join(" ");
    let mut text = format!(
        "IESNA:LM-63-2002\n[TEST] t\n[MANUFAC] m\n[COLORTEMP] 3000K\nTILT=NONE\n1 3142 1 {} {} 1 2 {w} {l} {h}\n1 1 10\n{}\n{}\n",
        g.len(),
        c.len(),
        list(&g),
        list(&c)
    );
    for _ in c {
        text.push_str(&plane.join(" "));
        text.push('\n');
    }
    std::fs::write(dir.join(name), text).unwrap();
}

fn info(dir: &std::path::Path, file: &str) -> serde_json::Value {
    serde_json::from_str(&ok(&run(&["info", file, "--json"], dir))).unwrap()
}

/// An IES circle (negative width and length) becomes a EULUMDAT disk (width 0,
/// positive diameter), keeps its UGR table and its colour temperature, and comes back as the
/// same LM-63 circle.
#[test]
fn a_circular_opening_and_the_lamp_colour_survive_ies_ldt_ies() {
    let dir = tempfile::tempdir().unwrap();
    ies_with_opening(dir.path(), "disk.ies", -0.225, -0.225, 0.0);
    ok(&run(&["convert", "disk.ies", "disk.ldt"], dir.path()));
    ok(&run(&["convert", "disk.ldt", "back.ies"], dir.path()));
    let (a, b, c) = (
        info(dir.path(), "disk.ies"),
        info(dir.path(), "disk.ldt"),
        info(dir.path(), "back.ies"),
    );
    for v in [&a, &b, &c] {
        let d = &v["luminous_dimensions_m"];
        assert_eq!(d["shape"], "ellipse", "{d}");
        assert!((d["length_m"].as_f64().unwrap() - 0.225).abs() < 1e-9, "{d}");
        assert!((d["width_m"].as_f64().unwrap() - 0.225).abs() < 1e-9, "{d}");
        assert_eq!(v["lamp_color"]["cct_k"], 3000.0, "{}", v["lamp_color"]);
        assert!(v["ugr_table"].get("undefined").is_none(), "{}", v["ugr_table"]);
    }
    // The same UGR table in every format, to 1e-6 relative (the EULUMDAT file keeps 8
    // significant digits of the cd/klm values, which moves the table by about 1e-9).
    assert_numbers_close(&a["ugr_table"], &b["ugr_table"], "ies vs ldt");
    assert_numbers_close(&a["ugr_table"], &c["ugr_table"], "ies vs ies via ldt");
    let ldt = std::fs::read_to_string(dir.path().join("disk.ldt")).unwrap();
    assert!(!ldt.contains("-225"), "no negative dimensions in the EULUMDAT file");
}

/// An IES ellipse EULUMDAT cannot hold: written as a disk of the same area, with a warning.
#[test]
fn an_ellipse_is_named_when_eulumdat_cannot_hold_it() {
    let dir = tempfile::tempdir().unwrap();
    ies_with_opening(dir.path(), "ell.ies", -0.2, -0.8, 0.0);
    let o = run(&["convert", "ell.ies", "ell.ldt"], dir.path());
    ok(&o);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("field-not-kept") && err.contains("400 mm"), "{err}");
    let v = info(dir.path(), "ell.ldt");
    assert!((v["luminous_dimensions_m"]["length_m"].as_f64().unwrap() - 0.4).abs() < 1e-9);
}

/// Every number in `a` and `b` (same shape) equal to 1e-6 relative; every other value equal.
fn assert_numbers_close(a: &serde_json::Value, b: &serde_json::Value, what: &str) {
    use serde_json::Value;
    match (a, b) {
        (Value::Number(x), Value::Number(y)) => {
            let (x, y) = (x.as_f64().unwrap(), y.as_f64().unwrap());
            assert!((x - y).abs() <= 1e-6 * x.abs().max(y.abs()), "{what}: {x} vs {y}");
        }
        (Value::Array(x), Value::Array(y)) => {
            assert_eq!(x.len(), y.len(), "{what}");
            for (p, q) in x.iter().zip(y) {
                assert_numbers_close(p, q, what);
            }
        }
        (Value::Object(x), Value::Object(y)) => {
            assert_eq!(x.keys().collect::<Vec<_>>(), y.keys().collect::<Vec<_>>(), "{what}");
            for (k, p) in x {
                assert_numbers_close(p, &y[k], what);
            }
        }
        _ => assert_eq!(a, b, "{what}"),
    }
}

/// Every corpus file that loads, with its front given as `--front` would: `info`'s JSON of
/// the original and of its IES 2002, IES 2019, EULUMDAT and TM-33-23 conversions agree on
/// every key but `format`, `version`, `photometric_type`, `path`, `warnings` and the fields a
/// conversion warning named; numbers to 1e-6 relative (the EULUMDAT writer keeps 8
/// significant digits), the UGR table included.
#[test]
fn every_corpus_file_gives_the_same_info_through_every_format() {
    use photosolid::formats::ies::IesWriteVersion;
    use photosolid::formats::{ReadOptions, WriteOptions};
    use photosolid::report::info::{InfoReport, Tables};
    let Some(root) = crate::common::corpus() else { return };
    let dir = tempfile::tempdir().unwrap();
    let mut diffs: std::collections::BTreeMap<String, Vec<String>> = Default::default();
    let mut checked = 0;
    let info_of = |doc: &photosolid::formats::Document| {
        let r = InfoReport::of_document_with(doc, Tables::Compute, &Default::default());
        serde_json::to_value(&r).unwrap()
    };
    for e in crate::common::manifest(&root)
        .iter()
        .filter(|e| e.photometric() && !e.malformed())
    {
        let Ok(first) = photosolid::formats::load_document(&e.path) else {
            continue;
        };
        let opts = ReadOptions {
            front_c_deg: Some(first.luminaire.front().c_deg),
            ..Default::default()
        };
        let original = photosolid::formats::load_document_with(&e.path, &opts).unwrap();
        let a = info_of(&original);
        for (name, ext, version) in [
            ("ies2002", "ies", IesWriteVersion::Lm63_2002),
            ("ies2019", "ies", IesWriteVersion::Lm63_2019),
            ("ldt", "ldt", IesWriteVersion::Lm63_2002),
            ("tm33", "xml", IesWriteVersion::Lm63_2002),
        ] {
            let out = dir.path().join(format!("c.{ext}"));
            let target = photosolid::model::Format::from_extension(&out).unwrap();
            let named: Vec<String> = photosolid::formats::conversion_warnings(&original.luminaire, target)
                .iter()
                .map(|w| w.message.clone())
                .collect();
            photosolid::formats::save(&original, &out, &WriteOptions { ies_version: version }).unwrap();
            let back = match photosolid::formats::load_document_with(&out, &opts) {
                Ok(d) => d,
                Err(err) => {
                    diffs
                        .entry("(read back)".into())
                        .or_default()
                        .push(format!("{} -> {name}: {err}", e.rel));
                    continue;
                }
            };
            let b = info_of(&back);
            let mut found = Vec::new();
            json_differences(&a, &b, "", &mut found);
            for key in found {
                let top = key
                    .trim_start_matches('.')
                    .split(['.', '[', ':'])
                    .next()
                    .unwrap_or("")
                    .to_string();
                if ["format", "version", "photometric_type", "path", "warnings"].contains(&top.as_str()) {
                    continue;
                }
                // A conversion warning ends with the info keys it changes.
                let changes = |m: &String| {
                    m.rsplit_once("(changes info keys: ")
                        .is_some_and(|(_, keys)| keys.trim_end_matches(')').split(", ").any(|k| k == top))
                };
                if named.iter().any(changes) {
                    continue;
                }
                diffs
                    .entry(format!("{top} -> {name}"))
                    .or_default()
                    .push(format!("{}: {key}", e.rel));
            }
        }
        checked += 1;
    }
    let mut report = String::new();
    for (k, v) in &diffs {
        report.push_str(&format!(
            "{k}: {} cases, e.g. {}\n",
            v.len(),
            v.iter()
                .map(|x| x.split(": ").next().unwrap_or("").to_string())
                .collect::<std::collections::BTreeSet<_>>()
                .into_iter()
                .take(6)
                .collect::<Vec<_>>()
                .join("; ")
        ));
    }
    assert!(checked >= 100, "only {checked} files");
    assert!(diffs.is_empty(), "{report}");
}

/// Paths (`.key[i]`) where `a` and `b` differ; numbers to 1e-6 relative (absolute below 1e-9).
fn json_differences(a: &serde_json::Value, b: &serde_json::Value, at: &str, out: &mut Vec<String>) {
    use serde_json::Value;
    match (a, b) {
        (Value::Number(x), Value::Number(y)) => {
            let (x, y) = (x.as_f64().unwrap(), y.as_f64().unwrap());
            if (x - y).abs() > 1e-6 * x.abs().max(y.abs()) && (x - y).abs() > 1e-9 {
                out.push(format!("{at}: {x} vs {y}"));
            }
        }
        (Value::Array(x), Value::Array(y)) if x.len() == y.len() => {
            for (i, (p, q)) in x.iter().zip(y).enumerate() {
                json_differences(p, q, &format!("{at}[{i}]"), out);
            }
        }
        (Value::Object(x), Value::Object(y)) => {
            for k in x.keys().chain(y.keys().filter(|k| !x.contains_key(*k))) {
                match (x.get(k), y.get(k)) {
                    (Some(p), Some(q)) => json_differences(p, q, &format!("{at}.{k}"), out),
                    _ => out.push(format!("{at}.{k}: present in one only")),
                }
            }
        }
        _ if a == b => {}
        _ => out.push(format!("{at}: {} vs {}", short(a), short(b))),
    }
}

fn short(v: &serde_json::Value) -> String {
    let s = v.to_string();
    if s.len() > 60 {
        format!("{}…", &s[..60])
    } else {
        s
    }
}
