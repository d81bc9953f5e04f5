//! Isolux maps: one PNG per plane receiver, drawn with tiny-skia.
//!
//! False colour (viridis, 0 lx to the receiver's Emax) bilinear between the
//! calculation points (held at the edges), contour lines (marching squares
//! on the point grid) at 1–2–5 × 10^k lux levels, and every luminaire's
//! photometric centre projected onto the plane (a white-ringed black dot
//! with its number, also in the margins around the map). The plane's u edge runs left to right, v bottom to top.

use std::path::{Path, PathBuf};

use glam::DVec3;
use tiny_skia::{Color, Paint, PathBuilder, Pixmap, PremultipliedColorU8, Stroke, Transform};

use super::illuminance::SceneResult;
use super::{ReceiverShape, Scene, SceneError};
use crate::report::font;
use crate::solid::ColorMap;

/// Longest side of the map area, pixels.
pub const MAP_PIXELS: u32 = 800;
/// Margin around the map (title, legend), pixels.
const MARGIN: u32 = 40;

/// Contour levels (lx): the 1–2–5 × 10^k values strictly between `lo` and `hi`, at most about 8.
pub fn contour_levels(lo: f64, hi: f64) -> Vec<f64> {
    if !(hi > 0.0 && hi.is_finite() && hi > lo) {
        return Vec::new();
    }
    let span = hi - lo.max(0.0);
    let step0 = span / 8.0;
    let mag = 10f64.powf(step0.log10().floor());
    let step = [1.0, 2.0, 5.0, 10.0]
        .iter()
        .map(|m| m * mag)
        .find(|s| span / s <= 8.0)
        .unwrap_or(10.0 * mag);
    let mut v = (lo / step).floor() * step + step;
    let mut out = Vec::new();
    while v < hi && out.len() < 16 {
        if v > lo {
            out.push(v);
        }
        v += step;
    }
    out
}

/// The (s, t) plane coordinates in [0, 1]² of world point `p` on the plane
/// `origin + s·u + t·v` (least squares for points off the plane).
fn plane_coords(origin: DVec3, u: DVec3, v: DVec3, p: DVec3) -> (f64, f64) {
    let d = p - origin;
    let (uu, uv, vv) = (u.dot(u), u.dot(v), v.dot(v));
    let (du, dv) = (d.dot(u), d.dot(v));
    let det = uu * vv - uv * uv;
    if det == 0.0 {
        return (f64::NAN, f64::NAN);
    }
    ((du * vv - dv * uv) / det, (dv * uu - du * uv) / det)
}

/// Draw the isolux map of receiver `index` (a plane) with its values `e`
/// (lx, u fastest). Returns PNG bytes; `None` for a point receiver.
pub fn isolux_png(scene: &Scene, index: usize, e: &[f64]) -> Result<Option<Vec<u8>>, SceneError> {
    let r = &scene.receivers[index];
    let ReceiverShape::Plane { origin, u, v, nu, nv } = r.shape else {
        return Ok(None);
    };
    let (lu, lv) = (u.length(), v.length());
    let scale = f64::from(MAP_PIXELS) / lu.max(lv);
    let (w, h) = (
        ((lu * scale).round() as u32).max(1),
        ((lv * scale).round() as u32).max(1),
    );
    let (width, height) = (w + 2 * MARGIN, h + 3 * MARGIN);
    let internal = |m: &str| SceneError::Io {
        path: PathBuf::from(format!("isolux map of {}", r.name)),
        message: m.to_string(),
    };
    let mut pm = Pixmap::new(width, height).ok_or_else(|| internal("image size"))?;
    pm.fill(Color::WHITE);
    let emax = e.iter().copied().fold(0.0, f64::max);
    let emin = e.iter().copied().fold(f64::INFINITY, f64::min);
    // Value at plane coordinates (s, t) in [0, 1]: bilinear between cell centres, held at the edges.
    let at = |s: f64, t: f64| {
        let x = (s * nu as f64 - 0.5).clamp(0.0, (nu - 1) as f64);
        let y = (t * nv as f64 - 0.5).clamp(0.0, (nv - 1) as f64);
        let (i0, j0) = (x.floor() as usize, y.floor() as usize);
        let (i1, j1) = ((i0 + 1).min(nu - 1), (j0 + 1).min(nv - 1));
        let (fx, fy) = (x - i0 as f64, y - j0 as f64);
        let g = |i: usize, j: usize| e[j * nu + i];
        (g(i0, j0) * (1.0 - fx) + g(i1, j0) * fx) * (1.0 - fy) + (g(i0, j1) * (1.0 - fx) + g(i1, j1) * fx) * fy
    };
    let pixels = pm.pixels_mut();
    for py in 0..h {
        for px in 0..w {
            let (s, t) = (
                (f64::from(px) + 0.5) / f64::from(w),
                1.0 - (f64::from(py) + 0.5) / f64::from(h),
            );
            let val = at(s, t);
            let c = ColorMap::Viridis.rgb8(if emax > 0.0 { val / emax } else { 0.0 });
            let idx = ((py + MARGIN) * width + px + MARGIN) as usize;
            pixels[idx] = PremultipliedColorU8::from_rgba(c[0], c[1], c[2], 255).unwrap_or(pixels[idx]);
        }
    }
    // Map plane coordinates to pixels.
    let to_px = |s: f64, t: f64| {
        (
            MARGIN as f32 + (s * f64::from(w)) as f32,
            MARGIN as f32 + ((1.0 - t) * f64::from(h)) as f32,
        )
    };
    // Contours: marching squares between the cell centres.
    let levels = contour_levels(emin, emax);
    let mut pb = PathBuilder::new();
    let centre = |i: usize, j: usize| ((i as f64 + 0.5) / nu as f64, (j as f64 + 0.5) / nv as f64);
    for &level in &levels {
        for j in 0..nv.saturating_sub(1) {
            for i in 0..nu.saturating_sub(1) {
                let corners = [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)];
                let mut crossings = Vec::new();
                for k in 0..4 {
                    let (a, b) = (corners[k], corners[(k + 1) % 4]);
                    let (ea, eb) = (e[a.1 * nu + a.0], e[b.1 * nu + b.0]);
                    if (ea < level) != (eb < level) {
                        let f = (level - ea) / (eb - ea);
                        let (pa, pbb) = (centre(a.0, a.1), centre(b.0, b.1));
                        crossings.push((pa.0 + f * (pbb.0 - pa.0), pa.1 + f * (pbb.1 - pa.1)));
                    }
                }
                for pair in crossings.chunks_exact(2) {
                    let (x0, y0) = to_px(pair[0].0, pair[0].1);
                    let (x1, y1) = to_px(pair[1].0, pair[1].1);
                    pb.move_to(x0, y0);
                    pb.line_to(x1, y1);
                }
            }
        }
    }
    let mut paint = Paint {
        anti_alias: true,
        ..Paint::default()
    };
    paint.set_color_rgba8(255, 255, 255, 230);
    if let Some(path) = pb.finish() {
        let stroke = Stroke {
            width: 1.5,
            ..Stroke::default()
        };
        pm.stroke_path(&path, &paint, &stroke, Transform::identity(), None);
    }
    // Luminaires.
    for (k, l) in scene.luminaires.iter().enumerate() {
        let (s, t) = plane_coords(origin, u, v, l.pose.position);
        if !(s.is_finite() && t.is_finite()) {
            continue;
        }
        let (x, y) = to_px(s, t);
        if !(x >= 0.0 && y >= 0.0 && x < width as f32 && y < height as f32) {
            continue; // beyond the picture's margins
        }
        for (radius, rgb) in [(7.0, [255u8, 255, 255]), (5.0, [0, 0, 0])] {
            if let Some(c) = PathBuilder::from_circle(x, y, radius) {
                paint.set_color_rgba8(rgb[0], rgb[1], rgb[2], 255);
                pm.fill_path(&c, &paint, tiny_skia::FillRule::Winding, Transform::identity(), None);
            }
        }
        font::draw_text(
            &mut pm,
            x as i32 + 9,
            y as i32 - 8,
            &format!("L{}", k + 1),
            2,
            [0, 0, 0],
        );
    }
    let title = format!(
        "{}: Emin {:.3} lx, Emax {:.3} lx, {} x {} points ({:.2} x {:.2} m)",
        r.name, emin, emax, nu, nv, lu, lv
    );
    font::draw_text(&mut pm, MARGIN as i32, 12, &title, 2, [40, 40, 40]);
    let levels_text = if levels.is_empty() {
        "no contour levels (uniform or dark)".to_string()
    } else {
        format!(
            "contours at {} lx; colour 0-{:.1} lx",
            levels.iter().map(|l| format!("{l}")).collect::<Vec<_>>().join(", "),
            emax
        )
    };
    font::draw_text(
        &mut pm,
        MARGIN as i32,
        (h + 2 * MARGIN + 12) as i32,
        &levels_text,
        2,
        [40, 40, 40],
    );
    let png = pm.encode_png().map_err(|e| internal(&e.to_string()))?;
    Ok(Some(png))
}

/// Write `isolux_<k>_<name>.png` for every plane receiver into `dir`; returns the paths.
pub fn write_maps(scene: &Scene, result: &SceneResult, dir: &Path) -> Result<Vec<PathBuf>, SceneError> {
    let io = |p: &Path, e: std::io::Error| SceneError::Io {
        path: p.to_path_buf(),
        message: e.to_string(),
    };
    std::fs::create_dir_all(dir).map_err(|e| io(dir, e))?;
    let mut out = Vec::new();
    for (k, r) in result.receivers.iter().enumerate() {
        let e: Vec<f64> = r.points.iter().map(|p| p.e_lux).collect();
        if let Some(png) = isolux_png(scene, k, &e)? {
            let safe: String = r
                .name
                .chars()
                .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
                .collect();
            let path = dir.join(format!("isolux_{}_{safe}.png", k + 1));
            std::fs::write(&path, png).map_err(|e| io(&path, e))?;
            out.push(path);
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn levels_are_nice_and_inside() {
        assert_eq!(contour_levels(0.0, 10.0), vec![2.0, 4.0, 6.0, 8.0]);
        let l = contour_levels(3.2, 47.0);
        assert!(
            l.iter().all(|&x| x > 3.2 && x < 47.0) && !l.is_empty() && l.len() <= 9,
            "{l:?}"
        );
        assert!(contour_levels(0.0, 0.0).is_empty());
        assert!(contour_levels(5.0, 5.0).is_empty());
    }
}
