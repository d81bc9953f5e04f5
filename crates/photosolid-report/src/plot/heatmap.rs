//! A value over C × γ as coloured cells, with a colour bar.

use crate::error::{Error, ModelError};
use crate::font;
use crate::solid::ColorMap;

use super::axis::{degree_step, fmt_tick, nice_step, ticks_in};
use super::canvas::{Align, Canvas};
use super::texture::tone_map;
use super::{Plot, AXIS, HEATMAP_SIZE, INK, NO_DATA};

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

/// How [`heatmap()`] maps a value to a colour.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ColorScale {
    /// Viridis over the range, linear.
    Sequential,
    /// Blue–white–red over ±max |value| (0 is white), for signed errors.
    Diverging,
    /// Viridis of Wallner's exposure curve [`tone_map`] with this k (> 0)
    /// on (value − lo) / (hi − lo): dim regions lifted, as a rendered light
    /// looks; the colour bar runs evenly through viridis with its ticks (in
    /// the values' unit) where the curve puts them.
    Exposure(f64),
}

impl ColorScale {
    /// The colour map and the position on it of `t` in [0, 1] along the range.
    fn color(self, t: f64) -> [u8; 3] {
        match self {
            ColorScale::Sequential => ColorMap::Viridis.rgb8(t),
            ColorScale::Diverging => ColorMap::RdBu.rgb8(t),
            ColorScale::Exposure(k) => ColorMap::Viridis.rgb8(tone_map(t, k)),
        }
    }
}

/// What [`heatmap()`] draws. `Default` gives an empty 900 × 500 px map.
#[derive(Debug, Clone, Copy)]
pub struct HeatmapSpec<'a> {
    /// Title at the top.
    pub title: &'a str,
    /// Cell centres in C (degrees).
    pub xs: &'a [f64],
    /// Cell centres in γ (degrees).
    pub ys: &'a [f64],
    /// `values[iy * xs.len() + ix]`; NaN cells stay grey.
    pub values: &'a [f64],
    /// Unit of the values, written over the colour bar.
    pub unit: &'a str,
    /// Value-to-colour mapping.
    pub scale: ColorScale,
    /// Colour range (lo, hi) in the values' unit; `None`: from the finite
    /// values (min..max, or ±max |value| when diverging).
    pub range: Option<(f64, f64)>,
    /// Width × height, px (each 120..=8192).
    pub size: (u32, u32),
}

impl Default for HeatmapSpec<'_> {
    fn default() -> Self {
        Self {
            title: "",
            xs: &[],
            ys: &[],
            values: &[],
            unit: "",
            scale: ColorScale::Sequential,
            range: None,
            size: HEATMAP_SIZE,
        }
    }
}

/// Heat map over C (x, degrees, axis 0–360) × γ (y, degrees, axis 0–180, 0 at
/// the top), `spec.size` px: `values[iy * xs.len() + ix]` at centres
/// `xs[ix]`, `ys[iy]` (any spacing; cells reach halfway to their neighbours).
/// The colour range is `range` when given, else the finite values'
/// min..max, or ±max |value| around 0 when [`ColorScale::Diverging`]. NaN cells stay
/// grey. The axes widen to take in centres outside 0–360 / 0–180.
///
/// # Errors
/// [`ModelError::Parameter`] for a size outside 120..=8192 px, if
/// `values.len() != xs.len() * ys.len()`, for a `range` that is not finite
/// with lo < hi, or for an exposure k that is not positive and finite;
/// [`Error::Encode`] if encoding fails.
pub fn heatmap(spec: &HeatmapSpec) -> Result<Vec<u8>, Error> {
    Ok(heatmap_plot(spec)?.png)
}

/// [`heatmap()`] with the boxes of its texts ([`Plot`]).
///
/// # Errors
/// As [`heatmap()`].
pub fn heatmap_plot(spec: &HeatmapSpec) -> Result<Plot, Error> {
    heatmap_with(spec, "")
}

/// The exposure colour bar's ticks: (value, position 0..1 up the bar) for
/// I_max-relative tone `k` over [lo, hi]: both ends and the 1–2–5 × 10^j
/// values between them, kept where they stand at least `min_gap` (a
/// fraction of the bar) from the ticks kept before them.
pub(super) fn exposure_ticks(lo: f64, hi: f64, k: f64, min_gap: f64) -> Vec<(f64, f64)> {
    let pos = |v: f64| tone_map((v - lo) / (hi - lo), k);
    let mut cands = vec![hi, lo];
    let span = hi - lo;
    if span > 0.0 && span.is_finite() {
        let top = span.log10().ceil() as i32;
        for e in (top - 6..=top).rev() {
            for m in [5.0, 2.0, 1.0] {
                let v = lo + m * 10f64.powi(e);
                if v > lo && v < hi {
                    cands.push(v);
                }
            }
        }
    }
    let mut kept: Vec<(f64, f64)> = Vec::new();
    for v in cands {
        let p = pos(v);
        if kept.iter().all(|&(_, q)| (p - q).abs() >= min_gap) {
            kept.push((v, p));
        }
    }
    kept.sort_by(|a, b| a.1.total_cmp(&b.1));
    kept
}

/// [`heatmap_plot`] with a second title line (`subtitle`, empty: none).
pub(super) fn heatmap_with(spec: &HeatmapSpec, subtitle: &str) -> Result<Plot, Error> {
    let HeatmapSpec {
        title,
        xs,
        ys,
        values,
        unit,
        scale,
        range,
        size: (w, h),
    } = *spec;
    check_grid(spec)?;
    let mut cv = Canvas::new(w, h, "heat map")?;
    let (wf, hf) = (cv.w(), cv.h());
    cv.title(title);
    let (left, top, right, bottom) = (92.0f32, 56.0f32, wf - 150.0, hf - 62.0);
    if !subtitle.is_empty() {
        cv.text(left, top - 18.0, subtitle, 2, Align::Left, INK, false);
    }
    let (pw, ph) = (right - left, bottom - top);

    let fin = |v: &&f64| v.is_finite();
    let area = CellArea {
        left,
        top,
        right,
        bottom,
        x0: xs.iter().filter(fin).fold(0.0f64, |a, &b| a.min(b)),
        x1: xs.iter().filter(fin).fold(360.0f64, |a, &b| a.max(b)),
        y0: ys.iter().filter(fin).fold(0.0f64, |a, &b| a.min(b)),
        y1: ys.iter().filter(fin).fold(180.0f64, |a, &b| a.max(b)),
    };
    let (any, (lo, hi)) = colour_range(values, range, scale == ColorScale::Diverging)?;
    let color_of = |v: f64| {
        if v.is_finite() {
            scale.color((v - lo) / (hi - lo))
        } else {
            NO_DATA
        }
    };

    draw_cells(&mut cv, &area, spec, &color_of);
    if !any {
        cv.no_data(left, top, right, bottom);
    }
    cv.frame(left - 1.0, top - 1.0, right + 1.0, bottom + 1.0, AXIS);
    draw_degree_axes(&mut cv, &area);
    cv.text(left + pw / 2.0, hf - 16.0, "C (°)", 2, Align::Center, INK, false);
    cv.text_vertical(18.0, top + ph / 2.0, "gamma (°), 0 = nadir", 2, INK);
    draw_colour_bar(&mut cv, &area, scale, (lo, hi), unit);
    cv.finish()
}

/// The plot area in pixels and the C (x) and γ (y) ranges, degrees, it spans.
struct CellArea {
    /// Left edge, px.
    left: f32,
    /// Top edge, px.
    top: f32,
    /// Right edge, px.
    right: f32,
    /// Bottom edge, px.
    bottom: f32,
    /// C at the left edge.
    x0: f64,
    /// C at the right edge.
    x1: f64,
    /// γ at the top edge.
    y0: f64,
    /// γ at the bottom edge.
    y1: f64,
}

impl CellArea {
    /// Pixel column of C = `x`.
    fn px(&self, x: f64) -> f32 {
        self.left + ((x - self.x0) / (self.x1 - self.x0)) as f32 * (self.right - self.left)
    }

    /// Pixel row of γ = `y`.
    fn py(&self, y: f64) -> f32 {
        self.top + ((y - self.y0) / (self.y1 - self.y0)) as f32 * (self.bottom - self.top)
    }
}

/// Refuse an exposure k that is not positive and finite, and values that do
/// not fill the grid.
fn check_grid(spec: &HeatmapSpec) -> Result<(), Error> {
    let HeatmapSpec { xs, ys, values, .. } = *spec;
    if let ColorScale::Exposure(k) = spec.scale {
        if !(k.is_finite() && k > 0.0) {
            return Err(ModelError::Parameter {
                name: "exposure",
                value: format!("heat map k = {k}"),
                reason: "must be a positive finite number".into(),
            }
            .into());
        }
    }
    if values.len() != xs.len() * ys.len() {
        return Err(ModelError::Parameter {
            name: "values",
            value: format!("heat map: {} values", values.len()),
            reason: format!("a {} x {} grid needs {}", xs.len(), ys.len(), xs.len() * ys.len()),
        }
        .into());
    }
    Ok(())
}

/// Whether any value is finite, and the colour range (lo, hi): `range` when
/// given (refused unless finite with lo < hi), else from the finite values
/// (±max |value| when `diverging`), widened when they are all one.
fn colour_range(values: &[f64], range: Option<(f64, f64)>, diverging: bool) -> Result<(bool, (f64, f64)), Error> {
    let (mut lo, mut hi) = values
        .iter()
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| (a.min(v), b.max(v)));
    let any = lo <= hi;
    if let Some((a, b)) = range {
        if !(a.is_finite() && b.is_finite() && a < b) {
            return Err(ModelError::Parameter {
                name: "range",
                value: format!("heat map colour range {a} .. {b}"),
                reason: "must be finite with lo < hi".into(),
            }
            .into());
        }
        (lo, hi) = (a, b);
    } else if diverging {
        let m = if any { lo.abs().max(hi.abs()) } else { 0.0 };
        let m = if m > 0.0 { m } else { 1.0 };
        (lo, hi) = (-m, m);
    } else if !any {
        (lo, hi) = (0.0, 1.0);
    } else if hi <= lo {
        let d = if lo == 0.0 { 1.0 } else { lo.abs() * 0.1 };
        (lo, hi) = if lo == 0.0 { (0.0, 1.0) } else { (lo - d, hi + d) };
    }
    Ok((any, (lo, hi)))
}

/// The cells of `spec`'s grid in their colours (`color_of`), on grey.
fn draw_cells(cv: &mut Canvas, area: &CellArea, spec: &HeatmapSpec, color_of: &dyn Fn(f64) -> [u8; 3]) {
    let (xs, ys, values) = (spec.xs, spec.ys, spec.values);
    cv.rect(
        area.left as i32,
        area.top as i32,
        area.right as i32,
        area.bottom as i32,
        NO_DATA,
    );
    let ex = cell_edges(xs, area.x0, area.x1);
    let ey = cell_edges(ys, area.y0, area.y1);
    for (iy, &(ya, yb)) in ey.iter().enumerate() {
        if !(ya.is_finite() && yb.is_finite()) {
            continue;
        }
        let (r0, r1) = (area.py(ya).round() as i32, area.py(yb).round() as i32);
        for (ix, &(xa, xb)) in ex.iter().enumerate() {
            if !(xa.is_finite() && xb.is_finite()) {
                continue;
            }
            let c = color_of(values[iy * xs.len() + ix]);
            cv.rect(area.px(xa).round() as i32, r0, area.px(xb).round() as i32, r1, c);
        }
    }
}

/// Tick marks and labels of the C and γ axes, in degrees.
fn draw_degree_axes(cv: &mut Canvas, area: &CellArea) {
    let (left, bottom) = (area.left, area.bottom);
    let sx = degree_step(area.x1 - area.x0, 8);
    for t in ticks_in(area.x0, area.x1, sx) {
        let x = area.px(t).round() + 0.5;
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
    let sy = degree_step(area.y1 - area.y0, 6);
    for t in ticks_in(area.y0, area.y1, sy) {
        let y = area.py(t).round() + 0.5;
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
}

/// Colour bar right of the plot area: top = hi, bottom = lo, with `unit`
/// over it. With an exposure the bar runs evenly through the colours and its
/// ticks sit where the tone curve puts their values, so that a colour in the
/// map reads off the bar.
fn draw_colour_bar(cv: &mut Canvas, area: &CellArea, scale: ColorScale, (lo, hi): (f64, f64), unit: &str) {
    let (top, right, bottom) = (area.top, area.right, area.bottom);
    let ph = bottom - top;
    let (bx0, bx1) = (right + 26.0, right + 48.0);
    for r in top as i32..bottom as i32 {
        let t = 1.0 - (f64::from(r) + 0.5 - f64::from(top)) / f64::from(ph);
        let c = match scale {
            ColorScale::Exposure(_) => ColorMap::Viridis.rgb8(t),
            _ => scale.color(t),
        };
        cv.rect(bx0 as i32, r, bx1 as i32, r + 1, c);
    }
    cv.frame(bx0 - 1.0, top - 1.0, bx1 + 1.0, bottom + 1.0, AXIS);
    for (_, p, label) in bar_ticks(scale, (lo, hi), ph) {
        let y = (bottom - p as f32 * ph).round() + 0.5;
        cv.line(bx1 + 1.0, y, bx1 + 6.0, y, AXIS, 1.0);
        cv.text(bx1 + 9.0, y, &label, 2, Align::Left, INK, false);
    }
    let uw = font::text_width(unit, 2) as f32;
    let ux = ((bx0 + bx1) / 2.0).min(cv.w() - 8.0 - uw / 2.0);
    cv.text(ux, top - 18.0, unit, 2, Align::Center, INK, false);
}

/// The colour bar's ticks for a bar `ph` px high: (value, position 0..1 up
/// the bar, label); with an exposure, spaced a text height apart at least.
fn bar_ticks(scale: ColorScale, (lo, hi): (f64, f64), ph: f32) -> Vec<(f64, f64, String)> {
    match scale {
        ColorScale::Exposure(k) => {
            let th = font::text_height(2) as f64 + 4.0;
            exposure_ticks(lo, hi, k, th / f64::from(ph))
                .into_iter()
                .map(|(v, p)| {
                    let label = if v == hi || v == lo {
                        crate::significant(v, 4)
                    } else {
                        fmt_tick(v, v)
                    };
                    (v, p, label)
                })
                .collect()
        }
        _ => {
            let sb = nice_step(hi - lo, 5);
            ticks_in(lo, hi, sb)
                .into_iter()
                .map(|t| (t, (t - lo) / (hi - lo), fmt_tick(t, sb)))
                .collect()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
}
