//! EULUMDAT reader. See the module docs of [`super`] for the rules.

use std::path::Path;

use super::{LampSetLayout, LdtHeader};
use crate::error::{Location, Num, ParseError, Warning, WarningCode};
use crate::formats::scan::{parse_number, Scanner, Separators};
use crate::formats::text::{Line, Lines, Source};
use crate::formats::ReadOptions;
use crate::model::{
    Declared, Dimensions, Distribution, Format, LampSet, LuminaireParts, Metadata, PhotometricType, Symmetry, Tilt,
};

mod grid;
use grid::Units;

/// Largest Mc accepted: 0.1° C steps.
const MAX_MC: i64 = 3600;
/// Largest Ng accepted: 0.1° γ steps.
const MAX_NG: i64 = 1801;
/// Largest number of lamp sets accepted (real files have up to a few dozen).
const MAX_LAMP_SETS: i64 = 10_000;

/// Read an EULUMDAT file's bytes. `path` names the file in errors.
///
/// Returns a luminaire whose distribution is in absolute candela (see the
/// module docs for the conversion), with every recoverable oddity as a
/// warning. Never panics; every error names the file, the line (and column
/// where it helps), what was expected and what was found.
pub fn read(bytes: &[u8], path: &Path, opts: &ReadOptions) -> Result<crate::formats::Document, ParseError> {
    let src = Source::new(path, bytes).map_err(|mut e| {
        // A file with no data at all still gets a line to point at.
        if e.location.line == 0 {
            e.location.line = 1;
        }
        e
    })?;
    Reader {
        src: &src,
        lines: src.lines(),
        warnings: Vec::new(),
    }
    .read(opts)
}

struct Reader<'s, 'a> {
    src: &'s Source<'a>,
    lines: Lines<'a>,
    warnings: Vec<Warning>,
}

/// The first number on a header line.
enum LineNumber {
    /// A number; `junk` when more text follows it.
    Value { v: f64, junk: bool },
    /// The line is empty.
    Blank,
    /// The line does not start with a number.
    NotNumber,
}

fn line_number(bytes: &[u8]) -> LineNumber {
    let is_blank = |b: &u8| b.is_ascii_whitespace() || *b == 0x1A;
    let start = match bytes.iter().position(|b| !is_blank(b)) {
        Some(s) => s,
        None => return LineNumber::Blank,
    };
    let rest = &bytes[start..];
    let end = rest.iter().position(is_blank).unwrap_or(rest.len());
    match parse_number(&rest[..end]) {
        Some(v) => LineNumber::Value {
            v,
            junk: rest[end..].iter().any(|b| !is_blank(b)),
        },
        None => LineNumber::NotNumber,
    }
}

fn show(bytes: &[u8]) -> String {
    let s = String::from_utf8_lossy(bytes);
    let s = s.trim();
    if s.is_empty() {
        "an empty line".into()
    } else if s.chars().count() > 40 {
        format!("`{}...`", s.chars().take(40).collect::<String>())
    } else {
        format!("`{s}`")
    }
}

/// Integral value of `v` (files write integers as `3.0`), if it is one.
fn integral(v: f64) -> Option<i64> {
    let r = v.round();
    ((v - r).abs() <= 1e-6 && r.abs() < 1e15).then_some(r as i64)
}

impl<'s, 'a> Reader<'s, 'a> {
    fn warn(&mut self, line: usize, code: WarningCode, message: impl Into<String>) {
        self.warnings.push(Warning::at(line, code, message));
    }

    fn next_line(&mut self, what: &str) -> Result<Line<'a>, ParseError> {
        let n = self.lines.line_number() + 1;
        self.lines
            .next()
            .ok_or_else(|| self.src.invalid(Location::line(n), what.to_string(), "end of file"))
    }

    fn text(&mut self, what: &str) -> Result<String, ParseError> {
        let l = self.next_line(what)?;
        Ok(self.src.text(l.bytes))
    }

    /// A number that the layout depends on: it must be there.
    fn required(&mut self, what: &str) -> Result<(f64, usize), ParseError> {
        let l = self.next_line(what)?;
        self.required_on(l, what).map(|v| (v, l.number))
    }

    fn required_on(&mut self, l: Line<'a>, what: &str) -> Result<f64, ParseError> {
        match line_number(l.bytes) {
            LineNumber::Value { v, junk } => {
                self.warn_junk(junk, l, what);
                Ok(v)
            }
            _ => Err(self
                .src
                .invalid(Location::line(l.number), what.to_string(), show(l.bytes))),
        }
    }

    /// Text after a header line's number is ignored, with a warning.
    fn warn_junk(&mut self, junk: bool, l: Line<'a>, what: &str) {
        if junk {
            self.warn(
                l.number,
                WarningCode::HeaderJunk,
                format!("{what}: took the first number of {}", show(l.bytes)),
            );
        }
    }

    /// An integer the layout depends on, in `[min, max]`.
    fn required_int(&mut self, what: &str, min: i64, max: i64) -> Result<(i64, usize), ParseError> {
        let (v, line) = self.required(what)?;
        match integral(v) {
            Some(i) if (min..=max).contains(&i) => Ok((i, line)),
            _ => Err(self.src.invalid(
                Location::line(line),
                format!("{what} (integer {min}..={max})"),
                format!("`{}`", Num(v)),
            )),
        }
    }

    /// A number nothing structural depends on: blank or junk gives `default` and a warning.
    fn lenient(&mut self, what: &str, default: f64) -> Result<f64, ParseError> {
        let l = self.next_line(what)?;
        Ok(self.lenient_on(l, what, default))
    }

    fn lenient_on(&mut self, l: Line<'a>, what: &str, default: f64) -> f64 {
        match line_number(l.bytes) {
            LineNumber::Value { v, junk } => {
                self.warn_junk(junk, l, what);
                v
            }
            LineNumber::Blank => {
                self.warn(
                    l.number,
                    WarningCode::BlankNumber,
                    format!("{what} is blank; taken as {default}"),
                );
                default
            }
            LineNumber::NotNumber => {
                self.warn(
                    l.number,
                    WarningCode::NotANumber,
                    format!("{what} is {}, not a number; taken as {default}", show(l.bytes)),
                );
                default
            }
        }
    }

    fn read(mut self, opts: &ReadOptions) -> Result<crate::formats::Document, ParseError> {
        let head = self.read_header()?;
        let (lamp_sets, layout, last_set_line) = self.read_lamp_sets(&head)?;
        // From line 27 on: a stream of numbers; positions counted from the last lamp-set line.
        let mut toks = Scanner::new(
            self.src.bytes,
            last_set_line.offset,
            last_set_line.number,
            Separators::Blanks,
        )
        .skip_to(self.lines.offset());
        let mut lists = self.read_angle_lists(&mut toks, &head)?;
        self.check_angle_lists(&head, &lists, opts)?;
        let stored = self.stored_planes(&head, &lists)?;
        let (mut cd, cd_first) = self.read_intensities(&mut toks, &head, &lists, stored.len())?;
        let units = self.candela_units(&head, &lamp_sets, opts, &mut cd, cd_first, stored.len())?;
        let (header_c, header_g) = (lists.c_file.clone(), lists.gamma.clone());
        let dist = self.model_grid(&head, &mut lists, &stored, cd, opts)?;
        self.warn_pole_spread(&dist, lists.g_first);
        let header = LdtHeader {
            ityp: head.ityp,
            isym: head.sym.isym(),
            mc: head.mc,
            dc: head.dc,
            ng: header_g.len(),
            dg: head.dg,
            file_name: head.file_name.clone(),
            luminous_heights_mm: [head.mm[5], head.mm[6], head.mm[7], head.mm[8]],
            dff_percent: head.dff,
            lorl_percent: head.lorl,
            cfli: head.cfli,
            tilt_deg: head.tilt,
            lamp_set_layout: layout,
            direct_ratios: lists.direct_ratios,
            c_angles: header_c,
            gamma_angles: header_g,
            cd_per_cdklm: units.scale,
        };
        self.finish(head, header, lamp_sets, &units, dist)
    }

    /// Lines 1-25: texts, counts and steps, dimensions, DFF, LORL, CFLI, tilt, lamp-set count.
    fn read_header(&mut self) -> Result<Head, ParseError> {
        let src = self.src;
        let company = self.text("line 1: company / databank")?;
        let ityp = self.lenient("Ityp (type indicator 0-3)", 0.0)?;
        let ityp_line = self.lines.line_number();
        let ityp = match integral(ityp) {
            Some(i @ 0..=3) => i,
            _ => {
                self.warn(
                    ityp_line,
                    WarningCode::Ityp,
                    format!("Ityp = {} is not 0-3; kept as 0", Num(ityp)),
                );
                0
            }
        };
        let (isym, isym_line) = self.required_int("Isym (symmetry indicator)", 0, 4)?;
        let sym = Symmetry::from_isym(isym)
            .ok_or_else(|| src.invalid(Location::line(isym_line), "Isym (integer 0..=4)", format!("`{isym}`")))?;
        let (mc, mc_line) = self.required_int("Mc (number of C-planes)", 1, MAX_MC)?;
        let dc = self.lenient("Dc (C-plane step, degrees)", 0.0)?;
        let (ng, ng_line) = self.required_int("Ng (number of gamma angles)", 1, MAX_NG)?;
        let dg = self.lenient("Dg (gamma step, degrees)", 0.0)?;
        let test_report = self.text("line 8: measurement report number")?;
        let luminaire_name = self.text("line 9: luminaire name")?;
        let catalogue = self.text("line 10: luminaire number")?;
        let file_name = self.text("line 11: file name")?;
        let date = self.text("line 12: date / user")?;
        // Lines 13-21, millimetres.
        let mut mm = [0.0; 9];
        let names = [
            "luminaire length or diameter (mm)",
            "luminaire width (mm)",
            "luminaire height (mm)",
            "luminous area length or diameter (mm)",
            "luminous area width (mm)",
            "luminous area height at C0 (mm)",
            "luminous area height at C90 (mm)",
            "luminous area height at C180 (mm)",
            "luminous area height at C270 (mm)",
        ];
        for (v, name) in mm.iter_mut().zip(names) {
            *v = self.lenient(name, 0.0)?;
        }
        let dff = self.lenient("DFF (downward flux fraction, %)", 0.0)?;
        let lorl = self.lenient("LORL (light output ratio, %)", 100.0)?;
        let cfli = self.read_cfli()?;
        let tilt = self.lenient("tilt during measurement (degrees)", 0.0)?;
        let (n_sets, n_line) = self.required_int("number of lamp sets", 1, MAX_LAMP_SETS)?;
        Ok(Head {
            company,
            ityp,
            isym,
            sym,
            mc: mc as usize,
            mc_line,
            dc,
            ng: ng as usize,
            ng_line,
            dg,
            test_report,
            luminaire_name,
            catalogue,
            file_name,
            date,
            mm,
            dff,
            lorl,
            cfli,
            tilt,
            n_sets: n_sets as usize,
            n_line,
        })
    }

    /// Line 24, CFLI: applied as the format defines it; a value other than 1, or an unusable one (taken as 1), warned.
    fn read_cfli(&mut self) -> Result<f64, ParseError> {
        let cfli_raw = self.lenient("CFLI (conversion factor for intensities)", 1.0)?;
        let cfli_line = self.lines.line_number();
        Ok(if cfli_raw > 0.0 && cfli_raw.is_finite() {
            if cfli_raw != 1.0 {
                self.warn(
                    cfli_line,
                    WarningCode::Cfli,
                    format!("CFLI = {}: intensities are multiplied by it", Num(cfli_raw)),
                );
            }
            cfli_raw
        } else {
            self.warn(
                cfli_line,
                WarningCode::Cfli,
                format!("CFLI = {} is not positive; taken as 1", Num(cfli_raw)),
            );
            1.0
        })
    }

    /// Lamp sets: 6n lines, checked against the file before they are collected;
    /// also the last of those lines (where the number stream's positions count from).
    fn read_lamp_sets(&mut self, head: &Head) -> Result<(Vec<LampSet>, LampSetLayout, Line<'a>), ParseError> {
        let (src, n_sets, n_line) = (self.src, head.n_sets, head.n_line);
        let have = self.lines.clone().take(6 * n_sets).count();
        if have < 6 * n_sets {
            return Err(src.invalid(
                Location::line(n_line),
                format!("{} lamp-set lines (6 per set) after line {n_line}", 6 * n_sets),
                format!("{n_sets} sets but only {have} lines left in the file"),
            ));
        }
        let set_lines: Vec<Line<'a>> = self.lines.by_ref().take(6 * n_sets).collect();
        let layout = choose_layout(&set_lines, n_sets);
        if n_sets > 1 {
            let how = match layout {
                LampSetLayout::FieldGroups => "field groups (n × 26a, then n × 26b, ...)",
                LampSetLayout::Blocks => "blocks of six lines per set",
            };
            self.warn(
                n_line,
                WarningCode::LampSetLayout,
                format!("{n_sets} lamp sets read as {how}"),
            );
        }
        let field = |set: usize, k: usize| match layout {
            LampSetLayout::FieldGroups => set_lines[k * n_sets + set],
            LampSetLayout::Blocks => set_lines[set * 6 + k],
        };
        let mut lamp_sets = Vec::with_capacity(n_sets);
        for s in 0..n_sets {
            let label = |what: &str| format!("lamp set {}: {what}", s + 1);
            let count = self.required_on(field(s, 0), &label("number of lamps (line 26a)"))?;
            let flux = self.required_on(field(s, 2), &label("total lamp flux in lm (line 26c)"))?;
            let watts = self.lenient_on(field(s, 5), &label("wattage including ballast (line 26f)"), 0.0);
            lamp_sets.push(LampSet {
                count,
                lamp_type: src.text(field(s, 1).bytes),
                flux_lm: flux,
                color: src.text(field(s, 3).bytes),
                cri: src.text(field(s, 4).bytes),
                watts,
            });
        }
        Ok((lamp_sets, layout, set_lines[6 * n_sets - 1]))
    }

    /// The luminaire: declared values, metadata and dimensions (m) from the header.
    fn finish(
        self,
        head: Head,
        header: LdtHeader,
        lamp_sets: Vec<LampSet>,
        units: &Units,
        dist: Distribution,
    ) -> Result<crate::formats::Document, ParseError> {
        let Units {
            absolute, flux_ok, phi, ..
        } = *units;
        let (mm, lorl, dff) = (head.mm, head.lorl, head.dff);
        let finite = |v: f64| v.is_finite().then_some(v);
        let lamp_flux = (!absolute && flux_ok).then_some(phi);
        let declared = Declared {
            lamp_flux_lm: lamp_flux,
            luminaire_flux_lm: if absolute {
                flux_ok.then_some(phi)
            } else {
                lamp_flux.and_then(|f| finite(f * lorl / 100.0))
            },
            lor: Some(lorl / 100.0),
            dff: Some(dff / 100.0),
            absolute,
            // The luminaire's input power is every lamp set's wattage, whichever
            // set the cd/klm values refer to (`info`, `batch` and the writers read this).
            input_watts: Some(lamp_sets.iter().map(|s| s.watts).sum::<f64>()).filter(|w| *w > 0.0 && w.is_finite()),
        };
        let lamp = lamp_sets[0].lamp_type.clone();
        let (company, catalogue, luminaire_name, test_report, date) = (
            head.company,
            head.catalogue,
            head.luminaire_name,
            head.test_report,
            head.date,
        );
        let luminous_heights_m = Some(header.luminous_heights_mm.map(|h| h / 1000.0));
        let parts = LuminaireParts {
            path: Some(self.src.path.to_path_buf()),
            format: Format::Ldt,
            version: "EULUMDAT".into(),
            photometric_type: PhotometricType::C,
            metadata: Metadata {
                manufacturer: company,
                catalogue,
                luminaire: luminaire_name,
                lamp,
                test_report,
                date,
            },
            lamp_sets,
            dimensions: Dimensions {
                length_m: mm[0] / 1000.0,
                width_m: mm[1] / 1000.0,
                height_m: mm[2] / 1000.0,
            },
            luminous_opening: Dimensions {
                length_m: mm[3] / 1000.0,
                width_m: mm[4] / 1000.0,
                // One height for the opening: the mean of the four plane heights (all kept in the header).
                height_m: (mm[5] + mm[6] + mm[7] + mm[8]) / 4000.0,
            },
            luminous_heights_m,
            declared,
            tilt: Tilt::None,
            distribution: dist,
            source_grid: None,
            warnings: self.warnings,
            front: crate::model::Front::convention(Format::Ldt),
        };
        crate::formats::document(self.src.path, parts, crate::formats::Header::Ldt(header))
    }
}

/// Lines 1-25 as read.
struct Head {
    company: String,
    ityp: i64,
    /// Isym as written, and as the model's symmetry.
    isym: i64,
    sym: Symmetry,
    mc: usize,
    mc_line: usize,
    dc: f64,
    ng: usize,
    ng_line: usize,
    dg: f64,
    test_report: String,
    luminaire_name: String,
    catalogue: String,
    file_name: String,
    date: String,
    /// Lines 13-21, millimetres.
    mm: [f64; 9],
    dff: f64,
    lorl: f64,
    cfli: f64,
    tilt: f64,
    n_sets: usize,
    /// Line of the lamp-set count.
    n_line: usize,
}

/// Field-group or block layout of `n` lamp sets (docs/domain.md §2.1): a layout
/// passes when every count, flux and wattage field (26a, 26c, 26f) holds a
/// number. Field groups win whenever they pass; blocks are used only when
/// field groups fail and blocks pass. The writer always writes field groups,
/// whose numeric fields always pass, so a written file is read back in the
/// layout it was written in whatever its text fields hold (a text-based
/// tie-break misread written files whose type or colour fields are numbers).
fn choose_layout(lines: &[Line<'_>], n: usize) -> LampSetLayout {
    if n == 1 {
        return LampSetLayout::FieldGroups;
    }
    let is_num = |l: &Line<'_>| matches!(line_number(l.bytes), LineNumber::Value { junk: false, .. });
    let passes = |layout: LampSetLayout| -> bool {
        let f = |s: usize, k: usize| match layout {
            LampSetLayout::FieldGroups => &lines[k * n + s],
            LampSetLayout::Blocks => &lines[s * 6 + k],
        };
        (0..n).all(|s| [0, 2, 5].iter().all(|&k| is_num(f(s, k))))
    };
    let fg_pass = passes(LampSetLayout::FieldGroups);
    let bl_pass = passes(LampSetLayout::Blocks);
    if bl_pass && !fg_pass {
        LampSetLayout::Blocks
    } else {
        LampSetLayout::FieldGroups
    }
}
