//! PNG plots for reports, drawn with tiny-skia and the crate's bitmap font
//! ([`super::font`]).
//!
//! Three kinds:
//! - [`polar_diagram`]: the photometric polar diagram of one plane pair
//!   (C0–C180, C90–C270, ...), nadir down, as lighting engineers draw it;
//! - [`heatmap`]: a value over C × γ (e.g. the relative error of a
//!   reconstruction), viridis or a diverging blue–white–red map;
//! - [`scatter`]: cost versus error of several methods, with the Pareto front.
//!
//! All of them return PNG bytes, never panic on empty or non-finite input
//! (non-finite points are skipped; nothing to draw gives a plot that says
//! "no data") and label their axes with the caller's units. White
//! background, anti-aliased 1–2 px strokes, dark grey text, tick values on
//! the 1–2–5 × 10^k sequence.

use tiny_skia::{Color, FillRule, Paint, PathBuilder, Pixmap, PremultipliedColorU8, Stroke, StrokeDash, Transform};

use crate::error::Error;

use super::font;

/// How a [`Series`] is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SeriesStyle {
    /// Solid 2 px line.
    Line,
    /// Dashed 2 px line.
    Dashed,
    /// Measured points: small filled circles, not joined.
    Markers,
}

/// One curve or point set.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// Legend text.
    pub label: String,
    /// Data points (x, y); for [`polar_diagram`] (signed γ in degrees, value).
    pub points: Vec<(f64, f64)>,
    /// sRGB colour, e.g. from [`palette`].
    pub color: [u8; 3],
    /// Line, dashed line or markers.
    pub style: SeriesStyle,
}

/// One point of a [`scatter`] plot.
#[derive(Debug, Clone, PartialEq)]
pub struct ScatterPoint {
    /// Name drawn next to the point.
    pub label: String,
    /// Abscissa (e.g. time per sample in ns).
    pub x: f64,
    /// Ordinate (e.g. RMS error in % of I_max).
    pub y: f64,
    /// Whether the point is Pareto-optimal (highlighted, joined by the front).
    pub pareto: bool,
}

/// Default size of [`polar_diagram`].
pub const POLAR_SIZE: (u32, u32) = (800, 800);
/// Default size of [`heatmap`].
pub const HEATMAP_SIZE: (u32, u32) = (900, 500);
/// Default size of [`scatter`].
pub const SCATTER_SIZE: (u32, u32) = (800, 550);

const WHITE: [u8; 3] = [255, 255, 255];
const INK: [u8; 3] = [50, 50, 50];
const AXIS: [u8; 3] = [110, 110, 110];
const GRID: [u8; 3] = [222, 222, 222];
const NO_DATA: [u8; 3] = [238, 238, 238];
const PARETO: [u8; 3] = [214, 39, 40];
const OTHER: [u8; 3] = [70, 120, 180];

/// A distinct colour for series `k` (d3's category10, which reads well on
/// white); `k` wraps around after 10.
pub fn palette(k: usize) -> [u8; 3] {
    const P: [[u8; 3]; 10] = [
        [31, 119, 180],
        [255, 127, 14],
        [44, 160, 44],
        [214, 39, 40],
        [148, 103, 189],
        [140, 86, 75],
        [227, 119, 194],
        [127, 127, 127],
        [188, 189, 34],
        [23, 190, 207],
    ];
    P[k % P.len()]
}

/// The colour of `t` in [0, 1] (clamped; NaN gives the no-data grey) on the
/// heat map's colour map: viridis, or blue–white–red (RdBu, 0.5 = white)
/// when `diverging`.
pub fn colormap(t: f64, diverging: bool) -> [u8; 3] {
    const VIRIDIS: [[u8; 3]; 9] = [
        [68, 1, 84],
        [71, 44, 122],
        [59, 81, 139],
        [44, 113, 142],
        [33, 144, 141],
        [39, 173, 129],
        [92, 200, 99],
        [170, 220, 50],
        [253, 231, 37],
    ];
    const RDBU: [[u8; 3]; 9] = [
        [5, 48, 97],
        [33, 102, 172],
        [67, 147, 195],
        [146, 197, 222],
        [247, 247, 247],
        [244, 165, 130],
        [214, 96, 77],
        [178, 24, 43],
        [103, 0, 31],
    ];
    if t.is_nan() {
        return NO_DATA;
    }
    let stops = if diverging { &RDBU } else { &VIRIDIS };
    let x = t.clamp(0.0, 1.0) * 8.0;
    let k = (x.floor() as usize).min(7);
    let f = x - k as f64;
    let (a, b) = (stops[k], stops[k + 1]);
    [0, 1, 2].map(|i| (f64::from(a[i]) + f * (f64::from(b[i]) - f64::from(a[i]))).round() as u8)
}

/// `png` as a `data:image/png;base64,...` URI, for self-contained HTML.
pub fn png_data_uri(png: &[u8]) -> String {
    const B64: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut s = String::with_capacity(22 + png.len().div_ceil(3) * 4);
    s.push_str("data:image/png;base64,");
    for chunk in png.chunks(3) {
        let b = [chunk[0], *chunk.get(1).unwrap_or(&0), *chunk.get(2).unwrap_or(&0)];
        let n = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for k in 0..4 {
            if k <= chunk.len() {
                s.push(B64[((n >> (18 - 6 * k)) & 63) as usize] as char);
            } else {
                s.push('=');
            }
        }
    }
    s
}

// ---------------------------------------------------------------------------
// Numbers and ticks

/// A step on the 1–2–5 × 10^k sequence giving about `target` intervals over `range`.
fn nice_step(range: f64, target: usize) -> f64 {
    let raw = range / target.max(1) as f64;
    if !(raw.is_finite() && raw > 0.0) {
        return 1.0;
    }
    let mag = 10f64.powf(raw.log10().floor());
    let f = raw / mag;
    // Tolerance: 1.2 / 6 must give 0.2, not 0.5.
    let m = if f <= 1.0 + 1e-9 {
        1.0
    } else if f <= 2.0 + 1e-9 {
        2.0
    } else if f <= 5.0 + 1e-9 {
        5.0
    } else {
        10.0
    };
    m * mag
}

/// Multiples of `step` in [lo, hi] (with a little tolerance).
fn ticks_in(lo: f64, hi: f64, step: f64) -> Vec<f64> {
    let eps = step * 1e-6;
    let first = (lo / step - 1e-6).ceil() as i64;
    let last = (hi / step + 1e-6).floor() as i64;
    if last < first || last - first > 1000 {
        return Vec::new();
    }
    (first..=last)
        .map(|k| k as f64 * step)
        .filter(|v| *v >= lo - eps && *v <= hi + eps)
        .collect()
}

/// A tick value, with as many decimals as `step` needs; exponent notation for
/// very large or very small steps ("2e6", "5e-7").
fn fmt_tick(v: f64, step: f64) -> String {
    if v.abs() < step.abs() * 1e-6 || v == 0.0 {
        return "0".into();
    }
    let sl = step.abs().log10().floor();
    if step.abs() >= 1e5 || step.abs() < 1e-3 {
        let e = v.abs().log10().floor();
        let m = v / 10f64.powf(e);
        let d = ((e - sl).max(0.0) as usize).min(3);
        let mut ms = format!("{m:.d$}");
        if ms.contains('.') {
            ms = ms.trim_end_matches('0').trim_end_matches('.').to_string();
        }
        return format!("{ms}e{}", e as i64);
    }
    let d = (-sl).max(0.0) as usize;
    format!("{v:.d$}")
}

// ---------------------------------------------------------------------------
// Drawing helpers

#[derive(Clone, Copy, PartialEq, Eq)]
enum Align {
    Left,
    Center,
    Right,
}

struct Canvas {
    pm: Pixmap,
}

fn paint(rgb: [u8; 3]) -> Paint<'static> {
    let mut p = Paint::default();
    p.set_color_rgba8(rgb[0], rgb[1], rgb[2], 255);
    p.anti_alias = true;
    p
}

fn finite2(p: &(f64, f64)) -> bool {
    p.0.is_finite() && p.1.is_finite()
}

impl Canvas {
    fn new(w: u32, h: u32, what: &str) -> Result<Self, Error> {
        if !(120..=8192).contains(&w) || !(120..=8192).contains(&h) {
            return Err(Error::Unsupported(format!(
                "{what} plot size {w} x {h} px: each side must be 120..=8192"
            )));
        }
        let mut pm = Pixmap::new(w, h).ok_or_else(|| Error::Unsupported(format!("{what} plot size {w} x {h}")))?;
        pm.fill(Color::WHITE);
        Ok(Self { pm })
    }

    fn w(&self) -> f32 {
        self.pm.width() as f32
    }

    fn h(&self) -> f32 {
        self.pm.height() as f32
    }

    fn png(&self) -> Result<Vec<u8>, Error> {
        self.pm
            .encode_png()
            .map_err(|e| Error::Unsupported(format!("cannot encode PNG: {e}")))
    }

    /// Stroke a polyline (at least two points).
    fn polyline(&mut self, pts: &[(f32, f32)], rgb: [u8; 3], width: f32, dashed: bool) {
        if pts.len() < 2 {
            return;
        }
        let mut pb = PathBuilder::new();
        pb.move_to(pts[0].0, pts[0].1);
        for p in &pts[1..] {
            pb.line_to(p.0, p.1);
        }
        let Some(path) = pb.finish() else { return };
        let stroke = Stroke {
            width,
            dash: if dashed {
                StrokeDash::new(vec![9.0, 6.0], 0.0)
            } else {
                None
            },
            line_join: tiny_skia::LineJoin::Round,
            line_cap: tiny_skia::LineCap::Butt,
            ..Stroke::default()
        };
        self.pm
            .stroke_path(&path, &paint(rgb), &stroke, Transform::identity(), None);
    }

    fn line(&mut self, x0: f32, y0: f32, x1: f32, y1: f32, rgb: [u8; 3], width: f32) {
        self.polyline(&[(x0, y0), (x1, y1)], rgb, width, false);
    }

    fn circle(&mut self, x: f32, y: f32, r: f32, fill: [u8; 3], outline: Option<[u8; 3]>) {
        let Some(path) = PathBuilder::from_circle(x, y, r) else {
            return;
        };
        self.pm
            .fill_path(&path, &paint(fill), FillRule::Winding, Transform::identity(), None);
        if let Some(o) = outline {
            let stroke = Stroke {
                width: 1.2,
                ..Stroke::default()
            };
            self.pm
                .stroke_path(&path, &paint(o), &stroke, Transform::identity(), None);
        }
    }

    fn ring(&mut self, x: f32, y: f32, r: f32, rgb: [u8; 3], width: f32) {
        let Some(path) = PathBuilder::from_circle(x, y, r) else {
            return;
        };
        let stroke = Stroke {
            width,
            ..Stroke::default()
        };
        self.pm
            .stroke_path(&path, &paint(rgb), &stroke, Transform::identity(), None);
    }

    /// Opaque pixel-aligned rectangle [x0, x1) × [y0, y1).
    fn rect(&mut self, x0: i32, y0: i32, x1: i32, y1: i32, rgb: [u8; 3]) {
        let (w, h) = (self.pm.width() as i32, self.pm.height() as i32);
        let (x0, x1, y0, y1) = (x0.clamp(0, w), x1.clamp(0, w), y0.clamp(0, h), y1.clamp(0, h));
        if x1 <= x0 || y1 <= y0 {
            return;
        }
        let c =
            PremultipliedColorU8::from_rgba(rgb[0], rgb[1], rgb[2], 255).unwrap_or(PremultipliedColorU8::TRANSPARENT);
        let px = self.pm.pixels_mut();
        for y in y0..y1 {
            let row = (y * w) as usize;
            px[row + x0 as usize..row + x1 as usize].fill(c);
        }
    }

    /// 1 px rectangle outline, crisp.
    fn frame(&mut self, x0: f32, y0: f32, x1: f32, y1: f32, rgb: [u8; 3]) {
        let (x0, y0, x1, y1) = (x0.round() + 0.5, y0.round() + 0.5, x1.round() - 0.5, y1.round() - 0.5);
        self.polyline(&[(x0, y0), (x1, y0), (x1, y1), (x0, y1), (x0, y0)], rgb, 1.0, false);
    }

    /// Text anchored horizontally by `align` at x and vertically centred on
    /// `yc`; with a white box behind it when `bg`. Returns its box.
    #[allow(clippy::too_many_arguments)]
    fn text(&mut self, x: f32, yc: f32, s: &str, scale: u32, align: Align, rgb: [u8; 3], bg: bool) -> [f32; 4] {
        let tw = font::text_width(s, scale) as f32;
        let th = font::text_height(scale) as f32;
        let x0 = match align {
            Align::Left => x,
            Align::Center => x - tw / 2.0,
            Align::Right => x - tw,
        }
        .round()
        .min(self.w() - tw - 2.0)
        .max(2.0);
        let y0 = (yc - th / 2.0).round();
        if bg {
            let p = scale as i32 + 1;
            self.rect(
                x0 as i32 - p,
                y0 as i32 - p,
                (x0 + tw) as i32 + p,
                (y0 + th) as i32 + p,
                WHITE,
            );
        }
        font::draw_text(&mut self.pm, x0 as i32, y0 as i32, s, scale, rgb);
        [x0, y0, x0 + tw, y0 + th]
    }

    /// Text rotated to read bottom to top, centred on (xc, yc).
    fn text_vertical(&mut self, xc: f32, yc: f32, s: &str, scale: u32, rgb: [u8; 3]) {
        let tw = font::text_width(s, scale) as f32;
        let th = font::text_height(scale) as f32;
        let x0 = (xc - th / 2.0).round() as i32;
        let y0 = (yc + tw / 2.0).round() as i32;
        font::draw_text_vertical(&mut self.pm, x0, y0, s, scale, rgb);
    }

    /// The title, centred at the top (scale 2, shortened to fit).
    fn title(&mut self, title: &str) {
        let max_chars = ((self.w() - 20.0) / 12.0).max(4.0) as usize;
        let t: String = if title.chars().count() > max_chars {
            title.chars().take(max_chars - 3).chain("...".chars()).collect()
        } else {
            title.to_string()
        };
        let w = self.w();
        // Bold: the same text twice, one pixel apart.
        self.text(w / 2.0, 18.0, &t, 2, Align::Center, INK, false);
        self.text(w / 2.0 + 1.0, 18.0, &t, 2, Align::Center, INK, false);
    }
}

/// Legend entries laid out left to right from (x, y), wrapping at `max_x`;
/// returns the height used. `dry` measures without drawing.
fn legend(cv: &mut Canvas, series: &[Series], x: f32, y: f32, max_x: f32, dry: bool) -> f32 {
    const ROW: f32 = 24.0;
    const SWATCH: f32 = 30.0;
    if series.is_empty() {
        return 0.0;
    }
    let (mut cx, mut cy) = (x, y + ROW / 2.0);
    for s in series {
        let item = SWATCH + 8.0 + font::text_width(&s.label, 2) as f32 + 24.0;
        if cx > x && cx + item - 24.0 > max_x {
            cx = x;
            cy += ROW;
        }
        if !dry {
            match s.style {
                SeriesStyle::Line | SeriesStyle::Dashed => {
                    cv.line(cx, cy, cx + SWATCH, cy, s.color, 2.0);
                    if s.style == SeriesStyle::Dashed {
                        // Punch gaps so the swatch reads as dashed.
                        cv.rect(
                            (cx + 9.0) as i32,
                            (cy - 2.0) as i32,
                            (cx + 14.0) as i32,
                            (cy + 3.0) as i32,
                            WHITE,
                        );
                        cv.rect(
                            (cx + 23.0) as i32,
                            (cy - 2.0) as i32,
                            (cx + 28.0) as i32,
                            (cy + 3.0) as i32,
                            WHITE,
                        );
                    }
                }
                SeriesStyle::Markers => {
                    for k in 0..3 {
                        cv.circle(cx + 5.0 + 10.0 * k as f32, cy, 3.0, s.color, None);
                    }
                }
            }
            cv.text(cx + SWATCH + 8.0, cy, &s.label, 2, Align::Left, INK, false);
        }
        cx += item;
    }
    cy + ROW / 2.0 - y
}

// ---------------------------------------------------------------------------
// Polar diagram

/// The smallest 1–2–5 step that covers `vmax` (> 0) with at most 5 rings.
fn ring_step(vmax: f64) -> f64 {
    let mut step = nice_step(vmax, 10);
    while (vmax / step - 1e-9).ceil() > 5.0 {
        step = nice_step(step * 1.01, 1);
    }
    step
}

/// Photometric polar diagram of one plane pair (800 × 800 px); see
/// [`polar_diagram_sized`].
///
/// # Errors
/// [`Error::Unsupported`] if PNG encoding fails.
pub fn polar_diagram(title: &str, left: &str, right: &str, unit: &str, series: &[Series]) -> Result<Vec<u8>, Error> {
    polar_diagram_sized(POLAR_SIZE.0, POLAR_SIZE.1, title, left, right, unit, series)
}

/// Photometric polar diagram of one plane pair, e.g. C0–C180, `w` × `h` px.
///
/// Points are (signed γ in degrees, value): positive γ on the `right`
/// half-plane (e.g. C0), negative on the `left` one (C180). Nadir (γ = 0)
/// points down, zenith up. Lines are interpolated in polar coordinates
/// (1° steps) after sorting each series by γ; negative values are drawn at
/// the centre; non-finite points are skipped. Marker series are drawn under
/// the curves and thinned to one marker per 12 px (the legend then says
/// "(k of n shown)"), so that dense measurements do not hide the curves.
///
/// # Errors
/// [`Error::Unsupported`] for a size outside 120..=8192 px or if encoding fails.
pub fn polar_diagram_sized(
    w: u32,
    h: u32,
    title: &str,
    left: &str,
    right: &str,
    unit: &str,
    series: &[Series],
) -> Result<Vec<u8>, Error> {
    let mut cv = Canvas::new(w, h, "polar")?;
    let (wf, hf) = (cv.w(), cv.h());
    cv.title(title);

    // Dense measured points (e.g. 361 gamma angles) would hide every curve:
    // markers are thinned to one per MARKER_GAP px of the diagram and drawn
    // under the curves; the legend says how many are shown.
    let mut shown_markers: Vec<Vec<(f64, f64)>> = Vec::with_capacity(series.len());
    let mut labels: Vec<Series> = series.to_vec();
    // Measure the legend with the longest marker labels it may get.
    let widest: Vec<Series> = series
        .iter()
        .map(|s| {
            let mut s = s.clone();
            if s.style == SeriesStyle::Markers {
                let n = s.points.len();
                s.label = format!("{} ({n} of {n} shown)", s.label);
            }
            s
        })
        .collect();
    let legend_h = legend(&mut cv, &widest, 20.0, 0.0, wf - 20.0, true);
    let top = 40.0;
    let bottom = hf - legend_h - 14.0;
    let side = 20.0 + font::text_width(left, 2).max(font::text_width(right, 2)).max(48) as f32;
    let radius = ((wf - 2.0 * side) / 2.0).min((bottom - top) / 2.0 - 26.0).max(20.0);
    let (cx, cy) = (wf / 2.0, top + (bottom - top) / 2.0);

    // Scale: the largest finite value, rounded up to a ring.
    let vmax = series
        .iter()
        .flat_map(|s| s.points.iter())
        .filter(|p| finite2(p))
        .map(|p| p.1)
        .fold(0.0f64, f64::max);
    let any = series.iter().any(|s| s.points.iter().any(finite2));
    let top_v = if vmax > 0.0 { vmax } else { 1.0 };
    let step = ring_step(top_v);
    let n_rings = ((top_v / step) - 1e-9).ceil().max(1.0) as usize;
    let rmax = step * n_rings as f64;
    let to_xy = |g: f64, v: f64| -> (f32, f32) {
        let r = (v.max(0.0) / rmax) * f64::from(radius);
        let a = g.to_radians();
        (cx + (r * a.sin()) as f32, cy + (r * a.cos()) as f32)
    };

    // Grid: radial lines every 30°, rings at each step.
    for k in 0..12 {
        let (x, y) = to_xy(k as f64 * 30.0, rmax);
        cv.line(cx, cy, x, y, GRID, 1.0);
    }
    for k in 1..=n_rings {
        let r = radius * k as f32 / n_rings as f32;
        cv.ring(cx, cy, r, if k == n_rings { AXIS } else { GRID }, 1.0);
    }
    // Angle labels outside the circle, 0..180 on both halves.
    for k in -5..=6 {
        let g = k as f64 * 30.0;
        let a = g.to_radians();
        let off = f64::from(radius) + 18.0;
        let (x, y) = (cx + (off * a.sin()) as f32, cy + (off * a.cos()) as f32);
        let s = format!("{}°", (k * 30i32).abs());
        let ww = font::text_width(&s, 2) as f32;
        // Push the label outwards by half its width on the sides.
        let x = x + (a.sin() as f32) * (ww / 2.0 - 4.0).max(0.0);
        cv.text(x, y, &s, 2, Align::Center, INK, false);
    }
    // Half-plane names at the sides, above the 90° labels.
    cv.text(12.0, cy - 40.0, left, 2, Align::Left, INK, false);
    cv.text(wf - 12.0, cy - 40.0, right, 2, Align::Right, INK, false);
    // Unit in the top-left corner.
    cv.text(12.0, top + 4.0, unit, 2, Align::Left, INK, false);
    // Ring labels along the zenith ray, on white.
    for k in 1..=n_rings {
        let v = step * k as f64;
        let (_, y) = to_xy(180.0, v);
        cv.text(cx + 5.0, y + 11.0, &fmt_tick(v, step), 2, Align::Left, AXIS, true);
    }
    // Axis cross through the centre, a little darker.
    cv.line(cx - radius, cy, cx + radius, cy, AXIS, 1.0);
    cv.line(cx, cy - radius, cx, cy + radius, AXIS, 1.0);

    for (s, lab) in series.iter().zip(labels.iter_mut()) {
        let mut pts: Vec<(f64, f64)> = s.points.iter().copied().filter(finite2).collect();
        pts.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut kept: Vec<(f64, f64)> = Vec::new();
        if s.style == SeriesStyle::Markers {
            let mut last: Option<(f32, f32)> = None;
            for &(g, v) in &pts {
                let (x, y) = to_xy(g, v);
                if last.is_none_or(|(lx, ly)| (x - lx).hypot(y - ly) >= MARKER_GAP) {
                    kept.push((g, v));
                    last = Some((x, y));
                }
            }
            if kept.len() < pts.len() {
                lab.label = format!("{} ({} of {} shown)", s.label, kept.len(), pts.len());
            }
        }
        shown_markers.push(kept);
    }
    for (s, kept) in series.iter().zip(&shown_markers) {
        if s.style == SeriesStyle::Markers {
            for &(g, v) in kept {
                let (x, y) = to_xy(g, v);
                cv.circle(x, y, 3.0, s.color, None);
            }
        }
    }
    for s in series {
        let mut pts: Vec<(f64, f64)> = s.points.iter().copied().filter(finite2).collect();
        pts.sort_by(|a, b| a.0.total_cmp(&b.0));
        match s.style {
            SeriesStyle::Markers => {}
            SeriesStyle::Line | SeriesStyle::Dashed => {
                if pts.len() == 1 {
                    let (x, y) = to_xy(pts[0].0, pts[0].1);
                    cv.circle(x, y, 3.0, s.color, None);
                    continue;
                }
                let mut line = Vec::with_capacity(pts.len() * 4);
                for (k, &(g, v)) in pts.iter().enumerate() {
                    if k > 0 {
                        let (g0, v0) = pts[k - 1];
                        let n = ((g - g0).abs().ceil() as usize).clamp(1, 720);
                        for j in 1..n {
                            let f = j as f64 / n as f64;
                            line.push(to_xy(g0 + f * (g - g0), v0 + f * (v - v0)));
                        }
                    }
                    line.push(to_xy(g, v));
                }
                cv.polyline(&line, s.color, 2.0, s.style == SeriesStyle::Dashed);
            }
        }
    }
    if !any {
        cv.text(cx, cy, "no data", 3, Align::Center, INK, true);
    }
    legend(&mut cv, &labels, 20.0, hf - legend_h - 8.0, wf - 20.0, false);
    cv.png()
}

/// Smallest distance (px) between two measured markers drawn on a polar diagram.
const MARKER_GAP: f32 = 12.0;

// ---------------------------------------------------------------------------
// Heat map

/// Cell edges of sorted-or-not centres `c` over the axis [lo, hi]: cell k
/// spans (edges[k].0, edges[k].1), between midpoints to its neighbours (by
/// value); an outer cell reaches the axis end when that is at most one
/// spacing away (no sliver of grey at C = 360 for C = 0, 15, ..., 345), half
/// a spacing otherwise.
/// Non-finite centres get an empty cell.
fn cell_edges(c: &[f64], lo: f64, hi: f64) -> Vec<(f64, f64)> {
    let mut idx: Vec<usize> = (0..c.len()).filter(|&k| c[k].is_finite()).collect();
    idx.sort_by(|&a, &b| c[a].total_cmp(&c[b]));
    let mut out = vec![(f64::NAN, f64::NAN); c.len()];
    let n = idx.len();
    for (j, &k) in idx.iter().enumerate() {
        let a = if j > 0 {
            0.5 * (c[idx[j - 1]] + c[k])
        } else if n > 1 {
            let d = c[idx[1]] - c[k];
            if c[k] - lo <= d * (1.0 + 1e-9) {
                lo
            } else {
                c[k] - 0.5 * d
            }
        } else {
            lo
        };
        let b = if j + 1 < n {
            0.5 * (c[k] + c[idx[j + 1]])
        } else if n > 1 {
            let d = c[k] - c[idx[j - 1]];
            if hi - c[k] <= d * (1.0 + 1e-9) {
                hi
            } else {
                c[k] + 0.5 * d
            }
        } else {
            hi
        };
        out[k] = (a, b);
    }
    out
}

/// Degree-friendly tick step for an axis span.
fn degree_step(span: f64, max_ticks: usize) -> f64 {
    for s in [1.0, 2.0, 5.0, 10.0, 15.0, 30.0, 45.0, 90.0, 180.0] {
        if span / s <= max_ticks as f64 {
            return s;
        }
    }
    nice_step(span, max_ticks)
}

/// Heat map over C × γ (900 × 500 px); see [`heatmap_sized`].
///
/// # Errors
/// [`Error::Unsupported`] if `values.len() != xs.len() * ys.len()` or PNG
/// encoding fails.
pub fn heatmap(
    title: &str,
    xs: &[f64],
    ys: &[f64],
    values: &[f64],
    unit: &str,
    diverging: bool,
) -> Result<Vec<u8>, Error> {
    heatmap_sized(HEATMAP_SIZE.0, HEATMAP_SIZE.1, title, xs, ys, values, unit, diverging)
}

/// Heat map over C (x, degrees, axis 0–360) × γ (y, degrees, axis 0–180, 0 at
/// the top), `w` × `h` px: `values[iy * xs.len() + ix]` at centres
/// `xs[ix]`, `ys[iy]` (any spacing; cells reach halfway to their neighbours).
/// The colour range is the finite values' min..max (viridis), or
/// ±max |value| around 0 when `diverging` (blue–white–red). NaN cells stay
/// grey. The axes widen to take in centres outside 0–360 / 0–180.
///
/// # Errors
/// [`Error::Unsupported`] for a size outside 120..=8192 px, if
/// `values.len() != xs.len() * ys.len()`, or if encoding fails.
#[allow(clippy::too_many_arguments)]
pub fn heatmap_sized(
    w: u32,
    h: u32,
    title: &str,
    xs: &[f64],
    ys: &[f64],
    values: &[f64],
    unit: &str,
    diverging: bool,
) -> Result<Vec<u8>, Error> {
    if values.len() != xs.len() * ys.len() {
        return Err(Error::Unsupported(format!(
            "heat map: {} values for a {} x {} grid",
            values.len(),
            xs.len(),
            ys.len()
        )));
    }
    let mut cv = Canvas::new(w, h, "heat map")?;
    let (wf, hf) = (cv.w(), cv.h());
    cv.title(title);
    let (left, top, right, bottom) = (92.0f32, 56.0f32, wf - 150.0, hf - 62.0);
    let (pw, ph) = (right - left, bottom - top);

    let fin = |v: &&f64| v.is_finite();
    let x0 = xs.iter().filter(fin).fold(0.0f64, |a, &b| a.min(b));
    let x1 = xs.iter().filter(fin).fold(360.0f64, |a, &b| a.max(b));
    let y0 = ys.iter().filter(fin).fold(0.0f64, |a, &b| a.min(b));
    let y1 = ys.iter().filter(fin).fold(180.0f64, |a, &b| a.max(b));
    let px = |x: f64| left + ((x - x0) / (x1 - x0)) as f32 * pw;
    let py = |y: f64| top + ((y - y0) / (y1 - y0)) as f32 * ph;

    // Colour range.
    let (mut lo, mut hi) = values
        .iter()
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| (a.min(v), b.max(v)));
    let any = lo <= hi;
    if diverging {
        let m = if any { lo.abs().max(hi.abs()) } else { 0.0 };
        let m = if m > 0.0 { m } else { 1.0 };
        (lo, hi) = (-m, m);
    } else if !any {
        (lo, hi) = (0.0, 1.0);
    } else if hi <= lo {
        let d = if lo == 0.0 { 1.0 } else { lo.abs() * 0.1 };
        (lo, hi) = if lo == 0.0 { (0.0, 1.0) } else { (lo - d, hi + d) };
    }
    let color_of = |v: f64| {
        if v.is_finite() {
            colormap((v - lo) / (hi - lo), diverging)
        } else {
            NO_DATA
        }
    };

    // Cells.
    cv.rect(left as i32, top as i32, right as i32, bottom as i32, NO_DATA);
    let ex = cell_edges(xs, x0, x1);
    let ey = cell_edges(ys, y0, y1);
    for (iy, &(ya, yb)) in ey.iter().enumerate() {
        if !(ya.is_finite() && yb.is_finite()) {
            continue;
        }
        let (r0, r1) = (py(ya).round() as i32, py(yb).round() as i32);
        for (ix, &(xa, xb)) in ex.iter().enumerate() {
            if !(xa.is_finite() && xb.is_finite()) {
                continue;
            }
            let c = color_of(values[iy * xs.len() + ix]);
            cv.rect(px(xa).round() as i32, r0, px(xb).round() as i32, r1, c);
        }
    }
    if !any {
        cv.text(left + pw / 2.0, top + ph / 2.0, "no data", 3, Align::Center, INK, true);
    }
    cv.frame(left - 1.0, top - 1.0, right + 1.0, bottom + 1.0, AXIS);

    // Axes: ticks in degrees.
    let sx = degree_step(x1 - x0, 8);
    for t in ticks_in(x0, x1, sx) {
        let x = px(t).round() + 0.5;
        cv.line(x, bottom + 1.0, x, bottom + 6.0, AXIS, 1.0);
        cv.text(
            x,
            bottom + 16.0,
            &format!("{}°", fmt_tick(t, sx)),
            2,
            Align::Center,
            INK,
            false,
        );
    }
    let sy = degree_step(y1 - y0, 6);
    for t in ticks_in(y0, y1, sy) {
        let y = py(t).round() + 0.5;
        cv.line(left - 6.0, y, left - 1.0, y, AXIS, 1.0);
        cv.text(
            left - 10.0,
            y,
            &format!("{}°", fmt_tick(t, sy)),
            2,
            Align::Right,
            INK,
            false,
        );
    }
    cv.text(left + pw / 2.0, hf - 16.0, "C (°)", 2, Align::Center, INK, false);
    cv.text_vertical(18.0, top + ph / 2.0, "gamma (°), 0 = nadir", 2, INK);

    // Colour bar: top = hi, bottom = lo.
    let (bx0, bx1) = (right + 26.0, right + 48.0);
    for r in top as i32..bottom as i32 {
        let t = 1.0 - (f64::from(r) + 0.5 - f64::from(top)) / f64::from(ph);
        cv.rect(bx0 as i32, r, bx1 as i32, r + 1, colormap(t, diverging));
    }
    cv.frame(bx0 - 1.0, top - 1.0, bx1 + 1.0, bottom + 1.0, AXIS);
    let sb = nice_step(hi - lo, 5);
    for t in ticks_in(lo, hi, sb) {
        let y = (top + ((hi - t) / (hi - lo)) as f32 * ph).round() + 0.5;
        cv.line(bx1 + 1.0, y, bx1 + 6.0, y, AXIS, 1.0);
        cv.text(bx1 + 9.0, y, &fmt_tick(t, sb), 2, Align::Left, INK, false);
    }
    let uw = font::text_width(unit, 2) as f32;
    let ux = ((bx0 + bx1) / 2.0).min(wf - 8.0 - uw / 2.0);
    cv.text(ux, top - 18.0, unit, 2, Align::Center, INK, false);
    cv.png()
}

// ---------------------------------------------------------------------------
// Scatter

/// Cost–error scatter plot (800 × 550 px); see [`scatter_sized`].
///
/// # Errors
/// [`Error::Unsupported`] if PNG encoding fails.
pub fn scatter(
    title: &str,
    x_label: &str,
    y_label: &str,
    points: &[ScatterPoint],
    log_x: bool,
) -> Result<Vec<u8>, Error> {
    scatter_sized(SCATTER_SIZE.0, SCATTER_SIZE.1, title, x_label, y_label, points, log_x)
}

/// Ratio of the largest to the smallest positive ordinate from which
/// [`scatter_sized`] draws its y axis logarithmic.
const LOG_Y_RATIO: f64 = 20.0;

/// Axis mapping of the scatter plot.
struct Axis {
    lo: f64,
    hi: f64,
    log: bool,
}

impl Axis {
    fn t(&self, v: f64) -> f64 {
        if self.log {
            (v.log10() - self.lo) / (self.hi - self.lo)
        } else {
            (v - self.lo) / (self.hi - self.lo)
        }
    }
    /// (value, label or "" for a minor tick).
    fn ticks(&self) -> Vec<(f64, String)> {
        if !self.log {
            let s = nice_step(self.hi - self.lo, 6);
            return ticks_in(self.lo, self.hi, s)
                .into_iter()
                .map(|t| (t, fmt_tick(t, s)))
                .collect();
        }
        let (a, b) = (self.lo.floor() as i32, self.hi.ceil() as i32);
        let decades = b - a;
        let mut out = Vec::new();
        for e in a..=b {
            for m in 1..10 {
                let v = f64::from(m) * 10f64.powi(e);
                let lv = v.log10();
                if lv < self.lo - 1e-9 || lv > self.hi + 1e-9 {
                    continue;
                }
                // Enough labels on a short log axis: every mantissa within
                // about a decade, 1-2-5 over two, powers of ten beyond.
                let span = self.hi - self.lo;
                let labelled = m == 1 || (span <= 1.2 && m != 7 && m != 9) || (decades <= 2 && (m == 2 || m == 5));
                let text = if !labelled {
                    String::new()
                } else if (-3..5).contains(&e) {
                    fmt_tick(v, 10f64.powi(e.min(0)))
                } else {
                    format!("{m}e{e}")
                };
                out.push((v, text));
            }
        }
        out
    }
}

/// Cost–error scatter, `w` × `h` px: x = e.g. time per sample (log axis when
/// `log_x`; points with x ≤ 0 are then skipped), y = e.g. RMS error. Every
/// point is named; Pareto-optimal points are drawn larger in red and joined
/// by the Pareto front, a staircase through them in x order (lower is better
/// on both axes). The y axis starts at 0 when all y are non-negative, and is
/// logarithmic when all y are positive and span a ratio of 20 or more.
/// Names are placed where they overlap no other name, point or front.
///
/// # Errors
/// [`Error::Unsupported`] for a size outside 120..=8192 px or if encoding fails.
pub fn scatter_sized(
    w: u32,
    h: u32,
    title: &str,
    x_label: &str,
    y_label: &str,
    points: &[ScatterPoint],
    log_x: bool,
) -> Result<Vec<u8>, Error> {
    let mut cv = Canvas::new(w, h, "scatter")?;
    let (wf, hf) = (cv.w(), cv.h());
    cv.title(title);
    let (top, right, bottom) = (64.0f32, wf - 30.0, hf - 64.0);

    let pts: Vec<&ScatterPoint> = points
        .iter()
        .filter(|p| p.x.is_finite() && p.y.is_finite() && (!log_x || p.x > 0.0))
        .collect();

    // Ranges, padded so that no point sits on the frame.
    let xv = |p: &ScatterPoint| if log_x { p.x.log10() } else { p.x };
    let (mut xa, mut xb) = pts.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
        (a.min(xv(p)), b.max(xv(p)))
    });
    if pts.is_empty() {
        (xa, xb) = if log_x { (0.0, 2.0) } else { (0.0, 1.0) };
    }
    if xb - xa < 1e-12 * xa.abs().max(1e-300) || xb <= xa {
        let d = if log_x { 0.5 } else { xa.abs().max(1e-300) * 0.5 };
        let d = if d > 0.0 && d.is_finite() { d } else { 1.0 };
        (xa, xb) = (xa - d, xb + d);
    }
    let pad = (xb - xa) * 0.08;
    let (xa, xb) = (xa - pad, xb + pad);
    let x_axis = if log_x {
        Axis {
            lo: xa,
            hi: xb,
            log: true,
        }
    } else {
        let s = nice_step(xb - xa, 6);
        Axis {
            lo: (xa / s).floor() * s,
            hi: (xb / s).ceil() * s,
            log: false,
        }
    };
    let (mut ya, mut yb) = pts
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| (a.min(p.y), b.max(p.y)));
    if pts.is_empty() {
        (ya, yb) = (0.0, 1.0);
    }
    // Errors spanning more than LOG_Y_RATIO (a fitted model next to filters)
    // would sit on the floor of a linear axis: log axis then.
    let log_y = ya > 0.0 && yb / ya >= LOG_Y_RATIO;
    let y_axis = if log_y {
        let (la, lb) = (ya.log10(), yb.log10());
        let pad = (lb - la) * 0.08;
        Axis {
            lo: la - pad,
            hi: lb + pad,
            log: true,
        }
    } else {
        if ya >= 0.0 {
            ya = 0.0;
        }
        if yb <= ya {
            yb = if ya == 0.0 { 1.0 } else { ya + ya.abs() };
        }
        let yb = yb + (yb - ya) * 0.08;
        let s = nice_step(yb - ya, 6);
        Axis {
            lo: (ya / s).floor() * s,
            hi: (yb / s).ceil() * s,
            log: false,
        }
    };
    // Left margin: the y label, then the widest tick label.
    let y_ticks = y_axis.ticks();
    let tick_w = y_ticks.iter().map(|(_, l)| font::text_width(l, 2)).max().unwrap_or(0) as f32;
    let left = (30.0 + 12.0 + tick_w + 12.0).max(72.0).min(wf / 3.0);
    let (pw, ph) = (right - left, bottom - top);
    let px = |x: f64| left + x_axis.t(x) as f32 * pw;
    let py = |y: f64| bottom - y_axis.t(y) as f32 * ph;

    // Grid and ticks.
    for (t, lab) in x_axis.ticks() {
        let x = px(t).round() + 0.5;
        let major = !lab.is_empty();
        cv.line(x, top, x, bottom, if major { GRID } else { [240, 240, 240] }, 1.0);
        cv.line(x, bottom, x, bottom + if major { 6.0 } else { 3.0 }, AXIS, 1.0);
        if major {
            cv.text(x, bottom + 16.0, &lab, 2, Align::Center, INK, false);
        }
    }
    for (t, lab) in y_ticks {
        let y = py(t).round() + 0.5;
        let major = !lab.is_empty();
        cv.line(left, y, right, y, if major { GRID } else { [240, 240, 240] }, 1.0);
        cv.line(left - if major { 6.0 } else { 3.0 }, y, left, y, AXIS, 1.0);
        if major {
            cv.text(left - 10.0, y, &lab, 2, Align::Right, INK, false);
        }
    }
    cv.frame(left, top, right + 1.0, bottom + 1.0, AXIS);
    cv.text(left + pw / 2.0, hf - 16.0, x_label, 2, Align::Center, INK, false);
    cv.text_vertical(16.0, top + ph / 2.0, y_label, 2, INK);

    // Legend above the plot, right-aligned.
    let lx = right - font::text_width("Pareto front", 2) as f32;
    cv.text(lx, top - 16.0, "Pareto front", 2, Align::Left, INK, false);
    cv.line(lx - 46.0, top - 16.0, lx - 10.0, top - 16.0, PARETO, 2.0);
    cv.circle(lx - 28.0, top - 16.0, 5.0, PARETO, Some([120, 20, 20]));
    let lx2 = lx - 70.0 - font::text_width("other", 2) as f32;
    cv.text(lx2, top - 16.0, "other", 2, Align::Left, INK, false);
    cv.circle(lx2 - 12.0, top - 16.0, 4.0, OTHER, None);

    // Pareto front: staircase through the Pareto points in x order.
    let mut front: Vec<(f64, f64)> = pts.iter().filter(|p| p.pareto).map(|p| (p.x, p.y)).collect();
    front.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut stair = Vec::new();
    for (k, &(x, y)) in front.iter().enumerate() {
        if k > 0 {
            stair.push((px(x), py(front[k - 1].1)));
        }
        stair.push((px(x), py(y)));
    }
    cv.polyline(&stair, PARETO, 2.0, false);
    let stair_boxes = stair.windows(2).map(|s| {
        [
            s[0].0.min(s[1].0) - 1.0,
            s[0].1.min(s[1].1) - 1.0,
            s[0].0.max(s[1].0) + 1.0,
            s[0].1.max(s[1].1) + 1.0,
        ]
    });

    // Points: others first, Pareto on top.
    let scale = if pts.len() <= 12 { 2 } else { 1 };
    let mut order: Vec<&&ScatterPoint> = pts.iter().collect();
    order.sort_by_key(|p| p.pareto);
    let mut boxes: Vec<[f32; 4]> = pts
        .iter()
        .map(|p| {
            let (x, y) = (px(p.x), py(p.y));
            [x - 6.0, y - 6.0, x + 6.0, y + 6.0]
        })
        .chain(stair_boxes)
        .collect();
    for p in &order {
        let (x, y) = (px(p.x), py(p.y));
        if p.pareto {
            cv.circle(x, y, 6.0, PARETO, Some([120, 20, 20]));
        } else {
            cv.circle(x, y, 4.5, OTHER, None);
        }
    }
    // Labels: first free spot among right, left, above, below.
    let th = font::text_height(scale) as f32;
    for p in &order {
        let (x, y) = (px(p.x), py(p.y));
        let tw = font::text_width(&p.label, scale) as f32;
        // Right, left, above, below; then right and left shifted up or down
        // by one and two text rows, so that neighbours' names never overlap.
        let mut cands = vec![
            (
                x + 9.0,
                y,
                Align::Left,
                [x + 9.0, y - th / 2.0, x + 9.0 + tw, y + th / 2.0],
            ),
            (
                x - 9.0,
                y,
                Align::Right,
                [x - 9.0 - tw, y - th / 2.0, x - 9.0, y + th / 2.0],
            ),
            (
                x,
                y - 9.0 - th / 2.0,
                Align::Center,
                [x - tw / 2.0, y - 9.0 - th, x + tw / 2.0, y - 9.0],
            ),
            (
                x,
                y + 9.0 + th / 2.0,
                Align::Center,
                [x - tw / 2.0, y + 9.0, x + tw / 2.0, y + 9.0 + th],
            ),
        ];
        for k in [1.0f32, -1.0, 2.0, -2.0, 3.0, -3.0] {
            let yc = y + k * (th + 4.0);
            cands.push((
                x + 9.0,
                yc,
                Align::Left,
                [x + 9.0, yc - th / 2.0, x + 9.0 + tw, yc + th / 2.0],
            ));
            cands.push((
                x - 9.0,
                yc,
                Align::Right,
                [x - 9.0 - tw, yc - th / 2.0, x - 9.0, yc + th / 2.0],
            ));
        }
        let inside =
            |b: &[f32; 4]| b[0] >= left + 2.0 && b[2] <= right - 2.0 && b[1] >= top + 2.0 && b[3] <= bottom - 2.0;
        let free = |b: &[f32; 4]| {
            boxes
                .iter()
                .all(|o| b[2] + 2.0 <= o[0] || b[0] - 2.0 >= o[2] || b[3] + 1.0 <= o[1] || b[1] - 1.0 >= o[3])
        };
        let pick = cands
            .iter()
            .find(|c| inside(&c.3) && free(&c.3))
            .or_else(|| cands.iter().find(|c| inside(&c.3)))
            .unwrap_or(&cands[0]);
        // A name moved off its point's row gets a leader line to the point.
        if (pick.1 - y).abs() > 1.0 && pick.2 != Align::Center {
            let ex = if pick.2 == Align::Left {
                pick.3[0] - 1.0
            } else {
                pick.3[2] + 1.0
            };
            cv.line(x, y, ex, pick.1, AXIS, 1.0);
        }
        let bx = cv.text(
            pick.0,
            pick.1,
            &p.label,
            scale,
            pick.2,
            if p.pareto { [120, 20, 20] } else { INK },
            true,
        );
        boxes.push(bx);
    }
    if pts.is_empty() {
        cv.text(left + pw / 2.0, top + ph / 2.0, "no data", 3, Align::Center, INK, true);
    }
    cv.png()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nice_steps_and_labels() {
        assert_eq!(nice_step(10.0, 5), 2.0);
        assert_eq!(nice_step(1e6, 4), 5e5);
        assert_eq!(nice_step(1.2, 6), 0.2);
        assert_eq!(fmt_tick(2e6, 5e5), "2e6");
        assert_eq!(fmt_tick(1.5e6, 5e5), "1.5e6");
        assert_eq!(fmt_tick(0.25, 0.05), "0.25");
        assert_eq!(fmt_tick(400.0, 100.0), "400");
        assert_eq!(fmt_tick(4e-7, 2e-7), "4e-7");
        assert_eq!(fmt_tick(0.0, 2e-7), "0");
        assert_eq!(ticks_in(0.0, 1.0, 0.25), vec![0.0, 0.25, 0.5, 0.75, 1.0]);
    }

    #[test]
    fn cell_edges_between_midpoints() {
        let e = cell_edges(&[0.0, 10.0, 30.0], 0.0, 360.0);
        assert_eq!(e, vec![(0.0, 5.0), (5.0, 20.0), (20.0, 40.0)]);
        let e = cell_edges(&[0.0, 15.0, 345.0, 330.0], 0.0, 360.0);
        assert_eq!(e, vec![(0.0, 7.5), (7.5, 172.5), (337.5, 360.0), (172.5, 337.5)]);
        let e = cell_edges(&[20.0, 30.0], 0.0, 180.0);
        assert_eq!(e, vec![(15.0, 25.0), (25.0, 35.0)]);
        assert_eq!(cell_edges(&[7.0], 0.0, 180.0), vec![(0.0, 180.0)]);
    }

    #[test]
    fn colormap_ends() {
        assert_eq!(colormap(0.0, false), [68, 1, 84]);
        assert_eq!(colormap(1.0, false), [253, 231, 37]);
        assert_eq!(colormap(0.5, true), [247, 247, 247]);
    }
}
