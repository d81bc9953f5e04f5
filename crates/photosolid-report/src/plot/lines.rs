//! Values against a parameter: one or more series of (x, y) points joined by
//! lines, each point marked (e.g. a representation's error against its
//! degree).

use crate::error::Error;

use super::area::{draw_axes, left_margin, x_axis_over, y_axis_over, Area};
use super::canvas::{finite2, legend, Canvas};
use super::{Plot, Series, SeriesStyle, SCATTER_SIZE};

/// What [`line_chart()`] draws. `Default` gives an empty 800 × 550 px plot.
#[derive(Debug, Clone, Copy)]
pub struct LineSpec<'a> {
    /// Title at the top.
    pub title: &'a str,
    /// Abscissa title with its unit, e.g. "degree L".
    pub x_label: &'a str,
    /// Ordinate title with its unit, e.g. "radial error (% of I_max)".
    pub y_label: &'a str,
    /// The series: [`SeriesStyle::Line`] and [`SeriesStyle::Dashed`] are
    /// joined in x order, [`SeriesStyle::Markers`] are not; every point is marked.
    pub series: &'a [Series],
    /// Width × height, px (each 120..=8192).
    pub size: (u32, u32),
}

impl Default for LineSpec<'_> {
    fn default() -> Self {
        Self {
            title: "",
            x_label: "",
            y_label: "",
            series: &[],
            size: SCATTER_SIZE,
        }
    }
}

/// Series against a parameter, `spec.size` px, with a legend under the
/// title. The x axis is linear over the points; the y axis starts at 0 when
/// no value is negative and is logarithmic when all are positive and span a
/// ratio of 20 or more (as [`super::scatter()`]'s). Non-finite points are
/// skipped; nothing to draw gives a plot that says "no data".
///
/// # Errors
/// [`crate::error::ModelError::Parameter`] for a size outside 120..=8192 px, [`Error::Encode`] if encoding fails.
pub fn line_chart(spec: &LineSpec) -> Result<Vec<u8>, Error> {
    Ok(line_chart_plot(spec)?.png)
}

/// [`line_chart()`] with the boxes of its texts ([`Plot`]).
///
/// # Errors
/// As [`line_chart()`].
pub fn line_chart_plot(spec: &LineSpec) -> Result<Plot, Error> {
    let LineSpec {
        title,
        x_label,
        y_label,
        series,
        size: (w, h),
    } = *spec;
    let mut cv = Canvas::new(w, h, "line chart")?;
    let (wf, hf) = (cv.w(), cv.h());
    cv.title(title);
    // Points in x order, non-finite ones dropped (a log axis needs y > 0, which the axis checks).
    let curves: Vec<Vec<(f64, f64)>> = series
        .iter()
        .map(|s| {
            let mut pts: Vec<(f64, f64)> = s.points.iter().copied().filter(finite2).collect();
            pts.sort_by(|a, b| a.0.total_cmp(&b.0));
            pts
        })
        .collect();
    let all = || curves.iter().flatten();
    let x_axis = x_axis_over(&all().map(|p| p.0).collect::<Vec<_>>(), false);
    let y_axis = y_axis_over(&all().map(|p| p.1).collect::<Vec<_>>());
    let y_ticks = y_axis.ticks();
    let left = left_margin(&y_ticks, wf);
    let right = wf - 30.0;
    // The legend sits between the title and the plot area, as many rows as it needs.
    let legend_h = legend(&mut cv, series, left, 44.0, right, true);
    let (top, bottom) = (52.0 + legend_h + 8.0, hf - 64.0);
    let area = Area {
        left,
        top,
        right,
        bottom,
        x_axis,
        y_axis,
    };
    draw_axes(&mut cv, &area, y_ticks, x_label, y_label);
    legend(&mut cv, series, left, 44.0, right, false);
    for (s, pts) in series.iter().zip(&curves) {
        let px: Vec<(f32, f32)> = pts.iter().map(|&(x, y)| (area.px(x), area.py(y))).collect();
        if s.style != SeriesStyle::Markers {
            cv.polyline(&px, s.color, 2.0, s.style == SeriesStyle::Dashed);
        }
        for &(x, y) in &px {
            cv.circle(x, y, 4.0, s.color, None);
        }
    }
    if all().next().is_none() {
        cv.no_data(left, top, right, bottom);
    }
    cv.finish()
}
