//! The IES reader: text header, TILT, one number stream, Type C symmetry.

use std::path::Path;

use crate::error::{Location, Num, ParseError, Warning, WarningCode};
use crate::formats::scan::{Scanner, Separators};
use crate::formats::text::Source;
use crate::formats::{declared_lamp_flux, ReadOptions};
use crate::model::{
    Dimensions, Distribution, Format, LampSet, LuminaireParts, Metadata, PhotometricType, SourceGrid, Tilt,
};

use super::grid::{check_or_repair, type_c, warn_negatives, warn_pole_spread};
use super::tilt::{read_tilt_file, read_tilt_table};
use super::{type_ab, IesHeader, IesLabel};

pub(super) const FEET_TO_M: f64 = 0.3048;

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
    let mut r = Reader {
        src: &src,
        opts,
        header: IesHeader::default(),
        warnings: Vec::new(),
    };
    let text = r.read_text()?;
    let mut tokens = Scanner::new(
        src.bytes,
        text.numbers_at,
        text.tilt_line + 1,
        Separators::BlanksAndCommas,
    );
    let tilt = r.read_tilt(&text, &mut tokens)?;
    let counts = r.read_first_record(&mut tokens)?;
    let ballast_line = tokens.next_line();
    let mut body = r.read_body_or_without_ballast(&mut tokens, &counts, ballast_line)?;
    r.scale_candela(text.version, ballast_line, &tokens, &mut body)?;
    let Body {
        v_start,
        h_start,
        mut vertical,
        mut horizontal,
        mut cd,
        ..
    } = body;
    // Strictly ascending angle lists (or a warned repair).
    let nh = horizontal.len();
    let (src, opts, warnings) = (r.src, r.opts, &mut r.warnings);
    check_or_repair(
        src,
        &v_start,
        "vertical",
        &mut vertical,
        nh,
        &mut cd,
        false,
        opts,
        warnings,
    )?;
    let nv = vertical.len();
    check_or_repair(
        src,
        &h_start,
        "horizontal",
        &mut horizontal,
        nv,
        &mut cd,
        true,
        opts,
        warnings,
    )?;
    warn_negatives(&cd, warnings);
    let (kind, distribution, source_grid) = r.distribution(&v_start, &h_start, vertical, horizontal, cd)?;
    warn_pole_spread(&distribution, &mut r.warnings);
    r.finish(text.version, kind, tilt, distribution, source_grid)
}

/// The reader's state: the source, the options, the header as read so far and the warnings.
struct Reader<'s, 'a> {
    src: &'s Source<'a>,
    opts: &'s ReadOptions,
    header: IesHeader,
    warnings: Vec<Warning>,
}

/// The text part: version, `TILT=` line, and where the numbers start.
struct TextPart<'a> {
    version: Version,
    /// Line number of the `TILT=` line.
    tilt_line: usize,
    /// The value after `TILT=` (trimmed).
    tilt_raw: &'a [u8],
    /// Byte offset of the line after `TILT=`.
    numbers_at: usize,
}

/// The first header record's angle counts, with marks to point errors at.
struct Counts<'a> {
    nv: usize,
    nh: usize,
    /// Numbers the grid needs: nv × nh candela values and both angle lists.
    grid: usize,
    /// The stream at the first header record (for the exact token count).
    first_record: Scanner<'a>,
    /// The stream at the number of vertical angles.
    counts_at: Scanner<'a>,
}

impl Counts<'_> {
    /// Numbers after the first header record (a full count: only on the rare paths).
    fn after_first(&self) -> u128 {
        self.first_record.count_remaining().saturating_sub(10) as u128
    }
}

/// What follows the first header record: the ballast record (or its
/// defaults), the angle lists with marks at their first values, and the raw
/// candela values.
struct Body<'a> {
    ballast: (f64, f64, f64),
    v_start: Scanner<'a>,
    h_start: Scanner<'a>,
    vertical: Vec<f64>,
    horizontal: Vec<f64>,
    cd: Vec<f64>,
}

impl<'s, 'a> Reader<'s, 'a> {
    /// Version line, keywords and labels, up to the `TILT=` line.
    fn read_text(&mut self) -> Result<TextPart<'a>, ParseError> {
        let src = self.src;
        let mut lines = src.lines();
        let mut version = Version::V1986;
        let mut first = true;
        for line in lines.by_ref() {
            if let Some(v) = tilt_value(line.bytes) {
                self.header.tilt = src.text(v);
                return Ok(TextPart {
                    version,
                    tilt_line: line.number,
                    tilt_raw: v,
                    numbers_at: lines.offset(),
                });
            }
            let t = trim(line.bytes);
            if t.is_empty() {
                continue;
            }
            if first {
                first = false;
                if let Some((v, known)) = parse_version(t) {
                    version = v;
                    self.header.version_line = Some(src.text(t));
                    if !known {
                        self.warnings.push(Warning::at(
                            line.number,
                            WarningCode::UnknownVersion,
                            format!("unknown version line `{}`; read as LM-63-2002", src.text(t)),
                        ));
                    }
                    continue;
                }
            }
            let label = match t.iter().position(|&c| c == b']') {
                Some(close) if t[0] == b'[' => IesLabel::Keyword {
                    key: src.text(&t[1..close]),
                    value: src.text(&t[close + 1..]),
                },
                _ => IesLabel::Text(src.text(t)),
            };
            self.header.labels.push(label);
        }
        Err(src.invalid(
            Location::line(lines.line_number().max(1)),
            "a `TILT=` line (NONE, INCLUDE or a file name)",
            format!("end of file after {} lines of text", lines.line_number()),
        ))
    }

    /// `TILT=NONE`, an included table, or a tilt file next to this one.
    fn read_tilt(&mut self, text: &TextPart<'_>, tokens: &mut Scanner<'_>) -> Result<Tilt, ParseError> {
        let (src, opts, warnings) = (self.src, self.opts, &mut self.warnings);
        Ok(if text.tilt_raw.eq_ignore_ascii_case(b"NONE") {
            Tilt::None
        } else if text.tilt_raw.eq_ignore_ascii_case(b"INCLUDE") {
            let remaining = tokens.count_remaining();
            Tilt::Include {
                table: read_tilt_table(src, tokens, remaining, opts, warnings)?,
            }
        } else {
            let (name, table) = read_tilt_file(src, text.tilt_line, &self.header.tilt, opts, warnings)?;
            Tilt::File { name, table }
        })
    }

    /// The first header record, and a size check of its counts against the
    /// file before anything is allocated.
    fn read_first_record(&mut self, tokens: &mut Scanner<'a>) -> Result<Counts<'a>, ParseError> {
        let (src, header) = (self.src, &mut self.header);
        let first_record = tokens.clone();
        header.lamps = tokens.number(src, "number of lamps")?;
        header.lumens_per_lamp = tokens.number(src, "lumens per lamp (-1 for absolute photometry)")?;
        let multiplier_at = tokens.clone();
        header.multiplier = tokens.number(src, "candela multiplier")?;
        if header.multiplier <= 0.0 {
            let (loc, found) = multiplier_at.nth(0);
            return Err(src.invalid(loc, "candela multiplier (> 0)", found));
        }
        let counts_at = tokens.clone();
        let nv = tokens.integer(src, "number of vertical angles", 1, i64::MAX)? as u64;
        let nh = tokens.integer(src, "number of horizontal angles", 1, i64::MAX)? as u64;
        header.photometric_type = tokens.integer(src, "photometric type (1 = C, 2 = B, 3 = A)", 1, 3)? as u8;
        header.units = tokens.integer(src, "units type (1 = feet, 2 = metres)", 1, 2)? as u8;
        header.width = tokens.number(src, "luminous opening width")?;
        header.length = tokens.number(src, "luminous opening length")?;
        header.height = tokens.number(src, "luminous opening height")?;
        // The counts must fit in what the file holds: a byte bound first (no
        // scan); the exact count only when it fails.
        let grid = (nv as u128) * (nh as u128) + nv as u128 + nh as u128;
        if grid > tokens.max_remaining() as u128 {
            let (loc, _) = counts_at.nth(0);
            let after_first = first_record.count_remaining().saturating_sub(10) as u128;
            return Err(size_error(src, loc, nv, nh, grid, after_first));
        }
        (header.n_vertical, header.n_horizontal) = (nv as usize, nh as usize);
        Ok(Counts {
            nv: nv as usize,
            nh: nh as usize,
            grid: grid as usize,
            first_record,
            counts_at,
        })
    }

    /// The second header record, which some generators omit, and the grid.
    /// Read as if the record is there; when that runs out of data and the
    /// token count says the record is missing, read again without it (only
    /// that rare case counts).
    fn read_body_or_without_ballast(
        &mut self,
        tokens: &mut Scanner<'a>,
        counts: &Counts<'a>,
        ballast_line: usize,
    ) -> Result<Body<'a>, ParseError> {
        let mut attempt = tokens.clone();
        let body = match read_body(self.src, &mut attempt, counts.nv, counts.nh, true) {
            Ok(b) => {
                *tokens = attempt;
                self.header.ballast_record = true;
                b
            }
            Err(e) => {
                let after_first = counts.after_first();
                if after_first == counts.grid as u128 {
                    let mut again = tokens.clone();
                    let b = read_body(self.src, &mut again, counts.nv, counts.nh, false)?;
                    *tokens = again;
                    self.header.ballast_record = false;
                    self.warnings.push(Warning::at(
                        ballast_line,
                        WarningCode::MissingBallastLine,
                        "the ballast factor / future use / input watts record is missing (non-conformant LM-63); \
                         assumed 1, 1, 0",
                    ));
                    b
                } else if (counts.grid as u128) > after_first {
                    let (loc, _) = counts.counts_at.nth(0);
                    let (nv, nh) = (counts.nv as u64, counts.nh as u64);
                    return Err(size_error(self.src, loc, nv, nh, counts.grid as u128, after_first));
                } else {
                    return Err(e);
                }
            }
        };
        (
            self.header.ballast_factor,
            self.header.future_use,
            self.header.input_watts,
        ) = body.ballast;
        Ok(body)
    }

    /// Multiplier × ballast factor × ballast-lamp factor applied to the
    /// candela values, which must then lie in the model's range; trailing
    /// tokens warned about.
    fn scale_candela(
        &mut self,
        version: Version,
        ballast_line: usize,
        tokens: &Scanner<'_>,
        body: &mut Body<'_>,
    ) -> Result<(), ParseError> {
        let (src, header, warnings) = (self.src, &self.header, &mut self.warnings);
        let bf = header.ballast_factor;
        let bf = positive_or_one(
            bf,
            "ballast factor",
            WarningCode::InvalidBallastFactor,
            ballast_line,
            warnings,
        );
        let blpf = if version.applies_blpf() { header.future_use } else { 1.0 };
        let blpf = positive_or_one(
            blpf,
            "ballast-lamp photometric factor",
            WarningCode::InvalidBlpf,
            ballast_line,
            warnings,
        );
        let scale = header.multiplier * bf * blpf;
        if !(scale.is_normal() && scale > 0.0) {
            return Err(src.invalid(
                Location::line(ballast_line),
                "candela multiplier x ballast factor x ballast-lamp factor a positive normal number",
                format!(
                    "{} x {} x {} = {}",
                    Num(header.multiplier),
                    Num(bf),
                    Num(blpf),
                    Num(scale)
                ),
            ));
        }
        let extra = tokens.count_remaining();
        if extra > 0 {
            warnings.push(Warning::at(
                tokens.next_line(),
                WarningCode::ExtraValues,
                format!("{extra} extra token(s) after the candela values ignored"),
            ));
        }
        if scale != 1.0 {
            for v in &mut body.cd {
                *v *= scale;
            }
        }
        match crate::formats::into_model_range(&mut body.cd) {
            Ok(None) => Ok(()),
            Ok(Some(note)) => {
                warnings.push(Warning::at(ballast_line, WarningCode::RangeSnapped, note));
                Ok(())
            }
            Err((i, why)) => {
                let (loc, _) = body.h_start.nth(body.horizontal.len() + i);
                Err(src.invalid(
                    loc,
                    format!(
                        "candela values in the model's range after multiplier x ballast factor = {}",
                        Num(scale)
                    ),
                    why,
                ))
            }
        }
    }

    /// The grid as a Type C distribution; a Type A/B grid converted, and kept as the source grid.
    fn distribution(
        &mut self,
        v_start: &Scanner<'_>,
        h_start: &Scanner<'_>,
        vertical: Vec<f64>,
        horizontal: Vec<f64>,
        cd: Vec<f64>,
    ) -> Result<(PhotometricType, Distribution, Option<SourceGrid>), ParseError> {
        let kind = match self.header.photometric_type {
            1 => PhotometricType::C,
            2 => PhotometricType::B,
            _ => PhotometricType::A,
        };
        if kind == PhotometricType::C {
            let d = type_c(self.src, v_start, h_start, vertical, horizontal, cd, &mut self.warnings)?;
            return Ok((kind, d, None));
        }
        let sg = SourceGrid {
            kind,
            vertical,
            horizontal,
            cd,
        };
        let d = type_ab::to_type_c(&sg, self.opts.handedness).map_err(|e| {
            self.src.unsupported(
                h_start.nth(0).0,
                format!("a Type {:?} grid that converts to Type C", kind),
                e.to_string(),
            )
        })?;
        Ok((kind, d, Some(sg)))
    }

    /// The luminaire: metadata from the keywords, lamp and opening from the first record.
    fn finish(
        self,
        version: Version,
        kind: PhotometricType,
        tilt: Tilt,
        distribution: Distribution,
        source_grid: Option<SourceGrid>,
    ) -> Result<crate::formats::Document, ParseError> {
        let (header, mut warnings, path) = (self.header, self.warnings, self.src.path);
        let metadata = metadata(&header);
        let lpl = header.lumens_per_lamp;
        let absolute = lpl < 0.0;
        if absolute && (lpl + 1.0).abs() > 1e-9 {
            warnings.push(Warning::new(
                WarningCode::InvalidLumens,
                format!(
                    "lumens per lamp {} is negative but not -1; read as absolute photometry",
                    Num(lpl)
                ),
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
                .or_else(|| header.keyword("_COLORTEMP"))
                .unwrap_or_default(),
            cri: header
                .keyword("CRI")
                .or_else(|| header.keyword("_CRI"))
                .unwrap_or_default(),
            watts: header.input_watts,
        };
        let parts = LuminaireParts {
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
            declared: declared_lamp_flux(
                lamp_flux,
                absolute,
                (header.input_watts > 0.0).then_some(header.input_watts),
            ),
            tilt,
            distribution,
            source_grid,
            warnings,
            front: crate::model::Front::convention(Format::Ies),
        };
        crate::formats::document(path, parts, crate::formats::Header::Ies(header))
    }
}

/// The counts need more numbers than the file holds.
fn size_error(src: &Source<'_>, at: Location, nv: u64, nh: u64, grid: u128, after_first: u128) -> ParseError {
    src.invalid(
        at,
        format!(
            "angle counts that fit the data: {nv} vertical x {nh} horizontal angles need {grid} numbers \
             (+3 for the ballast record)"
        ),
        format!("only {after_first} numbers after the first header record"),
    )
}

/// The ballast record (when `ballast`), both angle lists and the candela values.
fn read_body<'a>(
    src: &Source<'_>,
    t: &mut Scanner<'a>,
    nv: usize,
    nh: usize,
    ballast: bool,
) -> Result<Body<'a>, ParseError> {
    let (mut bf, mut fu, mut w) = (1.0, 1.0, 0.0);
    if ballast {
        bf = t.number(src, "ballast factor")?;
        fu = t.number(
            src,
            "ballast-lamp photometric factor / future use / file-generation type",
        )?;
        w = t.number(src, "input watts")?;
    }
    let v_start = t.clone();
    let mut vertical = Vec::with_capacity(nv);
    t.numbers_into(src, nv, &mut vertical, &|i| {
        format!("vertical angle #{} of {nv}", i + 1)
    })?;
    let h_start = t.clone();
    let mut horizontal = Vec::with_capacity(nh);
    t.numbers_into(src, nh, &mut horizontal, &|i| {
        format!("horizontal angle #{} of {nh}", i + 1)
    })?;
    let mut cd = Vec::with_capacity(nv * nh);
    t.numbers_into(src, nv * nh, &mut cd, &|i| {
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
}

/// `v` when positive; otherwise 1, and a warning at `line`.
fn positive_or_one(v: f64, what: &str, code: WarningCode, line: usize, warnings: &mut Vec<Warning>) -> f64 {
    if v > 0.0 {
        return v;
    }
    warnings.push(Warning::at(
        line,
        code,
        format!("{what} {} is not positive; 1.0 used", Num(v)),
    ));
    1.0
}

/// Metadata from the keywords; 1986 files carry their description as free-form label lines.
fn metadata(header: &IesHeader) -> Metadata {
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
    metadata
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
