//! TM-33-23 writer: [`Luminaire`] → XML (root `IESTM33-22`, version 1.1).

use std::fmt::Write;

use crate::formats::xml::escape;
use crate::formats::Document;
use crate::model::Symmetry;

/// The TM-33-23 code of a symmetry.
fn symmetry_code(s: Symmetry) -> &'static str {
    match s {
        Symmetry::None => "Symm _ None",
        Symmetry::Rotational => "Symm _ Full",
        Symmetry::C0C180 => "Symm _ Bi _ 0",
        Symmetry::C90C270 => "Symm _ Bi _ 90",
        Symmetry::Quadrant => "Symm _ Quad",
    }
}

/// `<name>text</name>` on its own line at `indent`, omitted when `text` is empty.
fn element(out: &mut String, indent: usize, name: &str, text: &str) {
    if !text.is_empty() {
        let _ = writeln!(out, "{:indent$}<{name}>{}</{name}>", "", escape(text));
    }
}

/// Write `lum` as a TM-33-23 document: the header text, dimensions (mm, each
/// left out when it overflows),
/// one emitter with its rated flux (relative photometry only), wattage and
/// the stored C-planes as `IntensityData` in absolute candela with
/// `Multiplier` 1 (shortest round-trip decimals: lossless).
pub fn write(doc: &Document) -> String {
    let lum = &doc.luminaire;
    let m = lum.metadata();
    let d = lum.distribution();
    let mut s = String::with_capacity(64 * d.intensities_cd().len() + 1024);
    s.push_str("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<IESTM33-22>\n  <Version>1.1</Version>\n  <Header>\n");
    element(&mut s, 4, "Manufacturer", &m.manufacturer);
    element(&mut s, 4, "CatalogNumber", &m.catalogue);
    element(&mut s, 4, "Description", &m.luminaire);
    element(&mut s, 4, "ReportNumber", &m.test_report);
    element(&mut s, 4, "ReportDate", &m.date);
    s.push_str("  </Header>\n  <Luminaire>\n    <Dimensions>\n");
    let dims = lum.dimensions();
    for (name, metres) in [
        ("Length", dims.length_m),
        ("Width", dims.width_m),
        ("Height", dims.height_m),
    ] {
        // A dimension too large to state in millimetres (over 1.8e305 m: damaged input) is left out.
        let mm = metres * 1000.0;
        if mm.is_finite() {
            let _ = writeln!(s, "      <{name}>{mm}</{name}>");
        }
    }
    s.push_str("    </Dimensions>\n    <NumEmitters>1</NumEmitters>\n  </Luminaire>\n  <Emitter>\n");
    let quantity = lum.lamp_sets().first().map_or(1.0, |l| l.count.abs().max(1.0)).round();
    let _ = writeln!(s, "    <Quantity>{quantity}</Quantity>");
    element(&mut s, 4, "Description", &m.lamp);
    if let (false, Some(flux)) = (lum.declared().absolute, lum.declared().lamp_flux_lm) {
        let _ = writeln!(s, "    <RatedLumens>{}</RatedLumens>", flux / quantity);
    }
    if let Some(w) = lum.declared().input_watts {
        let _ = writeln!(s, "    <InputWattage>{w}</InputWattage>");
    }
    s.push_str("    <LuminousData>\n      <PhotometryType>CIE _ C</PhotometryType>\n      <Metric>Luminous</Metric>\n");
    let _ = writeln!(s, "      <SymmType>{}</SymmType>", symmetry_code(d.symmetry()));
    s.push_str("      <Multiplier>1</Multiplier>\n");
    let _ = writeln!(
        s,
        "      <AbsolutePhotometry>{}</AbsolutePhotometry>",
        lum.declared().absolute
    );
    for (ic, &c) in d.c_angles_deg().iter().enumerate() {
        for (ig, &g) in d.gamma_angles_deg().iter().enumerate() {
            let _ = writeln!(
                s,
                "      <IntensityData horz=\"{c}\" vert=\"{g}\">{}</IntensityData>",
                d.value_cd(ic, ig)
            );
        }
    }
    s.push_str("    </LuminousData>\n  </Emitter>\n</IESTM33-22>\n");
    s
}
