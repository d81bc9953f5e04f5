//! PNG preview of a rendered light texture ([`Rendered`]): the texture as a
//! [`heatmap()`] over C (0–360°, left to right) × γ (0–180°, nadir at the top),
//! one cell per texel, with axis titles in degrees and a colour bar in
//! candela (I / I_max when the texture carries no I_max).
//!
//! Tone mapping: Wallner's exposure curve `y = 1 − exp(−k·x)` on
//! `x = I / I_max`, divided by `1 − exp(−k)` so that I_max is full brightness
//! (k > 0; larger k lifts dim regions), then viridis
//! ([`ColorScale::Exposure`]). The colour bar shows the same curve, so its
//! ticks stay at their candela values.

use std::path::Path;

use crate::error::{Error, ModelError};
use crate::reconstruct::Rendered;

use super::heatmap::{heatmap, ColorScale, HeatmapSpec};

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
            "Light texture: {}, factor {}, I_max {} cd, exposure k = {}",
            tex.filter,
            tex.factor,
            crate::report::significant(tex.i_max_cd, 4),
            k
        )
    } else {
        spec.title.to_string()
    };
    heatmap(&HeatmapSpec {
        title: &title,
        xs: &xs,
        ys: &ys,
        values: &values,
        unit,
        scale: ColorScale::Exposure(k),
        range: Some((0.0, scale)),
        size: spec.size,
    })
}

/// Write the preview PNG to `path` atomically (temporary file, then rename).
///
/// # Errors
/// As [`texture_preview`], and [`Error::Io`] when writing fails.
pub fn write_texture_preview(path: impl AsRef<Path>, spec: &TexturePreview) -> Result<(), Error> {
    let bytes = texture_preview(spec)?;
    crate::formats::write_atomic(path.as_ref(), &bytes)
}
