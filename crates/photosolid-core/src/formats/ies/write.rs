//! The IES writer: LM-63-2002 or LM-63-2019 text.

use std::fmt::Write as _;

use crate::formats::Document;
use crate::model::{PhotometricType, Symmetry, ANGLE_EPS};

use super::{IesLabel, IesWriteVersion};

/// Line end of written files: LM-63-2002 specifies CRLF.
const EOL: &str = "\r\n";
/// Longest line written, in bytes without the CRLF (LM-63-2002: 256 including it).
const MAX_LINE: usize = 254;
/// Numbers are wrapped well below the limit, for readability.
const WRAP: usize = 200;

/// Write `lum` as IES text (CRLF line ends).
///
/// - Version line `IESNA:LM-63-2002` or `IES:LM-63-2019`.
/// - A luminaire read from IES keeps its keyword lines in order and its header
///   numbers (lamps, lm/lamp, multiplier, units, dimensions, ballast factor,
///   watts); free-form 1986 label lines become `[OTHER]` lines. Any other
///   luminaire gets keywords from its [`crate::model::Metadata`] and an absolute
///   header (lm/lamp = −1 when its photometry is absolute, multiplier 1, metres).
///   The required `[TEST] [TESTLAB] [ISSUEDATE] [MANUFAC]` are added when missing.
///   Long keyword values are continued on `[MORE]` lines (lines ≤ 256 bytes with CRLF).
/// - `TILT=NONE`, or `TILT=INCLUDE` with the table (a `TILT=<file>` source is
///   written inline since the file may not travel; 2019 forbids the file form).
/// - Type A/B sources write their original grid and type back; Type C writes
///   the stored planes: rotational {0}, quadrant 0..90, C0-C180 0..180,
///   C90-C270 90..270, none: the planes plus a closing 360 plane equal to C0
///   (a missing C0 plane is interpolated across the seam first).
/// - The second header value is the future-use field (2002: kept from 1995-2002
///   sources, else 1.0) or the file-generation type (2019: kept from 2019 sources,
///   else 1.00001 "undefined"). A 1986/1991 ballast-lamp factor is folded into the values.
///
/// # Precision
/// Angles are written as the shortest decimal that reads back to the same
/// `f64`. Candela values are divided by the header's multiplier × ballast factor;
/// when that product is 1 they are written exactly the same way (shortest
/// round trip, so reading back gives identical values); otherwise the quotient
/// is first rounded to 15 significant digits, and reading back reproduces the
/// value within a relative 1e-14. When the header's factors cannot
/// represent the values (their product is zero, subnormal or makes a
/// quotient overflow), multiplier and ballast factor are written as 1 and
/// the values as absolute candela. Magnitudes outside [1e-5, 1e15) use exponent
/// notation (`1.5e-7`).
pub fn write(doc: &Document, version: IesWriteVersion) -> String {
    let lum = &doc.luminaire;
    let mut w = Writer {
        out: String::with_capacity(64 * 1024),
        col: 0,
    };
    w.line(match version {
        IesWriteVersion::Lm63_2002 => "IESNA:LM-63-2002",
        IesWriteVersion::Lm63_2019 => "IES:LM-63-2019",
    });
    for (k, v) in keywords(doc) {
        w.keyword(&k, &v);
    }
    match lum.tilt().table() {
        None => w.line("TILT=NONE"),
        Some(t) => {
            w.line("TILT=INCLUDE");
            w.num(t.geometry as f64);
            w.end();
            w.num(t.angles.len() as f64);
            w.end();
            w.nums(&t.angles);
            w.nums(&t.multipliers);
        }
    }
    let grid = Grid::of(lum);
    let mut rec = HeaderRecords::of(doc, version);
    // The reader multiplies by multiplier × ballast factor (a non-positive ballast factor reads as 1).
    let mut scale = rec.multiplier
        * if rec.ballast_factor > 0.0 {
            rec.ballast_factor
        } else {
            1.0
        };
    let representable = scale.is_normal()
        && scale > 0.0
        && grid.planes.iter().all(|&v| {
            let q = v / scale;
            q.is_finite() && (q * scale).is_finite()
        });
    if !representable {
        // Values divided by these factors would not print as numbers (an
        // underflowing product gives NaN): write absolute candela instead.
        (rec.multiplier, rec.ballast_factor, scale) = (1.0, 1.0, 1.0);
    }
    let (nv, nh) = (grid.vertical.len() as f64, grid.horizontal.len() as f64);
    for v in [rec.lamps, rec.lumens_per_lamp, rec.multiplier, nv, nh] {
        w.num(v);
    }
    w.num(grid.type_code as f64);
    for v in [rec.units, rec.width, rec.length, rec.height] {
        w.num(v);
    }
    w.end();
    for v in [rec.ballast_factor, rec.future_use, rec.input_watts] {
        w.num(v);
    }
    w.end();
    w.nums(&grid.vertical);
    w.nums(&grid.horizontal);
    for p in grid.planes.chunks(grid.vertical.len().max(1)) {
        if scale == 1.0 {
            w.nums(p);
        } else {
            for &v in p {
                w.num(v / scale);
            }
            w.end();
        }
    }
    w.out
}

/// The keyword lines: the file's own labels (unlabelled text as `OTHER`) or
/// the model's metadata, after the keywords LM-63-2002 requires that the
/// file lacks (written empty when unknown).
fn keywords(doc: &Document) -> Vec<(String, String)> {
    let lum = &doc.luminaire;
    let md = lum.metadata();
    let mut kws: Vec<(String, String)> = Vec::new();
    match doc.ies_header() {
        Some(h) => {
            for l in &h.labels {
                match l {
                    IesLabel::Keyword { key, value } => kws.push((key.clone(), value.clone())),
                    IesLabel::Text(t) => kws.push(("OTHER".into(), t.clone())),
                }
            }
        }
        None => {
            let lamp = if md.lamp.is_empty() {
                lum.lamp_sets().first().map(|s| s.lamp_type.clone()).unwrap_or_default()
            } else {
                md.lamp.clone()
            };
            // Lamp colour and colour rendering have no LM-63 keyword: user keywords (LM-63-2002
            // §5.2, a leading underscore) keep them, and the reader reads them back.
            let first = lum.lamp_sets().first();
            let colour = first.map(|s| s.color.clone()).unwrap_or_default();
            let cri = first.map(|s| s.cri.clone()).unwrap_or_default();
            for (k, v) in [
                ("LUMCAT", &md.catalogue),
                ("LUMINAIRE", &md.luminaire),
                ("LAMP", &lamp),
                ("_COLORTEMP", &colour),
                ("_CRI", &cri),
            ] {
                if !v.trim().is_empty() {
                    kws.push((k.into(), v.clone()));
                }
            }
        }
    }
    let required = [
        ("TEST", md.test_report.clone()),
        ("TESTLAB", String::new()),
        ("ISSUEDATE", md.date.clone()),
        ("MANUFAC", md.manufacturer.clone()),
    ];
    let mut out: Vec<(String, String)> = required
        .into_iter()
        .filter(|(k, _)| !kws.iter().any(|(kk, _)| kk.eq_ignore_ascii_case(k)))
        .map(|(k, v)| (k.to_string(), v))
        .collect();
    out.extend(kws);
    out
}

/// The angle grid and values to write: the Type A/B source grid when the
/// luminaire keeps one, else the Type C planes of its distribution.
struct Grid {
    /// LM-63 photometric type: 1 = C, 2 = B, 3 = A.
    type_code: u8,
    /// Vertical angles, degrees.
    vertical: Vec<f64>,
    /// Horizontal angles, degrees.
    horizontal: Vec<f64>,
    /// Candela, one run of `vertical.len()` values per horizontal angle.
    planes: Vec<f64>,
}

impl Grid {
    fn of(lum: &crate::model::Luminaire) -> Self {
        match lum.source_grid() {
            Some(sg) => Grid {
                type_code: if sg.kind == PhotometricType::A { 3 } else { 2 },
                vertical: sg.vertical.clone(),
                horizontal: sg.horizontal.clone(),
                planes: sg.cd.clone(),
            },
            None => {
                let (horizontal, planes) = type_c_planes(lum.distribution());
                Grid {
                    type_code: 1,
                    vertical: lum.distribution().gamma_angles_deg().to_vec(),
                    horizontal,
                    planes,
                }
            }
        }
    }
}

/// The numeric header records (LM-63 lines 10 and 11) as they will be written.
struct HeaderRecords {
    lamps: f64,
    /// -1 for absolute photometry.
    lumens_per_lamp: f64,
    multiplier: f64,
    /// 1 = feet, 2 = metres.
    units: f64,
    /// Luminous opening, in `units` (feet or metres), LM-63's sign conventions.
    width: f64,
    length: f64,
    height: f64,
    ballast_factor: f64,
    /// The 2002 "future use" field, or the 2019 file-generation type.
    future_use: f64,
    input_watts: f64,
}

impl HeaderRecords {
    /// The file's own records when it was an IES file, else records derived
    /// from the model (metres, absolute or relative by the declared flux).
    fn of(doc: &Document, version: IesWriteVersion) -> Self {
        let lum = &doc.luminaire;
        if let Some(h) = doc.ies_header() {
            let blpf_applied = matches!(lum.version(), "LM-63-1986" | "LM-63-1991");
            let future_use = match version {
                IesWriteVersion::Lm63_2002 if !blpf_applied && lum.version() != "LM-63-2019" => h.future_use,
                IesWriteVersion::Lm63_2002 => 1.0,
                IesWriteVersion::Lm63_2019 if lum.version() == "LM-63-2019" => h.future_use,
                IesWriteVersion::Lm63_2019 => 1.00001,
            };
            // LM-63-1986/1991/1995 encode some shapes with other signs than the
            // 2002/2019 line this file gets: write the shape in the new signs.
            let (width, length, height) = match crate::model::opening::Opening::of_luminaire(lum) {
                Ok(shape) if matches!(lum.version(), "LM-63-1986" | "LM-63-1991" | "LM-63-1995") => {
                    let per_metre = if h.units == 1 {
                        1.0 / super::read::FEET_TO_M
                    } else {
                        1.0
                    };
                    let (w, l, ht, _) = shape.to_ies();
                    (w * per_metre, l * per_metre, ht * per_metre)
                }
                _ => (h.width, h.length, h.height),
            };
            return HeaderRecords {
                lamps: h.lamps,
                lumens_per_lamp: h.lumens_per_lamp,
                multiplier: h.multiplier,
                units: h.units as f64,
                width,
                length,
                height,
                ballast_factor: h.ballast_factor,
                future_use,
                input_watts: h.input_watts,
            };
        }
        let count: f64 = lum.lamp_sets().iter().map(|s| s.count.abs()).sum();
        let n = if count > 0.0 && count.is_finite() { count } else { 1.0 };
        let flux = lum
            .declared()
            .lamp_flux_lm
            .unwrap_or_else(|| lum.lamp_sets().iter().map(|s| s.flux_lm).sum());
        // A lamp count so small that flux / count overflows is written as one lamp.
        let (lamps, lumens_per_lamp) = if lum.declared().absolute || flux <= 0.0 || !flux.is_finite() {
            (n, -1.0)
        } else if (flux / n).is_finite() {
            (n, flux / n)
        } else {
            (1.0, flux)
        };
        let dims = ies_opening(lum);
        let watts = lum
            .declared()
            .input_watts
            .unwrap_or_else(|| lum.lamp_sets().iter().map(|s| s.watts).sum());
        HeaderRecords {
            lamps,
            lumens_per_lamp,
            multiplier: 1.0,
            units: 2.0,
            width: dims.width_m,
            length: dims.length_m,
            height: dims.height_m,
            ballast_factor: 1.0,
            future_use: match version {
                IesWriteVersion::Lm63_2002 => 1.0,
                IesWriteVersion::Lm63_2019 => 1.00001,
            },
            // Summed lamp-set wattages can overflow; an unknown wattage is written as 0.
            input_watts: if watts.is_finite() { watts } else { 0.0 },
        }
    }
}

/// The luminous opening in LM-63's signs, metres: an IES luminaire's as it
/// is; another format's through its shape ([`Opening::to_ies`]), so a
/// EULUMDAT disk becomes LM-63's circle; no opening stays a point.
fn ies_opening(lum: &crate::model::Luminaire) -> crate::model::Dimensions {
    use crate::model::opening::Opening;
    let o = lum.luminous_opening();
    let declared = o.length_m != 0.0 || o.width_m != 0.0 || o.height_m != 0.0;
    let signed = |(w, l, h, _): (f64, f64, f64, Option<String>)| crate::model::Dimensions {
        length_m: l,
        width_m: w,
        height_m: h,
    };
    match (lum.format(), declared) {
        (crate::model::Format::Ies, true) => o,
        (_, true) => Opening::of_luminaire(lum).map_or(o, |op| signed(op.to_ies())),
        // No opening is a point source in every format: not the luminaire's own
        // dimensions, which would give the converted file a UGR table the source has not.
        (_, false) => crate::model::Dimensions::default(),
    }
}

/// Round to 15 significant digits (so `v / scale` does not print 17 digits of noise).
fn round15(v: f64) -> f64 {
    if !v.is_finite() || v == 0.0 {
        return v;
    }
    let s = format!("{v:.14e}");
    // Near f64::MAX the rounded text would read back as infinity: keep the value.
    s.parse().ok().filter(|r: &f64| r.is_finite()).unwrap_or(v)
}

struct Writer {
    out: String,
    /// Bytes on the current line (0: at a line start).
    col: usize,
}

impl Writer {
    fn line(&mut self, s: &str) {
        self.end();
        self.out.push_str(s);
        self.out.push_str(EOL);
    }

    /// End the current line of numbers, if one is open.
    fn end(&mut self) {
        if self.col > 0 {
            self.out.push_str(EOL);
            self.col = 0;
        }
    }

    /// Append `v` rounded to 15 significant digits: what the data can carry,
    /// without the last-digit noise of arithmetic (770.0160000000001).
    fn num(&mut self, v: f64) {
        let v = round15(v);
        let start = self.out.len();
        if self.col > 0 {
            self.out.push(' ');
        }
        let a = v.abs();
        if v == 0.0 {
            self.out.push('0');
        } else if (1e-5..1e15).contains(&a) {
            let _ = write!(self.out, "{v}");
        } else {
            let _ = write!(self.out, "{v:e}");
        }
        self.col += self.out.len() - start;
        if self.col >= WRAP {
            self.end();
        }
    }

    fn nums(&mut self, vs: &[f64]) {
        for &v in vs {
            self.num(v);
        }
        self.end();
    }

    /// `[KEY] value`, continued on `[MORE]` lines to keep lines ≤ 256 bytes.
    fn keyword(&mut self, key: &str, value: &str) {
        let clean = |s: &str, drop: &[char]| -> String {
            s.chars()
                .map(|c| if c.is_control() { ' ' } else { c })
                .filter(|c| !drop.contains(c))
                .collect()
        };
        let mut key = clean(key, &['[', ']']);
        if key.is_empty() {
            key = "OTHER".into();
        }
        let value = clean(value, &[]);
        let value = value.trim();
        let mut prefix = format!("[{key}]");
        if prefix.len() > 40 {
            // A keyword longer than any real one: keep it readable and short.
            prefix = format!("[{}]", key.chars().take(38).collect::<String>());
        }
        let mut rest = value;
        loop {
            self.end();
            self.out.push_str(&prefix);
            if !rest.is_empty() {
                self.out.push(' ');
                let room = MAX_LINE - prefix.len() - 1;
                let mut cut = rest.len().min(room);
                while !rest.is_char_boundary(cut) {
                    cut -= 1;
                }
                self.out.push_str(&rest[..cut]);
                rest = &rest[cut..];
            }
            self.out.push_str(EOL);
            if rest.is_empty() {
                break;
            }
            prefix = "[MORE]".into();
        }
    }
}

/// The horizontal angles and planes (each plane = values at every vertical
/// angle, cd) an IES file holds for a Type C distribution: the stored planes
/// (rotational {0}, quadrant 0..90, C0-C180 0..180, C90-C270 90..270) and,
/// without symmetry, a closing 360 plane equal to C0 (a missing C0 plane is
/// interpolated across the seam first). Engines that read IES files see this table.
pub fn type_c_planes(d: &crate::model::Distribution) -> (Vec<f64>, Vec<f64>) {
    let ng = d.n_gamma();
    let mut h = d.c_angles_deg().to_vec();
    let mut cd = d.intensities_cd().to_vec();
    if d.symmetry() == Symmetry::None {
        // A first plane within ANGLE_EPS of 0 is the C0 plane (the reader's
        // duplicate rule): inserting another would write a duplicate.
        if h[0] > ANGLE_EPS {
            // No C0 plane: interpolate it across the seam so the file
            // starts at 0 as LM-63 wants.
            let (c_last, c_first) = (h[h.len() - 1], h[0]);
            let t = (360.0 - c_last) / (c_first + 360.0 - c_last);
            let last = d.plane_cd(h.len() - 1);
            let first = d.plane_cd(0);
            let p0: Vec<f64> = (0..ng).map(|i| last[i] + t * (first[i] - last[i])).collect();
            h.insert(0, 0.0);
            let mut v = p0;
            v.extend_from_slice(&cd);
            cd = v;
        }
        h.push(360.0);
        let p0 = cd[..ng].to_vec();
        cd.extend_from_slice(&p0);
    }
    (h, cd)
}
