//! Tests of the GLDF container reader: containers are written here with the
//! `zip` crate around files of `data/` and a `product.xml` in the layout of
//! the GLDF documentation (globallightingdata/website, docs/structure/photometries.md).

use std::io::Write;
use std::path::{Path, PathBuf};

use super::*;
use crate::formats::{collect_files, load, load_with};

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data").join(name)
}

/// A zip archive of `(member, bytes)` (deflated) at `path`.
fn write_zip(path: &Path, members: &[(&str, Vec<u8>)]) {
    let mut z = zip::ZipWriter::new(std::io::Cursor::new(Vec::new()));
    let opts = zip::write::SimpleFileOptions::default().compression_method(zip::CompressionMethod::Deflated);
    for (name, bytes) in members {
        z.start_file(*name, opts).unwrap();
        z.write_all(bytes).unwrap();
    }
    std::fs::write(path, z.finish().unwrap().into_inner()).unwrap();
}

/// A product.xml with photometries `(id, fileId, file name, DescriptivePhotometry children)`.
fn product(photometries: &[(&str, &str, &str, &str)]) -> Vec<u8> {
    let mut files = String::new();
    let mut phs = String::new();
    for (id, file_id, name, desc) in photometries {
        let ct = if name.ends_with(".ies") {
            "ldc/iesna"
        } else {
            "ldc/eulumdat"
        };
        files.push_str(&format!(
            "      <File id=\"{file_id}\" contentType=\"{ct}\" type=\"localFileName\">{name}</File>\n"
        ));
        phs.push_str(&format!(
            "      <Photometry id=\"{id}\">\n        <PhotometryFileReference fileId=\"{file_id}\" />\n\
             <DescriptivePhotometry>{desc}</DescriptivePhotometry>\n      </Photometry>\n"
        ));
    }
    format!(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<Root>\n  <Header/>\n  <GeneralDefinitions>\n    <Files>\n{files}    \
         </Files>\n    <Photometries>\n{phs}    </Photometries>\n  </GeneralDefinitions>\n  <ProductDefinitions/>\n</Root>\n"
    )
    .into_bytes()
}

const DECLARED: &str = "<LightOutputRatio>0.85</LightOutputRatio><DownwardFluxFraction>0.9</DownwardFluxFraction>\
    <CIE-FluxCode>44 75 94 100 100</CIE-FluxCode><UGR-4H8H-70-50-20-LQ><X>19.5</X><Y>20.1</Y></UGR-4H8H-70-50-20-LQ>\
    <LightDistributionBUG-Rating>B1 U0 G1</LightDistributionBUG-Rating><LuminousEfficacy>98.2</LuminousEfficacy>";

/// A container holding data/roadway.ldt (id `road`) and data/batwing.ies (id `bat`).
fn two_photometries(dir: &Path) -> PathBuf {
    let p = dir.join("lum.gldf");
    write_zip(
        &p,
        &[
            (
                "product.xml",
                product(&[
                    ("road", "f1", "roadway.ldt", DECLARED),
                    ("bat", "f2", "batwing.ies", ""),
                ]),
            ),
            ("ldc/roadway.ldt", std::fs::read(data("roadway.ldt")).unwrap()),
            ("ldc/batwing.ies", std::fs::read(data("batwing.ies")).unwrap()),
        ],
    );
    p
}

#[test]
fn each_photometry_loads_like_its_file_and_carries_the_declared_values() {
    let dir = tempfile::tempdir().unwrap();
    let p = two_photometries(dir.path());
    let road = crate::formats::load_document(reference(&p, "road")).unwrap();
    let file = load(data("roadway.ldt")).unwrap();
    assert_eq!(road.distribution(), file.distribution());
    assert_eq!(road.path(), Some(reference(&p, "road").as_path()));
    let g = road.gldf.as_ref().unwrap();
    assert_eq!((g.id.as_str(), g.file.as_str()), ("road", "ldc/roadway.ldt"));
    assert_eq!((g.lor, g.dff), (Some(0.85), Some(0.9)));
    assert_eq!(g.cie_flux_code.as_deref(), Some("44 75 94 100 100"));
    assert_eq!(
        g.ugr_4h8h_70_50_20,
        Some(DeclaredUgr {
            crosswise: 19.5,
            endwise: 20.1
        })
    );
    assert_eq!(g.bug_rating.as_deref(), Some("B1 U0 G1"));
    assert_eq!(g.luminous_efficacy_lm_per_w, Some(98.2));
    let bat = crate::formats::load_document(reference(&p, "bat")).unwrap();
    assert_eq!(bat.distribution(), load(data("batwing.ies")).unwrap().distribution());
    assert_eq!(bat.gldf.as_ref().unwrap().lor, None);
}

#[test]
fn several_photometries_need_an_id_and_a_directory_expands() {
    let dir = tempfile::tempdir().unwrap();
    let p = two_photometries(dir.path());
    let e = load(&p).unwrap_err().to_string();
    assert!(e.contains("road, bat") && e.contains("#ID"), "{e}");
    let e = load(reference(&p, "nope")).unwrap_err().to_string();
    assert!(e.contains("`nope`") && e.contains("road, bat"), "{e}");
    let mut files = Vec::new();
    collect_files(dir.path(), &mut files).unwrap();
    assert_eq!(files, vec![reference(&p, "road"), reference(&p, "bat")]);
    let mut files = Vec::new();
    collect_files(&p, &mut files).unwrap();
    assert_eq!(files.len(), 2);
    // One photometry: the container alone names it.
    let one = dir.path().join("one.gldf");
    write_zip(
        &one,
        &[
            ("product.xml", product(&[("only", "f", "lambertian.ldt", "")])),
            ("ldc/lambertian.ldt", std::fs::read(data("lambertian.ldt")).unwrap()),
        ],
    );
    let lum = load_with(&one, &ReadOptions::default()).unwrap();
    assert_eq!(lum.distribution(), load(data("lambertian.ldt")).unwrap().distribution());
}

/// Every broken container: the error names the container and what was expected.
#[test]
fn broken_containers_get_clear_errors() {
    let dir = tempfile::tempdir().unwrap();
    let ldt = std::fs::read(data("roadway.ldt")).unwrap();
    let err = |name: &str, members: &[(&str, Vec<u8>)]| {
        let p = dir.path().join(name);
        write_zip(&p, members);
        let e = load(&p).unwrap_err().to_string();
        assert!(e.contains(name), "{e}");
        e
    };
    let e = err("no_product.gldf", &[("ldc/roadway.ldt", ldt.clone())]);
    assert!(e.contains("product.xml"), "{e}");
    let e = err(
        "missing_file.gldf",
        &[("product.xml", product(&[("a", "f", "gone.ldt", "")]))],
    );
    assert!(e.contains("ldc/gone.ldt") && e.contains("photometry a"), "{e}");
    let bad_ref = product(&[("a", "f", "roadway.ldt", "")]);
    let bad_ref = String::from_utf8(bad_ref)
        .unwrap()
        .replace("fileId=\"f\"", "fileId=\"g\"");
    let e = err(
        "bad_ref.gldf",
        &[("product.xml", bad_ref.into_bytes()), ("ldc/roadway.ldt", ldt.clone())],
    );
    assert!(e.contains("no File with id `g`") && e.contains("product.xml:"), "{e}");
    // Malformed XML: the line inside product.xml.
    let e = err(
        "malformed.gldf",
        &[("product.xml", b"<Root>\n<GeneralDefinitions>\n</Root>".to_vec())],
    );
    assert!(e.contains("malformed.gldf/product.xml:3:"), "{e}");
    // A photometric file that is itself broken: named FILE.gldf#ID.
    let e = err(
        "broken_ldt.gldf",
        &[
            ("product.xml", product(&[("a", "f", "x.ldt", "")])),
            ("ldc/x.ldt", b"just\nsome\ntext\n".to_vec()),
        ],
    );
    assert!(e.contains("broken_ldt.gldf#a"), "{e}");
    // A photometry whose file is a URL: listed, refused when loaded, naming it.
    let url = String::from_utf8(product(&[("web", "f", "x.ldt", "")]))
        .unwrap()
        .replace("type=\"localFileName\">x.ldt", "type=\"url\">https://example.com/x.ldt");
    let p = dir.path().join("url.gldf");
    write_zip(&p, &[("product.xml", url.into_bytes())]);
    assert_eq!(GldfContainer::open(&p).unwrap().ids(), vec!["web"]);
    let e = load(&p).unwrap_err().to_string();
    assert!(
        e.contains("url.gldf#web") && e.contains("type=\"url\"") && e.contains("https://example.com/x.ldt"),
        "{e}"
    );
    // Not a zip at all.
    let p = dir.path().join("text.gldf");
    std::fs::write(&p, "not a zip").unwrap();
    let e = load(&p).unwrap_err().to_string();
    assert!(e.contains("text.gldf") && e.contains("zip archive"), "{e}");
}

#[test]
fn zip_bombs_are_refused_by_size_and_by_entry_count() {
    let dir = tempfile::tempdir().unwrap();
    // 65 MiB of zeros deflate to about 65 KiB: more than MAX_MEMBER_BYTES once inflated.
    let zeros = vec![0u8; (MAX_MEMBER_BYTES + (1 << 20)) as usize];
    let p = dir.path().join("bomb.gldf");
    write_zip(
        &p,
        &[
            ("product.xml", product(&[("a", "f", "x.ldt", "")])),
            ("ldc/x.ldt", zeros.clone()),
        ],
    );
    assert!(std::fs::metadata(&p).unwrap().len() < 1 << 20);
    let e = load(reference(&p, "a")).unwrap_err().to_string();
    assert!(e.contains("zip bomb") && e.contains("ldc/x.ldt"), "{e}");
    let p = dir.path().join("xml_bomb.gldf");
    write_zip(&p, &[("product.xml", zeros)]);
    let e = load(&p).unwrap_err().to_string();
    assert!(e.contains("zip bomb") && e.contains("product.xml"), "{e}");
    // Too many entries.
    let p = dir.path().join("many.gldf");
    let names: Vec<String> = (0..=MAX_ENTRIES).map(|i| format!("e{i}")).collect();
    let members: Vec<(&str, Vec<u8>)> = names.iter().map(|n| (n.as_str(), Vec::new())).collect();
    write_zip(&p, &members);
    let e = load(&p).unwrap_err().to_string();
    assert!(e.contains(&format!("at most {MAX_ENTRIES} entries")), "{e}");
}

/// Every truncation of a container is an error naming it, never a panic.
#[test]
fn truncated_containers_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let p = two_photometries(dir.path());
    let bytes = std::fs::read(&p).unwrap();
    let cut = dir.path().join("cut.gldf");
    for end in (0..bytes.len()).step_by(97) {
        std::fs::write(&cut, &bytes[..end]).unwrap();
        let e = load(reference(&cut, "road")).unwrap_err().to_string();
        assert!(e.contains("cut.gldf"), "cut at {end}: {e}");
    }
}

#[test]
fn references_split_only_gldf_names() {
    assert_eq!(
        split_reference(Path::new("a/b.GLDF#x#y")),
        Some((PathBuf::from("a/b.GLDF"), Some("x#y".into())))
    );
    assert_eq!(
        split_reference(Path::new("a/b.gldf#id 1")),
        Some((PathBuf::from("a/b.gldf"), Some("id 1".into())))
    );
    assert_eq!(
        split_reference(Path::new("a/b.gldf")),
        Some((PathBuf::from("a/b.gldf"), None))
    );
    assert_eq!(split_reference(Path::new("a/b.ldt#x")), None);
}
