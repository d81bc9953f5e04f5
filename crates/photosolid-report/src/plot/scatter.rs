//! Cost versus error of several methods, with the Pareto front.

use crate::error::Error;
use crate::font;

use super::area::{draw_axes, left_margin, x_axis_over, y_axis_over, Area};
use super::canvas::{Align, Canvas};
use super::{Plot, ScatterPoint, AXIS, INK, OTHER, PARETO, SCATTER_SIZE};

/// A label's anchor (x, y), alignment and box.
type Spot = (f32, f32, Align, [f32; 4]);

/// What [`scatter()`] draws. `Default` gives an empty 800 × 550 px plot with a
/// linear x axis.
#[derive(Debug, Clone, Copy)]
pub struct ScatterSpec<'a> {
    /// Title at the top.
    pub title: &'a str,
    /// Abscissa title with its unit, e.g. "time per sample (ns)".
    pub x_label: &'a str,
    /// Ordinate title with its unit, e.g. "RMS error (% of I_max)".
    pub y_label: &'a str,
    /// The named points.
    pub points: &'a [ScatterPoint],
    /// Logarithmic x axis (points with x ≤ 0 are then skipped).
    pub log_x: bool,
    /// Width × height, px (each 120..=8192).
    pub size: (u32, u32),
}

impl Default for ScatterSpec<'_> {
    fn default() -> Self {
        Self {
            title: "",
            x_label: "",
            y_label: "",
            points: &[],
            log_x: false,
            size: SCATTER_SIZE,
        }
    }
}

/// Cost–error scatter, `spec.size` px: x = e.g. time per sample (log axis when
/// `log_x`; points with x ≤ 0 are then skipped), y = e.g. RMS error. Every
/// point is named; Pareto-optimal points are drawn larger in red and joined
/// by the Pareto front, a staircase through them in x order (lower is better
/// on both axes). The y axis starts at 0 when all y are non-negative, and is
/// logarithmic when all y are positive and span a ratio of 20 or more.
/// Names are placed where they overlap no other name, point or front.
///
/// # Errors
/// [`crate::error::ModelError::Parameter`] for a size outside 120..=8192 px, [`Error::Encode`] if encoding fails.
pub fn scatter(spec: &ScatterSpec) -> Result<Vec<u8>, Error> {
    Ok(scatter_plot(spec)?.png)
}

/// [`scatter()`] with the boxes of its texts ([`Plot`]).
///
/// # Errors
/// As [`scatter()`].
pub fn scatter_plot(spec: &ScatterSpec) -> Result<Plot, Error> {
    let ScatterSpec {
        title,
        x_label,
        y_label,
        points,
        log_x,
        size: (w, h),
    } = *spec;
    let mut cv = Canvas::new(w, h, "scatter")?;
    let (wf, hf) = (cv.w(), cv.h());
    cv.title(title);
    let (top, right, bottom) = (64.0f32, wf - 30.0, hf - 64.0);

    let shown: Vec<&ScatterPoint> = points
        .iter()
        .filter(|p| p.x.is_finite() && p.y.is_finite() && (!log_x || p.x > 0.0))
        .collect();
    let marked = front_of(&shown);
    let pts: Vec<&Marked> = marked.iter().collect();
    let x_axis = x_axis_over(&pts.iter().map(|p| p.x).collect::<Vec<_>>(), log_x);
    let y_axis = y_axis_over(&pts.iter().map(|p| p.y).collect::<Vec<_>>());
    // Left margin: the y label, then the widest tick label.
    let y_ticks = y_axis.ticks();
    let left = left_margin(&y_ticks, wf);
    let area = Area {
        left,
        top,
        right,
        bottom,
        x_axis,
        y_axis,
    };

    draw_axes(&mut cv, &area, y_ticks, x_label, y_label);
    draw_legend(&mut cv, right, top);

    let stair = pareto_stair(&pts, &area);
    cv.polyline(&stair, PARETO, 2.0, false);
    // Points: others first, Pareto on top.
    let scale = if pts.len() <= 12 { 2 } else { 1 };
    let mut order: Vec<&&Marked> = pts.iter().collect();
    order.sort_by_key(|p| p.pareto);
    let boxes = obstacles(&pts, &area, &stair);
    draw_points(&mut cv, &area, &order);
    let left_out = draw_labels(&mut cv, &area, &order, boxes, scale);
    if left_out > 0 {
        let note = format!(
            "{left_out} {} not shown (no room)",
            if left_out == 1 { "name" } else { "names" }
        );
        cv.text(left, top - 16.0, &note, 2, Align::Left, INK, false);
    }
    if pts.is_empty() {
        cv.no_data(left, top, right, bottom);
    }
    cv.finish()
}

/// The legend above the plot area, right-aligned at `right`: the Pareto
/// front's line and point, then the other points' marker.
fn draw_legend(cv: &mut Canvas, right: f32, top: f32) {
    let lx = right - font::text_width("Pareto front", 2) as f32;
    cv.text(lx, top - 16.0, "Pareto front", 2, Align::Left, INK, false);
    cv.line(lx - 46.0, top - 16.0, lx - 10.0, top - 16.0, PARETO, 2.0);
    cv.circle(lx - 28.0, top - 16.0, 5.0, PARETO, Some([120, 20, 20]));
    let lx2 = lx - 70.0 - font::text_width("other", 2) as f32;
    cv.text(lx2, top - 16.0, "other", 2, Align::Left, INK, false);
    cv.circle(lx2 - 12.0, top - 16.0, 4.0, OTHER, None);
}

/// A point as drawn: whether it is on the front of this scatter's two axes.
struct Marked<'a> {
    label: &'a str,
    x: f64,
    y: f64,
    pareto: bool,
}

/// `points` marked with the Pareto front of their own two axes (lower is
/// better on both): a point is on it when no other point is as low on both
/// and lower on one. A front over more quantities (time, bytes and error)
/// would mark points another beats on the two axes drawn.
fn front_of<'a>(points: &[&'a ScatterPoint]) -> Vec<Marked<'a>> {
    points
        .iter()
        .map(|p| Marked {
            label: &p.label,
            x: p.x,
            y: p.y,
            pareto: !points
                .iter()
                .any(|q| q.x <= p.x && q.y <= p.y && (q.x < p.x || q.y < p.y)),
        })
        .collect()
}

/// The Pareto front in pixels: a staircase through the Pareto points in x order.
fn pareto_stair(pts: &[&Marked], area: &Area) -> Vec<(f32, f32)> {
    let mut front: Vec<(f64, f64)> = pts.iter().filter(|p| p.pareto).map(|p| (p.x, p.y)).collect();
    front.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut stair = Vec::new();
    for (k, &(x, y)) in front.iter().enumerate() {
        if k > 0 {
            stair.push((area.px(x), area.py(front[k - 1].1)));
        }
        stair.push((area.px(x), area.py(y)));
    }
    stair
}

/// The boxes no name may overlap: every point's, and every step's of the
/// Pareto front (`stair`).
fn obstacles(pts: &[&Marked], area: &Area, stair: &[(f32, f32)]) -> Vec<[f32; 4]> {
    let stair_boxes = stair.windows(2).map(|s| {
        [
            s[0].0.min(s[1].0) - 1.0,
            s[0].1.min(s[1].1) - 1.0,
            s[0].0.max(s[1].0) + 1.0,
            s[0].1.max(s[1].1) + 1.0,
        ]
    });
    pts.iter()
        .map(|p| {
            let (x, y) = (area.px(p.x), area.py(p.y));
            [x - 6.0, y - 6.0, x + 6.0, y + 6.0]
        })
        .chain(stair_boxes)
        .collect()
}

/// The points in drawing `order`: Pareto ones larger, in red.
fn draw_points(cv: &mut Canvas, area: &Area, order: &[&&Marked]) {
    for p in order {
        let (x, y) = (area.px(p.x), area.py(p.y));
        if p.pareto {
            cv.circle(x, y, 6.0, PARETO, Some([120, 20, 20]));
        } else {
            cv.circle(x, y, 4.5, OTHER, None);
        }
    }
}

/// The names of the points in `order`, each at a spot that overlaps none of
/// `boxes` (points, front, names already placed), at text `scale`; returns
/// how many found no room and were left out.
fn draw_labels(cv: &mut Canvas, area: &Area, order: &[&&Marked], mut boxes: Vec<[f32; 4]>, scale: u32) -> usize {
    let th = font::text_height(scale) as f32;
    let mut left_out = 0usize;
    for p in order {
        let (x, y) = (area.px(p.x), area.py(p.y));
        let tw = font::text_width(p.label, scale) as f32;
        // Text boxes keep the white pad of their background (scale + 1 px)
        // clear of every other box.
        let gap = scale as f32 + 2.0;
        let free = |b: &[f32; 4]| {
            boxes
                .iter()
                .all(|o| b[2] + gap <= o[0] || b[0] - gap >= o[2] || b[3] + gap <= o[1] || b[1] - gap >= o[3])
        };
        let near = label_candidates(x, y, tw, th)
            .into_iter()
            .find(|c| area.holds(&c.3) && free(&c.3));
        // Crowded: the free spot of the plot area nearest the point, with a
        // leader line; none at all: the name is left out and counted.
        let pick = near.or_else(|| nearest_free_spot(area, (x, y), (tw, th), &free));
        let Some(pick) = pick else {
            left_out += 1;
            continue;
        };
        // A name moved off its point gets a leader line to the point.
        let b = pick.3;
        let (ex, ey) = (x.clamp(b[0] - 1.0, b[2] + 1.0), y.clamp(b[1] - 1.0, b[3] + 1.0));
        if (ex - x).hypot(ey - y) > 10.0 {
            cv.line(x, y, ex, ey, AXIS, 1.0);
        }
        let bx = cv.text(
            pick.0,
            pick.1,
            p.label,
            scale,
            pick.2,
            if p.pareto { [120, 20, 20] } else { INK },
            true,
        );
        boxes.push(bx);
    }
    left_out
}

/// Spots next to the point (x, y) for a name `tw` × `th` px, in order of
/// preference: right, left, above, below; then right and left shifted up or
/// down by one, two and three text rows, so that neighbours' names never overlap.
fn label_candidates(x: f32, y: f32, tw: f32, th: f32) -> Vec<Spot> {
    let mut cands = vec![
        (
            x + 9.0,
            y,
            Align::Left,
            [x + 9.0, y - th / 2.0, x + 9.0 + tw, y + th / 2.0],
        ),
        (
            x - 9.0,
            y,
            Align::Right,
            [x - 9.0 - tw, y - th / 2.0, x - 9.0, y + th / 2.0],
        ),
        (
            x,
            y - 9.0 - th / 2.0,
            Align::Center,
            [x - tw / 2.0, y - 9.0 - th, x + tw / 2.0, y - 9.0],
        ),
        (
            x,
            y + 9.0 + th / 2.0,
            Align::Center,
            [x - tw / 2.0, y + 9.0, x + tw / 2.0, y + 9.0 + th],
        ),
    ];
    for k in [1.0f32, -1.0, 2.0, -2.0, 3.0, -3.0] {
        let yc = y + k * (th + 4.0);
        cands.push((
            x + 9.0,
            yc,
            Align::Left,
            [x + 9.0, yc - th / 2.0, x + 9.0 + tw, yc + th / 2.0],
        ));
        cands.push((
            x - 9.0,
            yc,
            Align::Right,
            [x - 9.0 - tw, yc - th / 2.0, x - 9.0, yc + th / 2.0],
        ));
    }
    cands
}

/// The `free` spot for a name of size (tw, th) px nearest the point, on a
/// 6 px raster over the plot area; `None` when there is none.
fn nearest_free_spot(
    area: &Area,
    (x, y): (f32, f32),
    (tw, th): (f32, f32),
    free: &dyn Fn(&[f32; 4]) -> bool,
) -> Option<Spot> {
    let mut best: Option<(Spot, f32)> = None;
    let mut gy = area.top + 2.0 + th / 2.0;
    while gy + th / 2.0 <= area.bottom - 2.0 {
        let mut gx = area.left + 2.0;
        while gx + tw <= area.right - 2.0 {
            let b = [gx, gy - th / 2.0, gx + tw, gy + th / 2.0];
            let dx = (b[0] - x).max(x - b[2]).max(0.0);
            let dy = (b[1] - y).max(y - b[3]).max(0.0);
            let d = dx * dx + dy * dy;
            if best.as_ref().is_none_or(|(_, bd)| d < *bd) && free(&b) {
                best = Some(((gx, gy, Align::Left, b), d));
            }
            gx += 6.0;
        }
        gy += 6.0;
    }
    best.map(|(c, _)| c)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The front is the scatter's own: at equal bytes, the lower error wins, whatever a
    /// front over more quantities said (bilinear and mitchell beside catmull-rom).
    #[test]
    fn the_front_is_of_the_two_axes_drawn() {
        let p = |label: &str, x: f64, y: f64| ScatterPoint {
            label: label.into(),
            x,
            y,
        };
        let pts = [
            p("bilinear", 1000.0, 0.9),
            p("catmull-rom", 1000.0, 0.5),
            p("mitchell", 1000.0, 0.6),
            p("sh:4", 100.0, 3.0),
            p("texture", 4000.0, 0.1),
            p("worse", 5000.0, 0.2),
        ];
        let refs: Vec<&ScatterPoint> = pts.iter().collect();
        let on: Vec<&str> = front_of(&refs).iter().filter(|m| m.pareto).map(|m| m.label).collect();
        assert_eq!(on, ["catmull-rom", "sh:4", "texture"]);
    }
}
