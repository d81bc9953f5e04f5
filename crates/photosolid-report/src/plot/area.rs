//! The rectangular plot area shared by the x-y plots ([`super::scatter()`],
//! [`super::line_chart()`]): value axes fitted to the data, the mapping onto
//! pixels, and the grid with its tick labels.

use super::axis::{nice_step, Axis};
use super::canvas::{Align, Canvas};
use super::{AXIS, GRID, INK};
use crate::font;

/// The plot area's left edge, px, in an image `width` px wide: room for the
/// y label, then the widest of `y_ticks`' labels (at least 72 px, at most a third).
pub(super) fn left_margin(y_ticks: &[(f64, String)], width: f32) -> f32 {
    let tick_w = y_ticks.iter().map(|(_, l)| font::text_width(l, 2)).max().unwrap_or(0) as f32;
    (30.0 + 12.0 + tick_w + 12.0).max(72.0).min(width / 3.0)
}

/// Ratio of the largest to the smallest positive ordinate from which the y
/// axis is drawn logarithmic.
const LOG_Y_RATIO: f64 = 20.0;

/// The plot area in pixels and the value axes mapped onto it.
pub(super) struct Area {
    /// Left edge, px.
    pub left: f32,
    /// Top edge, px.
    pub top: f32,
    /// Right edge, px.
    pub right: f32,
    /// Bottom edge, px.
    pub bottom: f32,
    /// The abscissa.
    pub x_axis: Axis,
    /// The ordinate.
    pub y_axis: Axis,
}

impl Area {
    /// Pixel column of abscissa `x`.
    pub fn px(&self, x: f64) -> f32 {
        self.left + self.x_axis.t(x) as f32 * (self.right - self.left)
    }

    /// Pixel row of ordinate `y`.
    pub fn py(&self, y: f64) -> f32 {
        self.bottom - self.y_axis.t(y) as f32 * (self.bottom - self.top)
    }

    /// Whether box `b` lies inside the area, 2 px from its edges.
    pub fn holds(&self, b: &[f32; 4]) -> bool {
        b[0] >= self.left + 2.0 && b[2] <= self.right - 2.0 && b[1] >= self.top + 2.0 && b[3] <= self.bottom - 2.0
    }
}

/// The x axis over the finite abscissae `xs` (log10 of them when `log_x`;
/// all > 0 then), padded so that no point sits on the frame.
pub(super) fn x_axis_over(xs: &[f64], log_x: bool) -> Axis {
    let xv = |x: f64| if log_x { x.log10() } else { x };
    let (mut xa, mut xb) = xs.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
        (a.min(xv(x)), b.max(xv(x)))
    });
    if xs.is_empty() {
        (xa, xb) = if log_x { (0.0, 2.0) } else { (0.0, 1.0) };
    }
    if xb - xa < 1e-12 * xa.abs().max(1e-300) || xb <= xa {
        let d = if log_x { 0.5 } else { xa.abs().max(1e-300) * 0.5 };
        let d = if d > 0.0 && d.is_finite() { d } else { 1.0 };
        (xa, xb) = (xa - d, xb + d);
    }
    let pad = (xb - xa) * 0.08;
    // The padding never takes a linear axis of non-negative data below 0
    // (degrees 2..32 would otherwise start at -10).
    let floor = if !log_x && xs.iter().all(|&x| x >= 0.0) {
        0.0
    } else {
        f64::NEG_INFINITY
    };
    let (xa, xb) = ((xa - pad).max(floor), xb + pad);
    if log_x {
        Axis {
            lo: xa,
            hi: xb,
            log: true,
        }
    } else {
        let s = nice_step(xb - xa, 6);
        Axis {
            lo: (xa / s).floor() * s,
            hi: (xb / s).ceil() * s,
            log: false,
        }
    }
}

/// The y axis over the finite ordinates `ys`: from 0 when none is negative,
/// logarithmic when all are positive and span [`LOG_Y_RATIO`] or more.
pub(super) fn y_axis_over(ys: &[f64]) -> Axis {
    let (mut ya, mut yb) = ys
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &y| (a.min(y), b.max(y)));
    if ys.is_empty() {
        (ya, yb) = (0.0, 1.0);
    }
    // Errors spanning more than LOG_Y_RATIO (a fitted model next to filters)
    // would sit on the floor of a linear axis: log axis then.
    let log_y = ya > 0.0 && yb / ya >= LOG_Y_RATIO;
    if log_y {
        let (la, lb) = (ya.log10(), yb.log10());
        let pad = (lb - la) * 0.08;
        Axis {
            lo: la - pad,
            hi: lb + pad,
            log: true,
        }
    } else {
        if ya >= 0.0 {
            ya = 0.0;
        }
        if yb <= ya {
            yb = if ya == 0.0 { 1.0 } else { ya + ya.abs() };
        }
        let yb = yb + (yb - ya) * 0.08;
        let s = nice_step(yb - ya, 6);
        Axis {
            lo: (ya / s).floor() * s,
            hi: (yb / s).ceil() * s,
            log: false,
        }
    }
}

/// The axes of an x-y plot: [`draw_grid`], the frame, `x_label` centred
/// under the area and `y_label` written upwards at the left edge.
pub(super) fn draw_axes(cv: &mut Canvas, area: &Area, y_ticks: Vec<(f64, String)>, x_label: &str, y_label: &str) {
    let (left, top, right, bottom) = (area.left, area.top, area.right, area.bottom);
    draw_grid(cv, area, y_ticks);
    cv.frame(left, top, right + 1.0, bottom + 1.0, AXIS);
    let h = cv.h();
    cv.text(
        left + (right - left) / 2.0,
        h - 16.0,
        x_label,
        2,
        Align::Center,
        INK,
        false,
    );
    cv.text_vertical(16.0, top + (bottom - top) / 2.0, y_label, 2, INK);
}

/// Grid lines, tick marks and tick labels of both axes (`y_ticks` as
/// `area.y_axis` gives them); minor ticks are shorter, their lines lighter.
pub(super) fn draw_grid(cv: &mut Canvas, area: &Area, y_ticks: Vec<(f64, String)>) {
    let Area {
        left,
        top,
        right,
        bottom,
        ..
    } = *area;
    for (t, lab) in area.x_axis.ticks() {
        let x = area.px(t).round() + 0.5;
        let major = !lab.is_empty();
        cv.line(x, top, x, bottom, if major { GRID } else { [240, 240, 240] }, 1.0);
        cv.line(x, bottom, x, bottom + if major { 6.0 } else { 3.0 }, AXIS, 1.0);
        if major {
            cv.text(x, bottom + 16.0, &lab, 2, Align::Center, INK, false);
        }
    }
    for (t, lab) in y_ticks {
        let y = area.py(t).round() + 0.5;
        let major = !lab.is_empty();
        cv.line(left, y, right, y, if major { GRID } else { [240, 240, 240] }, 1.0);
        cv.line(left - if major { 6.0 } else { 3.0 }, y, left, y, AXIS, 1.0);
        if major {
            cv.text(left - 10.0, y, &lab, 2, Align::Right, INK, false);
        }
    }
}

#[cfg(test)]
mod axis_tests {
    use super::*;

    /// A linear axis of non-negative data starts at 0 at the lowest, never below.
    #[test]
    fn a_linear_axis_of_non_negative_data_does_not_start_below_zero() {
        for xs in [vec![2.0, 4.0, 8.0, 16.0, 32.0], vec![0.0, 1.0], vec![2.0, 3.0]] {
            let a = x_axis_over(&xs, false);
            assert!(
                a.lo >= 0.0 && a.lo <= xs[0] && a.hi >= *xs.last().unwrap(),
                "{xs:?}: {} .. {}",
                a.lo,
                a.hi
            );
        }
        let a = x_axis_over(&[-5.0, 5.0], false);
        assert!(a.lo < -5.0);
    }
}
