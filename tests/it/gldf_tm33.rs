//! GLDF containers and TM-33 XML through the real binary: `info` on every
//! photometry of a container with the declared values next to the computed
//! ones, `validate` expanding a container, one-file commands naming the ids,
//! `convert` to TM-33-23 and back. Containers are written here around
//! files of data/.

use crate::common;

use std::io::Write;
use std::path::Path;

use common::cli::{fails, ok, run};

fn data(name: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("data").join(name)
}

/// `dir/lum.gldf` holding roadway.ldt as `road` (declared LOR 0.5, DFF 0.25,
/// CIE flux code, UGR, BUG) and batwing.ies as `bat` (nothing declared).
fn container(dir: &Path) -> std::path::PathBuf {
    let product = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<Root>\n<Header/>\n<GeneralDefinitions>\n<Files>\n\
        <File id=\"f1\" contentType=\"ldc/eulumdat\" type=\"localFileName\">roadway.ldt</File>\n\
        <File id=\"f2\" contentType=\"ldc/iesna\" type=\"localFileName\">batwing.ies</File>\n</Files>\n<Photometries>\n\
        <Photometry id=\"road\"><PhotometryFileReference fileId=\"f1\"/><DescriptivePhotometry>\
        <LightOutputRatio>0.5</LightOutputRatio><DownwardFluxFraction>0.25</DownwardFluxFraction>\
        <CIE-FluxCode>44 75 94 100 100</CIE-FluxCode>\
        <UGR-4H8H-70-50-20-LQ><X>19.5</X><Y>20.1</Y></UGR-4H8H-70-50-20-LQ>\
        <LightDistributionBUG-Rating>B1 U0 G1</LightDistributionBUG-Rating></DescriptivePhotometry></Photometry>\n\
        <Photometry id=\"bat\"><PhotometryFileReference fileId=\"f2\"/></Photometry>\n\
        </Photometries>\n</GeneralDefinitions>\n</Root>\n";
    let p = dir.join("lum.gldf");
    let mut z = zip::ZipWriter::new(std::io::Cursor::new(Vec::new()));
    let opts = zip::write::SimpleFileOptions::default();
    for (name, bytes) in [
        ("product.xml", product.as_bytes().to_vec()),
        ("ldc/roadway.ldt", std::fs::read(data("roadway.ldt")).unwrap()),
        ("ldc/batwing.ies", std::fs::read(data("batwing.ies")).unwrap()),
    ] {
        z.start_file(name, opts).unwrap();
        z.write_all(&bytes).unwrap();
    }
    std::fs::write(&p, z.finish().unwrap().into_inner()).unwrap();
    p
}

#[test]
fn info_reports_every_photometry_with_declared_next_to_computed() {
    let t = tempfile::tempdir().unwrap();
    container(t.path());
    let v: serde_json::Value = serde_json::from_str(&ok(&run(&["info", "lum.gldf", "--json"], t.path()))).unwrap();
    let all = v.as_array().expect("two photometries: an array");
    assert_eq!(all.len(), 2);
    let road = &all[0];
    let file: serde_json::Value = serde_json::from_str(&ok(&run(
        &["info", data("roadway.ldt").to_str().unwrap(), "--json"],
        t.path(),
    )))
    .unwrap();
    // The photometry reads exactly like its file.
    for key in ["flux_lm", "lor", "dff", "max_cd", "n_c"] {
        assert_eq!(road[key], file[key], "{key}");
    }
    let g = &road["gldf_declared"];
    assert_eq!(g["id"], "road");
    assert_eq!(g["lor"], 0.5);
    assert_eq!(g["dff"], 0.25);
    assert_eq!(g["cie_flux_code"], "44 75 94 100 100");
    assert_eq!(g["ugr_4h8h_70_50_20"]["endwise"], 20.1);
    assert_eq!(g["bug_rating"], "B1 U0 G1");
    // The DFF row: declared 25 %, computed the report's own `dff`, their difference in pp.
    let rows = road["gldf_comparison"].as_array().unwrap();
    let row = |q: &str| rows.iter().find(|r| r["quantity"] == q).unwrap();
    let dff = road["dff"].as_f64().unwrap();
    assert_eq!(row("DFF")["declared"], "25.00 %");
    assert_eq!(row("DFF")["computed"], format!("{:.2} %", dff * 100.0));
    assert_eq!(row("DFF")["difference"], format!("{:+.2} pp", (dff - 0.25) * 100.0));
    // data/roadway.ldt is absolute photometry: no computed LOR to set against the declared one.
    assert_eq!(road["absolute"], true);
    assert_eq!(row("LOR")["declared"], "50.00 %");
    assert!(row("LOR")["computed"].is_null() && row("LOR")["difference"].is_null());
    // The flux code: ours (from `cie_flux_code`) next to the declared one.
    assert_eq!(row("CIE flux code")["computed"], road["cie_flux_code"]["code"]);
    assert!(all[1]["gldf_declared"]["lor"].is_null());
    // Text: one block per photometry, each named FILE.gldf#ID, and the comparison table.
    let text = ok(&run(&["info", "lum.gldf"], t.path()));
    assert!(
        text.contains("lum.gldf#road\n") && text.contains("lum.gldf#bat\n"),
        "{text}"
    );
    assert!(
        text.contains("declared vs computed") && text.contains("BUG rating"),
        "{text}"
    );
    // One photometry by id: a single JSON object.
    let one: serde_json::Value =
        serde_json::from_str(&ok(&run(&["info", "lum.gldf#bat", "--json"], t.path()))).unwrap();
    assert!(one.is_object());
}

#[test]
fn validate_expands_and_one_file_commands_name_the_ids() {
    let t = tempfile::tempdir().unwrap();
    container(t.path());
    let out = ok(&run(&["validate", "."], t.path()));
    assert!(out.contains("lum.gldf#road") && out.contains("lum.gldf#bat"), "{out}");
    let e = fails(&run(&["grid", "lum.gldf"], t.path()), 1);
    assert!(e.contains("road, bat") && e.contains("lum.gldf#ID"), "{e}");
    ok(&run(&["grid", "lum.gldf#road"], t.path()));
    // A broken container: an error naming it, no panic.
    std::fs::write(t.path().join("bad.gldf"), "not a zip").unwrap();
    let e = fails(&run(&["info", "bad.gldf"], t.path()), 1);
    assert!(e.contains("bad.gldf") && e.contains("zip archive"), "{e}");
}

#[test]
fn convert_to_tm33_and_back() {
    let t = tempfile::tempdir().unwrap();
    container(t.path());
    ok(&run(&["convert", "lum.gldf#bat", "bat.xml"], t.path()));
    let text = std::fs::read_to_string(t.path().join("bat.xml")).unwrap();
    assert!(text.contains("<IESTM33-22>"), "{text}");
    let info =
        |f: &str| -> serde_json::Value { serde_json::from_str(&ok(&run(&["info", f, "--json"], t.path()))).unwrap() };
    let (xml, ies) = (info("bat.xml"), info(data("batwing.ies").to_str().unwrap()));
    assert_eq!(xml["format"], "tm33");
    assert_eq!(xml["version"], "TM-33-23");
    for key in ["flux_lm", "max_cd", "symmetry", "n_c", "n_gamma", "absolute"] {
        assert_eq!(xml[key], ies[key], "{key}");
    }
    ok(&run(&["convert", "bat.xml", "back.ldt"], t.path()));
    // A directory: TM-33 documents are found by their root element, other XML is not
    // loaded, only counted as skipped (issue 27).
    std::fs::write(t.path().join("product.xml"), "<Root/>").unwrap();
    let out = ok(&run(&["validate", "."], t.path()));
    assert!(out.contains("bat.xml") && !out.contains("ok   ./product.xml"), "{out}");
    assert!(out.contains("1 file skipped: not photometric (./product.xml)"), "{out}");
    // A malformed document: line and element in the message.
    std::fs::write(t.path().join("bad.xml"), text.replacen(" vert=", " vertical=", 1)).unwrap();
    let e = fails(&run(&["info", "bad.xml"], t.path()), 1);
    assert!(e.contains("bad.xml:") && e.contains("IntensityData"), "{e}");
}

/// A TM-33-23 document with two emitters (written here: bat.xml's emitter
/// twice, with the `<ID>`s `a` and `b`): `info` reports each, named
/// `FILE.xml#ID`; `FILE.xml#b` reads one; a one-file command on `FILE.xml`
/// names the ids; `validate` of a directory expands it.
#[test]
fn tm33_with_several_emitters_by_id() {
    let t = tempfile::tempdir().unwrap();
    ok(&run(
        &["convert", data("batwing.ies").to_str().unwrap(), "bat.xml"],
        t.path(),
    ));
    let text = std::fs::read_to_string(t.path().join("bat.xml")).unwrap();
    let (start, end) = (text.find("<Emitter>").unwrap(), text.find("</Emitter>").unwrap() + 10);
    let emitter = &text[start..end];
    let two = format!(
        "{}{}\n{}{}",
        &text[..start],
        emitter.replacen("<Emitter>", "<Emitter>\n<ID>a</ID>", 1),
        emitter.replacen("<Emitter>", "<Emitter>\n<ID>b</ID>", 1),
        &text[end..]
    );
    std::fs::write(t.path().join("two.xml"), two).unwrap();
    let v: serde_json::Value = serde_json::from_str(&ok(&run(&["info", "two.xml", "--json"], t.path()))).unwrap();
    let all = v.as_array().expect("two emitters: an array");
    assert_eq!(all.len(), 2);
    let one: serde_json::Value = serde_json::from_str(&ok(&run(&["info", "two.xml#b", "--json"], t.path()))).unwrap();
    let bat: serde_json::Value = serde_json::from_str(&ok(&run(&["info", "bat.xml", "--json"], t.path()))).unwrap();
    for key in ["flux_lm", "max_cd", "symmetry"] {
        assert_eq!(one[key], bat[key], "{key}");
        assert_eq!(all[0][key], bat[key], "{key}");
    }
    let text = ok(&run(&["info", "two.xml"], t.path()));
    assert!(text.contains("two.xml#a\n") && text.contains("two.xml#b\n"), "{text}");
    let e = fails(&run(&["grid", "two.xml"], t.path()), 1);
    assert!(e.contains("the ids a, b") && e.contains("two.xml#ID"), "{e}");
    let e = fails(&run(&["grid", "two.xml#c"], t.path()), 1);
    assert!(e.contains("two.xml#c") && e.contains("a, b"), "{e}");
    let out = ok(&run(&["validate", "."], t.path()));
    assert!(out.contains("two.xml#a") && out.contains("two.xml#b"), "{out}");
}

/// `convert X.ldt Y.xml` keeps what the derived photometry needs, on every
/// readable EULUMDAT file of the corpus: the XML read back has the same
/// luminous area (so the same UGR table and luminance table, or both
/// undefined), the same lamp colour, and LDT -> XML -> LDT gives the same
/// `declared_flux_lm`, LOR and DFF in `info --json` (before: the XML had no
/// luminous area, a 4000 K colour was gone, and `eulumdat-rs/wiki-batwing.ldt`
/// went from 3400 to 11664.5 lm).
#[test]
fn tm33_conversion_keeps_what_the_derived_photometry_needs() {
    use photosolid::formats::{load_document, save, WriteOptions};
    use photosolid::report::InfoReport;
    let Some(root) = common::corpus() else { return };
    let t = tempfile::tempdir().unwrap();
    let mut checked = 0;
    for e in common::manifest(&root) {
        if e.format != "ldt" || e.malformed() {
            continue;
        }
        let Ok(doc) = load_document(&e.path) else { continue };
        let (xml, back) = (t.path().join("y.xml"), t.path().join("z.ldt"));
        save(&doc, &xml, &WriteOptions::default()).unwrap();
        let via_xml = load_document(&xml).unwrap_or_else(|err| panic!("{}: {err}", e.rel));
        save(&via_xml, &back, &WriteOptions::default()).unwrap();
        let again = load_document(&back).unwrap_or_else(|err| panic!("{}: {err}", e.rel));
        let json = |d: &photosolid::formats::Document| serde_json::to_value(InfoReport::of_document(d)).unwrap();
        let (a, x, z) = (json(&doc), json(&via_xml), json(&again));
        for key in ["declared_flux_lm", "declared_lor", "dff", "lamp_color"] {
            assert_eq!(a[key], z[key], "{}: {key} after LDT -> XML -> LDT", e.rel);
        }
        assert_eq!(a["lamp_color"], x["lamp_color"], "{}: lamp colour in the XML", e.rel);
        for key in ["ugr_table", "luminance_table"] {
            assert_eq!(a[key], x[key], "{}: {key} of the XML", e.rel);
            assert_eq!(a[key], z[key], "{}: {key} after LDT -> XML -> LDT", e.rel);
        }
        checked += 1;
    }
    assert!(checked >= 20, "only {checked} EULUMDAT files checked");
}

/// A document parsed from the bytes `document_source_bytes` read is the one
/// `load_document` reads, for a plain file of each format, a file without an
/// extension, a GLDF photometry and a TM-33 emitter by id; after the files are
/// gone too (what a Python pickle relies on).
#[test]
fn documents_from_their_bytes_equal_the_loaded_ones() {
    use photosolid::formats::{document_source_bytes, load_document, load_document_from_bytes};
    use photosolid::ReadOptions;
    let t = tempfile::tempdir().unwrap();
    let dir = t.path();
    let gldf = container(dir);
    std::fs::copy(data("spot_p8_c40.ies"), dir.join("no_extension")).unwrap();
    ok(&run(
        &["convert", data("batwing.ies").to_str().unwrap(), "bat.xml"],
        dir,
    ));
    let mut paths: Vec<std::path::PathBuf> = ["roadway.ldt", "batwing.ies", "cosine_p5.ldt"]
        .iter()
        .map(|n| data(n))
        .collect();
    paths.push(dir.join("no_extension"));
    paths.push(dir.join("bat.xml"));
    paths.push(std::path::PathBuf::from(format!("{}#road", gldf.display())));
    paths.push(std::path::PathBuf::from(format!("{}#bat", gldf.display())));
    let kept: Vec<_> = paths
        .iter()
        .map(|p| (p.clone(), load_document(p).unwrap(), document_source_bytes(p).unwrap()))
        .collect();
    drop(t); // the temporary files are gone: the bytes are all there is
    for (p, loaded, bytes) in kept {
        let again = load_document_from_bytes(&p, bytes, &ReadOptions::default()).unwrap();
        assert_eq!(again, loaded, "{}", p.display());
        assert_eq!(again.luminaire.distribution(), loaded.luminaire.distribution());
    }
    let e = load_document_from_bytes(
        std::path::Path::new("x.gldf#a"),
        b"not a zip".to_vec(),
        &ReadOptions::default(),
    )
    .unwrap_err();
    assert!(e.to_string().contains("x.gldf") && e.to_string().contains("zip"), "{e}");
}
