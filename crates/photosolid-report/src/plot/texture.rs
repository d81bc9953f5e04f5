//! PNG preview of a rendered light texture ([`Rendered`]): the texture as a
//! [`heatmap()`](super::heatmap()) over C (0–360°, left to right) × γ (0–180°, nadir at the top),
//! one cell per texel, with axis titles in degrees and a colour bar in
//! candela (I / I_max when the texture carries no I_max).
//!
//! Tone mapping: Wallner's exposure curve `y = 1 − exp(−k·x)` on
//! `x = I / I_max`, divided by `1 − exp(−k)` so that I_max is full brightness
//! (k > 0; larger k lifts dim regions), then viridis
//! ([`ColorScale::Exposure`]). Nothing saturates below I_max: the curve
//! compresses the bright end (k = 4 reaches half the colour range at
//! 0.17 I_max). The colour bar runs evenly through the colours and puts its
//! candela ticks where the curve puts them, so a colour reads off the bar;
//! the second title line says k and the value at mid-bar.

use std::path::Path;

use crate::error::{Error, ModelError};
use crate::reconstruct::Rendered;

use super::heatmap::{heatmap_with, ColorScale, HeatmapSpec};
use super::Plot;

/// Default exposure k of the preview.
pub const DEFAULT_EXPOSURE: f64 = 4.0;

/// Default size of [`texture_preview`], px: a 720 × 360 px (2:1, one pixel
/// per half degree) plot area inside the heat map's margins.
pub const TEXTURE_SIZE: (u32, u32) = (962, 478);

/// Wallner's exposure curve, normalised so that x = 1 gives 1 (`k` > 0);
/// `x` is clamped to [0, 1].
pub fn tone_map(x: f64, k: f64) -> f64 {
    let x = x.clamp(0.0, 1.0);
    (1.0 - (-k * x).exp()) / (1.0 - (-k).exp())
}

/// What [`texture_preview`] draws; [`TexturePreview::new`] gives the defaults.
#[derive(Debug, Clone, Copy)]
pub struct TexturePreview<'a> {
    /// Title at the top; empty: the filter, factor, I_max and exposure.
    pub title: &'a str,
    /// The texture (texels in I / I_max, `i_max_cd` to scale them).
    pub texture: &'a Rendered,
    /// Exposure k of the tone curve (> 0, finite). Default [`DEFAULT_EXPOSURE`].
    pub exposure: f64,
    /// Width × height, px (each 120..=8192). Default [`TEXTURE_SIZE`].
    pub size: (u32, u32),
}

impl<'a> TexturePreview<'a> {
    /// The preview of `texture` with the default title, exposure and size.
    pub fn new(texture: &'a Rendered) -> Self {
        Self {
            title: "",
            texture,
            exposure: DEFAULT_EXPOSURE,
            size: TEXTURE_SIZE,
        }
    }
}

/// The preview as PNG bytes.
///
/// # Errors
/// [`ModelError::Parameter`] for an exposure that is not positive and
/// finite, a bad size, or a texture whose data does not match its mapping;
/// [`Error::Encode`] if encoding fails.
pub fn texture_preview(spec: &TexturePreview) -> Result<Vec<u8>, Error> {
    Ok(texture_preview_plot(spec)?.png)
}

/// The value x in [0, 1] that the exposure curve [`tone_map`] brings to
/// `y` in [0, 1] (its inverse).
pub fn tone_map_inverse(y: f64, k: f64) -> f64 {
    let y = y.clamp(0.0, 1.0);
    (-(1.0 - y * (1.0 - (-k).exp())).ln() / k).clamp(0.0, 1.0)
}

/// [`texture_preview`] with the boxes of its texts ([`Plot`]).
///
/// # Errors
/// As [`texture_preview`].
pub fn texture_preview_plot(spec: &TexturePreview) -> Result<Plot, Error> {
    let k = spec.exposure;
    if !(k.is_finite() && k > 0.0) {
        return Err(ModelError::Parameter {
            name: "exposure",
            value: k.to_string(),
            reason: "must be a positive finite number".into(),
        }
        .into());
    }
    let tex = spec.texture;
    let m = &tex.mapping;
    let xs: Vec<f64> = (0..m.width).map(|j| m.c_of_column(j)).collect();
    let ys: Vec<f64> = (0..m.height).map(|i| m.gamma_of_row(i)).collect();
    // Candela when the texture says how to scale it, else the ratio itself.
    let scaled = tex.i_max_cd.is_finite() && tex.i_max_cd > 0.0;
    let (scale, unit) = if scaled {
        (tex.i_max_cd, "cd")
    } else {
        (1.0, "I / I_max")
    };
    let values: Vec<f64> = tex.data.iter().map(|&v| f64::from(v) * scale).collect();
    let title = if spec.title.is_empty() {
        format!(
            "Light texture: {}, factor {}, I_max {} cd",
            tex.filter,
            tex.factor,
            crate::significant(tex.i_max_cd, 4),
        )
    } else {
        spec.title.to_string()
    };
    // What the exposure does, in the unit of the bar: the curve lifts dim
    // values (nothing saturates below I_max) and half the colour range is
    // reached at this value.
    let half = tone_map_inverse(0.5, k);
    let half_text = if scaled {
        format!("{} cd", crate::significant(half * scale, 3))
    } else {
        crate::significant(half, 2)
    };
    let subtitle = format!("exposure k = {k}: colour 1-exp(-k I/I_max), mid-bar {half_text}");
    heatmap_with(
        &HeatmapSpec {
            title: &title,
            xs: &xs,
            ys: &ys,
            values: &values,
            unit,
            scale: ColorScale::Exposure(k),
            range: Some((0.0, scale)),
            size: spec.size,
        },
        &subtitle,
    )
}

/// Write the preview PNG to `path` atomically (temporary file, then rename).
///
/// # Errors
/// As [`texture_preview`], and [`Error::Io`] when writing fails.
pub fn write_texture_preview(path: impl AsRef<Path>, spec: &TexturePreview) -> Result<(), Error> {
    let bytes = texture_preview(spec)?;
    crate::formats::write_atomic(path.as_ref(), &bytes)
}
