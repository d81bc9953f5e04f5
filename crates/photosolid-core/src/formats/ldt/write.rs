//! EULUMDAT writer.

use std::fmt::Write as _;

use super::{stored_plane_indices, LdtHeader, SIGNIFICANT_DIGITS};
use crate::formats::Document;
use crate::model::{periodic_widths, Distribution, LampSet, Symmetry, ANGLE_EPS};

/// Write `lum` as EULUMDAT text: lines 1-30 in order, CRLF line ends, one
/// value per line, lamp sets in the field-group layout.
///
/// # Header fields
/// For a document read from an EULUMDAT file ([`Document::ldt_header`] is set) the
/// header's Ityp, file name, luminous heights, CFLI, tilt, direct ratios and
/// intensity scale are reproduced, and so are Mc, Dc, Dg and the line-28
/// C-angle list as long as they still describe the distribution's grid (same
/// symmetry, same γ angles, every stored plane found). Text, dimensions,
/// lamp sets, DFF and LORL come from the luminaire itself.
///
/// For any other source they are derived:
/// - Isym from [`Distribution::symmetry`]; Ityp 1 for rotational data, else 3;
/// - the C-angle list from [`Distribution::full_planes`] (the whole circle);
///   rotational data is written with Mc = 24, Dc = 15 (the usual layout of
///   real Isym 1 files; only the first plane is stored);
/// - Dc / Dg as the step when the angles are equidistant from 0 (C) or from
///   the first γ, else 0;
/// - intensities in cd/klm relative to the flux written in lamp set 1. For
///   relative photometry that is the lamp set's flux. For absolute photometry
///   (or no usable lamp flux) the lamp count is written as −1 and the flux
///   field holds the luminaire flux: the declared one, else the distribution's
///   flux by the zonal rule, else (an all-zero distribution) 1000 lm, so that
///   cd/klm = cd. LORL is then 100;
/// - DFF and LORL from [`crate::model::Declared`], else computed by the zonal rule;
/// - direct ratios 0 (they need utilisation tables this crate does not compute).
///
/// # Precision
/// Intensities, fluxes, dimensions and percentages keep
/// [`SIGNIFICANT_DIGITS`] significant digits (relative error ≤ 5e-8; header
/// values below 1e-7 are written with at most 15 decimals, intensities with
/// at least the decimals the peak needs, so each is within 5e-8 × the peak);
/// the intensity scale (file flux) is one every value divided by it prints
/// as a finite number, else the absolute layout below is used; angles are written with
/// at most 9 decimals, so file angles come back exactly. The flux written is
/// the one the intensities are scaled by, so reading the file back gives the
/// model's candela values within that relative error.
pub fn write(doc: &Document) -> String {
    let dist = doc.luminaire.distribution();
    let grid = doc
        .ldt_header()
        .and_then(|h| header_grid(h, dist))
        .unwrap_or_else(|| derived_grid(dist));
    let rel = Relative::of(doc);
    let mut out = Lines(String::with_capacity(
        64 * 40 + dist.intensities_cd().len() * 10 + grid.c.len() * 8,
    ));
    write_header(&mut out, doc, &grid, &rel);
    write_intensities(&mut out, dist, &grid, rel.scale);
    out.0
}

/// What the intensities are relative to: the lamp sets as written (the
/// first one carries the flux the cd/klm values refer to), the scale
/// (cd per cd/klm), and the LORL and DFF lines (%).
struct Relative {
    sets: Vec<LampSet>,
    scale: f64,
    lorl: f64,
    dff: f64,
}

impl Relative {
    fn of(doc: &Document) -> Self {
        let lum = &doc.luminaire;
        let dist = lum.distribution();
        let mut sets: Vec<LampSet> = lum.lamp_sets().to_vec();
        if sets.is_empty() {
            sets.push(LampSet {
                count: 1.0,
                ..LampSet::default()
            });
        }
        let (full_flux, down_flux) = zonal_flux(dist);
        let mut lorl = lum.declared().lor.map(|l| l * 100.0);
        // A scale is usable when every intensity divided by it prints as a finite number.
        let usable = |scale: f64| {
            scale.is_normal() && scale > 0.0 && dist.intensities_cd().iter().all(|v| (v / scale).is_finite())
        };
        let scale = match doc.ldt_header() {
            Some(h) if usable(h.cd_per_cdklm) => h.cd_per_cdklm,
            _ => {
                let lamp_flux = round_sig(sets[0].flux_lm);
                if !lum.declared().absolute && sets[0].count >= 0.0 && usable(lamp_flux / 1000.0) {
                    sets[0].flux_lm = lamp_flux;
                    lamp_flux / 1000.0
                } else {
                    let declared = lum.declared().luminaire_flux_lm.filter(|f| *f > 0.0 && f.is_finite());
                    let flux = declared.unwrap_or(if full_flux > 0.0 && full_flux.is_finite() {
                        full_flux
                    } else {
                        1000.0
                    });
                    // A flux that rounds to 0 in print would make every intensity infinite.
                    let flux = Some(round_sig(flux)).filter(|f| usable(f / 1000.0)).unwrap_or(1000.0);
                    sets[0].count = -sets[0].count.abs().max(1.0);
                    sets[0].flux_lm = flux;
                    lorl = Some(100.0);
                    flux / 1000.0
                }
            }
        };
        let lorl = lorl.unwrap_or_else(|| {
            let lamp = sets[0].flux_lm;
            if lamp > 0.0 {
                100.0 * full_flux / lamp
            } else {
                100.0
            }
        });
        let dff = lum.declared().dff.map(|d| d * 100.0).unwrap_or(if full_flux > 0.0 {
            100.0 * down_flux / full_flux
        } else {
            100.0
        });
        Relative { sets, scale, lorl, dff }
    }
}

/// EULUMDAT output: one value per CRLF-terminated line.
struct Lines(String);

impl Lines {
    /// A text field: one line, so line breaks inside it (which would shift
    /// every later line) become spaces.
    fn text(&mut self, s: &str) {
        for ch in s.chars() {
            self.0.push(if ch == '\r' || ch == '\n' { ' ' } else { ch });
        }
        self.0.push_str("\r\n");
    }
    fn num(&mut self, v: f64) {
        push_sig(&mut self.0, v);
        self.0.push_str("\r\n");
    }
    fn angle(&mut self, v: f64) {
        crate::numfmt::push_fixed_trimmed(&mut self.0, v, 9);
        self.0.push_str("\r\n");
    }
    fn int(&mut self, v: i64) {
        let _ = write!(self.0, "{v}\r\n");
    }
}

/// Lines 1-28 and the γ list: identification, grid, dimensions, lamp sets,
/// direct ratios and angles.
fn write_header(out: &mut Lines, doc: &Document, grid: &Grid, rel: &Relative) {
    let lum = &doc.luminaire;
    let dist = lum.distribution();
    let sym = dist.symmetry();
    let header = doc.ldt_header();
    let m = lum.metadata();
    out.text(&m.manufacturer);
    out.int(header.map_or(if sym == Symmetry::Rotational { 1 } else { 3 }, |h| h.ityp));
    out.int(sym.isym() as i64);
    out.int(grid.c.len() as i64);
    out.angle(grid.dc);
    out.int(dist.n_gamma() as i64);
    out.angle(grid.dg);
    out.text(&m.test_report);
    out.text(&m.luminaire);
    out.text(&m.catalogue);
    let file_name = match header {
        Some(h) => h.file_name.clone(),
        None => lum
            .path()
            .as_ref()
            .and_then(|p| p.file_stem())
            .map(|s| format!("{}.ldt", s.to_string_lossy()))
            .unwrap_or_default(),
    };
    out.text(&file_name);
    out.text(&m.date);
    let dims = lum.dimensions();
    for v in [dims.length_m, dims.width_m, dims.height_m] {
        out.num(v * 1000.0);
    }
    let (length_m, width_m, heights_m) = ldt_opening(lum);
    out.num(length_m * 1000.0);
    out.num(width_m * 1000.0);
    let heights_mm = heights_m.map(|v| v * 1000.0);
    for v in header.map_or(heights_mm, |h| h.luminous_heights_mm) {
        out.num(v);
    }
    out.num(rel.dff);
    out.num(rel.lorl);
    out.num(header.map_or(1.0, |h| h.cfli));
    out.num(header.map_or(0.0, |h| h.tilt_deg));
    let sets = &rel.sets;
    out.int(sets.len() as i64);
    sets.iter().for_each(|s| out.num(s.count));
    sets.iter().for_each(|s| out.text(&s.lamp_type));
    sets.iter().for_each(|s| out.num(s.flux_lm));
    sets.iter().for_each(|s| out.text(&s.color));
    sets.iter().for_each(|s| out.text(&s.cri));
    sets.iter().for_each(|s| out.num(s.watts));
    for v in header.map_or([0.0; 10], |h| h.direct_ratios) {
        out.num(v);
    }
    grid.c.iter().for_each(|&c| out.angle(c));
    dist.gamma_angles_deg().iter().for_each(|&g| out.angle(g));
}

/// The intensities of the stored planes, in cd/klm (cd / `scale`).
fn write_intensities(out: &mut Lines, dist: &Distribution, grid: &Grid, scale: f64) {
    // Small values get at least the decimals the peak needs, so every value
    // is written within 5e-8 of the peak even when the peak itself is tiny.
    let peak = dist
        .intensities_cd()
        .iter()
        .fold(0.0f64, |m, v| m.max((v / scale).abs()));
    let floor_decimals = if peak > 0.0 {
        (SIGNIFICANT_DIGITS as i32 - 1 - peak.log10().floor() as i32).clamp(15, 330) as usize
    } else {
        15
    };
    for &ic in &grid.planes {
        for &v in dist.plane_cd(ic) {
            push_sig_with(&mut out.0, v / scale, floor_decimals);
            out.0.push_str("\r\n");
        }
    }
}

/// The grid as written: line-28 angles, steps, and the model plane of each stored file plane.
struct Grid {
    c: Vec<f64>,
    dc: f64,
    dg: f64,
    planes: Vec<usize>,
}

/// The header's grid, if it still describes `dist`.
fn header_grid(h: &LdtHeader, dist: &Distribution) -> Option<Grid> {
    let sym = dist.symmetry();
    let g = dist.gamma_angles_deg();
    // A header whose lists were repaired on reading (unsorted, duplicates)
    // no longer describes a readable file: the grid is derived instead.
    if h.isym != sym.isym()
        || h.c_angles.is_empty()
        || crate::formats::angles::first_disorder(&h.c_angles).is_some()
        || crate::formats::angles::first_disorder(&h.gamma_angles).is_some()
        || h.gamma_angles.len() != g.len()
        || h.gamma_angles.iter().zip(g).any(|(a, b)| (a - b).abs() > ANGLE_EPS)
    {
        return None;
    }
    let planes = file_planes(sym, &h.c_angles, dist)?;
    Some(Grid {
        c: h.c_angles.clone(),
        dc: h.dc,
        dg: h.dg,
        planes,
    })
}

/// Model plane of each stored file plane; None unless every model plane is written.
fn file_planes(sym: Symmetry, c: &[f64], dist: &Distribution) -> Option<Vec<usize>> {
    let planes: Vec<usize> = stored_plane_indices(sym, c)
        .into_iter()
        .map(|i| dist.find_plane(sym.fold(c[i])))
        .collect::<Option<_>>()?;
    let mut seen = vec![false; dist.n_c()];
    planes.iter().for_each(|&p| seen[p] = true);
    seen.iter().all(|&s| s).then_some(planes)
}

fn derived_grid(dist: &Distribution) -> Grid {
    let sym = dist.symmetry();
    let c: Vec<f64> = if sym == Symmetry::Rotational {
        (0..24).map(|i| i as f64 * 15.0).collect()
    } else {
        dist.full_planes().into_iter().map(|p| p.0).collect()
    };
    let step = |v: &[f64], origin: f64| -> f64 {
        if v.len() < 2 {
            return 0.0;
        }
        let d = v[1] - v[0];
        let uniform = (v[0] - origin).abs() <= ANGLE_EPS
            && v.iter()
                .enumerate()
                .all(|(i, &x)| (x - v[0] - i as f64 * d).abs() <= 1e-6);
        if uniform {
            d
        } else {
            0.0
        }
    };
    let dc = step(&c, 0.0);
    // A full-circle list must close: Mc × Dc = 360.
    let dc = if (dc * c.len() as f64 - 360.0).abs() <= 1e-6 {
        dc
    } else {
        0.0
    };
    let g = dist.gamma_angles_deg();
    let dg = step(g, g[0]);
    let planes = file_planes(sym, &c, dist).unwrap_or_else(|| (0..dist.n_c()).collect());
    Grid { c, dc, dg, planes }
}

/// Flux (lm) of the distribution by the zonal midpoint rule (docs/domain.md §5), and its part below γ = 90.
fn zonal_flux(dist: &Distribution) -> (f64, f64) {
    let g = dist.gamma_angles_deg();
    let ng = g.len();
    let rad = std::f64::consts::PI / 180.0;
    // Zone bounds: midpoints between γ samples, clamped to the data range.
    let lo = |i: usize| if i == 0 { g[0] } else { 0.5 * (g[i - 1] + g[i]) };
    let hi = |i: usize| {
        if i + 1 == ng {
            g[ng - 1]
        } else {
            0.5 * (g[i] + g[i + 1])
        }
    };
    let zone = |a: f64, b: f64| (a * rad).cos() - (b * rad).cos();
    let (planes, widths): (Vec<usize>, Vec<f64>) = if dist.symmetry() == Symmetry::Rotational {
        (vec![0], vec![360.0])
    } else {
        let full = dist.full_planes();
        let angles: Vec<f64> = full.iter().map(|p| p.0).collect();
        (full.iter().map(|p| p.1).collect(), periodic_widths(&angles))
    };
    let (mut total, mut down) = (0.0, 0.0);
    for (&ic, &w) in planes.iter().zip(&widths) {
        let p = dist.plane_cd(ic);
        for (i, &v) in p.iter().enumerate() {
            let (a, b) = (lo(i), hi(i));
            total += v * w * rad * zone(a, b);
            if a < 90.0 {
                down += v * w * rad * zone(a, b.min(90.0));
            }
        }
    }
    (total, down)
}

/// `v` rounded to [`SIGNIFICANT_DIGITS`], as the writer prints it.
fn round_sig(v: f64) -> f64 {
    let mut s = String::new();
    push_sig(&mut s, v);
    s.parse().unwrap_or(v)
}

/// Append `v` with [`SIGNIFICANT_DIGITS`] significant digits (at most 15 decimals), trailing zeros trimmed.
fn push_sig(out: &mut String, v: f64) {
    push_sig_with(out, v, 15);
}

/// Append `v` with [`SIGNIFICANT_DIGITS`] significant digits and at most
/// `max_decimals` decimals, trailing zeros trimmed.
fn push_sig_with(out: &mut String, v: f64, max_decimals: usize) {
    if v == 0.0 || !v.is_finite() {
        out.push('0');
        return;
    }
    let mag = v.abs().log10().floor() as i32;
    let decimals = (SIGNIFICANT_DIGITS as i32 - 1 - mag).clamp(0, max_decimals as i32) as usize;
    crate::numfmt::push_fixed_trimmed(out, v, decimals);
}

/// The luminous area in EULUMDAT's terms (length, width with 0 for a disk,
/// the four side heights; metres): a EULUMDAT luminaire's as it is, another
/// format's through its shape ([`crate::model::opening::Opening::to_ldt`]),
/// so an LM-63 circle (negative width and length) becomes a disk.
fn ldt_opening(lum: &crate::model::Luminaire) -> (f64, f64, [f64; 4]) {
    let o = lum.luminous_opening();
    let as_is = (
        o.length_m,
        o.width_m,
        lum.luminous_heights_m().unwrap_or([o.height_m; 4]),
    );
    if lum.format() == crate::model::Format::Ldt {
        return as_is;
    }
    match crate::model::opening::Opening::of_luminaire(lum) {
        Ok(shape) => {
            let (l, w, h, _) = shape.to_ldt();
            (l, w, h)
        }
        Err(_) => (o.length_m.abs(), o.width_m.abs(), [o.height_m.abs(); 4]),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_trimmed_and_rounded() {
        let f = |v: f64| {
            let mut s = String::new();
            push_sig(&mut s, v);
            s
        };
        assert_eq!(f(0.0), "0");
        assert_eq!(f(123.4), "123.4");
        assert_eq!(f(123.39999999999999), "123.4");
        assert_eq!(f(87.00000000000001), "87");
        assert_eq!(f(-0.000000001), "-0.000000001");
        assert_eq!(f(1234567.891), "1234567.9");
        assert_eq!(f(-1e-20), "0");
        let mut s = String::new();
        crate::numfmt::push_fixed_trimmed(&mut s, 7.300000000000011, 9);
        assert_eq!(s, "7.3");
    }

    #[test]
    fn zonal_flux_of_isotropic_source_is_4pi() {
        let g: Vec<f64> = (0..=180).map(|i| i as f64).collect();
        let d = Distribution::new(vec![0.0], g.clone(), vec![1.0; g.len()], Symmetry::Rotational).unwrap();
        let (t, down) = zonal_flux(&d);
        assert!((t - 4.0 * std::f64::consts::PI).abs() < 1e-9, "{t}");
        assert!((down - 2.0 * std::f64::consts::PI).abs() < 1e-9, "{down}");
    }
}
