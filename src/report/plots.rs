//! PLACEHOLDER: the real plots module is written in parallel; the lead takes
//! that file at merge. These stand-ins return a 1x1 PNG with the final API.

use crate::error::Error;

/// One curve or point set of a diagram.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// Legend label.
    pub label: String,
    /// (x, y) points.
    pub points: Vec<(f64, f64)>,
    /// RGB colour.
    pub color: [u8; 3],
    /// How the points are drawn.
    pub style: SeriesStyle,
}

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SeriesStyle {
    /// Solid line.
    Line,
    /// Dashed line.
    Dashed,
    /// Markers only.
    Markers,
}

fn tiny_png() -> Result<Vec<u8>, Error> {
    let mut p = tiny_skia::Pixmap::new(1, 1).ok_or_else(|| Error::Unsupported("pixmap".into()))?;
    p.fill(tiny_skia::Color::WHITE);
    p.encode_png().map_err(|e| Error::Unsupported(e.to_string()))
}

/// points are (signed gamma in degrees in [-180, 180], cd): positive on the `right` half-plane (e.g. C0), negative on `left` (C180)
pub fn polar_diagram(title: &str, left: &str, right: &str, unit: &str, series: &[Series]) -> Result<Vec<u8>, Error> {
    let _ = (title, left, right, unit, series);
    tiny_png()
}

/// values[iy * xs.len() + ix] at C = xs[ix] (degrees), gamma = ys[iy] (degrees)
pub fn heatmap(
    title: &str,
    xs: &[f64],
    ys: &[f64],
    values: &[f64],
    unit: &str,
    diverging: bool,
) -> Result<Vec<u8>, Error> {
    let _ = (title, xs, ys, values, unit, diverging);
    tiny_png()
}

/// One point of a scatter plot.
#[derive(Debug, Clone, PartialEq)]
pub struct ScatterPoint {
    /// Label drawn next to the point.
    pub label: String,
    /// x value.
    pub x: f64,
    /// y value.
    pub y: f64,
    /// On the Pareto front (marked).
    pub pareto: bool,
}

/// A labelled scatter plot, optionally with a logarithmic x axis.
pub fn scatter(
    title: &str,
    x_label: &str,
    y_label: &str,
    points: &[ScatterPoint],
    log_x: bool,
) -> Result<Vec<u8>, Error> {
    let _ = (title, x_label, y_label, points, log_x);
    tiny_png()
}

/// The k-th colour of a qualitative palette.
pub fn palette(k: usize) -> [u8; 3] {
    const P: [[u8; 3]; 8] = [
        [31, 119, 180],
        [255, 127, 14],
        [44, 160, 44],
        [214, 39, 40],
        [148, 103, 189],
        [140, 86, 75],
        [227, 119, 194],
        [127, 127, 127],
    ];
    P[k % P.len()]
}

/// `data:image/png;base64,...` for inline use in HTML.
pub fn png_data_uri(png: &[u8]) -> String {
    const T: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut s = String::from("data:image/png;base64,");
    for ch in png.chunks(3) {
        let b = [ch[0], *ch.get(1).unwrap_or(&0), *ch.get(2).unwrap_or(&0)];
        let n = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for k in 0..4 {
            if k <= ch.len() {
                s.push(T[((n >> (18 - 6 * k)) & 63) as usize] as char);
            } else {
                s.push('=');
            }
        }
    }
    s
}
