//! The photometric polar diagram of one plane pair.

use crate::error::Error;
use crate::font;

use super::axis::{fmt_tick, nice_step};
use super::canvas::{finite2, legend, Align, Canvas};
use super::{Series, SeriesStyle, AXIS, GRID, INK, POLAR_SIZE};

/// The smallest 1–2–5 step that covers `vmax` (> 0) with at most 5 rings.
fn ring_step(vmax: f64) -> f64 {
    let mut step = nice_step(vmax, 10);
    while (vmax / step - 1e-9).ceil() > 5.0 {
        step = nice_step(step * 1.01, 1);
    }
    step
}

/// What [`polar_diagram`] draws. `Default` gives an empty 800 × 800 px diagram.
#[derive(Debug, Clone, Copy)]
pub struct PolarSpec<'a> {
    /// Title at the top.
    pub title: &'a str,
    /// Name of the left half-plane (negative γ), e.g. "C180".
    pub left: &'a str,
    /// Name of the right half-plane (positive γ), e.g. "C0".
    pub right: &'a str,
    /// Unit of the values, e.g. "cd" or "cd/klm".
    pub unit: &'a str,
    /// The curves and measured point sets.
    pub series: &'a [Series],
    /// Width × height, px (each 120..=8192).
    pub size: (u32, u32),
}

impl Default for PolarSpec<'_> {
    fn default() -> Self {
        Self {
            title: "",
            left: "",
            right: "",
            unit: "",
            series: &[],
            size: POLAR_SIZE,
        }
    }
}

/// Photometric polar diagram of one plane pair, e.g. C0–C180, `spec.size` px.
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
/// [`crate::error::ModelError::Parameter`] for a size outside 120..=8192 px, [`Error::Encode`] if encoding fails.
pub fn polar_diagram(spec: &PolarSpec) -> Result<Vec<u8>, Error> {
    let PolarSpec {
        title,
        left,
        right,
        unit,
        series,
        size: (w, h),
    } = *spec;
    let mut cv = Canvas::new(w, h, "polar")?;
    let (wf, hf) = (cv.w(), cv.h());
    cv.title(title);

    // Dense measured points (e.g. 361 gamma angles) would hide every curve:
    // markers are thinned to one per MARKER_GAP px of the diagram and drawn
    // under the curves; the legend says how many are shown.
    let mut labels: Vec<Series> = series.to_vec();
    // Measure the legend with the longest marker labels it may get.
    let legend_h = legend(&mut cv, &widest_labels(series), 20.0, 0.0, wf - 20.0, true);
    let top = 40.0;
    let bottom = hf - legend_h - 14.0;
    let side = 20.0 + font::text_width(left, 2).max(font::text_width(right, 2)).max(48) as f32;
    let radius = ((wf - 2.0 * side) / 2.0).min((bottom - top) / 2.0 - 26.0).max(20.0);
    let (cx, cy) = (wf / 2.0, top + (bottom - top) / 2.0);
    let any = series.iter().any(|s| s.points.iter().any(finite2));
    let p = Disc::new(series, (cx, cy), radius);

    draw_grid(&mut cv, &p);
    // Half-plane names at the sides, above the 90° labels.
    cv.text(12.0, cy - 40.0, left, 2, Align::Left, INK, false);
    cv.text(wf - 12.0, cy - 40.0, right, 2, Align::Right, INK, false);
    // Unit in the top-left corner.
    cv.text(12.0, top + 4.0, unit, 2, Align::Left, INK, false);
    draw_ring_labels_and_cross(&mut cv, &p);

    let shown_markers = thin_markers(series, &mut labels, &p);
    for (s, kept) in series.iter().zip(&shown_markers) {
        if s.style == SeriesStyle::Markers {
            for &(g, v) in kept {
                let (x, y) = p.to_xy(g, v);
                cv.circle(x, y, 3.0, s.color, None);
            }
        }
    }
    draw_curves(&mut cv, series, &p);
    if !any {
        cv.text(cx, cy, "no data", 3, Align::Center, INK, true);
    }
    legend(&mut cv, &labels, 20.0, hf - legend_h - 8.0, wf - 20.0, false);
    cv.png()
}

/// The diagram's disc: centre and radius, px, and its value scale.
struct Disc {
    /// Centre, px.
    cx: f32,
    /// Centre, px.
    cy: f32,
    /// Radius of the outer ring, px.
    radius: f32,
    /// Value step between rings.
    step: f64,
    /// Number of rings.
    n_rings: usize,
    /// Value at the outer ring.
    rmax: f64,
}

impl Disc {
    /// The disc at `(cx, cy)` of `radius` px, scaled to the largest finite
    /// value of `series` rounded up to a ring.
    fn new(series: &[Series], (cx, cy): (f32, f32), radius: f32) -> Self {
        let vmax = series
            .iter()
            .flat_map(|s| s.points.iter())
            .filter(|p| finite2(p))
            .map(|p| p.1)
            .fold(0.0f64, f64::max);
        let top_v = if vmax > 0.0 { vmax } else { 1.0 };
        let step = ring_step(top_v);
        let n_rings = ((top_v / step) - 1e-9).ceil().max(1.0) as usize;
        let rmax = step * n_rings as f64;
        Self {
            cx,
            cy,
            radius,
            step,
            n_rings,
            rmax,
        }
    }

    /// Pixel position of value `v` at signed γ = `g` degrees (negative
    /// values at the centre).
    fn to_xy(&self, g: f64, v: f64) -> (f32, f32) {
        let r = (v.max(0.0) / self.rmax) * f64::from(self.radius);
        let a = g.to_radians();
        (self.cx + (r * a.sin()) as f32, self.cy + (r * a.cos()) as f32)
    }
}

/// The series with each marker label as long as it may get ("(n of n
/// shown)"), to measure the legend.
fn widest_labels(series: &[Series]) -> Vec<Series> {
    series
        .iter()
        .map(|s| {
            let mut s = s.clone();
            if s.style == SeriesStyle::Markers {
                let n = s.points.len();
                s.label = format!("{} ({n} of {n} shown)", s.label);
            }
            s
        })
        .collect()
}

/// Grid: radial lines every 30°, rings at each step, and the angle labels
/// outside the circle, 0..180 on both halves.
fn draw_grid(cv: &mut Canvas, p: &Disc) {
    let (cx, cy, radius) = (p.cx, p.cy, p.radius);
    for k in 0..12 {
        let (x, y) = p.to_xy(k as f64 * 30.0, p.rmax);
        cv.line(cx, cy, x, y, GRID, 1.0);
    }
    for k in 1..=p.n_rings {
        let r = radius * k as f32 / p.n_rings as f32;
        cv.ring(cx, cy, r, if k == p.n_rings { AXIS } else { GRID }, 1.0);
    }
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
}

/// Ring labels along the zenith ray, on white, and the axis cross through
/// the centre, a little darker than the grid.
fn draw_ring_labels_and_cross(cv: &mut Canvas, p: &Disc) {
    let (cx, cy, radius) = (p.cx, p.cy, p.radius);
    for k in 1..=p.n_rings {
        let v = p.step * k as f64;
        let (_, y) = p.to_xy(180.0, v);
        cv.text(cx + 5.0, y + 11.0, &fmt_tick(v, p.step), 2, Align::Left, AXIS, true);
    }
    cv.line(cx - radius, cy, cx + radius, cy, AXIS, 1.0);
    cv.line(cx, cy - radius, cx, cy + radius, AXIS, 1.0);
}

/// The finite points of each series sorted by γ, marker series thinned to
/// one point per [`MARKER_GAP`] px (their legend `labels` then say how many
/// are shown); empty for the other series.
fn thin_markers(series: &[Series], labels: &mut [Series], p: &Disc) -> Vec<Vec<(f64, f64)>> {
    let mut shown_markers: Vec<Vec<(f64, f64)>> = Vec::with_capacity(series.len());
    for (s, lab) in series.iter().zip(labels.iter_mut()) {
        let mut pts: Vec<(f64, f64)> = s.points.iter().copied().filter(finite2).collect();
        pts.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut kept: Vec<(f64, f64)> = Vec::new();
        if s.style == SeriesStyle::Markers {
            let mut last: Option<(f32, f32)> = None;
            for &(g, v) in &pts {
                let (x, y) = p.to_xy(g, v);
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
    shown_markers
}

/// The line and dashed series, sorted by γ and interpolated in polar
/// coordinates (1° steps); a single point is drawn as a dot.
fn draw_curves(cv: &mut Canvas, series: &[Series], p: &Disc) {
    for s in series {
        let mut pts: Vec<(f64, f64)> = s.points.iter().copied().filter(finite2).collect();
        pts.sort_by(|a, b| a.0.total_cmp(&b.0));
        match s.style {
            SeriesStyle::Markers => {}
            SeriesStyle::Line | SeriesStyle::Dashed => {
                if pts.len() == 1 {
                    let (x, y) = p.to_xy(pts[0].0, pts[0].1);
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
                            line.push(p.to_xy(g0 + f * (g - g0), v0 + f * (v - v0)));
                        }
                    }
                    line.push(p.to_xy(g, v));
                }
                cv.polyline(&line, s.color, 2.0, s.style == SeriesStyle::Dashed);
            }
        }
    }
}

/// Smallest distance (px) between two measured markers drawn on a polar diagram.
const MARKER_GAP: f32 = 12.0;
