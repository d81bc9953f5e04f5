//! The drawing surface of the plots: a white tiny-skia pixmap with strokes,
//! filled shapes, crisp rectangles, text in the crate's bitmap font
//! ([`crate::font`]) and the series legend.

use tiny_skia::{Color, FillRule, Paint, PathBuilder, Pixmap, PremultipliedColorU8, Stroke, StrokeDash, Transform};

use crate::error::{Error, ModelError};
use crate::font;

use super::{Plot, Series, SeriesStyle, TextBox, INK, WHITE};

/// Horizontal anchoring of a text.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(super) enum Align {
    Left,
    Center,
    Right,
}

/// A plot being drawn.
pub(super) struct Canvas {
    pub pm: Pixmap,
    /// Every text drawn, with its box (what [`Plot::texts`] returns).
    pub texts: Vec<TextBox>,
}

pub(super) fn paint(rgb: [u8; 3]) -> Paint<'static> {
    let mut p = Paint::default();
    p.set_color_rgba8(rgb[0], rgb[1], rgb[2], 255);
    p.anti_alias = true;
    p
}

/// Both coordinates finite.
pub(super) fn finite2(p: &(f64, f64)) -> bool {
    p.0.is_finite() && p.1.is_finite()
}

impl Canvas {
    /// A white `w` × `h` px canvas; `what` names the plot in the error.
    pub fn new(w: u32, h: u32, what: &str) -> Result<Self, Error> {
        if !(120..=8192).contains(&w) || !(120..=8192).contains(&h) {
            return Err(ModelError::Parameter {
                name: "size",
                value: format!("{what} plot {w} x {h} px"),
                reason: "each side must be 120..=8192".into(),
            }
            .into());
        }
        let mut pm = Pixmap::new(w, h).ok_or_else(|| Error::Encode {
            format: "PNG",
            message: format!("cannot allocate a {what} plot of {w} x {h} px"),
        })?;
        pm.fill(Color::WHITE);
        Ok(Self { pm, texts: Vec::new() })
    }

    /// Width, px.
    pub fn w(&self) -> f32 {
        self.pm.width() as f32
    }

    /// Height, px.
    pub fn h(&self) -> f32 {
        self.pm.height() as f32
    }

    /// The canvas as PNG bytes.
    pub fn png(&self) -> Result<Vec<u8>, Error> {
        self.pm.encode_png().map_err(|e| Error::Encode {
            format: "PNG",
            message: e.to_string(),
        })
    }

    /// The PNG bytes and the boxes of the texts drawn.
    pub fn finish(self) -> Result<Plot, Error> {
        let png = self.png()?;
        Ok(Plot { png, texts: self.texts })
    }

    /// Stroke a polyline (at least two points).
    pub fn polyline(&mut self, pts: &[(f32, f32)], rgb: [u8; 3], width: f32, dashed: bool) {
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

    /// A straight stroke.
    pub fn line(&mut self, x0: f32, y0: f32, x1: f32, y1: f32, rgb: [u8; 3], width: f32) {
        self.polyline(&[(x0, y0), (x1, y1)], rgb, width, false);
    }

    /// A filled disc, optionally outlined.
    pub fn circle(&mut self, x: f32, y: f32, r: f32, fill: [u8; 3], outline: Option<[u8; 3]>) {
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

    /// A circle outline.
    pub fn ring(&mut self, x: f32, y: f32, r: f32, rgb: [u8; 3], width: f32) {
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
    pub fn rect(&mut self, x0: i32, y0: i32, x1: i32, y1: i32, rgb: [u8; 3]) {
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
    pub fn frame(&mut self, x0: f32, y0: f32, x1: f32, y1: f32, rgb: [u8; 3]) {
        let (x0, y0, x1, y1) = (x0.round() + 0.5, y0.round() + 0.5, x1.round() - 0.5, y1.round() - 0.5);
        self.polyline(&[(x0, y0), (x1, y0), (x1, y1), (x0, y1), (x0, y0)], rgb, 1.0, false);
    }

    /// Text anchored horizontally by `align` at x and vertically centred on
    /// `yc`; with a white box behind it when `bg`. Returns its box.
    #[allow(clippy::too_many_arguments)]
    pub fn text(&mut self, x: f32, yc: f32, s: &str, scale: u32, align: Align, rgb: [u8; 3], bg: bool) -> [f32; 4] {
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
        let b = [x0, y0, x0 + tw, y0 + th];
        self.texts.push(TextBox {
            text: s.to_string(),
            rect: b,
        });
        b
    }

    /// Text rotated to read bottom to top, centred on (xc, yc).
    pub fn text_vertical(&mut self, xc: f32, yc: f32, s: &str, scale: u32, rgb: [u8; 3]) {
        let tw = font::text_width(s, scale) as f32;
        let th = font::text_height(scale) as f32;
        let x0 = (xc - th / 2.0).round() as i32;
        let y0 = (yc + tw / 2.0).round() as i32;
        font::draw_text_vertical(&mut self.pm, x0, y0, s, scale, rgb);
        self.texts.push(TextBox {
            text: s.to_string(),
            rect: [x0 as f32, y0 as f32 - tw, x0 as f32 + th, y0 as f32],
        });
    }

    /// "no data" in large letters on a white box, centred in the rectangle
    /// `left, top, right, bottom` (px): what a plot with nothing to draw says.
    pub fn no_data(&mut self, left: f32, top: f32, right: f32, bottom: f32) {
        let (x, y) = (left + (right - left) / 2.0, top + (bottom - top) / 2.0);
        self.text(x, y, "no data", 3, Align::Center, INK, true);
    }

    /// The title, centred at the top (scale 2, shortened to fit).
    pub fn title(&mut self, title: &str) {
        let max_chars = ((self.w() - 20.0) / 12.0).max(4.0) as usize;
        let t: String = if title.chars().count() > max_chars {
            title.chars().take(max_chars - 3).chain("...".chars()).collect()
        } else {
            title.to_string()
        };
        let w = self.w();
        // Bold: the same text twice, one pixel apart (one box, one pixel wider).
        let b = self.text(w / 2.0, 18.0, &t, 2, Align::Center, INK, false);
        font::draw_text(&mut self.pm, b[0] as i32 + 1, b[1] as i32, &t, 2, INK);
        if let Some(last) = self.texts.last_mut() {
            last.rect[2] += 1.0;
        }
    }
}

/// `text` at scale 2 within `room` px: as it is when it fits, else cut at a
/// character boundary and ended with "...".
pub(super) fn fit_text(text: &str, room: f32) -> String {
    if font::text_width(text, 2) as f32 <= room {
        return text.to_string();
    }
    let mut out = String::new();
    for ch in text.chars() {
        let next = format!("{out}{ch}...");
        if font::text_width(&next, 2) as f32 > room {
            break;
        }
        out.push(ch);
    }
    format!("{}...", out.trim_end())
}

/// Legend entries laid out left to right from (x, y), wrapping at `max_x`;
/// returns the height used. `dry` measures without drawing.
pub(super) fn legend(cv: &mut Canvas, series: &[Series], x: f32, y: f32, max_x: f32, dry: bool) -> f32 {
    const ROW: f32 = 24.0;
    const SWATCH: f32 = 30.0;
    if series.is_empty() {
        return 0.0;
    }
    let (mut cx, mut cy) = (x, y + ROW / 2.0);
    // A label longer than a whole row is shortened to fit it, ending in "...".
    let room = (max_x - x - SWATCH - 8.0).max(0.0);
    for s in series {
        let label = fit_text(&s.label, room);
        let item = SWATCH + 8.0 + font::text_width(&label, 2) as f32 + 24.0;
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
                        for gap in [9.0, 23.0] {
                            cv.rect(
                                (cx + gap) as i32,
                                (cy - 2.0) as i32,
                                (cx + gap + 5.0) as i32,
                                (cy + 3.0) as i32,
                                WHITE,
                            );
                        }
                    }
                }
                SeriesStyle::Markers => {
                    for k in 0..3 {
                        cv.circle(cx + 5.0 + 10.0 * k as f32, cy, 3.0, s.color, None);
                    }
                }
            }
            cv.text(cx + SWATCH + 8.0, cy, &label, 2, Align::Left, INK, false);
        }
        cx += item;
    }
    cy + ROW / 2.0 - y
}

#[cfg(test)]
mod fit_tests {
    use super::*;

    /// A legend label keeps its text when it fits, else is cut to fit and says so.
    #[test]
    fn labels_longer_than_a_row_are_cut_to_fit() {
        assert_eq!(fit_text("pbrt", 400.0), "pbrt");
        let long = "babylon: squared candela x file-generation type (Babylon.js < 9.23.0, before PR #18833)";
        let cut = fit_text(long, 500.0);
        assert!(cut.ends_with("...") && cut.len() < long.len(), "{cut}");
        assert!(font::text_width(&cut, 2) as f32 <= 500.0, "{cut}");
        assert!(long.starts_with(cut.trim_end_matches("...")));
    }
}
