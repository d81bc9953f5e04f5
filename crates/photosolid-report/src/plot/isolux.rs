//! Isolux map of a plane receiver: false colour (viridis, 0 lx to Emax)
//! bilinear between the calculation points (held at the edges), contour
//! lines (marching squares on the point grid) at 1–2–5 × 10^k lux, axes in
//! metres, a colour bar in lux with the contour levels marked on it, E_avg,
//! E_min, E_max and U0 under the title, and the luminaires' photometric
//! centres projected onto the plane (`L1`, `L2`, ...; marks that fall on
//! one spot share one label, `L1/L2`). The plane's u edge runs left to
//! right, v bottom to top.

use crate::error::Error;
use crate::font;
use crate::solid::ColorMap;

use super::axis::{fmt_tick, nice_step, ticks_in};
use super::canvas::{Align, Canvas};
use super::{Plot, AXIS, INK};

/// Longest side of the map area, pixels.
pub const MAP_PIXELS: u32 = 800;
/// Left edge of the map area in the image, px.
pub const MAP_LEFT: u32 = 84;
/// Top edge of the map area in the image, px: room for the title, the
/// statistics line and, under it, the colour bar's unit.
pub const MAP_TOP: u32 = 76;
/// Room right of the map (colour bar and its ticks), px.
const RIGHT: u32 = 150;
/// Room under the map (tick labels, axis title, contour line), px.
const BOTTOM: u32 = 88;
/// Shortest colour bar, px.
const MIN_BAR: u32 = 160;

/// One axis of the map: the coordinate at the plane's s (or t) = 0 and 1,
/// and its title (e.g. "x (m)").
#[derive(Debug, Clone, PartialEq)]
pub struct MapAxis {
    /// Coordinate at s = 0, m.
    pub start: f64,
    /// Coordinate at s = 1, m.
    pub end: f64,
    /// Axis title with its unit.
    pub title: String,
}

/// The quantity a map shows: its symbol, its unit and the map's name.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MapQuantity {
    /// Symbol in the statistics line (`E`, `L`).
    pub symbol: &'static str,
    /// Unit (ASCII: the plot font has no superscripts).
    pub unit: &'static str,
    /// The title's first word (`Isolux`, `Isoluminance`).
    pub title: &'static str,
}

impl MapQuantity {
    /// Illuminance, lx.
    pub const ILLUMINANCE: MapQuantity = MapQuantity {
        symbol: "E",
        unit: "lx",
        title: "Isolux",
    };
    /// Luminance, cd/m².
    pub const LUMINANCE: MapQuantity = MapQuantity {
        symbol: "L",
        unit: "cd/m2",
        title: "Isoluminance",
    };
}

/// What [`isolux_plot`] draws.
#[derive(Debug, Clone)]
pub struct IsoluxSpec<'a> {
    /// What the values are (illuminance in lx, or luminance in cd/m²).
    pub quantity: MapQuantity,
    /// Receiver name (title).
    pub name: &'a str,
    /// Values at the cell centres in `quantity`'s unit, u fastest (`nu * nv` values).
    pub values: &'a [f64],
    /// Points along u and v.
    pub grid: (usize, usize),
    /// Lengths of the u and v edges, m.
    pub size_m: (f64, f64),
    /// Average value in `quantity`'s unit (as the result states it).
    pub e_avg_lux: f64,
    /// The horizontal (u) axis.
    pub u_axis: MapAxis,
    /// The vertical (v) axis.
    pub v_axis: MapAxis,
    /// Each luminaire's centre in plane coordinates (s, t), [0, 1] on the
    /// plane; `marks[k]` is labelled `L{k+1}`; non-finite ones are skipped.
    pub marks: &'a [(f64, f64)],
    /// Limits to mark (a lighting class's): each drawn as a red contour on
    /// the map and a red line on the colour bar, and named under the map.
    pub limits: &'a [MapLimit],
}

/// A limit marked on a map: a value in the map quantity's unit and what it is.
#[derive(Debug, Clone, PartialEq)]
pub struct MapLimit {
    /// The value, in the map quantity's unit.
    pub value: f64,
    /// What it is, e.g. "M3: L >= 0.4 L_av".
    pub label: String,
}

/// The colour of limits on a map.
const LIMIT_RGB: [u8; 3] = [230, 40, 30];

/// Contour levels (lx): the 1–2–5 × 10^k values strictly between `lo` and
/// `hi`, from hi / 200 up, the highest 8 of them.
pub fn contour_levels(lo: f64, hi: f64) -> Vec<f64> {
    if !(hi > 0.0 && hi.is_finite() && hi > lo) {
        return Vec::new();
    }
    let top = hi.log10().ceil() as i32;
    let mut out = Vec::new();
    'outer: for e in (top - 12..=top).rev() {
        for m in [5.0, 2.0, 1.0] {
            let v = m * 10f64.powi(e);
            if v < hi * (1.0 - 1e-12) && v > lo && v >= hi / 200.0 {
                out.push(v);
                if out.len() == 8 {
                    break 'outer;
                }
            }
        }
    }
    out.reverse();
    out
}

/// A lux value for the map's text: 3 significant digits.
fn lux(v: f64) -> String {
    crate::significant(v, 3)
}

/// The map's size in pixels (map area) for edges of `lu` × `lv` m.
fn map_size(lu: f64, lv: f64) -> (u32, u32) {
    let long = lu.max(lv);
    let scale = if long > 0.0 && long.is_finite() {
        f64::from(MAP_PIXELS) / long
    } else {
        1.0
    };
    (
        ((lu * scale).round() as u32).clamp(1, MAP_PIXELS),
        ((lv * scale).round() as u32).clamp(1, MAP_PIXELS),
    )
}

/// Do two boxes overlap, `gap` px apart at least?
fn clash(a: &[f32; 4], b: &[f32; 4], gap: f32) -> bool {
    !(a[2] + gap <= b[0] || b[2] + gap <= a[0] || a[3] + gap <= b[1] || b[3] + gap <= a[1])
}

/// Draw the isolux map: PNG and text boxes.
///
/// # Errors
/// [`crate::error::ModelError::Parameter`] if `values` is not `nu * nv` long or the
/// image would be too large; [`Error::Encode`] if encoding fails.
pub fn isolux_plot(spec: &IsoluxSpec) -> Result<Plot, Error> {
    let (nu, nv) = spec.grid;
    let e = spec.values;
    if nu == 0 || nv == 0 || e.len() != nu * nv {
        return Err(crate::error::ModelError::Parameter {
            name: "values",
            value: format!("isolux map of {}: {} values", spec.name, e.len()),
            reason: format!("a {nu} x {nv} grid needs {}", nu * nv),
        }
        .into());
    }
    let (lu, lv) = spec.size_m;
    let (w, h) = map_size(lu, lv);
    let fin = |v: &&f64| v.is_finite();
    let emax = e.iter().filter(fin).copied().fold(0.0, f64::max);
    let emin = e.iter().filter(fin).copied().fold(f64::INFINITY, f64::min);
    let emin = if emin.is_finite() { emin } else { 0.0 };
    let levels = contour_levels(emin, emax);

    // The texts under the title and under the map, to size the image.
    let stats = stats_line(spec, emin, emax);
    // A map shorter than its vertical axis title is centred in a band as
    // tall as the title, so the title stays beside the map, inside the image.
    let band = h.max(font::text_width(&spec.v_axis.title, 2) + 16);
    let map = MapArea {
        l: MAP_LEFT as f32,
        t: (MAP_TOP + (band - h) / 2) as f32,
        w,
        h,
    };
    let (groups, off) = group_marks(spec.marks, &map);
    let footer = footer_line(&levels, spec.quantity.unit, &off);
    let limits_line = limits_line(spec.limits, emin, emax);
    let title = format!("{}: {}", spec.quantity.title, spec.name);
    let text_w = [&stats, &footer, &limits_line]
        .iter()
        .map(|s| font::text_width(s, 2))
        .max()
        .unwrap_or(0)
        + 2 * 12;
    let width = (MAP_LEFT + w + RIGHT).max(text_w).max(font::text_width(&title, 2) + 24);
    let height = MAP_TOP + band.max(MIN_BAR) + BOTTOM + if limits_line.is_empty() { 0 } else { 24 };
    let mut cv = Canvas::new(width.min(8192), height.min(8192), "isolux")?;
    cv.title(&title);
    cv.text(12.0, 42.0, &stats, 2, Align::Left, INK, false);

    let field = Field { e, nu, nv };
    draw_false_colour(&mut cv, &map, &field, emax);
    draw_contours(&mut cv, &map, &field, &levels, [255, 255, 255], 1.5);
    let limit_values: Vec<f64> = spec.limits.iter().map(|l| l.value).collect();
    draw_contours(&mut cv, &map, &field, &limit_values, LIMIT_RGB, 3.0);
    let (l, t) = (map.l, map.t);
    cv.frame(l - 1.0, t - 1.0, l + w as f32 + 1.0, t + h as f32 + 1.0, AXIS);
    draw_map_axes(&mut cv, &map, &spec.u_axis, &spec.v_axis);
    cv.text(
        12.0,
        (MAP_TOP + band.max(MIN_BAR)) as f32 + 64.0,
        &footer,
        2,
        Align::Left,
        INK,
        false,
    );
    if !limits_line.is_empty() {
        cv.text(
            12.0,
            (MAP_TOP + band.max(MIN_BAR)) as f32 + 88.0,
            &limits_line,
            2,
            Align::Left,
            LIMIT_RGB,
            false,
        );
    }
    draw_colour_bar(&mut cv, &map, emax, &levels, spec.quantity.unit);
    draw_bar_limits(&mut cv, &map, emax, &limit_values);
    draw_luminaires(&mut cv, &groups);
    cv.finish()
}

/// The map area of the image: its top-left corner (`l`, `t`) and size
/// (`w` × `h`), px.
struct MapArea {
    /// Left edge, px.
    l: f32,
    /// Top edge, px.
    t: f32,
    /// Width, px.
    w: u32,
    /// Height, px.
    h: u32,
}

impl MapArea {
    /// Pixel position of plane coordinates (s, t), each 0 to 1 (t upwards).
    fn to_px(&self, s: f64, tt: f64) -> (f32, f32) {
        (
            self.l + (s * f64::from(self.w)) as f32,
            self.t + ((1.0 - tt) * f64::from(self.h)) as f32,
        )
    }
}

/// The values at the calculation points: `e[j * nu + i]`, u fastest.
struct Field<'a> {
    /// The values.
    e: &'a [f64],
    /// Points along u.
    nu: usize,
    /// Points along v.
    nv: usize,
}

impl Field<'_> {
    /// The value at plane coordinates (s, t): bilinear between the cell
    /// centres, held at the edges.
    fn at(&self, s: f64, tt: f64) -> f64 {
        let (nu, nv, e) = (self.nu, self.nv, self.e);
        let x = (s * nu as f64 - 0.5).clamp(0.0, (nu - 1) as f64);
        let y = (tt * nv as f64 - 0.5).clamp(0.0, (nv - 1) as f64);
        let (i0, j0) = (x.floor() as usize, y.floor() as usize);
        let (i1, j1) = ((i0 + 1).min(nu - 1), (j0 + 1).min(nv - 1));
        let (fx, fy) = (x - i0 as f64, y - j0 as f64);
        let g = |i: usize, j: usize| e[j * nu + i];
        (g(i0, j0) * (1.0 - fx) + g(i1, j0) * fx) * (1.0 - fy) + (g(i0, j1) * (1.0 - fx) + g(i1, j1) * fx) * fy
    }

    /// Plane coordinates (s, t) of point (i, j).
    fn centre(&self, i: usize, j: usize) -> (f64, f64) {
        ((i as f64 + 0.5) / self.nu as f64, (j as f64 + 0.5) / self.nv as f64)
    }
}

/// Luminaire marks that share one spot: the spot, px, and the marks' indices.
type MarkGroup = ((f32, f32), Vec<usize>);

/// The statistics under the title: average, minimum, maximum, U0 and the grid.
fn stats_line(spec: &IsoluxSpec, emin: f64, emax: f64) -> String {
    let (nu, nv) = spec.grid;
    let u0 = if spec.e_avg_lux > 0.0 {
        format!(", U0 {}", crate::significant(emin / spec.e_avg_lux, 2))
    } else {
        String::new()
    };
    let (sym, unit) = (spec.quantity.symbol, spec.quantity.unit);
    format!(
        "{sym}_avg {} {unit}, {sym}_min {} {unit}, {sym}_max {} {unit}{u0}; {nu} x {nv} points",
        lux(spec.e_avg_lux),
        lux(emin),
        lux(emax)
    )
}

/// The marks on the map, those within 10 px of each other in one group,
/// and the names (`L3`) of those off the map, which the footer lists.
fn group_marks(marks: &[(f64, f64)], map: &MapArea) -> (Vec<MarkGroup>, Vec<String>) {
    let (l, t, w, h) = (map.l, map.t, map.w, map.h);
    let mut groups: Vec<MarkGroup> = Vec::new();
    let mut off = Vec::new();
    for (k, &(s, tt)) in marks.iter().enumerate() {
        if !(s.is_finite() && tt.is_finite()) {
            continue;
        }
        let (x, y) = map.to_px(s, tt);
        if x < l - 2.0 || x > l + w as f32 + 2.0 || y < t - 2.0 || y > t + h as f32 + 2.0 {
            off.push(format!("L{}", k + 1));
            continue;
        }
        let (x, y) = (x.clamp(l, l + w as f32), y.clamp(t, t + h as f32));
        match groups
            .iter_mut()
            .find(|(p, _)| (p.0 - x).abs() < 10.0 && (p.1 - y).abs() < 10.0)
        {
            Some(g) => g.1.push(k),
            None => groups.push(((x, y), vec![k])),
        }
    }
    (groups, off)
}

/// The line under the map: the contour levels, and the marks `off` the map.
fn footer_line(levels: &[f64], unit: &str, off: &[String]) -> String {
    let mut footer = if levels.is_empty() {
        "no contour lines (uniform or dark)".to_string()
    } else {
        format!(
            "contours (white): {} {unit}",
            levels.iter().map(|v| fmt_tick(*v, *v)).collect::<Vec<_>>().join(", ")
        )
    };
    if !off.is_empty() {
        footer.push_str(&format!("; beyond the map: {}", off.join(", ")));
    }
    footer
}

/// False colour, one pixel at a time: viridis from 0 to `emax`.
fn draw_false_colour(cv: &mut Canvas, map: &MapArea, field: &Field, emax: f64) {
    let (w, h) = (map.w, map.h);
    for py in 0..h {
        for px in 0..w {
            let (s, tt) = (
                (f64::from(px) + 0.5) / f64::from(w),
                1.0 - (f64::from(py) + 0.5) / f64::from(h),
            );
            let val = field.at(s, tt);
            let c = ColorMap::Viridis.rgb8(if emax > 0.0 && val.is_finite() { val / emax } else { 0.0 });
            let (x, y) = ((map.l as u32 + px) as i32, (map.t as u32 + py) as i32);
            cv.rect(x, y, x + 1, y + 1, c);
        }
    }
}

/// Contours at `levels`: marching squares between the cell centres.
fn draw_contours(cv: &mut Canvas, map: &MapArea, field: &Field, levels: &[f64], rgb: [u8; 3], width: f32) {
    let (nu, nv, e) = (field.nu, field.nv, field.e);
    for &level in levels {
        for j in 0..nv.saturating_sub(1) {
            for i in 0..nu.saturating_sub(1) {
                let corners = [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)];
                let mut crossings = Vec::new();
                for k in 0..4 {
                    let (a, b) = (corners[k], corners[(k + 1) % 4]);
                    let (ea, eb) = (e[a.1 * nu + a.0], e[b.1 * nu + b.0]);
                    if (ea < level) != (eb < level) {
                        let f = (level - ea) / (eb - ea);
                        let (pa, pb) = (field.centre(a.0, a.1), field.centre(b.0, b.1));
                        crossings.push((pa.0 + f * (pb.0 - pa.0), pa.1 + f * (pb.1 - pa.1)));
                    }
                }
                for pair in crossings.chunks_exact(2) {
                    let (p0, p1) = (map.to_px(pair[0].0, pair[0].1), map.to_px(pair[1].0, pair[1].1));
                    cv.line(p0.0, p0.1, p1.0, p1.1, rgb, width);
                }
            }
        }
    }
}

/// Ticks of a map axis `px_len` px long: (position 0 to 1 along the plane
/// edge, label), in metres.
fn map_axis_ticks(a: &MapAxis, px_len: u32) -> Vec<(f64, String)> {
    let (lo, hi) = (a.start.min(a.end), a.start.max(a.end));
    let step = nice_step(hi - lo, (px_len / 90).clamp(2, 10) as usize);
    ticks_in(lo, hi, step)
        .into_iter()
        .map(|v| ((v - a.start) / (a.end - a.start), fmt_tick(v, step)))
        .filter(|(f, _)| f.is_finite())
        .collect::<Vec<_>>()
}

/// The u axis under the map and the v axis left of it, in metres, with
/// their titles; tick labels that would crowd the previous one are skipped.
fn draw_map_axes(cv: &mut Canvas, map: &MapArea, u_axis: &MapAxis, v_axis: &MapAxis) {
    let (l, t, w, h) = (map.l, map.t, map.w, map.h);
    let bottom = t + h as f32;
    let mut last_right = f32::NEG_INFINITY;
    for (f, lab) in map_axis_ticks(u_axis, w) {
        let x = (l + f as f32 * w as f32).round() + 0.5;
        cv.line(x, bottom + 1.0, x, bottom + 6.0, AXIS, 1.0);
        let tw = font::text_width(&lab, 2) as f32;
        if x - tw / 2.0 > last_right + 8.0 {
            let b = cv.text(x, bottom + 16.0, &lab, 2, Align::Center, INK, false);
            last_right = b[2];
        }
    }
    cv.text(
        l + w as f32 / 2.0,
        bottom + 40.0,
        &u_axis.title,
        2,
        Align::Center,
        INK,
        false,
    );
    let mut last_top = f32::INFINITY;
    for (f, lab) in map_axis_ticks(v_axis, h) {
        let y = (bottom - f as f32 * h as f32).round() + 0.5;
        cv.line(l - 6.0, y, l - 1.0, y, AXIS, 1.0);
        if y + 9.0 < last_top - 4.0 {
            let b = cv.text(l - 9.0, y, &lab, 2, Align::Right, INK, false);
            last_top = b[1];
        }
    }
    cv.text_vertical(16.0, t + h as f32 / 2.0, &v_axis.title, 2, INK);
}

/// Colour bar right of the map, 0 to `emax`, with the contour `levels` on
/// it and `unit` over it.
fn draw_colour_bar(cv: &mut Canvas, map: &MapArea, emax: f64, levels: &[f64], unit: &str) {
    let (l, t, w, h) = (map.l, map.t, map.w, map.h);
    let bar_h = h.max(MIN_BAR) as f32;
    let (bx0, bx1) = (l + w as f32 + 30.0, l + w as f32 + 52.0);
    for r in 0..bar_h as i32 {
        let f = 1.0 - (f64::from(r) + 0.5) / f64::from(bar_h);
        let y = t as i32 + r;
        cv.rect(bx0 as i32, y, bx1 as i32, y + 1, ColorMap::Viridis.rgb8(f));
    }
    cv.frame(bx0 - 1.0, t - 1.0, bx1 + 1.0, t + bar_h + 1.0, AXIS);
    let top_lux = if emax > 0.0 { emax } else { 1.0 };
    let yb = |v: f64| (t + bar_h - (v / top_lux) as f32 * bar_h).round() + 0.5;
    for &v in levels {
        cv.line(bx0, yb(v), bx1, yb(v), [255, 255, 255], 1.0);
    }
    let sb = nice_step(top_lux, ((bar_h / 40.0) as usize).clamp(2, 8));
    for v in ticks_in(0.0, top_lux, sb) {
        let y = yb(v);
        cv.line(bx1 + 1.0, y, bx1 + 6.0, y, AXIS, 1.0);
        cv.text(bx1 + 9.0, y, &fmt_tick(v, sb), 2, Align::Left, INK, false);
    }
    cv.text((bx0 + bx1) / 2.0, t - 12.0, unit, 2, Align::Center, INK, false);
}

/// The line naming the limits, and where each lies against the map's values
/// (`emin`..`emax`): one that no point reaches or every point exceeds has no
/// contour, so the line says so.
fn limits_line(limits: &[MapLimit], emin: f64, emax: f64) -> String {
    if limits.is_empty() {
        return String::new();
    }
    let parts: Vec<String> = limits
        .iter()
        .map(|l| {
            let side = if l.value > emax {
                " (above every point)"
            } else if l.value < emin {
                " (below every point)"
            } else {
                ""
            };
            format!("{}{side}", l.label)
        })
        .collect();
    format!("limits (red): {}", parts.join("; "))
}

/// A red line across the colour bar at each limit (clamped to the bar).
fn draw_bar_limits(cv: &mut Canvas, map: &MapArea, emax: f64, values: &[f64]) {
    let (l, t, w, h) = (map.l, map.t, map.w, map.h);
    let bar_h = h.max(MIN_BAR) as f32;
    let (bx0, bx1) = (l + w as f32 + 26.0, l + w as f32 + 56.0);
    let top = if emax > 0.0 { emax } else { 1.0 };
    for &v in values {
        if !v.is_finite() {
            continue;
        }
        let y = (t + bar_h - ((v / top) as f32).clamp(0.0, 1.0) * bar_h).round() + 0.5;
        cv.line(bx0, y, bx1, y, LIMIT_RGB, 3.0);
    }
}

/// Luminaires: a white-ringed black dot per group, its label (`L1/L2`) on a
/// side where it overlaps no text and no dot, else where it overlaps no text.
fn draw_luminaires(cv: &mut Canvas, groups: &[MarkGroup]) {
    let dots: Vec<[f32; 4]> = groups
        .iter()
        .map(|((x, y), _)| [x - 7.0, y - 7.0, x + 7.0, y + 7.0])
        .collect();
    for ((x, y), _) in groups {
        cv.circle(*x, *y, 7.0, [255, 255, 255], None);
        cv.circle(*x, *y, 5.0, [0, 0, 0], None);
    }
    let mut placed: Vec<[f32; 4]> = cv.texts.iter().map(|tb| tb.rect).collect();
    let th = font::text_height(2) as f32;
    let (wf, hf) = (cv.w(), cv.h());
    for ((x, y), ks) in groups {
        let label = ks.iter().map(|k| format!("L{}", k + 1)).collect::<Vec<_>>().join("/");
        let tw = font::text_width(&label, 2) as f32;
        let cands = [
            (x + 11.0, y - 10.0),
            (x + 11.0, y + 10.0),
            (x - 11.0 - tw, y - 10.0),
            (x - 11.0 - tw, y + 10.0),
            (x - tw / 2.0, y - 12.0 - th / 2.0),
            (x - tw / 2.0, y + 12.0 + th / 2.0),
        ];
        let boxed = |(bx, by): (f32, f32)| {
            [
                bx.round(),
                (by - th / 2.0).round(),
                bx.round() + tw,
                (by - th / 2.0).round() + th,
            ]
        };
        let ok = |b: &[f32; 4]| {
            b[0] >= 4.0
                && b[1] >= 4.0
                && b[2] <= wf - 4.0
                && b[3] <= hf - 4.0
                && !placed.iter().chain(&dots).any(|o| clash(b, o, 4.0))
        };
        let pick = cands.iter().copied().find(|c| ok(&boxed(*c))).or_else(|| {
            cands
                .iter()
                .copied()
                .find(|c| !placed.iter().any(|o| clash(&boxed(*c), o, 4.0)))
        });
        if let Some((bx, by)) = pick {
            let b = cv.text(bx, by, &label, 2, Align::Left, [0, 0, 0], true);
            placed.push(b);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn levels_are_1_2_5_and_inside() {
        assert_eq!(contour_levels(0.0, 10.0), vec![0.05, 0.1, 0.2, 0.5, 1.0, 2.0, 5.0]);
        assert_eq!(contour_levels(30.0, 112.0), vec![50.0, 100.0]);
        let l = contour_levels(3.2, 47.0);
        assert_eq!(l, vec![5.0, 10.0, 20.0]);
        assert!(contour_levels(0.0, 0.0).is_empty());
        assert!(contour_levels(5.0, 5.0).is_empty());
    }
}
