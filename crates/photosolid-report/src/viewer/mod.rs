//! The interactive 3D view of photometric solids in every HTML report.
//!
//! [`ViewerData::new`] samples a reference field and each reconstruction on
//! one regular (C, γ) grid, decimated to what a screen needs (2–5° steps,
//! coarser when there are many solids, so the page stays small), and
//! packs them as base64 binary, little-endian:
//! - once, the unit direction of every grid vertex in the luminaire frame
//!   ([`crate::model::frame`]: C0 = +x, C90 = +y, nadir = −z), 3 × `i16`
//!   (component · 32767), so the page never converts angles itself;
//! - per solid, the radius (= intensity) of every vertex as a `u16` over
//!   [0, R] (R the largest radius of all solids): vertex = direction · radius;
//! - per reconstruction, the signed radial error against the reference at each
//!   vertex, (recon − reference) / I_max · 100 (% of I_max, computed here, in
//!   Rust, not in the page), quantised to an `i16` over ±`err_max_pct`: the
//!   error of largest magnitude among nine points around the vertex, a
//!   fraction of a step off it in C and γ, so that the error between the
//!   measured directions shows (interpolating filters are exact at them);
//!   each solid's `max_abs_err_pct`, the legend's "max |err|", is the largest
//!   of these.
//!
//! The triangles are implied by the grid (vertex `ic * ng + ig`, C-planes
//! wrapping at 360°), so no index buffer is embedded. [`html`] returns the
//! HTML fragment: the JSON data, the page's own small WebGL viewer
//! (`viewer.js`, no library, no network) and its CSS. Where WebGL is
//! unavailable the fragment shows a message and the report's static PNGs
//! (written next to it, unchanged) remain the figures.

use std::fmt::Write as _;

use serde::Serialize;

use crate::compare_report::esc;
use crate::model::frame;
use crate::plot::{base64, palette};
use crate::solid::ColorMap;

#[cfg(test)]
use crate::compare::view::STEPS_DEG;
pub use crate::compare::view::{grid_step, SampledSolids, SolidSet, MESH_BUDGET_BYTES};

/// Entries of the diverging colour table handed to the page (RdBu, blue = negative).
const LUT_ENTRIES: usize = 33;

/// One solid of the viewer, packed.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PackedSolid {
    /// Name shown next to its checkbox.
    pub name: String,
    /// `reference` or `reconstruction`.
    pub role: &'static str,
    /// Colour of its checkbox swatch and polar curve, `#rrggbb` (the plots' palette).
    pub color: String,
    /// Radii: one `u16` per vertex (radius / R · 65535), little-endian, base64.
    pub radius: String,
    /// Signed radial errors: one `i16` per vertex, little-endian, base64 (empty for the reference).
    pub err: String,
    /// Largest |error| of this solid, % of I_max (0 for the reference).
    pub max_abs_err_pct: f64,
    /// Half-range of its colour scale, % of I_max: the 1-2-5 step at or above
    /// `max_abs_err_pct`. The page colours every visible surface on the
    /// largest scale among them, so one poor fit does not wash out the others.
    pub scale_pct: f64,
}

/// What the page receives (serialised as JSON inside the report).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ViewerData {
    /// What the errors are measured against, in words.
    pub reference: String,
    /// Optional note on the colours.
    pub note: Option<String>,
    /// What the legend's number beside each reconstruction is: `max |err|`
    /// (against the report's reference), or, when the colours show something
    /// else (a [`SolidSet::note`]), `max |diff from <the reference shown>|`.
    pub legend_quantity: String,
    /// Reference I_max (report unit).
    pub i_max: f64,
    /// C step of the grid, degrees.
    pub c_step_deg: f64,
    /// γ step of the grid, degrees.
    pub gamma_step_deg: f64,
    /// C-planes (0 .. 360 − step).
    pub nc: usize,
    /// γ rows (0 ..= 180).
    pub ng: usize,
    /// Unit directions of the vertices: 3 × `i16` (component · 32767) per vertex, little-endian, base64.
    pub directions: String,
    /// R: the quantisation range of the radii, [0, R] (report unit): the largest radius of all solids.
    pub radius: f64,
    /// Quantisation range of the errors, % of I_max: i16 ±32767 maps to ±this.
    pub err_max_pct: f64,
    /// The diverging colour table, `[r, g, b]` 0..=255, from −scale to +scale.
    pub lut: Vec<[u8; 3]>,
    /// The reference first, then the reconstructions.
    pub solids: Vec<PackedSolid>,
}

/// The smallest of 1, 2, 5 × 10^k at or above `x` (> 0); 1 for 0 or non-finite.
fn nice_ceiling(x: f64) -> f64 {
    if !(x.is_finite() && x > 0.0) {
        return 1.0;
    }
    let p = 10f64.powf(x.log10().floor());
    [1.0, 2.0, 5.0, 10.0]
        .into_iter()
        .map(|m| m * p)
        .find(|&v| v >= x * (1.0 - 1e-12))
        .unwrap_or(10.0 * p)
}

/// A finite, non-negative intensity (a field's undershoot is drawn at the origin).
fn radius_of(v: f64) -> f64 {
    if v.is_finite() {
        v.max(0.0)
    } else {
        0.0
    }
}

/// `u16` of `x` in [0, r].
fn quantise_u16(x: f64, r: f64) -> u16 {
    ((x / r).clamp(0.0, 1.0) * 65535.0).round() as u16
}

/// The inverse of `quantise_u16` (for tests and readers).
pub fn dequantise_u16(q: u16, r: f64) -> f64 {
    f64::from(q) / 65535.0 * r
}

impl ViewerData {
    /// Sample and pack `set` (see the module docs).
    pub fn new(set: &SolidSet<'_>) -> ViewerData {
        ViewerData::from_samples(&SampledSolids::new(set))
    }

    /// Pack solids sampled by [`SampledSolids::new`] (see the module docs).
    pub fn from_samples(samples: &SampledSolids) -> ViewerData {
        let SampledSolids {
            c_step_deg: dc,
            gamma_step_deg: dg,
            nc,
            ng,
            i_max,
            ..
        } = *samples;
        let reference = &samples.reference;
        let radius = std::iter::once(reference)
            .chain(samples.recons.iter().map(|r| &r.values))
            .flat_map(|v| v.iter().map(|&x| radius_of(x)))
            .fold(0.0, f64::max);
        let radius = if radius > 0.0 { radius } else { 1.0 };
        let err_max_pct = samples
            .recons
            .iter()
            .map(|r| max_abs(&r.errors_pct))
            .fold(0.0, f64::max);
        ViewerData {
            reference: samples.reference_label.clone(),
            note: samples.note.clone(),
            legend_quantity: legend_quantity(samples),
            i_max,
            c_step_deg: dc,
            gamma_step_deg: dg,
            nc,
            ng,
            directions: packed_directions(samples),
            radius,
            err_max_pct,
            lut: (0..LUT_ENTRIES)
                .map(|k| ColorMap::RdBu.rgb8(k as f64 / (LUT_ENTRIES - 1) as f64))
                .collect(),
            solids: packed_solids(samples, radius, err_max_pct),
        }
    }
}

/// The largest |e|, 0 for none.
fn max_abs(e: &[f64]) -> f64 {
    e.iter().fold(0.0, |m: f64, x| m.max(x.abs()))
}

/// What the legend's number is: `max |err|`, or with a note (the colours
/// show another difference) `max |diff from <the reference shown>|`.
fn legend_quantity(samples: &SampledSolids) -> String {
    match samples.note {
        // A cropped representation's error, over the directions it keeps.
        None if samples.error_domain.is_some() => {
            format!(
                "max |err| over {}",
                samples.error_domain.as_ref().map_or(String::new(), |d| d.to_string())
            )
        }
        None => "max |err|".into(),
        Some(_) => format!(
            "max |diff from {}|",
            samples
                .reference_label
                .split(" (")
                .next()
                .unwrap_or(&samples.reference_label)
        ),
    }
}

/// The unit direction of every grid vertex (C-planes outer, γ inner),
/// 3 × `i16` each, base64.
fn packed_directions(samples: &SampledSolids) -> String {
    let cs: Vec<f64> = (0..samples.nc).map(|k| k as f64 * samples.c_step_deg).collect();
    let gs: Vec<f64> = (0..samples.ng).map(|k| k as f64 * samples.gamma_step_deg).collect();
    let dirs: Vec<glam::DVec3> = cs
        .iter()
        .flat_map(|&c| gs.iter().map(move |&g| frame::direction(c, g)))
        .collect();
    let direction_bytes: Vec<u8> = dirs
        .iter()
        .flat_map(|d| [d.x, d.y, d.z])
        .flat_map(|x| ((x.clamp(-1.0, 1.0) * 32767.0).round() as i16).to_le_bytes())
        .collect();
    base64(&direction_bytes)
}

/// The reference, then each reconstruction in its palette colour: radii
/// quantised over [0, `radius`], errors over ±`err_max_pct` (±1 when 0).
fn packed_solids(samples: &SampledSolids, radius: f64, err_max_pct: f64) -> Vec<PackedSolid> {
    let pack_radius = |v: &[f64]| -> String {
        let bytes: Vec<u8> = v
            .iter()
            .flat_map(|&x| quantise_u16(radius_of(x), radius).to_le_bytes())
            .collect();
        base64(&bytes)
    };
    let q_err = if err_max_pct > 0.0 { err_max_pct } else { 1.0 };
    let pack_err = |e: &[f64]| -> String {
        let bytes: Vec<u8> = e
            .iter()
            .flat_map(|x| (((x / q_err).clamp(-1.0, 1.0) * 32767.0).round() as i16).to_le_bytes())
            .collect();
        base64(&bytes)
    };
    let hex = |c: [u8; 3]| format!("#{:02x}{:02x}{:02x}", c[0], c[1], c[2]);
    let mut solids = vec![PackedSolid {
        name: "reference".into(),
        role: "reference",
        color: "#000000".into(),
        radius: pack_radius(&samples.reference),
        err: String::new(),
        max_abs_err_pct: 0.0,
        scale_pct: 0.0,
    }];
    for (k, r) in samples.recons.iter().enumerate() {
        let e = &r.errors_pct;
        solids.push(PackedSolid {
            name: r.name.clone(),
            role: "reconstruction",
            color: hex(palette(k)),
            radius: pack_radius(&r.values),
            err: pack_err(e),
            max_abs_err_pct: max_abs(e),
            scale_pct: nice_ceiling(max_abs(e)),
        });
    }
    solids
}

/// The viewer's script: the page's own WebGL code (orbit, pan, zoom, the
/// frame's axes, the colour scale and the polar panel). Plain ES2017, no library.
const VIEWER_JS: &str = include_str!("viewer.js");
/// The viewer's style sheet.
const VIEWER_CSS: &str = include_str!("viewer.css");

/// The HTML fragment of the viewer of `data`, to place in a report's `<body>`.
/// `fallback` names the static figures the page falls back to without WebGL.
pub fn html(data: &ViewerData, fallback: &str) -> String {
    // '<' escaped so that no string in the data can close the script element.
    let json = serde_json::to_string(data)
        .unwrap_or_else(|_| "null".into())
        .replace('<', "\\u003c");
    let mut s = String::new();
    let _ = write!(
        s,
        "<section class=\"psv\">\n<h2>Interactive 3D view of the photometric solids</h2>\n\
<p class=\"psv-caption\">Reference: {}. Surfaces coloured by the signed radial error \
(reconstruction &minus; reference) in % of I_max = {}, on the scale of the largest error shown; \
the reference is the black wire mesh. \
Grid {}&deg; in C &times; {}&deg; in &gamma;. Drag to orbit, shift-drag, right-drag or two fingers to pan, \
wheel or pinch to zoom.{}</p>\n\
<div class=\"psv-nogl\" hidden>WebGL is not available in this browser: the interactive view is off; \
{} show the same data.</div>\n\
<div class=\"psv-main\"><div class=\"psv-stage\"><canvas class=\"psv-gl\" width=\"640\" height=\"480\"></canvas>\
<canvas class=\"psv-labels\" width=\"640\" height=\"480\"></canvas></div>\n\
<div class=\"psv-side\"><div class=\"psv-toggles\"></div>\
<canvas class=\"psv-scale\" width=\"300\" height=\"56\"></canvas>\
<label class=\"psv-plane\">C-plane <input type=\"range\" class=\"psv-c\" min=\"0\" max=\"179\" step=\"1\" value=\"0\"> \
<output class=\"psv-cval\">C0 &ndash; C180</output></label>\
<canvas class=\"psv-polar\" width=\"300\" height=\"300\"></canvas></div></div>\n\
<script type=\"application/json\" class=\"psv-data\">{}</script>\n",
        esc(&data.reference),
        crate::significant(data.i_max, 4),
        data.c_step_deg,
        data.gamma_step_deg,
        data.note.as_ref().map(|n| format!(" {}", esc(n))).unwrap_or_default(),
        esc(fallback),
        json
    );
    let _ = write!(
        s,
        "<style>\n{VIEWER_CSS}</style>\n<script>\n{VIEWER_JS}</script>\n</section>\n"
    );
    s
}

#[cfg(test)]
mod tests;
