//! EULUMDAT reader. See the module docs of [`super`] for the rules.

use std::path::Path;

use super::stream::{bad, check_range, nth_location, number, Stream};
use super::{formula_plane_count, parse_number, stored_plane_indices, LampSetLayout, LdtHeader};
use crate::error::{Location, ParseError, Warning, WarningCode};
use crate::formats::text::{Line, Lines, Source};
use crate::formats::{angles, LampSetFlux, ReadOptions};
use crate::model::{
    Declared, Dimensions, Distribution, Format, LampSet, LuminaireParts, Metadata, PhotometricType, Symmetry, Tilt,
    ANGLE_EPS,
};

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
                if junk {
                    self.warn(
                        l.number,
                        WarningCode::HeaderJunk,
                        format!("{what}: took the first number of {}", show(l.bytes)),
                    );
                }
                Ok(v)
            }
            _ => Err(self
                .src
                .invalid(Location::line(l.number), what.to_string(), show(l.bytes))),
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
                format!("`{v}`"),
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
                if junk {
                    self.warn(
                        l.number,
                        WarningCode::HeaderJunk,
                        format!("{what}: took the first number of {}", show(l.bytes)),
                    );
                }
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
        let src = self.src;
        // Lines 1-12.
        let company = self.text("line 1: company / databank")?;
        let ityp = self.lenient("Ityp (type indicator 0-3)", 0.0)?;
        let ityp_line = self.lines.line_number();
        let ityp = match integral(ityp) {
            Some(i @ 0..=3) => i,
            _ => {
                self.warn(
                    ityp_line,
                    WarningCode::Ityp,
                    format!("Ityp = {ityp} is not 0-3; kept as 0"),
                );
                0
            }
        };
        let (isym, isym_line) = self.required_int("Isym (symmetry indicator)", 0, 4)?;
        let sym = Symmetry::from_isym(isym)
            .ok_or_else(|| src.invalid(Location::line(isym_line), "Isym (integer 0..=4)", format!("`{isym}`")))?;
        let (mc, mc_line) = self.required_int("Mc (number of C-planes)", 1, MAX_MC)?;
        let mc = mc as usize;
        let dc = self.lenient("Dc (C-plane step, degrees)", 0.0)?;
        let (ng, ng_line) = self.required_int("Ng (number of gamma angles)", 1, MAX_NG)?;
        let ng = ng as usize;
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
        let cfli_raw = self.lenient("CFLI (conversion factor for intensities)", 1.0)?;
        let cfli_line = self.lines.line_number();
        let cfli = if cfli_raw > 0.0 && cfli_raw.is_finite() {
            if cfli_raw != 1.0 {
                self.warn(
                    cfli_line,
                    WarningCode::Cfli,
                    format!("CFLI = {cfli_raw}: intensities are multiplied by it"),
                );
            }
            cfli_raw
        } else {
            self.warn(
                cfli_line,
                WarningCode::Cfli,
                format!("CFLI = {cfli_raw} is not positive; taken as 1"),
            );
            1.0
        };
        let tilt = self.lenient("tilt during measurement (degrees)", 0.0)?;
        let (n_sets, n_line) = self.required_int("number of lamp sets", 1, MAX_LAMP_SETS)?;
        let n_sets = n_sets as usize;

        // Lamp sets: 6n lines, checked against the file before they are collected.
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

        // From line 27 on: a stream of numbers.
        let mut toks = Stream {
            b: src.bytes,
            pos: self.lines.offset(),
        };
        // Every value takes at least two bytes (a digit and a separator), which
        // bounds the counts before anything is allocated, without a counting pass.
        let max_values = (src.bytes.len() - self.lines.offset()) / 2 + 1;
        let minimum = 10 + mc + ng + ng;
        if minimum > max_values {
            let remaining = toks.count_remaining();
            return Err(src.invalid(
                toks.end_location(),
                format!(
                    "at least {minimum} values after the lamp sets (10 direct ratios, {mc} C-angles, {ng} gamma angles, \
                     {ng}+ intensities)"
                ),
                format!("{remaining} values"),
            ));
        }
        let mut direct_ratios = [0.0; 10];
        for (i, d) in direct_ratios.iter_mut().enumerate() {
            *d = number(src, &mut toks, &|| format!("direct ratio {} of 10 (line 27)", i + 1))?;
        }
        let c_first = toks.next_line();
        // Kept to point errors about the i-th angle at its own line and column.
        let c_toks = toks.clone();
        let mut c_file = Vec::with_capacity(mc);
        for i in 0..mc {
            c_file.push(number(src, &mut toks, &|| {
                format!("C-angle {} of {mc} (line 28, degrees)", i + 1)
            })?);
        }
        let g_first = toks.next_line();
        let g_toks = toks.clone();
        let mut gamma = Vec::with_capacity(ng);
        for i in 0..ng {
            gamma.push(number(src, &mut toks, &|| {
                format!("gamma angle {} of {ng} (line 29, degrees)", i + 1)
            })?);
        }
        // Angle lists: range, order.
        check_range(src, &c_file, &c_toks, "C", 360.0)?;
        check_range(src, &gamma, &g_toks, "gamma", 180.0)?;
        let c_sorted = strictly_ascending(&c_file);
        let g_sorted = strictly_ascending(&gamma);
        for (ok, at, what) in [(c_sorted, &c_toks, "C"), (g_sorted, &g_toks, "gamma")] {
            if let Err((i, a, b)) = ok {
                let loc = nth_location(at, i);
                if opts.repair {
                    self.warn(
                        loc.line,
                        WarningCode::UnsortedAngles,
                        format!(
                            "{what} angles not strictly ascending (#{} = {b} after {a}); sorted, duplicates dropped",
                            i + 1
                        ),
                    );
                } else {
                    return Err(src.invalid(
                        loc,
                        format!("strictly ascending {what} angles"),
                        format!(
                            "{what} angle #{} = {b} after {a} (use the repair option to sort them)",
                            i + 1
                        ),
                    ));
                }
            }
        }
        if dc > 0.0
            && c_sorted.is_ok()
            && c_file
                .iter()
                .enumerate()
                .any(|(i, &c)| (c - c_file[0] - i as f64 * dc).abs() > 1e-3)
        {
            self.warn(
                mc_line + 1,
                WarningCode::DcMismatch,
                format!("Dc = {dc} but the C-angles of line 28 are not spaced by it; the list is used"),
            );
        }
        if dg > 0.0
            && g_sorted.is_ok()
            && gamma
                .iter()
                .enumerate()
                .any(|(i, &g)| (g - gamma[0] - i as f64 * dg).abs() > 1e-3)
        {
            self.warn(
                ng_line + 1,
                WarningCode::DgMismatch,
                format!("Dg = {dg} but the gamma angles of line 29 are not spaced by it; the list is used"),
            );
        }

        // Stored planes, by angle value.
        let stored = stored_plane_indices(sym, &c_file);
        if stored.is_empty() {
            let (lo, hi) = sym.stored_range();
            return Err(src.invalid(
                Location::line(c_first),
                format!("C-angles in [{lo}, {hi}] for Isym {isym}"),
                "none in line 28",
            ));
        }
        match formula_plane_count(sym, mc) {
            None => self.warn(
                mc_line,
                WarningCode::McDivisibility,
                format!(
                    "Mc = {mc} is not divisible as Isym {isym} requires; the stored planes are taken by angle ({} planes)",
                    stored.len()
                ),
            ),
            Some(n) if n != stored.len() => self.warn(
                mc_line,
                WarningCode::PlaneCount,
                format!(
                    "Isym {isym} with Mc = {mc} stores {n} planes by the format's formula, but line 28 has {} angles in the stored range; those are used",
                    stored.len()
                ),
            ),
            _ => {}
        }

        // Intensities.
        let nstored = stored.len();
        let need = nstored * ng;
        let truncated = |found: usize, toks: &Stream<'_>| {
            src.invalid(
                toks.end_location(),
                format!("{need} intensities ({nstored} C-planes × {ng} gamma angles, line 30 on)"),
                format!("{found} values before the end of the file"),
            )
        };
        if 10 + mc + ng + need > max_values {
            return Err(truncated(toks.count_remaining(), &toks));
        }
        let cd_first = toks.next_line();
        let mut cd = Vec::with_capacity(need);
        for i in 0..need {
            if let Some(v) = toks.fast_number() {
                cd.push(v);
                continue;
            }
            let t = toks.next().ok_or_else(|| truncated(i, &toks))?;
            match parse_number(t.bytes) {
                Some(v) => cd.push(v),
                None => {
                    let what = format!(
                        "intensity in cd/klm (plane {} of {nstored}, gamma {} of {ng})",
                        i / ng + 1,
                        i % ng + 1
                    );
                    return Err(bad(src, &toks, &t, what));
                }
            }
        }
        if toks.clone().next().is_some() {
            let extra = toks.count_remaining();
            self.warn(
                toks.next_line(),
                WarningCode::ExtraValues,
                format!("{extra} values after the {need} intensities were ignored"),
            );
        }

        // Units: cd = cd/klm × CFLI × Φ_ref / 1000.
        let absolute = lamp_sets[0].count < 0.0;
        let flux_first = lamp_sets[0].flux_lm;
        let flux_sum: f64 = lamp_sets.iter().map(|s| s.flux_lm).sum();
        let watts_first = lamp_sets[0].watts;
        let watts_sum: f64 = lamp_sets.iter().map(|s| s.watts).sum();
        let (mut phi, watts) = match opts.lamp_set_flux {
            LampSetFlux::First => (flux_first, watts_first),
            LampSetFlux::Sum => (flux_sum, watts_sum),
        };
        // A subnormal flux would scale every intensity to 0 (or overflow cd/klm × flux).
        let flux_ok = phi.is_normal() && phi > 0.0;
        if !flux_ok {
            self.warn(
                n_line + 1,
                WarningCode::ZeroLampFlux,
                format!("reference flux is {phi} lm; intensities taken as cd (1000 lm assumed)"),
            );
            phi = 1000.0;
        }
        let scale = cfli * phi / 1000.0;
        let mut min = f64::INFINITY;
        let mut negatives = 0usize;
        for v in &mut cd {
            if *v < 0.0 {
                negatives += 1;
                min = min.min(*v);
            }
            *v *= scale;
        }
        let snapped = crate::formats::into_model_range(&mut cd);
        if let Ok(Some(note)) = &snapped {
            self.warn(cd_first, WarningCode::RangeSnapped, note.clone());
        }
        if let Err((i, why)) = snapped {
            return Err(src.invalid(
                Location::line(cd_first),
                format!(
                    "intensities whose candela values (cd/klm × flux {phi} lm × CFLI {cfli} / 1000) \
                     lie in the model's range"
                ),
                format!("plane {} of {nstored}, gamma {} of {ng}: {why}", i / ng + 1, i % ng + 1),
            ));
        }
        if negatives > 0 {
            self.warn(
                cd_first,
                WarningCode::NegativeIntensity,
                format!("{negatives} negative intensities (lowest {min} cd/klm) kept as they are"),
            );
        }

        // Model grid: relabel planes, order them, drop a duplicate C360.
        let header_c = c_file.clone();
        let header_g = gamma.clone();
        let mut c_model: Vec<f64> = stored
            .iter()
            .map(|&i| match sym {
                Symmetry::None => c_file[i],
                _ => sym.fold(c_file[i]),
            })
            .collect();
        if sym == Symmetry::None && c_model.len() > 1 && c_model[c_model.len() - 1] >= 360.0 - ANGLE_EPS {
            let last = c_model.len() - 1;
            let diff = (0..ng).map(|g| (cd[last * ng + g] - cd[g]).abs()).fold(0.0, f64::max);
            self.warn(
                c_first,
                WarningCode::C360Plane,
                format!(
                    "C = 360 duplicates C = 0 and was dropped (largest difference {} cd)",
                    crate::report::significant(diff, 6)
                ),
            );
            c_model.pop();
            cd.truncate(last * ng);
        }
        if is_strictly_descending(&c_model) {
            // Isym 3: file order C270 ... C345, C0 ... C90 is model C270 down to C90.
            c_model.reverse();
            reverse_planes(&mut cd, ng);
        }
        if strictly_ascending(&c_model).is_err() {
            if !opts.repair {
                return Err(src.invalid(
                    Location::line(c_first),
                    "stored C-planes with distinct, ordered angles",
                    format!("{c_model:?} after mapping Isym {isym} planes"),
                ));
            }
            (c_model, cd) = sort_planes(&c_model, &cd, ng);
        }
        if g_sorted.is_err() {
            (gamma, cd) = sort_gamma(&gamma, &cd);
        }
        let ng = gamma.len();
        let dist = Distribution::new(c_model, gamma, cd, sym).map_err(|e| {
            src.invalid(
                Location::line(c_first),
                format!("a valid Isym {isym} grid"),
                e.to_string(),
            )
        })?;
        let (nadir, zenith) = dist.pole_spread();
        for (spread, name, ig) in [(nadir, "nadir (gamma 0)", 0), (zenith, "zenith (gamma 180)", ng - 1)] {
            // Differences at float-noise level are no mismatch.
            if spread > 0.0 && spread > 1e-9 * dist.max_cd().abs().max(1.0) {
                let mean = (0..dist.n_c()).map(|ic| dist.value(ic, ig)).sum::<f64>() / dist.n_c() as f64;
                self.warn(
                    g_first,
                    WarningCode::PoleMismatch,
                    format!(
                        "{name} values differ between planes by {spread:.6} cd ({:.3} % of their mean {mean:.6} cd); kept",
                        if mean.abs() > 0.0 { 100.0 * spread / mean.abs() } else { 0.0 }
                    ),
                );
            }
        }

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
            input_watts: (watts > 0.0).then_some(watts),
        };
        let header = LdtHeader {
            ityp,
            isym: sym.isym(),
            mc,
            dc,
            ng: header_g.len(),
            dg,
            file_name,
            luminous_heights_mm: [mm[5], mm[6], mm[7], mm[8]],
            dff_percent: dff,
            lorl_percent: lorl,
            cfli,
            tilt_deg: tilt,
            lamp_set_layout: layout,
            direct_ratios,
            c_angles: header_c,
            gamma_angles: header_g,
            cd_per_cdklm: scale,
        };
        let lamp = lamp_sets[0].lamp_type.clone();
        let luminous_heights_m = Some(header.luminous_heights_mm.map(|h| h / 1000.0));
        crate::formats::document(
            src.path,
            LuminaireParts {
                path: Some(src.path.to_path_buf()),
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
            },
            crate::formats::Header::Ldt(header),
        )
    }
}

/// Ok, or the first offending index with (previous, value) ([`angles::first_disorder`]).
fn strictly_ascending(v: &[f64]) -> Result<(), (usize, f64, f64)> {
    match angles::first_disorder(v) {
        None => Ok(()),
        Some(i) => Err((i, v[i - 1], v[i])),
    }
}

fn is_strictly_descending(v: &[f64]) -> bool {
    v.len() > 1 && v.windows(2).all(|w| w[1] < w[0] - ANGLE_EPS)
}

/// Reverse the order of the planes of a C-major block in place.
fn reverse_planes(cd: &mut [f64], ng: usize) {
    let n = cd.len() / ng;
    for i in 0..n / 2 {
        let (a, b) = cd.split_at_mut((n - 1 - i) * ng);
        a[i * ng..(i + 1) * ng].swap_with_slice(&mut b[..ng]);
    }
}

/// Repair: planes sorted by angle, duplicates dropped ([`angles::repair_order`]).
fn sort_planes(c: &[f64], cd: &[f64], ng: usize) -> (Vec<f64>, Vec<f64>) {
    let order = angles::repair_order(c);
    (
        order.iter().map(|&i| c[i]).collect(),
        angles::reorder_planes(cd, ng, &order),
    )
}

/// Repair: γ sorted within every plane, duplicates dropped ([`angles::repair_order`]).
fn sort_gamma(g: &[f64], cd: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let order = angles::repair_order(g);
    (
        order.iter().map(|&i| g[i]).collect(),
        angles::reorder_rows(cd, g.len(), &order),
    )
}

/// Field-group or block layout of `n` lamp sets (DOMAIN §2.1): a layout
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
