//! PNG plots for reports, drawn with tiny-skia and the crate's bitmap font
//! ([`super::font`]).
//!
//! Five kinds, each drawn from one spec struct whose `Default` gives the
//! standard size:
//! - [`polar_diagram`] ([`PolarSpec`]): the photometric polar diagram of one
//!   plane pair (C0–C180, C90–C270, ...), nadir down, as lighting engineers draw it;
//! - [`heatmap()`] ([`HeatmapSpec`]): a value over C × γ (e.g. the relative error
//!   of a reconstruction), viridis or a diverging blue–white–red map;
//! - [`scatter()`] ([`ScatterSpec`]): cost versus error of several methods, with
//!   the Pareto front;
//! - [`line_chart()`] ([`LineSpec`]): values against a parameter, e.g. a
//!   representation's error against its degree;
//! - [`texture_preview`] ([`TexturePreview`]): a rendered light texture as a
//!   C × γ heat map in candela through an exposure tone curve.
//!
//! Modules: [`canvas`] (pixmap, text, legend), [`axis`] (ticks and their
//! labels), `area` (the x-y plots' axes, pixel mapping and grid), one module per kind. Colours come from
//! [`crate::solid::ColorMap`], the crate's one colour map.
//!
//! All of them return PNG bytes, never panic on empty or non-finite input
//! (non-finite points are skipped; nothing to draw gives a plot that says
//! "no data") and label their axes with the caller's units. White
//! background, anti-aliased 1–2 px strokes, dark grey text, tick values on
//! the 1–2–5 × 10^k sequence.

mod area;
pub mod axis;
pub mod canvas;
pub mod heatmap;
pub mod isolux;
pub mod lines;
pub mod polar;
pub mod scatter;
pub mod texture;

pub use heatmap::{heatmap, heatmap_plot, ColorScale, HeatmapSpec};
pub use isolux::{contour_levels, isolux_plot, IsoluxSpec, MapAxis, MapLimit, MapQuantity};
pub use lines::{line_chart, line_chart_plot, LineSpec};
pub use polar::{polar_diagram, PolarSpec};
pub use scatter::{scatter, scatter_plot, ScatterSpec};
pub use texture::{
    texture_preview, texture_preview_plot, tone_map, tone_map_inverse, write_texture_preview, TexturePreview,
    DEFAULT_EXPOSURE, TEXTURE_SIZE,
};

/// One text a plot drew: what it says and its box in pixels
/// `[x0, y0, x1, y1]` (x0, y0 inclusive at the top left; x1, y1 exclusive).
/// Vertical texts give the box they cover once turned.
#[derive(Debug, Clone, PartialEq)]
pub struct TextBox {
    /// The text.
    pub text: String,
    /// `[x0, y0, x1, y1]`, px.
    pub rect: [f32; 4],
}

/// A drawn plot: its PNG and the boxes of every text on it, so that a test
/// (or a caller laying out a page) can check that none overlap or leave the image.
#[derive(Debug, Clone)]
pub struct Plot {
    /// PNG bytes.
    pub png: Vec<u8>,
    /// Every text drawn, in drawing order.
    pub texts: Vec<TextBox>,
}

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

/// One point of a [`scatter()`] plot.
#[derive(Debug, Clone, PartialEq)]
pub struct ScatterPoint {
    /// Name drawn next to the point.
    pub label: String,
    /// Abscissa (e.g. time per sample in ns).
    pub x: f64,
    /// Ordinate (e.g. RMS error in % of I_max).
    pub y: f64,
}

/// Default size of [`polar_diagram`].
pub const POLAR_SIZE: (u32, u32) = (800, 800);
/// Default size of [`heatmap()`].
pub const HEATMAP_SIZE: (u32, u32) = (900, 500);
/// Default size of [`scatter()`].
pub const SCATTER_SIZE: (u32, u32) = (800, 550);

pub(crate) const WHITE: [u8; 3] = [255, 255, 255];
pub(crate) const INK: [u8; 3] = [50, 50, 50];
pub(crate) const AXIS: [u8; 3] = [110, 110, 110];
pub(crate) const GRID: [u8; 3] = [222, 222, 222];
pub(crate) const NO_DATA: [u8; 3] = [238, 238, 238];
pub(crate) const PARETO: [u8; 3] = [214, 39, 40];
pub(crate) const OTHER: [u8; 3] = [70, 120, 180];

/// A distinct colour for series `k`: d3's category10 (which reads well on
/// white) for the first 10, the same ten at 60 % brightness for the next 10
/// (drawn dashed by the plots, [`style_of`]), so 20 curves stay apart; wraps
/// after 20.
pub fn palette(k: usize) -> [u8; 3] {
    let base = category10(k % 10);
    if (k / 10).is_multiple_of(2) {
        base
    } else {
        base.map(|c| (f64::from(c) * 0.6).round() as u8)
    }
}

/// The line style of curve `k` beside [`palette`]: solid for the first ten,
/// dashed for the next ten (the darker colours), so colour and dash tell 20
/// curves apart.
pub fn style_of(k: usize) -> SeriesStyle {
    if (k / 10).is_multiple_of(2) {
        SeriesStyle::Line
    } else {
        SeriesStyle::Dashed
    }
}

/// d3's category10 colour `k` (0-9).
fn category10(k: usize) -> [u8; 3] {
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

/// `png` as a `data:image/png;base64,...` URI, for self-contained HTML.
pub fn png_data_uri(png: &[u8]) -> String {
    format!("data:image/png;base64,{}", base64(png))
}

/// `bytes` in standard base64 (RFC 4648, `+/`, `=` padding): what HTML
/// data URIs and the viewer's embedded meshes ([`crate::viewer`]) use.
pub fn base64(bytes: &[u8]) -> String {
    const B64: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut s = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
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
