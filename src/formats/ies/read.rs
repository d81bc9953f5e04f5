//! The IES reader: text header, TILT, one number stream, Type C symmetry.

use std::path::Path;

use crate::error::{Location, ParseError, Warning, WarningCode};
use crate::formats::text::Source;
use crate::formats::{angles, ReadOptions};
use crate::model::{
    Declared, Dimensions, Distribution, Format, LampSet, LuminaireParts, Metadata, PhotometricType, SourceGrid,
    Symmetry, Tilt, ANGLE_EPS,
};

use super::stream::Stream;
use super::tilt::{read_tilt_file, read_tilt_table};
use super::{type_ab, IesHeader, IesLabel};

const FEET_TO_M: f64 = 0.3048;

/// LM-63 version of a file, from its first line.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Version {
    V1986,
    V1991,
    Draft94,
    Draft95,
    V1995,
    V2002,
    V2019,
}

impl Version {
    fn name(self) -> &'static str {
        match self {
            Version::V1986 => "LM-63-1986",
            Version::V1991 => "LM-63-1991",
            Version::Draft94 => "IESNA94",
            Version::Draft95 => "IESNA95",
            Version::V1995 => "LM-63-1995",
            Version::V2002 => "LM-63-2002",
            Version::V2019 => "LM-63-2019",
        }
    }
    /// The ballast-lamp photometric factor multiplies candela only in 1986 and
    /// 1991; from 1995 (and in the drafts leading to it) the field is unused.
    fn applies_blpf(self) -> bool {
        matches!(self, Version::V1986 | Version::V1991)
    }
}

/// Recognise a version line; None means "a 1986 label line".
fn parse_version(line: &[u8]) -> Option<(Version, bool)> {
    // Compact: drop blanks, upper-case, so `IESNA: LM-63-2002 ` matches.
    let compact: Vec<u8> = line
        .iter()
        .filter(|c| !c.is_ascii_whitespace())
        .map(|c| c.to_ascii_uppercase())
        .collect();
    let known = |v| Some((v, true));
    match compact.as_slice() {
        b"IESNA91" => return known(Version::V1991),
        b"IESNA94" => return known(Version::Draft94),
        b"IESNA95" => return known(Version::Draft95),
        _ => {}
    }
    if !(compact.starts_with(b"IESNA:") || compact.starts_with(b"IES:")) {
        return None;
    }
    let pos = compact.windows(6).position(|w| w == b"LM-63-");
    let year = pos.and_then(|p| compact.get(p + 6..p + 10));
    match year {
        Some(b"1986") => known(Version::V1986),
        Some(b"1991") => known(Version::V1991),
        Some(b"1995") => known(Version::V1995),
        Some(b"2002") => known(Version::V2002),
        Some(b"2019") => known(Version::V2019),
        // An IES-looking version line we do not know: read it as the newest
        // layout before 2019 and say so.
        _ => Some((Version::V2002, false)),
    }
}

fn trim(b: &[u8]) -> &[u8] {
    let s = b.iter().position(|c| !c.is_ascii_whitespace()).unwrap_or(b.len());
    let e = b.iter().rposition(|c| !c.is_ascii_whitespace()).map_or(s, |e| e + 1);
    &b[s..e.max(s)]
}

/// If `line` is a TILT line, the bytes after `=` (trimmed).
fn tilt_value(line: &[u8]) -> Option<&[u8]> {
    let t = trim(line);
    if t.len() < 4 || !t[..4].eq_ignore_ascii_case(b"TILT") {
        return None;
    }
    let rest = trim(&t[4..]);
    rest.strip_prefix(b"=").map(trim)
}

/// Read an IES file's bytes. `path` names the file in errors and locates `TILT=<file>`.
pub fn read(bytes: &[u8], path: &Path, opts: &ReadOptions) -> Result<crate::formats::Document, ParseError> {
    let src = Source::new(path, bytes).map_err(|mut e| {
        // Every error names a line; an empty file is wrong from line 1.
        if e.location.line == 0 {
            e.location.line = 1;
        }
        e
    })?;
    let mut warnings: Vec<Warning> = Vec::new();
    let mut header = IesHeader::default();

    // ---- Text part: version line, keywords, labels, up to TILT=.
    let mut lines = src.lines();
    let mut version = Version::V1986;
    let mut first = true;
    let mut tilt_line = None;
    for line in lines.by_ref() {
        if let Some(v) = tilt_value(line.bytes) {
            tilt_line = Some((line.number, v));
            break;
        }
        let t = trim(line.bytes);
        if first && !t.is_empty() {
            first = false;
            if let Some((v, known)) = parse_version(t) {
                version = v;
                header.version_line = Some(src.text(t));
                if !known {
                    warnings.push(Warning::at(
                        line.number,
                        WarningCode::UnknownVersion,
                        format!("unknown version line `{}`; read as LM-63-2002", src.text(t)),
                    ));
                }
                continue;
            }
        }
        if t.is_empty() {
            continue;
        }
        if t[0] == b'[' {
            if let Some(close) = t.iter().position(|&c| c == b']') {
                header.labels.push(IesLabel::Keyword {
                    key: src.text(&t[1..close]),
                    value: src.text(&t[close + 1..]),
                });
                continue;
            }
        }
        header.labels.push(IesLabel::Text(src.text(t)));
    }
    let (tilt_line_no, tilt_raw) = match tilt_line {
        Some(t) => t,
        None => {
            return Err(src.invalid(
                Location::line(lines.line_number().max(1)),
                "a `TILT=` line (NONE, INCLUDE or a file name)",
                format!("end of file after {} lines of text", lines.line_number()),
            ))
        }
    };
    header.tilt = src.text(tilt_raw);

    let mut tokens = Stream::new(src.bytes, lines.offset(), tilt_line_no + 1);

    // ---- TILT.
    let tilt = if tilt_raw.eq_ignore_ascii_case(b"NONE") {
        Tilt::None
    } else if tilt_raw.eq_ignore_ascii_case(b"INCLUDE") {
        let remaining = tokens.count_remaining();
        Tilt::Include {
            table: read_tilt_table(&src, &mut tokens, remaining, opts, &mut warnings)?,
        }
    } else {
        let (name, table) = read_tilt_file(&src, tilt_line_no, &header.tilt, opts, &mut warnings)?;
        Tilt::File { name, table }
    };

    // ---- First header record.
    let first_record = tokens.clone();
    header.lamps = tokens.number(&src, "number of lamps")?;
    header.lumens_per_lamp = tokens.number(&src, "lumens per lamp (-1 for absolute photometry)")?;
    let mult_idx = tokens.index();
    header.multiplier = tokens.number(&src, "candela multiplier")?;
    if header.multiplier <= 0.0 {
        let (loc, found) = tokens.locate(mult_idx);
        return Err(src.invalid(loc, "candela multiplier (> 0)", found));
    }
    let nv_idx = tokens.index();
    let nv = tokens.integer(&src, "number of vertical angles", 1, i64::MAX)? as u64;
    let nh = tokens.integer(&src, "number of horizontal angles", 1, i64::MAX)? as u64;
    header.photometric_type = tokens.integer(&src, "photometric type (1 = C, 2 = B, 3 = A)", 1, 3)? as u8;
    header.units = tokens.integer(&src, "units type (1 = feet, 2 = metres)", 1, 2)? as u8;
    header.width = tokens.number(&src, "luminous opening width")?;
    header.length = tokens.number(&src, "luminous opening length")?;
    header.height = tokens.number(&src, "luminous opening height")?;

    // Size check before any allocation: the counts must fit in what the file
    // holds. A byte bound first (no scan); the exact count only when it fails.
    let grid = (nv as u128) * (nh as u128) + nv as u128 + nh as u128;
    let exact_after_first = || first_record.count_remaining().saturating_sub(10) as u128;
    let size_error = |tokens: &Stream, after_first: u128| {
        let (loc, _) = tokens.locate(nv_idx);
        src.invalid(
            loc,
            format!(
                "angle counts that fit the data: {nv} vertical x {nh} horizontal angles need {grid} numbers \
                 (+3 for the ballast record)"
            ),
            format!("only {after_first} numbers after the first header record"),
        )
    };
    if grid > tokens.max_remaining() as u128 {
        return Err(size_error(&tokens, exact_after_first()));
    }
    let (nv, nh) = (nv as usize, nh as usize);
    let grid = grid as usize;
    header.n_vertical = nv;
    header.n_horizontal = nh;

    // ---- Second header record, which some generators omit. Read as if it
    // is there; when that runs out of data and the token count says the
    // record is missing, read again without it (only that rare case counts).
    let ballast_line = tokens.line_of(tokens.index());
    let read_body = |t: &mut Stream<'_>, ballast: bool| -> Result<Body, ParseError> {
        let (mut bf, mut fu, mut w) = (1.0, 1.0, 0.0);
        if ballast {
            bf = t.number(&src, "ballast factor")?;
            fu = t.number(
                &src,
                "ballast-lamp photometric factor / future use / file-generation type",
            )?;
            w = t.number(&src, "input watts")?;
        }
        let v_start = t.index();
        let mut vertical = Vec::with_capacity(nv);
        t.numbers_into(&src, nv, &mut vertical, &|i| {
            format!("vertical angle #{} of {nv}", i + 1)
        })?;
        let h_start = t.index();
        let mut horizontal = Vec::with_capacity(nh);
        t.numbers_into(&src, nh, &mut horizontal, &|i| {
            format!("horizontal angle #{} of {nh}", i + 1)
        })?;
        let mut cd = Vec::with_capacity(nv * nh);
        t.numbers_into(&src, nv * nh, &mut cd, &|i| {
            format!(
                "candela value #{} of {} (horizontal angle #{}, vertical angle #{})",
                i + 1,
                nv * nh,
                i / nv + 1,
                i % nv + 1
            )
        })?;
        Ok(Body {
            ballast: (bf, fu, w),
            v_start,
            h_start,
            vertical,
            horizontal,
            cd,
        })
    };
    let mut attempt = tokens.clone();
    let body = match read_body(&mut attempt, true) {
        Ok(b) => {
            tokens = attempt;
            header.ballast_record = true;
            b
        }
        Err(e) => {
            let after_first = exact_after_first();
            if after_first == grid as u128 {
                let mut again = tokens.clone();
                let b = read_body(&mut again, false)?;
                tokens = again;
                header.ballast_record = false;
                warnings.push(Warning::at(
                    ballast_line,
                    WarningCode::MissingBallastLine,
                    "the ballast factor / future use / input watts record is missing (non-conformant LM-63); \
                     assumed 1, 1, 0",
                ));
                b
            } else if (grid as u128) > after_first {
                return Err(size_error(&tokens, after_first));
            } else {
                return Err(e);
            }
        }
    };
    (header.ballast_factor, header.future_use, header.input_watts) = body.ballast;
    let Body {
        v_start,
        h_start,
        mut vertical,
        mut horizontal,
        mut cd,
        ..
    } = body;
    let mut bf = header.ballast_factor;
    if bf <= 0.0 {
        warnings.push(Warning::at(
            ballast_line,
            WarningCode::InvalidBallastFactor,
            format!("ballast factor {bf} is not positive; 1.0 used"),
        ));
        bf = 1.0;
    }
    let mut blpf = if version.applies_blpf() { header.future_use } else { 1.0 };
    if blpf <= 0.0 {
        warnings.push(Warning::at(
            ballast_line,
            WarningCode::InvalidBlpf,
            format!("ballast-lamp photometric factor {blpf} is not positive; 1.0 used"),
        ));
        blpf = 1.0;
    }
    let scale = header.multiplier * bf * blpf;
    if !(scale.is_normal() && scale > 0.0) {
        return Err(src.invalid(
            Location::line(ballast_line),
            "candela multiplier x ballast factor x ballast-lamp factor a positive normal number",
            format!("{} x {bf} x {blpf} = {scale}", header.multiplier),
        ));
    }
    let extra = tokens.count_remaining();
    if extra > 0 {
        warnings.push(Warning::at(
            tokens.line_of(tokens.index()),
            WarningCode::ExtraValues,
            format!("{extra} extra token(s) after the candela values ignored"),
        ));
    }
    if scale != 1.0 {
        for v in &mut cd {
            *v *= scale;
        }
    }
    match crate::formats::into_model_range(&mut cd) {
        Ok(None) => {}
        Ok(Some(note)) => warnings.push(Warning::at(ballast_line, WarningCode::RangeSnapped, note)),
        Err((i, why)) => {
            let (loc, _) = tokens.locate(h_start + nh + i);
            return Err(src.invalid(
                loc,
                format!("candela values in the model's range after multiplier x ballast factor = {scale}"),
                why,
            ));
        }
    }

    // Strictly ascending angle lists (or a warned repair).
    let v_at = (&tokens, v_start);
    let h_at = (&tokens, h_start);
    check_or_repair(
        &src,
        v_at,
        "vertical",
        &mut vertical,
        nh,
        &mut cd,
        false,
        opts,
        &mut warnings,
    )?;
    check_or_repair(
        &src,
        h_at,
        "horizontal",
        &mut horizontal,
        vertical.len(),
        &mut cd,
        true,
        opts,
        &mut warnings,
    )?;

    let negatives = cd.iter().filter(|&&v| v < 0.0).count();
    if negatives > 0 {
        let min = cd.iter().cloned().fold(f64::INFINITY, f64::min);
        warnings.push(Warning::new(
            WarningCode::NegativeIntensity,
            format!(
                "{negatives} negative candela value(s) kept (lowest {} cd)",
                crate::report::significant(min, 6)
            ),
        ));
    }

    // ---- Grid to distribution.
    let kind = match header.photometric_type {
        1 => PhotometricType::C,
        2 => PhotometricType::B,
        _ => PhotometricType::A,
    };
    let (distribution, source_grid) = match kind {
        PhotometricType::C => {
            let d = type_c(&src, v_at, h_at, vertical, horizontal, cd, &mut warnings)?;
            (d, None)
        }
        _ => {
            let sg = SourceGrid {
                kind,
                vertical,
                horizontal,
                cd,
            };
            let d = type_ab::to_type_c(&sg, opts.handedness).map_err(|msg| {
                src.unsupported(
                    tokens.locate(h_start).0,
                    format!("a Type {:?} grid that converts to Type C", kind),
                    msg,
                )
            })?;
            (d, Some(sg))
        }
    };

    let (nadir, zenith) = distribution.pole_spread();
    let peak = distribution.max_cd().abs().max(f64::MIN_POSITIVE);
    for (name, spread) in [("nadir (gamma 0)", nadir), ("zenith (gamma 180)", zenith)] {
        if spread > 1e-9 * peak {
            warnings.push(Warning::new(
                WarningCode::PoleMismatch,
                format!(
                    "the {name} value differs between planes by {} cd; kept as measured",
                    crate::report::significant(spread, 6)
                ),
            ));
        }
    }

    // ---- Metadata.
    let kw = |k: &str| header.keyword(k).unwrap_or_default();
    let mut metadata = Metadata {
        manufacturer: kw("MANUFAC"),
        catalogue: kw("LUMCAT"),
        luminaire: kw("LUMINAIRE"),
        lamp: kw("LAMP"),
        test_report: kw("TEST"),
        date: header
            .keyword("ISSUEDATE")
            .or_else(|| header.keyword("DATE"))
            .unwrap_or_default(),
    };
    if metadata.luminaire.is_empty() {
        // 1986 files carry their description as free-form label lines.
        let texts: Vec<&str> = header
            .labels
            .iter()
            .filter_map(|l| match l {
                IesLabel::Text(t) if !t.is_empty() && t != "-" => Some(t.as_str()),
                _ => None,
            })
            .collect();
        metadata.luminaire = texts.join(" ");
    }
    let lpl = header.lumens_per_lamp;
    let absolute = lpl < 0.0;
    if absolute && (lpl + 1.0).abs() > 1e-9 {
        warnings.push(Warning::new(
            WarningCode::InvalidLumens,
            format!("lumens per lamp {lpl} is negative but not -1; read as absolute photometry"),
        ));
    }
    let lamp_flux = if absolute { None } else { Some(header.lamps * lpl) };
    let to_m = if header.units == 1 { FEET_TO_M } else { 1.0 };
    let opening = Dimensions {
        length_m: header.length * to_m,
        width_m: header.width * to_m,
        height_m: header.height * to_m,
    };
    let lamp_set = LampSet {
        count: header.lamps,
        lamp_type: metadata.lamp.clone(),
        flux_lm: lamp_flux.unwrap_or(0.0),
        color: header
            .keyword("COLORTEMP")
            .or_else(|| header.keyword("CCT"))
            .unwrap_or_default(),
        cri: header.keyword("CRI").unwrap_or_default(),
        watts: header.input_watts,
    };
    crate::formats::document(
        path,
        LuminaireParts {
            path: Some(path.to_path_buf()),
            format: Format::Ies,
            version: version.name().to_string(),
            photometric_type: kind,
            metadata,
            lamp_sets: vec![lamp_set],
            dimensions: Dimensions {
                length_m: opening.length_m.abs(),
                width_m: opening.width_m.abs(),
                height_m: opening.height_m.abs(),
            },
            luminous_opening: opening,
            luminous_heights_m: None,
            declared: Declared {
                lamp_flux_lm: lamp_flux,
                luminaire_flux_lm: None,
                lor: None,
                dff: None,
                absolute,
                input_watts: (header.input_watts > 0.0).then_some(header.input_watts),
            },
            tilt,
            distribution,
            source_grid,
            warnings,
        },
        crate::formats::Header::Ies(header),
    )
}

/// A list's place in the stream: the stream and the index of its first token.
type At<'s, 'a> = (&'s Stream<'a>, usize);

/// Location and text of the `i`-th token of the list at `at`.
fn token_location(at: At<'_, '_>, i: usize) -> (Location, String) {
    at.0.locate(at.1 + i)
}

/// Check that `angles` ascend strictly; with `opts.repair` sort them (stable, so
/// the first of duplicates is kept) and reorder the values with them.
/// `planes`: the angles index planes of `stride` values (horizontal), or rows
/// inside each of `stride` planes (vertical).
#[allow(clippy::too_many_arguments)]
pub(super) fn check_or_repair(
    src: &Source<'_>,
    start: At<'_, '_>,
    what: &str,
    angles: &mut Vec<f64>,
    stride: usize,
    cd: &mut Vec<f64>,
    planes: bool,
    opts: &ReadOptions,
    warnings: &mut Vec<Warning>,
) -> Result<(), ParseError> {
    let Some(bad) = angles::first_disorder(angles) else {
        return Ok(());
    };
    if !opts.repair {
        let (loc, found) = token_location(start, bad);
        let why = if angles::is_duplicate(angles[bad], angles[bad - 1]) {
            "duplicate"
        } else {
            "unsorted"
        };
        return Err(src.invalid(
            loc,
            format!(
                "{what} angles in strictly ascending order (angle #{} = {} follows {}: {why}; \
                 the repair option sorts them)",
                bad + 1,
                angles[bad],
                angles[bad - 1]
            ),
            found,
        ));
    }
    let n = angles.len();
    let order = angles::repair_order(angles);
    let dropped = n - order.len();
    let new_angles: Vec<f64> = order.iter().map(|&i| angles[i]).collect();
    // Planes of `stride` (vertical count) values each, or rows inside each of `stride` planes of `n` values.
    let new_cd = if planes {
        angles::reorder_planes(cd, stride, &order)
    } else {
        angles::reorder_rows(cd, n, &order)
    };
    warnings.push(Warning::at(
        start.0.line_of(start.1),
        WarningCode::AnglesRepaired,
        format!("{what} angles were not strictly ascending: sorted, {dropped} duplicate(s) dropped (first kept)"),
    ));
    *angles = new_angles;
    *cd = new_cd;
    Ok(())
}

/// Type C grid → distribution: symmetry from the horizontal angle set (LM-63 / DOMAIN §1.4).
///
/// | H set | symmetry |
/// |---|---|
/// | one angle (0, or anywhere: warned) | rotational |
/// | 0 … 90 | quadrant |
/// | 0 … 180 | C0-C180 |
/// | 90 … 270 with a plane strictly between | C90-C270 |
/// | last angle in (180, 360], first ≥ 0 | none (a 360 plane is checked against 0 and dropped) |
///
/// Anything else (0 … 45, 90 … 180, negative angles) matches no LM-63 layout
/// and is refused rather than guessed. `{90, 270}` alone is refused too: both
/// planes lie on the C90-C270 mirror, so the half circle the 90–270 layout
/// describes (centred on C180) is not measured at all.
fn type_c(
    src: &Source<'_>,
    v_start: At<'_, '_>,
    h_start: At<'_, '_>,
    vertical: Vec<f64>,
    mut horizontal: Vec<f64>,
    mut cd: Vec<f64>,
    warnings: &mut Vec<Warning>,
) -> Result<Distribution, ParseError> {
    let nv = vertical.len();
    let nh = horizontal.len();
    let near = |a: f64, b: f64| (a - b).abs() <= ANGLE_EPS;
    if let Some(i) = vertical
        .iter()
        .position(|&v| !(-ANGLE_EPS..=180.0 + ANGLE_EPS).contains(&v))
    {
        let (loc, found) = token_location(v_start, i);
        return Err(src.invalid(
            loc,
            "Type C vertical angles within 0..180 degrees (negative angles suggest Type A/B data marked as C)",
            found,
        ));
    }
    if let Some(i) = horizontal
        .iter()
        .position(|&h| !(-ANGLE_EPS..=360.0 + ANGLE_EPS).contains(&h))
    {
        let (loc, found) = token_location(h_start, i);
        return Err(src.invalid(loc, "Type C horizontal angles within 0..360 degrees", found));
    }
    // Snap angles within tolerance onto the range ends the model checks exactly.
    let vertical: Vec<f64> = vertical.iter().map(|&v| v.clamp(0.0, 180.0)).collect();
    for h in &mut horizontal {
        *h = h.clamp(0.0, 360.0);
    }
    let (first, last) = (horizontal[0], horizontal[nh - 1]);
    let symmetry = if nh == 1 {
        if !near(first, 0.0) {
            warnings.push(Warning::new(
                WarningCode::SinglePlane,
                format!("a single horizontal angle at {first} degrees: read as rotationally symmetric"),
            ));
        }
        horizontal[0] = 0.0;
        Symmetry::Rotational
    } else if near(first, 0.0) && near(last, 90.0) {
        Symmetry::Quadrant
    } else if near(first, 0.0) && near(last, 180.0) {
        Symmetry::C0C180
    } else if near(first, 90.0) && near(last, 270.0) {
        if nh == 2 {
            let (loc, found) = token_location(h_start, 0);
            return Err(src.invalid(
                loc,
                "a 90-270 horizontal angle set with planes between 90 and 270 (C90-C270 symmetry \
                 describes the half circle around C180; 90 and 270 alone lie on its mirror plane)",
                format!("{found} and `270` only"),
            ));
        }
        Symmetry::C90C270
    } else if last > 180.0 + ANGLE_EPS {
        if near(last, 360.0) {
            crate::formats::angles::drop_360_plane(&mut horizontal, &mut cd, nv, warnings);
        }
        Symmetry::None
    } else {
        let (loc, _) = token_location(h_start, 0);
        return Err(src.unsupported(
            loc,
            "a horizontal angle set of LM-63 Type C: {0}, 0..90, 0..180, 90..270 or a last angle in (180, 360]",
            format!("{first}..{last} ({nh} angles)"),
        ));
    };
    Distribution::new(horizontal, vertical, cd, symmetry).map_err(|e| {
        let (loc, _) = token_location(h_start, 0);
        src.invalid(loc, "a valid Type C grid", e.to_string())
    })
}

/// What follows the first header record: the ballast record (or its
/// defaults), the angle lists and the raw candela values.
struct Body {
    ballast: (f64, f64, f64),
    v_start: usize,
    h_start: usize,
    vertical: Vec<f64>,
    horizontal: Vec<f64>,
    cd: Vec<f64>,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn version_lines() {
        let v = |s: &str| parse_version(s.as_bytes()).map(|(v, k)| (v.name(), k));
        assert_eq!(v("IESNA: LM-63-2002 "), Some(("LM-63-2002", true)));
        assert_eq!(v("IESNA:LM-63-2019"), Some(("LM-63-2019", true)));
        assert_eq!(v("IES:LM-63-2019"), Some(("LM-63-2019", true)));
        assert_eq!(v("IESNA:LM-63-1995"), Some(("LM-63-1995", true)));
        assert_eq!(v("iesna91"), Some(("LM-63-1991", true)));
        assert_eq!(v("IESNA94"), Some(("IESNA94", true)));
        assert_eq!(v("IESNA95"), Some(("IESNA95", true)));
        assert_eq!(v("IESNA:LM-63-2077"), Some(("LM-63-2002", false)));
        assert_eq!(v("ERCO Leuchten GmbH"), None);
    }

    #[test]
    fn tilt_lines() {
        assert_eq!(tilt_value(b"TILT=NONE"), Some(&b"NONE"[..]));
        assert_eq!(tilt_value(b"  tilt = INCLUDE  "), Some(&b"INCLUDE"[..]));
        assert_eq!(tilt_value(b"TILT=FILE x.dat"), Some(&b"FILE x.dat"[..]));
        assert_eq!(tilt_value(b"TILTED"), None);
        assert_eq!(tilt_value(b"[TILT] x"), None);
    }
}
