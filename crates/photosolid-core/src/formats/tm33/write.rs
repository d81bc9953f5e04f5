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
    let set = lum.lamp_sets().first();
    if let Some(k) = set.and_then(|l| kelvin(&l.color)) {
        let _ = writeln!(s, "    <CCT>{k}</CCT>");
    }
    if let Some(ra) = set
        .and_then(|l| l.cri.trim().parse::<f64>().ok())
        .filter(|v| v.is_finite())
    {
        let _ = writeln!(s, "    <ColorRendering>\n      <Ra>{ra}</Ra>\n    </ColorRendering>");
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
    s.push_str("    </LuminousData>\n  </Emitter>\n");
    declarations(&mut s, lum);
    s.push_str("</IESTM33-22>\n");
    s
}

/// A colour temperature in kelvin from a lamp colour text (`4000K`, `4000 K`, `3000`): None when it is no number.
fn kelvin(color: &str) -> Option<f64> {
    let t = color.trim();
    let t = t.strip_suffix(['K', 'k']).unwrap_or(t).trim();
    t.parse::<f64>().ok().filter(|k| k.is_finite() && *k > 0.0)
}

/// What TM-33-23 has no element for and the derived photometry needs, in the
/// schema's extension element (`CustomData`, [`super::DECLARATIONS_ID`]):
/// the luminous area (its signed LM-63 dimensions, or the EULUMDAT length,
/// width and four heights), the declared LOR, DFF and luminaire flux, and the
/// lamp colour and CRI texts as the source file has them. Readers that do not
/// know the identifier skip it; ours restores them ([`super::read`]).
fn declarations(s: &mut String, lum: &crate::model::Luminaire) {
    // Metres in Rust's shortest round-trip form: read back bit for bit.
    let mm = |m: f64| if m.is_finite() { m } else { 0.0 };
    let o = normalised_opening(lum);
    let _ = writeln!(
        s,
        "  <CustomData>\n    <Name>photosolid declarations</Name>\n    <UniqueIdentifier>{}</UniqueIdentifier>\n    <Declarations xmlns=\"{}\">",
        super::DECLARATIONS_ID,
        super::DECLARATIONS_ID
    );
    let _ = writeln!(
        s,
        "      <LuminousArea length_m=\"{}\" width_m=\"{}\" height_m=\"{}\"/>",
        mm(o.length_m),
        mm(o.width_m),
        mm(o.height_m)
    );
    if let Some(h) = lum.luminous_heights_m() {
        let _ = writeln!(
            s,
            "      <LuminousHeights c0_m=\"{}\" c90_m=\"{}\" c180_m=\"{}\" c270_m=\"{}\"/>",
            mm(h[0]),
            mm(h[1]),
            mm(h[2]),
            mm(h[3])
        );
    }
    let d = lum.declared();
    for (name, v) in [("LOR", d.lor), ("DFF", d.dff), ("LuminaireFlux", d.luminaire_flux_lm)] {
        if let Some(v) = v.filter(|v| v.is_finite()) {
            let _ = writeln!(s, "      <{name}>{v}</{name}>");
        }
    }
    if let Some(set) = lum.lamp_sets().first() {
        element(s, 6, "LampColour", &set.color);
        element(s, 6, "LampCri", &set.cri);
    }
    s.push_str("    </Declarations>\n  </CustomData>\n");
}

/// The luminous opening in the signs LM-63-2002 gives each shape (the
/// convention a TM-33 document read back is interpreted in): LM-63-1986/1991
/// disks and vertical cylinders and LM-63-1995 spheres, which leave the
/// length 0, get it equal to the width. EULUMDAT dimensions are unchanged
/// (their heights go with them and select the EULUMDAT convention).
fn normalised_opening(lum: &crate::model::Luminaire) -> crate::model::Dimensions {
    let mut o = lum.luminous_opening();
    // Signs that match no shape stay as they are (they then read back as no shape).
    if crate::model::opening::Opening::of_luminaire(lum).is_err() {
        return o;
    }
    let old = matches!(lum.version(), "LM-63-1986" | "LM-63-1991" | "LM-63-1995");
    if lum.format() == crate::model::Format::Ies && old && o.width_m < 0.0 && o.length_m == 0.0 {
        o.length_m = o.width_m;
        if o.height_m < 0.0 {
            o.height_m = o.width_m;
        }
    }
    o
}
