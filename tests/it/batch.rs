//! `photosolid batch`: the Parquet table read back with the parquet crate
//! equals the CLI's own per-file commands (`info`, `holdout`, `fit --json`),
//! broken files are rows (not a failed batch), `--resume` keeps earlier rows,
//! the JSON Lines and the catalogue page agree with the table; the corpus
//! (when present) gives one row per file, failing exactly where the manifest says.

use crate::common;

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use arrow_array::{Array, BooleanArray, Float64Array, ListArray, RecordBatch, StringArray};
use common::cli::{ok, run};
use parquet::arrow::arrow_reader::ParquetRecordBatchReaderBuilder;

fn data() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("data")
}

/// Every record batch of a Parquet file, read with the parquet crate alone.
fn read(path: &Path) -> Vec<RecordBatch> {
    let f = std::fs::File::open(path).unwrap();
    ParquetRecordBatchReaderBuilder::try_new(f)
        .unwrap()
        .build()
        .unwrap()
        .map(|b| b.unwrap())
        .collect()
}

/// One row of the table as a JSON object (column name -> value), from the Arrow arrays.
fn rows(batches: &[RecordBatch]) -> Vec<serde_json::Map<String, serde_json::Value>> {
    use serde_json::Value;
    let mut out = Vec::new();
    for b in batches {
        for i in 0..b.num_rows() {
            let mut m = serde_json::Map::new();
            for (f, c) in b.schema().fields().iter().zip(b.columns()) {
                let v = if c.is_null(i) {
                    Value::Null
                } else if let Some(a) = c.as_any().downcast_ref::<StringArray>() {
                    Value::from(a.value(i))
                } else if let Some(a) = c.as_any().downcast_ref::<Float64Array>() {
                    Value::from(a.value(i))
                } else if let Some(a) = c.as_any().downcast_ref::<BooleanArray>() {
                    Value::from(a.value(i))
                } else if let Some(a) = c.as_any().downcast_ref::<arrow_array::UInt32Array>() {
                    Value::from(a.value(i))
                } else if let Some(a) = c.as_any().downcast_ref::<ListArray>() {
                    let v = a.value(i);
                    let s = v.as_any().downcast_ref::<StringArray>().unwrap();
                    Value::from((0..s.len()).map(|j| s.value(j).to_string()).collect::<Vec<_>>())
                } else {
                    panic!("column {} has an unexpected type {}", f.name(), c.data_type());
                };
                m.insert(f.name().clone(), v);
            }
            out.push(m);
        }
    }
    out
}

fn json(args: &[&str], dir: &Path) -> serde_json::Value {
    serde_json::from_str(&ok(&run(args, dir))).unwrap()
}

fn close(a: &serde_json::Value, b: &serde_json::Value, what: &str) {
    match (a.as_f64(), b.as_f64()) {
        (Some(x), Some(y)) => assert_close!(x, y, abs = 1e-12 * x.abs().max(1.0), "{what}: {x} vs {y}"),
        _ => assert_eq!(a, b, "{what}"),
    }
}

/// data/ plus a broken file: one row each; every number equals the CLI's per-file JSON.
#[test]
fn table_equals_the_per_file_commands() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(d.join("broken.ies"), "IESNA:LM-63-2002\nTILT=NONE\n1 1000 1 x\n").unwrap();
    let data = data();
    let out = ok(&run(
        &[
            "batch",
            data.to_str().unwrap(),
            "broken.ies",
            "-o",
            "t.parquet",
            "--jsonl",
            "t.jsonl",
            "--report",
            "cat",
        ],
        d,
    ));
    assert!(out.contains("failed to load"), "{out}");
    let table = rows(&read(&d.join("t.parquet")));
    // Schema 2 (issue 27: lamp flux, manufacturer, catalogue, input watts, efficacy).
    let builder = ParquetRecordBatchReaderBuilder::try_new(std::fs::File::open(d.join("t.parquet")).unwrap()).unwrap();
    let schema = builder
        .metadata()
        .file_metadata()
        .key_value_metadata()
        .and_then(|kv| kv.iter().find(|kv| kv.key == "photosolid.batch.schema"))
        .and_then(|kv| kv.value.clone());
    assert_eq!(schema.as_deref(), Some("4"));
    assert_eq!(photosolid::batch::table::SCHEMA_VERSION, "4");
    // Schema 3: the compact columns exist and, without --compact, say nothing was measured.
    for r in &table {
        assert_eq!(r["smallest_within_1pct"], serde_json::Value::Null, "{r:?}");
        assert_eq!(r["compact_ms"], serde_json::Value::Null, "{r:?}");
    }
    let n_data = std::fs::read_dir(&data)
        .unwrap()
        .filter(|e| {
            let p = e.as_ref().unwrap().path();
            matches!(p.extension().and_then(|x| x.to_str()), Some("ies" | "ldt"))
        })
        .count();
    assert_eq!(table.len(), n_data + 1);
    for row in &table {
        let path = row["path"].as_str().unwrap();
        if path == "broken.ies" {
            assert_eq!(row["ok"], false);
            let errs = row["errors"].as_array().unwrap();
            assert_eq!(errs.len(), 1);
            assert!(errs[0].as_str().unwrap().starts_with("broken.ies:3"), "{errs:?}");
            assert!(row["flux_lm"].is_null() && row["best_filter"].is_null());
            continue;
        }
        assert_eq!(row["ok"], true, "{row:?}");
        assert_eq!(row["errors"].as_array().unwrap().len(), 0, "{row:?}");
        let info = json(&["info", path, "--json"], d);
        for k in [
            "format",
            "version",
            "symmetry",
            "max_cd",
            "flux_lm",
            "declared_flux_lm",
            "flux_ratio",
            "lor",
            "dlor",
            "ulor",
            "n_c",
            "n_c_full",
            "n_gamma",
            // Schema 2 (issue 27).
            "lamp_flux_lm",
            "manufacturer",
            "catalogue",
            "input_watts",
            "efficacy_lm_per_w",
            // Schema 4.
            "front_c_deg",
        ] {
            close(&row[k], &info[k], &format!("{path} {k}"));
        }
        close(&row["beam_angle_deg"], &info["beam_angles"]["ies_beam_deg"][0], "beam");
        close(
            &row["field_angle_c90_deg"],
            &info["beam_angles"]["ies_field_deg"][1],
            "field c90",
        );
        let codes: Vec<&str> = info["warnings"]
            .as_array()
            .unwrap()
            .iter()
            .map(|w| w["code"].as_str().unwrap())
            .collect();
        let got: Vec<&str> = row["warnings"]
            .as_array()
            .unwrap()
            .iter()
            .map(|w| w.as_str().unwrap())
            .collect();
        assert_eq!(got, codes, "{path}");
        // The best filter: the smallest rms_percent of `holdout --json` (its defaults are the batch's hold-out).
        let ho = json(&["holdout", path, "--json"], d);
        let best = ho
            .as_array()
            .unwrap()
            .iter()
            .min_by(|a, b| {
                a["rms_percent"]
                    .as_f64()
                    .unwrap()
                    .total_cmp(&b["rms_percent"].as_f64().unwrap())
            })
            .unwrap();
        close(&row["best_filter_rms_pct"], &best["rms_percent"], "best rms");
        close(&row["best_filter_max_pct"], &best["max_percent"], "best max");
        let best_name = serde_json::to_value(&best["filter"]).unwrap();
        assert_eq!(row["best_filter"], best_name, "{path}");
        let fit = json(&["fit", path, "--json"], d);
        close(&row["fitted_gl_error"], &fit["error"], "fit error");
        assert_eq!(row["fitted_gl"], fit["chosen"], "{path}");
    }
    // The JSON Lines hold the same rows.
    let text = std::fs::read_to_string(d.join("t.jsonl")).unwrap();
    let lines: Vec<serde_json::Value> = text.lines().map(|l| serde_json::from_str(l).unwrap()).collect();
    assert_eq!(lines.len(), table.len());
    for (l, r) in lines.iter().zip(&table) {
        for (k, v) in r {
            close(&l[k], v, k);
        }
    }
    // The catalogue lists the broken file first, and has a thumbnail per loaded file.
    let html = std::fs::read_to_string(d.join("cat/index.html")).unwrap();
    let first_row = html.find("<tbody>").unwrap();
    assert!(html[first_row..].find("broken.ies").unwrap() < html[first_row..].find("data/").unwrap());
    let thumbs = std::fs::read_dir(d.join("cat"))
        .unwrap()
        .filter(|e| e.as_ref().unwrap().file_name().to_string_lossy().starts_with("thumb-"))
        .count();
    assert_eq!(thumbs, n_data);
}

/// `--resume` keeps the rows already in the table (their timings prove they were not redone) and adds the rest.
#[test]
fn resume_adds_only_new_files() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let (a, b) = (d.join("a"), d.join("b"));
    std::fs::create_dir_all(&a).unwrap();
    std::fs::create_dir_all(&b).unwrap();
    for (src, dst) in [("isotropic.ies", &a), ("roadway.ldt", &a), ("batwing.ies", &b)] {
        std::fs::copy(data().join(src), dst.join(src)).unwrap();
    }
    ok(&run(&["batch", "a", "-o", "t.parquet"], d));
    let first = rows(&read(&d.join("t.parquet")));
    assert_eq!(first.len(), 2);
    let out = ok(&run(&["batch", "a", "b", "-o", "t.parquet", "--resume"], d));
    assert!(out.contains("2 resumed, 1 analysed"), "{out}");
    assert!(!out.contains("--compact"), "{out}");
    let second = rows(&read(&d.join("t.parquet")));
    assert_eq!(second.len(), 3);
    assert_eq!(&second[..2], &first[..], "resumed rows are kept as they were");
    assert_eq!(second[2]["path"], "b/batwing.ies");
    // Without --resume the table is rebuilt: the timings are new.
    ok(&run(&["batch", "a", "-o", "t.parquet"], d));
    let third = rows(&read(&d.join("t.parquet")));
    assert_eq!(third.len(), 2);
    // From the JSON Lines when the table is missing.
    ok(&run(&["batch", "a", "-o", "u.parquet", "--jsonl", "u.jsonl"], d));
    std::fs::remove_file(d.join("u.parquet")).unwrap();
    let out = ok(&run(
        &["batch", "a", "b", "-o", "u.parquet", "--jsonl", "u.jsonl", "--resume"],
        d,
    ));
    assert!(out.contains("2 resumed, 1 analysed"), "{out}");
    // Resumed rows measured with another --compact choice are named, not silently mixed.
    ok(&run(&["batch", "a", "-o", "v.parquet"], d));
    let out = ok(&run(
        &["batch", "a", "b", "-o", "v.parquet", "--resume", "--compact"],
        d,
    ));
    assert!(
        out.contains("2 resumed rows were measured without --compact: their smallest_within_1pct stays null"),
        "{out}"
    );
    let v = rows(&read(&d.join("v.parquet")));
    assert!(
        v[0]["compact_ms"].is_null() && v[2]["compact_ms"].as_f64().is_some(),
        "{v:?}"
    );
}

/// The corpus: a row per photometric file; ok exactly where the manifest says the file loads.
#[test]
fn corpus_rows_follow_the_manifest() {
    let Some(root) = common::corpus() else { return };
    let dir = tempfile::tempdir().unwrap();
    ok(&run(&["batch", root.to_str().unwrap(), "-o", "c.parquet"], dir.path()));
    let table = rows(&read(&dir.path().join("c.parquet")));
    let by_path: HashMap<String, &serde_json::Map<String, serde_json::Value>> = table
        .iter()
        .map(|r| (r["path"].as_str().unwrap().to_string(), r))
        .collect();
    let mut checked = 0;
    for e in common::manifest(&root).iter().filter(|e| e.photometric()) {
        let row = by_path
            .get(&e.path.display().to_string())
            .unwrap_or_else(|| panic!("no row for {}", e.rel));
        assert_eq!(row["ok"], !e.malformed(), "{}: {:?}", e.rel, row["errors"]);
        if e.malformed() {
            assert!(!row["errors"].as_array().unwrap().is_empty());
        } else {
            assert!(row["flux_lm"].as_f64().unwrap().is_finite());
        }
        checked += 1;
    }
    assert!(checked >= 100, "{checked}");
}

/// `batch --compact` fills `smallest_within_1pct` by the rule of
/// `tradeoff` over the hold-out: an isotropic file is `sh:2` (12 bytes, zonal, exact:
/// `lobes:1` is a hemisphere), a Lambertian one `lobes:1` (20 bytes, exact),
/// each with its time; the Parquet table and the JSON Lines agree.
#[test]
fn compact_names_the_smallest_within_1pct() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::create_dir(d.join("files")).unwrap();
    for (kind, file) in [
        ("isotropic", "files/iso.ldt"),
        ("lambertian", "files/lamb.ldt"),
        ("roadway", "files/road.ldt"),
    ] {
        ok(&run(&["synth", kind, "-o", file], d));
    }
    ok(&run(
        &["batch", "files", "-o", "t.parquet", "--jsonl", "t.jsonl", "--compact"],
        d,
    ));
    let table = rows(&read(&d.join("t.parquet")));
    let lines: Vec<serde_json::Value> = std::fs::read_to_string(d.join("t.jsonl"))
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    let want = [("iso.ldt", Some("sh:2")), ("lamb.ldt", Some("lobes:1"))];
    for (name, expected) in want {
        let r = table
            .iter()
            .find(|r| r["path"].as_str().unwrap().ends_with(name))
            .unwrap();
        assert_eq!(r["smallest_within_1pct"].as_str(), expected, "{name}: {r:?}");
        assert!(r["compact_ms"].as_f64().is_some_and(|t| t > 0.0), "{name}: {r:?}");
    }
    for r in &table {
        let j = lines.iter().find(|l| l["path"] == r["path"]).unwrap();
        assert_eq!(j["smallest_within_1pct"], r["smallest_within_1pct"], "{r:?}");
        let name = r["smallest_within_1pct"].as_str().unwrap_or("none");
        eprintln!("{}: smallest within 1 %: {name}", r["path"]);
    }
}

/// `batch --front DEG` reads every file with that front, as `info --front DEG` does, and
/// the `front_c_deg` column says which front each row used (negative angles wrap).
#[test]
fn batch_takes_the_reader_options_and_records_the_front() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let data = data();
    let files = [data.join("roadway.ies"), data.join("roadway.ldt")];
    let names: Vec<&str> = files.iter().map(|p| p.to_str().unwrap()).collect();
    ok(&run(&[&["batch"], &names[..], &["-o", "plain.parquet"]].concat(), d));
    ok(&run(
        &[&["batch"], &names[..], &["-o", "front.parquet", "--front", "-45"]].concat(),
        d,
    ));
    let plain = rows(&read(&d.join("plain.parquet")));
    let turned = rows(&read(&d.join("front.parquet")));
    let fronts = |t: &[serde_json::Map<String, serde_json::Value>]| -> Vec<f64> {
        t.iter().map(|r| r["front_c_deg"].as_f64().unwrap()).collect()
    };
    assert_eq!(
        fronts(&plain),
        [0.0, 90.0],
        "the formats' conventions: IES C0, EULUMDAT C90"
    );
    assert_eq!(fronts(&turned), [315.0, 315.0]);
    let info = serde_json::from_str::<serde_json::Value>(&ok(&run(&["info", names[1], "--json", "--front", "-45"], d)))
        .unwrap();
    assert_eq!(info["front_c_deg"], 315.0);
}
