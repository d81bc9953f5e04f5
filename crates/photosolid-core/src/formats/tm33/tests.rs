//! Tests of the TM-33 reader and writer: documents written here by hand in
//! the element layout of the published TM-33-23 examples (eulumdat-rs,
//! `crates/atla/tests/samples/tm33-23/minimal.xml`) and of TM-33-18.

use std::path::Path;

use super::*;
use crate::error::ErrorKind;
use crate::formats::ReadOptions;
use crate::model::{Format, Symmetry};

fn parse(text: &str) -> Result<crate::formats::Document, crate::error::ParseError> {
    read(text.as_bytes(), Path::new("t.xml"), &ReadOptions::default())
}

/// A TM-33-23 document around `points` (`(horz, vert, value)`) and extra `LuminousData` children.
fn doc23(block_extra: &str, points: &[(f64, f64, f64)]) -> String {
    let mut s = String::from(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<IESTM33-22>\n<Version>1.1</Version>\n<Header>\n\
         <Manufacturer>ACME &amp; Sons</Manufacturer>\n<CatalogNumber>X-1</CatalogNumber>\n\
         <ReportNumber>R7</ReportNumber>\n<ReportDate>2024-01-15</ReportDate>\n</Header>\n\
         <Luminaire><Dimensions><Length>600</Length><Width>300</Width><Height>50</Height></Dimensions></Luminaire>\n\
         <Emitter>\n<Quantity>2</Quantity>\n<RatedLumens>1500</RatedLumens>\n<InputWattage>40</InputWattage>\n\
         <CCT>4000</CCT>\n<LuminousData>\n<PhotometryType>CIE _ C</PhotometryType>\n<Metric>Luminous</Metric>\n",
    );
    s.push_str(block_extra);
    for (h, v, cd) in points {
        s.push_str(&format!(
            "<IntensityData horz=\"{h}\" vert=\"{v}\">{cd}</IntensityData>\n"
        ));
    }
    s.push_str("</LuminousData>\n</Emitter>\n</IESTM33-22>\n");
    s
}

fn grid(hs: &[f64], vs: &[f64], f: impl Fn(f64, f64) -> f64) -> Vec<(f64, f64, f64)> {
    hs.iter()
        .flat_map(|&h| vs.iter().map(move |&v| (h, v, 0.0)))
        .map(|(h, v, _)| (h, v, f(h, v)))
        .collect()
}

#[test]
fn tm33_23_values_multiplier_symmetry_and_flags() {
    let pts = grid(&[0.0, 45.0, 90.0], &[0.0, 45.0, 90.0], |h, v| 100.0 + h - v);
    let lum = parse(&doc23(
        "<SymmType>Symm _ Quad</SymmType>\n<Multiplier>2.5</Multiplier>\n<AbsolutePhotometry>false</AbsolutePhotometry>\n",
        &pts,
    ))
    .unwrap();
    assert_eq!(lum.format(), Format::Tm33);
    assert_eq!(lum.version(), "TM-33-23");
    let d = lum.distribution();
    assert_eq!(d.symmetry(), Symmetry::Quadrant);
    assert_eq!(d.c_angles_deg(), &[0.0, 45.0, 90.0]);
    assert_eq!(d.gamma_angles_deg(), &[0.0, 45.0, 90.0]);
    for (ic, &h) in d.c_angles_deg().iter().enumerate() {
        for (ig, &v) in d.gamma_angles_deg().iter().enumerate() {
            assert_eq!(d.value_cd(ic, ig), (100.0 + h - v) * 2.5);
        }
    }
    assert!(!lum.declared().absolute);
    // Relative photometry: lamp flux = Quantity x RatedLumens.
    assert_eq!(lum.declared().lamp_flux_lm, Some(3000.0));
    assert_eq!(lum.declared().input_watts, Some(40.0));
    assert_eq!(lum.metadata().manufacturer, "ACME & Sons");
    assert_eq!(lum.metadata().date, "2024-01-15");
    assert_eq!(lum.dimensions().length_m, 0.6);
    assert_eq!(lum.lamp_sets()[0].color, "4000K");
}

#[test]
fn absolute_flag_and_every_symmetry_code() {
    let vs = [0.0, 90.0, 180.0];
    let cases: [(&str, &[f64], Symmetry); 6] = [
        ("Symm _ Full", &[0.0], Symmetry::Rotational),
        ("Symm _ Bi _ 0", &[0.0, 90.0, 180.0], Symmetry::C0C180),
        ("Symm _ Bi _ 90", &[90.0, 180.0, 270.0], Symmetry::C90C270),
        ("Symm _ Quad", &[0.0, 90.0], Symmetry::Quadrant),
        ("Symm _ None", &[0.0, 120.0, 240.0], Symmetry::None),
        ("Symm _ Arbitrary", &[0.0, 120.0, 240.0], Symmetry::None),
    ];
    for (code, hs, want) in cases {
        let text = doc23(
            &format!("<SymmType>{code}</SymmType>\n<AbsolutePhotometry>true</AbsolutePhotometry>\n"),
            &grid(hs, &vs, |h, v| 10.0 + h + v),
        );
        let lum = parse(&text).unwrap_or_else(|e| panic!("{code}: {e}"));
        assert_eq!(lum.distribution().symmetry(), want, "{code}");
        assert!(lum.declared().absolute);
        assert_eq!(lum.declared().lamp_flux_lm, None, "absolute: no lamp flux");
        // Written back, the code and the values survive.
        let back = parse(&write(&lum)).unwrap();
        assert_eq!(back.distribution(), lum.distribution(), "{code}");
        assert!(back.declared().absolute);
    }
}

#[test]
fn tm33_18_with_namespace_and_no_symmetry_code() {
    let text = "<?xml version=\"1.0\"?>\n<LuminaireOpticalData version=\"1.0\" xmlns=\"http://www.ies.org/tm-33\">\n\
        <Header><Manufacturer>M</Manufacturer><TestDate>2024-01-20</TestDate></Header>\n<Emitter>\n\
        <RatedLumens>1600</RatedLumens>\n<IntensityDistribution>\n<PhotometryType>C</PhotometryType>\n\
        <IntensityData horz=\"0\" vert=\"0\">80</IntensityData>\n<IntensityData horz=\"0\" vert=\"90\">65</IntensityData>\n\
        <IntensityData horz=\"0\" vert=\"180\">80</IntensityData>\n</IntensityDistribution>\n</Emitter>\n\
        </LuminaireOpticalData>";
    let lum = parse(text).unwrap();
    assert_eq!(lum.version(), "TM-33-18");
    assert_eq!(lum.distribution().symmetry(), Symmetry::Rotational);
    assert_eq!(lum.distribution().intensities_cd(), &[80.0, 65.0, 80.0]);
    // No AbsolutePhotometry but a rated flux: relative.
    assert_eq!(lum.declared().lamp_flux_lm, Some(1600.0));
    assert_eq!(lum.metadata().date, "2024-01-20");
    assert!(looks_like(text.as_bytes()));
    assert_eq!(crate::formats::sniff(text.as_bytes()), Format::Tm33);
}

#[test]
fn a_360_plane_is_dropped_and_compared_with_c0() {
    let pts = grid(&[0.0, 180.0, 360.0], &[0.0, 90.0], |h, v| {
        if h == 360.0 {
            7.0
        } else {
            5.0 + v
        }
    });
    let lum = parse(&doc23("<SymmType>Symm _ None</SymmType>\n", &pts)).unwrap();
    assert_eq!(lum.distribution().c_angles_deg(), &[0.0, 180.0]);
    assert!(
        lum.warnings().iter().any(|w| w.code == "seam-mismatch"),
        "{:?}",
        lum.warnings()
    );
}

/// Each malformed document: the error's line, and a word of its message.
#[test]
fn malformed_documents_name_line_and_element() {
    let ok = grid(&[0.0, 90.0], &[0.0, 90.0], |_, _| 1.0);
    let good = doc23("<SymmType>Symm _ Quad</SymmType>\n", &ok);
    // The line of the last occurrence of `needle`.
    let line_of = |text: &str, needle: &str| 1 + text[..text.rfind(needle).unwrap()].matches('\n').count();
    let check = |text: String, needle: &str, word: &str, kind: ErrorKind| {
        let e = parse(&text).unwrap_err();
        assert_eq!(e.location.line, line_of(&text, needle), "{e}");
        assert!(e.to_string().contains(word), "{e}");
        assert_eq!(e.kind, kind, "{e}");
    };
    use ErrorKind::{Invalid, Unsupported};
    let all = usize::MAX;
    // (replace, by, how often, where the error points, a word of its message, its kind).
    #[rustfmt::skip]
    let edits = [
        // Not well formed: an unclosed element.
        ("</Emitter>", "", 1, "</IESTM33-22>", "well-formed XML", Invalid),
        // A missing attribute, a bad value, a bad angle.
        (" vert=\"90\"", "", 1, "<IntensityData horz=\"0\">", "<IESTM33-22/Emitter/LuminousData/IntensityData>", Invalid),
        (">1</", ">abc</", 1, "abc", "`abc`", Invalid),
        ("vert=\"90\"", "vert=\"190\"", 1, "vert=\"190\"", "0..180", Invalid),
        // A code that does not fit the angles, an unknown code.
        ("Symm _ Quad", "Symm _ Bi _ 90", 1, "<SymmType>", "C90-C270", Invalid),
        ("Symm _ Quad", "Symm _ Diagonal", 1, "<SymmType>", "Symm _ Quad", Invalid),
        // Unsupported: Type B, radiant data.
        ("CIE _ C", "CIE _ B", 1, "<PhotometryType>", "Type C", Unsupported),
        (">Luminous<", ">Radiant<", 1, "<Metric>", "Luminous", Unsupported),
        // A wrong root element.
        ("IESTM33-22>", "Photometry>", all, "<Photometry>", "IESTM33-22", Invalid),
        // A non-positive multiplier.
        ("<SymmType>", "<Multiplier>0</Multiplier>\n<SymmType>", 1, "<Multiplier>", "multiplier > 0", Invalid),
    ];
    for (from, to, n, needle, word, kind) in edits {
        check(good.replacen(from, to, n), needle, word, kind);
    }
    // A point missing from the grid, a duplicated point.
    let mut dup = ok.clone();
    dup[3] = dup[2];
    let grids = [
        (&ok[..3], "<LuminousData>", "no value at horz = 90, vert = 90"),
        (&dup[..], "horz=\"90\" vert=\"0\"", "second value"),
    ];
    for (points, needle, word) in grids {
        check(doc23("", points), needle, word, Invalid);
    }
    // A DTD.
    let e = parse(&good.replace("<IESTM33-22>", "<!DOCTYPE x [<!ENTITY a \"b\">]><IESTM33-22>")).unwrap_err();
    assert!(e.to_string().contains("without a DTD"), "{e}");
}

/// The writer's text read by the XML parser itself (not our reader): the
/// root, the version and one IntensityData per stored grid point.
#[test]
fn written_document_structure() {
    let lum =
        crate::formats::load_document(Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/roadway.ldt")).unwrap();
    let text = write(&lum);
    let doc = roxmltree::Document::parse(&text).unwrap();
    let root = doc.root_element();
    assert_eq!(root.tag_name().name(), "IESTM33-22");
    let n = root.descendants().filter(|n| n.has_tag_name("IntensityData")).count();
    assert_eq!(n, lum.distribution().intensities_cd().len());
    assert_eq!(
        root.descendants()
            .find(|n| n.has_tag_name("Version"))
            .and_then(|n| n.text()),
        Some("1.1")
    );
    let back = parse(&text).unwrap();
    assert_eq!(back.distribution(), lum.distribution());
    assert_eq!(back.metadata().manufacturer, lum.metadata().manufacturer);
    assert_eq!(back.declared().absolute, lum.declared().absolute);
}

/// Every truncation of a written document is refused (never a panic) with
/// an error that names the file and a line.
#[test]
fn every_truncation_is_refused_with_a_line() {
    let pts = grid(&[0.0, 90.0], &[0.0, 45.0, 90.0], |h, v| 1.0 + h + v);
    let text = write(&parse(&doc23("<SymmType>Symm _ Quad</SymmType>\n", &pts)).unwrap());
    for end in 0..text.len() - 1 {
        let e = parse(&text[..end]).unwrap_err();
        assert!(e.location.line >= 1 || end == 0, "cut at {end}: {e}");
        assert_eq!(e.path, Path::new("t.xml"));
    }
}

/// A TM-33-23 document with one emitter per `(id, peak cd)`: `<ID>` when
/// given, a rotationally symmetric grid (γ 0, 90, 180) falling from the peak.
fn multi(emitters: &[(Option<&str>, f64)]) -> String {
    let mut s = String::from(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<IESTM33-22>\n<Version>1.1</Version>\n\
         <Luminaire><NumEmitters>2</NumEmitters></Luminaire>\n",
    );
    for (id, peak) in emitters {
        s.push_str("<Emitter>\n");
        if let Some(id) = id {
            s.push_str(&format!("<ID>{id}</ID>\n"));
        }
        s.push_str("<Quantity>1</Quantity>\n<RatedLumens>1000</RatedLumens>\n<LuminousData>\n<SymmType>Symm _ Full</SymmType>\n");
        for (v, k) in [(0.0, 1.0), (90.0, 0.5), (180.0, 0.0)] {
            s.push_str(&format!(
                "<IntensityData horz=\"0\" vert=\"{v}\">{}</IntensityData>\n",
                peak * k
            ));
        }
        s.push_str("</LuminousData>\n</Emitter>\n");
    }
    s.push_str("</IESTM33-22>\n");
    s
}

/// Several emitters: each is read by its `<ID>` (or its position when it has
/// none or shares it); unnamed, the document is refused with the ids listed
/// and how to name one; an unknown id is refused with the ids it holds.
#[test]
fn several_emitters_are_read_one_at_a_time_by_id() {
    let text = multi(&[(Some("down"), 100.0), (Some("up"), 300.0), (None, 500.0)]);
    assert_eq!(emitter_ids(text.as_bytes()), ["down", "up", "3"]);
    let opts = ReadOptions::default();
    for (id, peak) in [("down", 100.0), ("up", 300.0), ("3", 500.0)] {
        let name = format!("m.xml#{id}");
        let d = read_emitter(text.as_bytes(), Path::new(&name), Some(id), &opts).unwrap();
        assert_eq!(d.distribution().max_cd(), peak, "{id}");
        assert_eq!(d.path(), Some(Path::new(&name)));
    }
    let e = parse(&text).unwrap_err();
    assert_eq!(e.kind, ErrorKind::Invalid);
    assert!(
        e.expected.contains("this document holds 3") && e.expected.contains("t.xml#ID"),
        "{e}"
    );
    assert_eq!(e.found, "the ids down, up, 3");
    let e = read_emitter(text.as_bytes(), Path::new("m.xml#side"), Some("side"), &opts).unwrap_err();
    assert!(
        e.expected.contains("an emitter id of the document: down, up, 3") && e.found == "`side`",
        "{e}"
    );
    // A shared id names neither emitter: both go by position.
    let dup = multi(&[(Some("a"), 100.0), (Some("a"), 200.0)]);
    assert_eq!(emitter_ids(dup.as_bytes()), ["1", "2"]);
    // One emitter reads as before, with or without an id; not TM-33 has none.
    assert!(parse(&multi(&[(Some("only"), 100.0)])).is_ok());
    assert!(emitter_ids(b"<Root/>").is_empty() && emitter_ids(b"not xml").is_empty());
}

/// `FILE.xml#ID` through `load`, and a several-emitter document expanded to
/// one path per emitter by `photometries_in` and `collect_files` (as a GLDF
/// container is); `FILE.xml` alone names the ids in its error.
#[test]
fn file_xml_hash_id_loads_one_emitter() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("two.xml");
    std::fs::write(&p, multi(&[(Some("down"), 100.0), (Some("up"), 300.0)])).unwrap();
    let want: Vec<std::path::PathBuf> = ["down", "up"].iter().map(|id| emitters::reference(&p, id)).collect();
    assert_eq!(crate::formats::photometries_in(&p), want);
    let mut files = Vec::new();
    crate::formats::collect_files(dir.path(), &mut files).unwrap();
    assert_eq!(files, want);
    let l = crate::formats::load(&want[1]).unwrap();
    assert_eq!(l.distribution().max_cd(), 300.0);
    let e = crate::formats::load(&p).unwrap_err().to_string();
    assert!(e.contains("two.xml") && e.contains("the ids down, up"), "{e}");
    let e = crate::formats::load(emitters::reference(&p, "nope"))
        .unwrap_err()
        .to_string();
    assert!(e.contains("two.xml#nope") && e.contains("`nope`"), "{e}");
    assert_eq!(
        split_reference(Path::new("a/b.XML#x#y")),
        Some((std::path::PathBuf::from("a/b.XML"), "x#y".to_string()))
    );
    assert_eq!(split_reference(Path::new("a/b.ldt#x")), None);
    // One emitter: the path itself.
    let one = dir.path().join("one.xml");
    std::fs::write(&one, multi(&[(None, 100.0)])).unwrap();
    assert_eq!(crate::formats::photometries_in(&one), vec![one.clone()]);
}

/// A document whose angles (C 0 and 90) do not fit its `Symm _ Bi _ 90`
/// code: refused with a hint at `--repair`; with it, read by the angles it
/// has (quadrant symmetry) with a `symmetry-repaired` warning at the code's line.
#[test]
fn repair_reads_a_symmetry_code_the_angles_do_not_fit_by_the_angles() {
    let vs = [0.0, 45.0, 90.0];
    let text = doc23(
        "<SymmType>Symm _ Bi _ 90</SymmType>\n",
        &grid(&[0.0, 90.0], &vs, |h, v| 100.0 + h - v),
    );
    let e = parse(&text).unwrap_err();
    assert!(e.expected.contains("--repair"), "{e}");
    let repair = ReadOptions {
        repair: true,
        ..ReadOptions::default()
    };
    let lum = read(text.as_bytes(), Path::new("t.xml"), &repair).unwrap();
    assert_eq!(lum.distribution().symmetry(), Symmetry::Quadrant);
    assert_eq!(lum.distribution().value_cd(1, 0), 190.0);
    let w = lum.warnings().iter().find(|w| w.code == "symmetry-repaired").unwrap();
    let code_line = text.lines().position(|l| l.contains("<SymmType>")).unwrap() + 1;
    assert_eq!(w.line, Some(code_line), "{w}");
    assert!(w.message.contains("0, 90"), "{w}");
}
