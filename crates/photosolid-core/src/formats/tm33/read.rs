//! TM-33 reader: XML → [`Luminaire`] (see the module docs of `tm33` for the elements read).

use std::path::Path;

use roxmltree::Node;

use super::Tm33Edition;
use crate::error::{ErrorKind, Location, Num, ParseError, Warning, WarningCode};
use crate::formats::scan::parse_f64;
use crate::formats::xml::{self, child, child_number, child_text, children, error_at};
use crate::formats::{angles, declared_lamp_flux, ReadOptions};
use crate::model::{
    Dimensions, Distribution, Format, LampSet, LuminaireParts, Metadata, PhotometricType, Symmetry, Tilt, ANGLE_EPS,
};

/// Names of the element holding the intensity data, by edition and spelling.
const INTENSITY_BLOCKS: [&str; 3] = ["LuminousData", "LuminousIntensity", "IntensityDistribution"];

/// Read a TM-33-18 or TM-33-23 document of one emitter (with intensity
/// data). `path` names the file in messages.
///
/// # Errors
/// As [`read_emitter`]; a document with several emitters is refused with
/// their ids (name one as `FILE.xml#ID`).
pub fn read(bytes: &[u8], path: &Path, opts: &ReadOptions) -> Result<crate::formats::Document, ParseError> {
    read_emitter(bytes, path, None, opts)
}

/// Read one emitter of a TM-33-18 or TM-33-23 document: the one named
/// `emitter` (its `<ID>`, or its 1-based position when it has none; see
/// [`super::emitters`]), or the only one when `None`. `path` names the
/// file in messages (`FILE.xml#ID` when an emitter is named).
///
/// # Errors
/// Malformed XML, a root element that is neither `LuminaireOpticalData` nor
/// `IESTM33-22`, no emitter with intensity data, several and none named, an
/// id the document does not hold, a missing or
/// unreadable `horz`/`vert`/value, an incomplete or duplicated grid point, a
/// symmetry code that does not match the `horz` angles; each at the line of
/// the offending element, naming it. Type A/B data and non-luminous metrics
/// are [`ErrorKind::Unsupported`].
pub fn read_emitter(
    bytes: &[u8],
    path: &Path,
    emitter: Option<&str>,
    opts: &ReadOptions,
) -> Result<crate::formats::Document, ParseError> {
    let text = xml::decode(bytes, path)?;
    let doc = xml::parse(text, path, "a TM-33 document")?;
    let root = doc.root_element();
    let edition = edition_of(path, root)?;
    let mut warnings = Vec::new();
    let emitter = super::emitters::choose(path, root, emitter)?;
    let block = intensity_block(path, emitter)?;
    check_type_and_metric(path, block)?;
    let multiplier = multiplier_of(path, block)?;
    let declared_symmetry = symmetry_code(path, block)?;
    let distribution = grid(path, block, multiplier, declared_symmetry, opts.repair, &mut warnings)?;

    let quantity = child_number(path, emitter, &["Quantity"])?.unwrap_or(1.0);
    let rated = child_number(path, emitter, &["RatedLumens"])?;
    let watts = child_number(path, emitter, &["InputWattage", "InputWatts"])?;
    let absolute = absolute_photometry(path, block, rated.is_some())?;
    let lamp_flux = if absolute {
        None
    } else {
        rated.map(|r| r * quantity.max(1.0)).filter(|f| *f > 0.0)
    };
    let mut lamp_set = lamp_set(emitter, quantity, absolute, lamp_flux, watts);
    let kept = declarations(path, root)?;
    let mut declared = declared_lamp_flux(lamp_flux, absolute, watts);
    if let Some(k) = &kept {
        declared.lor = k.lor;
        declared.dff = k.dff;
        declared.luminaire_flux_lm = k.luminaire_flux_lm;
        if let Some(c) = &k.colour {
            lamp_set.color.clone_from(c);
        }
        if let Some(c) = &k.cri {
            lamp_set.cri.clone_from(c);
        }
    }
    let dims = dimensions(path, root)?;
    let parts = LuminaireParts {
        path: Some(path.to_path_buf()),
        format: Format::Tm33,
        version: edition.version().into(),
        photometric_type: PhotometricType::C,
        metadata: metadata(root, &lamp_set.lamp_type),
        lamp_sets: vec![lamp_set],
        dimensions: dims,
        luminous_opening: kept.as_ref().map_or_else(Dimensions::default, |k| k.luminous_area),
        luminous_heights_m: kept.as_ref().and_then(|k| k.luminous_heights_m),
        declared,
        tilt: Tilt::None,
        distribution,
        source_grid: None,
        warnings,
        front: crate::model::Front::convention(Format::Tm33),
    };
    crate::formats::document(path, parts, crate::formats::Header::None)
}

/// The edition the root element names.
fn edition_of(path: &Path, root: Node<'_, '_>) -> Result<Tm33Edition, ParseError> {
    match root.tag_name().name() {
        "LuminaireOpticalData" => Ok(Tm33Edition::Tm33_18),
        "IESTM33-22" => Ok(Tm33Edition::Tm33_23),
        other => Err(error_at(
            path,
            root,
            ErrorKind::Invalid,
            "the root element LuminaireOpticalData (TM-33-18) or IESTM33-22 (TM-33-23)",
            format!("<{other}>"),
        )),
    }
}

/// The intensity block's `Multiplier` (1 when absent), which must be > 0.
fn multiplier_of(path: &Path, block: Node<'_, '_>) -> Result<f64, ParseError> {
    let multiplier = child_number(path, block, &["Multiplier"])?.unwrap_or(1.0);
    if multiplier <= 0.0 {
        let node = child(block, &["Multiplier"]).unwrap_or(block);
        return Err(error_at(
            path,
            node,
            ErrorKind::Invalid,
            "a multiplier > 0",
            Num(multiplier),
        ));
    }
    Ok(multiplier)
}

/// The luminaire's `Dimensions` (millimetres in the file, metres here; zero when absent).
fn dimensions(path: &Path, root: Node<'_, '_>) -> Result<Dimensions, ParseError> {
    Ok(
        match child(root, &["Luminaire"]).and_then(|l| child(l, &["Dimensions"])) {
            Some(d) => Dimensions {
                length_m: child_number(path, d, &["Length"])?.unwrap_or(0.0) / 1000.0,
                width_m: child_number(path, d, &["Width"])?.unwrap_or(0.0) / 1000.0,
                height_m: child_number(path, d, &["Height"])?.unwrap_or(0.0) / 1000.0,
            },
            None => Dimensions::default(),
        },
    )
}

/// The `Header`'s texts (empty when absent) and the lamp type.
fn metadata(root: Node<'_, '_>, lamp: &str) -> Metadata {
    let header = child(root, &["Header"]);
    let text_of = |names: &[&str]| -> String { header.and_then(|h| child_text(h, names)).unwrap_or("").to_string() };
    Metadata {
        manufacturer: text_of(&["Manufacturer"]),
        catalogue: text_of(&["CatalogNumber"]),
        luminaire: text_of(&["Description"]),
        lamp: lamp.to_string(),
        test_report: text_of(&["ReportNumber"]),
        date: text_of(&["ReportDate", "TestDate", "IssueDate"]),
    }
}

/// What our writer keeps in its `CustomData` item ([`super::DECLARATIONS_ID`]).
struct Kept {
    luminous_area: Dimensions,
    luminous_heights_m: Option<[f64; 4]>,
    lor: Option<f64>,
    dff: Option<f64>,
    luminaire_flux_lm: Option<f64>,
    colour: Option<String>,
    cri: Option<String>,
}

/// The declarations a document written by photosolid keeps (None in other documents).
///
/// # Errors
/// A number in them that does not parse, at its line.
fn declarations(path: &Path, root: Node<'_, '_>) -> Result<Option<Kept>, ParseError> {
    let Some(item) =
        children(root, "CustomData").find(|c| child_text(*c, &["UniqueIdentifier"]) == Some(super::DECLARATIONS_ID))
    else {
        return Ok(None);
    };
    let Some(d) = child(item, &["Declarations"]) else {
        return Ok(None);
    };
    let attr = |node: Node<'_, '_>, name: &str| -> Result<f64, ParseError> {
        let text = node.attribute(name).unwrap_or("0");
        parse_f64(text.trim().as_bytes())
            .filter(|v| v.is_finite())
            .ok_or_else(|| {
                error_at(
                    path,
                    node,
                    ErrorKind::Invalid,
                    format!("`{name}`, a finite number of metres"),
                    text,
                )
            })
    };
    let luminous_area = match child(d, &["LuminousArea"]) {
        Some(a) => Dimensions {
            length_m: attr(a, "length_m")?,
            width_m: attr(a, "width_m")?,
            height_m: attr(a, "height_m")?,
        },
        None => Dimensions::default(),
    };
    let luminous_heights_m = match child(d, &["LuminousHeights"]) {
        Some(h) => Some([
            attr(h, "c0_m")?,
            attr(h, "c90_m")?,
            attr(h, "c180_m")?,
            attr(h, "c270_m")?,
        ]),
        None => None,
    };
    let text = |name: &str| child(d, &[name]).and_then(|c| c.text()).map(str::to_string);
    Ok(Some(Kept {
        luminous_area,
        luminous_heights_m,
        lor: child_number(path, d, &["LOR"])?,
        dff: child_number(path, d, &["DFF"])?,
        luminaire_flux_lm: child_number(path, d, &["LuminaireFlux"])?,
        colour: text("LampColour"),
        cri: text("LampCri"),
    }))
}

/// `<AbsolutePhotometry>`; absent, absolute when no rated lumens are given.
fn absolute_photometry(path: &Path, block: Node<'_, '_>, rated: bool) -> Result<bool, ParseError> {
    let Some(n) = child(block, &["AbsolutePhotometry"]) else {
        return Ok(!rated);
    };
    match n.text().map(str::trim).unwrap_or("") {
        "true" | "1" => Ok(true),
        "false" | "0" => Ok(false),
        other => Err(error_at(
            path,
            n,
            ErrorKind::Invalid,
            "true or false",
            format!("`{other}`"),
        )),
    }
}

/// The emitter as a lamp set: count (negative for absolute photometry), flux in lm, CCT, CRI, watts.
fn lamp_set(
    emitter: Node<'_, '_>,
    quantity: f64,
    absolute: bool,
    lamp_flux: Option<f64>,
    watts: Option<f64>,
) -> LampSet {
    let cct = child_text(emitter, &["CCT", "FixedCCT"]).unwrap_or("");
    let cri = child(emitter, &["ColorRendering"])
        .and_then(|c| child_text(c, &["Ra"]))
        .unwrap_or("");
    let lamp = child_text(emitter, &["Description", "CatalogNumber"]).unwrap_or("");
    LampSet {
        count: if absolute {
            -quantity.max(1.0)
        } else {
            quantity.max(1.0)
        },
        lamp_type: lamp.to_string(),
        flux_lm: lamp_flux.unwrap_or(0.0),
        color: if cct.is_empty() {
            String::new()
        } else {
            format!("{cct}K")
        },
        cri: cri.to_string(),
        watts: watts.unwrap_or(0.0),
    }
}

/// The emitter's intensity block, when it holds `IntensityData`.
pub(super) fn block_of<'a, 'i>(emitter: Node<'a, 'i>) -> Option<Node<'a, 'i>> {
    emitter
        .children()
        .filter(|c| c.is_element() && INTENSITY_BLOCKS.contains(&c.tag_name().name()))
        .find(|b| children(*b, "IntensityData").next().is_some())
}

/// The emitter's intensity block (`choose` picks only emitters that have one;
/// the error is for a caller that does not).
fn intensity_block<'a, 'i>(path: &Path, emitter: Node<'a, 'i>) -> Result<Node<'a, 'i>, ParseError> {
    block_of(emitter).ok_or_else(|| {
        error_at(
            path,
            emitter,
            ErrorKind::Invalid,
            "an intensity block with <IntensityData>",
            "none",
        )
    })
}

/// Refuse Type A/B grids and radiant, photon or spectral data: the model holds Type C luminous intensity.
fn check_type_and_metric(path: &Path, block: Node<'_, '_>) -> Result<(), ParseError> {
    if let Some(n) = child(block, &["PhotometryType"]) {
        let t: String = n.text().unwrap_or("").chars().filter(|c| c.is_alphanumeric()).collect();
        let t = t.to_ascii_uppercase();
        if !matches!(t.as_str(), "C" | "CIEC" | "TYPEC") {
            return Err(error_at(
                path,
                n,
                ErrorKind::Unsupported,
                "Type C photometry (`CIE _ C`)",
                format!("`{}`", n.text().unwrap_or("").trim()),
            ));
        }
    }
    if let Some(n) = child(block, &["Metric"]) {
        let t = n.text().unwrap_or("").trim();
        if !t.eq_ignore_ascii_case("Luminous") {
            return Err(error_at(
                path,
                n,
                ErrorKind::Unsupported,
                "luminous intensity (`Luminous`)",
                format!("`{t}`"),
            ));
        }
    }
    Ok(())
}

/// The declared symmetry code, `None` when absent.
fn symmetry_code(path: &Path, block: Node<'_, '_>) -> Result<Option<(Symmetry, Location)>, ParseError> {
    let Some(n) = child(block, &["SymmType", "Symm"]) else {
        return Ok(None);
    };
    let raw = n.text().unwrap_or("").trim();
    let key: String = raw
        .chars()
        .filter(|c| c.is_alphanumeric())
        .collect::<String>()
        .to_ascii_uppercase();
    let key = key.strip_prefix("SYMM").unwrap_or(&key);
    let s = match key {
        "NONE" | "ARBITRARY" => Symmetry::None,
        "FULL" => Symmetry::Rotational,
        "BI0" => Symmetry::C0C180,
        "BI90" => Symmetry::C90C270,
        "QUAD" => Symmetry::Quadrant,
        _ => {
            return Err(error_at(
                path,
                n,
                ErrorKind::Invalid,
                "a symmetry code: Symm _ None, Symm _ Full, Symm _ Bi _ 0, Symm _ Bi _ 90, Symm _ Quad or Symm _ \
                 Arbitrary",
                format!("`{raw}`"),
            ))
        }
    };
    Ok(Some((s, xml::location(n))))
}

/// One `IntensityData` point: C, γ (degrees), value × multiplier (cd) and its element.
struct Point<'a, 'i> {
    c: f64,
    gamma: f64,
    cd: f64,
    node: Node<'a, 'i>,
}

fn attribute(path: &Path, n: Node<'_, '_>, name: &str) -> Result<f64, ParseError> {
    let raw = n.attribute(name).ok_or_else(|| {
        error_at(
            path,
            n,
            ErrorKind::Invalid,
            format!("the attribute {name} (degrees)"),
            "none",
        )
    })?;
    parse_f64(raw.trim().as_bytes()).ok_or_else(|| {
        error_at(
            path,
            n,
            ErrorKind::Invalid,
            format!("{name} as a finite number of degrees"),
            format!("`{raw}`"),
        )
    })
}

/// Sorted distinct angles, by the readers' one de-duplication rule
/// ([`angles::repair_order`]: closer than [`ANGLE_EPS`] counts as the same).
fn distinct(v: Vec<f64>) -> Vec<f64> {
    angles::repair_order(&v).into_iter().map(|i| v[i]).collect()
}

/// Index of `x` in the sorted distinct list `v` (it is there by construction).
fn index_of(v: &[f64], x: f64) -> usize {
    let i = v.partition_point(|&a| a < x - ANGLE_EPS);
    i.min(v.len() - 1)
}

/// Two `IntensityData` at one (horz, vert).
fn second_value(path: &Path, p: &Point<'_, '_>) -> ParseError {
    error_at(
        path,
        p.node,
        ErrorKind::Invalid,
        "one IntensityData per (horz, vert)",
        format!("a second value at horz = {}, vert = {}", Num(p.c), Num(p.gamma)),
    )
}

/// The `IntensityData` points as a Type C [`Distribution`].
fn grid(
    path: &Path,
    block: Node<'_, '_>,
    multiplier: f64,
    declared: Option<(Symmetry, Location)>,
    repair: bool,
    warnings: &mut Vec<Warning>,
) -> Result<Distribution, ParseError> {
    let points = points(path, block, multiplier)?;
    let hs = distinct(points.iter().map(|p| p.c).collect());
    let vs = distinct(points.iter().map(|p| p.gamma).collect());
    let nv = vs.len();
    let mut cd = complete_grid(path, block, &points, &hs, &vs)?;
    if let Some(note) = crate::formats::negative_intensities(&cd, "cd") {
        let first = points.iter().find(|p| p.cd < 0.0).map_or(block, |p| p.node);
        warnings.push(Warning::at(
            xml::location(first).line,
            WarningCode::NegativeIntensity,
            note,
        ));
    }
    match crate::formats::into_model_range(&mut cd) {
        Ok(Some(note)) => warnings.push(Warning::new(WarningCode::RangeSnapped, note)),
        Ok(None) => {}
        Err((i, why)) => {
            let at = points
                .iter()
                .find(|p| index_of(&hs, p.c) * nv + index_of(&vs, p.gamma) == i)
                .map_or(block, |p| p.node);
            return Err(error_at(
                path,
                at,
                ErrorKind::Invalid,
                "an intensity within the model's range",
                why,
            ));
        }
    }
    let symmetry = match declared {
        Some((s, _)) => s,
        None => inferred(&hs),
    };
    match layout(path, block, &hs, &vs, &cd, symmetry, declared, warnings) {
        Err(_) if repair && declared.is_some() && inferred(&hs) != symmetry => {
            // `--repair`: the angles the document has, not its code, say the layout.
            let by_angles = inferred(&hs);
            let d = layout(path, block, &hs, &vs, &cd, by_angles, None, warnings)?;
            let line = declared.map(|(_, l)| l.line);
            warnings.push(Warning {
                line,
                code: WarningCode::SymmetryRepaired,
                message: format!(
                    "the <SymmType> code says {} symmetry, which its horz angles ({}) do not fit; read as {} symmetry \
                     by the angles it has (--repair)",
                    symmetry.describe(),
                    angle_list(&hs),
                    by_angles.describe()
                ),
            });
            Ok(d)
        }
        other => other,
    }
}

/// `hs` as a short list for messages: every angle up to eight, else the first and last three.
fn angle_list(hs: &[f64]) -> String {
    let f = |v: &[f64]| v.iter().map(|&x| Num(x).to_string()).collect::<Vec<_>>().join(", ");
    if hs.len() <= 8 {
        f(hs)
    } else {
        format!("{}, ..., {}", f(&hs[..3]), f(&hs[hs.len() - 3..]))
    }
}

/// The grid laid out with `symmetry`; `declared` is the code it came from (`None`: from the
/// angles), for the error's location and wording.
#[allow(clippy::too_many_arguments, reason = "the grid's parts, as `grid` holds them")]
fn layout(
    path: &Path,
    block: Node<'_, '_>,
    hs: &[f64],
    vs: &[f64],
    cd: &[f64],
    symmetry: Symmetry,
    declared: Option<(Symmetry, Location)>,
    warnings: &mut Vec<Warning>,
) -> Result<Distribution, ParseError> {
    let (nh, nv) = (hs.len(), vs.len());
    let (mut hs, mut cd) = (hs.to_vec(), cd.to_vec());
    if symmetry == Symmetry::Rotational && nh > 1 {
        let at = declared.map_or_else(|| xml::location(block), |(_, l)| l);
        return Err(ParseError {
            path: path.to_path_buf(),
            location: at,
            kind: ErrorKind::Invalid,
            expected: "one horz angle for Symm _ Full (rotational symmetry); --repair reads the document by the \
                       angles it has"
                .into(),
            found: format!("{nh} horz angles"),
        });
    }
    if symmetry == Symmetry::Rotational {
        hs[0] = 0.0;
    }
    if symmetry == Symmetry::None && nh > 1 && (hs[nh - 1] - 360.0).abs() <= ANGLE_EPS {
        crate::formats::angles::drop_360_plane(&mut hs, &mut cd, nv, warnings);
    }
    Distribution::new(hs, vs.to_vec(), cd, symmetry).map_err(|e| {
        let at = declared.map_or_else(|| xml::location(block), |(_, l)| l);
        ParseError {
            path: path.to_path_buf(),
            location: at,
            kind: ErrorKind::Invalid,
            expected: match declared {
                Some(_) => format!(
                    "horz angles that fit the <SymmType> code ({} symmetry); --repair reads the document by the \
                     angles it has",
                    symmetry.describe()
                ),
                None => "horz angles of a Type C layout (0..90, 0..180, 90..270 or up to 360)".to_string(),
            },
            found: e.to_string(),
        }
    })
}

/// Symmetry from the `horz` set when no code is given, by the LM-63 rule
/// ([`angles::lm63_symmetry`]); any other set is a full circle.
fn inferred(hs: &[f64]) -> Symmetry {
    angles::lm63_symmetry(hs).unwrap_or(Symmetry::None)
}

/// Every `IntensityData` point, angles checked and snapped onto Type C's range, values × `multiplier`.
fn points<'a, 'i>(path: &Path, block: Node<'a, 'i>, multiplier: f64) -> Result<Vec<Point<'a, 'i>>, ParseError> {
    let mut points = Vec::new();
    for n in children(block, "IntensityData") {
        let c = attribute(path, n, "horz")?;
        let gamma = attribute(path, n, "vert")?;
        let raw = n.text().map(str::trim).unwrap_or("");
        let v = parse_f64(raw.as_bytes()).ok_or_else(|| {
            error_at(
                path,
                n,
                ErrorKind::Invalid,
                "an intensity (a finite number)",
                format!("`{raw}`"),
            )
        })?;
        if angles::first_outside(&[gamma], 180.0).is_some() {
            return Err(error_at(
                path,
                n,
                ErrorKind::Invalid,
                "vert within 0..180 degrees (Type C)",
                Num(gamma),
            ));
        }
        if angles::first_outside(&[c], 360.0).is_some() {
            return Err(error_at(
                path,
                n,
                ErrorKind::Invalid,
                "horz within 0..360 degrees (Type C)",
                Num(c),
            ));
        }
        points.push(Point {
            c: c.clamp(0.0, 360.0),
            gamma: gamma.clamp(0.0, 180.0),
            cd: v * multiplier,
            node: n,
        });
    }
    Ok(points)
}

/// The values of `points` on the `hs` × `vs` grid (C-major), which they must fill exactly once.
fn complete_grid(
    path: &Path,
    block: Node<'_, '_>,
    points: &[Point<'_, '_>],
    hs: &[f64],
    vs: &[f64],
) -> Result<Vec<f64>, ParseError> {
    let (nh, nv) = (hs.len(), vs.len());
    if nh.checked_mul(nv) != Some(points.len()) {
        // Find the first missing point to name it (only when the grid is small enough to enumerate).
        let mut have = std::collections::HashSet::new();
        for p in points {
            if !have.insert((index_of(hs, p.c), index_of(vs, p.gamma))) {
                return Err(second_value(path, p));
            }
        }
        let missing = (0..nh)
            .flat_map(|ih| (0..nv).map(move |iv| (ih, iv)))
            .find(|k| !have.contains(k))
            .map(|(ih, iv)| format!("no value at horz = {}, vert = {}", Num(hs[ih]), Num(vs[iv])))
            .unwrap_or_default();
        return Err(error_at(
            path,
            block,
            ErrorKind::Invalid,
            format!("a complete grid of {nh} horz x {nv} vert angles"),
            format!("{} IntensityData: {missing}", points.len()),
        ));
    }
    let mut cd = vec![f64::NAN; nh * nv];
    for p in points {
        let k = index_of(hs, p.c) * nv + index_of(vs, p.gamma);
        if !cd[k].is_nan() {
            return Err(second_value(path, p));
        }
        cd[k] = p.cd;
    }
    Ok(cd)
}
