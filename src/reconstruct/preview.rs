//! PNG preview of a [`Rendered`] texture (tiny-skia).
//!
//! Layout: the texture fills a 720 × 360 px plot (C 0–360 left to right, γ
//! 0–180 top to bottom, nearest texel per pixel), with tick marks every 45°
//! in C and 30° in γ labelled in degrees, and a colour bar on the right
//! labelled in percent of I_max. tiny-skia draws no text, so labels use the
//! crate's 5 × 7 pixel bitmap font ([`crate::report::font`]).
//!
//! Tone mapping: Wallner's exposure curve `y = 1 − exp(−k·x)` on `x = I/I_max`,
//! divided by `1 − exp(−k)` so that I_max is full brightness (k > 0; larger k
//! lifts dim regions), then a black–purple–orange–yellow–white ramp.

use std::path::Path;

use tiny_skia::{Pixmap, PremultipliedColorU8};

use crate::error::{Error, ModelError};
use crate::report::font;

use super::texture::Rendered;

/// Default exposure k of the preview.
pub const DEFAULT_EXPOSURE: f64 = 4.0;

const PLOT_W: u32 = 720;
const PLOT_H: u32 = 360;
const LEFT: u32 = 34;
const TOP: u32 = 10;
const BOTTOM: u32 = 24;
const BAR_GAP: u32 = 14;
const BAR_W: u32 = 16;
const RIGHT: u32 = 40;

/// Wallner's exposure curve, normalised so that x = 1 gives 1 (`k` > 0).
pub fn tone_map(x: f64, k: f64) -> f64 {
    let x = x.clamp(0.0, 1.0);
    (1.0 - (-k * x).exp()) / (1.0 - (-k).exp())
}

/// Colour ramp for y in [0, 1].
fn ramp(y: f64) -> [u8; 3] {
    const STOPS: [(f64, [f64; 3]); 5] = [
        (0.0, [0.0, 0.0, 0.0]),
        (0.3, [90.0, 20.0, 120.0]),
        (0.6, [220.0, 80.0, 40.0]),
        (0.85, [250.0, 200.0, 40.0]),
        (1.0, [255.0, 255.0, 255.0]),
    ];
    let y = y.clamp(0.0, 1.0);
    let k = STOPS.iter().position(|s| s.0 >= y).unwrap_or(4).max(1);
    let (a, b) = (STOPS[k - 1], STOPS[k]);
    let f = (y - a.0) / (b.0 - a.0);
    [0, 1, 2].map(|i| (a.1[i] + f * (b.1[i] - a.1[i])).round() as u8)
}

struct Canvas {
    w: u32,
    h: u32,
    px: Vec<[u8; 3]>,
}

impl Canvas {
    fn set(&mut self, x: u32, y: u32, c: [u8; 3]) {
        if x < self.w && y < self.h {
            self.px[(y * self.w + x) as usize] = c;
        }
    }
    fn rect(&mut self, x: u32, y: u32, w: u32, h: u32, c: [u8; 3]) {
        for yy in y..y + h {
            for xx in x..x + w {
                self.set(xx, yy, c);
            }
        }
    }
    /// Digits of `n` with the top-left corner at (x, y); returns the text width.
    fn number(&mut self, x: u32, y: u32, n: u32, c: [u8; 3]) -> u32 {
        font::for_each_pixel(&n.to_string(), |dx, dy| self.set(x + dx, y + dy, c));
        text_width(n)
    }
}

fn text_width(n: u32) -> u32 {
    font::text_width(&n.to_string(), 1)
}

/// The preview as PNG bytes, with exposure `k` (> 0, finite).
///
/// # Errors
/// [`ModelError::Parameter`] for a bad `k`; [`Error::Unsupported`] if encoding fails.
pub fn preview_png(tex: &Rendered, k: f64) -> Result<Vec<u8>, Error> {
    if !(k.is_finite() && k > 0.0) {
        return Err(ModelError::Parameter {
            name: "exposure",
            value: k.to_string(),
            reason: "must be a positive finite number".into(),
        }
        .into());
    }
    let (tw, th) = (tex.mapping.width, tex.mapping.height);
    let w = LEFT + PLOT_W + BAR_GAP + BAR_W + RIGHT;
    let h = TOP + PLOT_H + BOTTOM;
    let bg = [255, 255, 255];
    let ink = [0, 0, 0];
    let mut cv = Canvas {
        w,
        h,
        px: vec![bg; (w * h) as usize],
    };
    for py in 0..PLOT_H {
        let row = ((py as f64 + 0.5) / PLOT_H as f64 * th as f64) as usize;
        for px in 0..PLOT_W {
            let col = ((px as f64 + 0.5) / PLOT_W as f64 * tw as f64) as usize;
            let v = tex.data[row.min(th - 1) * tw + col.min(tw - 1)];
            cv.set(LEFT + px, TOP + py, ramp(tone_map(f64::from(v), k)));
        }
    }
    // C ticks and labels (degrees), every 45°, labels every 90°.
    for c in (0..=360).step_by(45) {
        let x = LEFT + (c * (PLOT_W - 1)) / 360;
        cv.rect(x, TOP + PLOT_H, 1, if c % 90 == 0 { 5 } else { 3 }, ink);
        if c % 90 == 0 {
            let tw = text_width(c);
            cv.number(x.saturating_sub(tw / 2), TOP + PLOT_H + 8, c, ink);
        }
    }
    // γ ticks and labels (degrees), every 30°.
    for g in (0..=180).step_by(30) {
        let y = TOP + (g * (PLOT_H - 1)) / 180;
        cv.rect(LEFT - 4, y, 4, 1, ink);
        let tw = text_width(g);
        cv.number(LEFT - 6 - tw, y.saturating_sub(3), g, ink);
    }
    // Colour bar: top = I_max, bottom = 0; labels in % of I_max.
    let bx = LEFT + PLOT_W + BAR_GAP;
    for py in 0..PLOT_H {
        let x = 1.0 - (py as f64 + 0.5) / PLOT_H as f64;
        cv.rect(bx, TOP + py, BAR_W, 1, ramp(tone_map(x, k)));
    }
    for p in [0u32, 25, 50, 75, 100] {
        let y = TOP + ((100 - p) * (PLOT_H - 1)) / 100;
        cv.rect(bx + BAR_W, y, 3, 1, ink);
        cv.number(bx + BAR_W + 5, y.saturating_sub(3), p, ink);
    }

    let mut pm = Pixmap::new(w, h).ok_or_else(|| Error::Unsupported("preview size".into()))?;
    for (dst, c) in pm.pixels_mut().iter_mut().zip(&cv.px) {
        *dst = PremultipliedColorU8::from_rgba(c[0], c[1], c[2], 255).expect("opaque");
    }
    pm.encode_png()
        .map_err(|e| Error::Unsupported(format!("cannot encode PNG: {e}")))
}

/// Write the preview PNG to `path` atomically ([`crate::formats::write_atomic`]).
///
/// # Errors
/// As [`preview_png`], and [`Error::Io`] when writing fails.
pub fn write_preview(path: impl AsRef<Path>, tex: &Rendered, k: f64) -> Result<(), Error> {
    let path = path.as_ref();
    let bytes = preview_png(tex, k)?;
    crate::formats::write_atomic(path, &bytes)
}
