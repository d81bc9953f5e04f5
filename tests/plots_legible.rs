//! Plots a lighting engineer can read (issue 12): dense measured points do
//! not hide the curves of a polar diagram, and errors spanning decades are
//! not squashed onto the floor of the speed/accuracy scatter.

use photosolid::report::plot::{
    palette, polar_diagram, scatter, PolarSpec, ScatterPoint, ScatterSpec, Series, SeriesStyle,
};
use tiny_skia::Pixmap;

fn pixels_like(pm: &Pixmap, rgb: [u8; 3], tol: i32) -> Vec<(u32, u32)> {
    let mut v = Vec::new();
    for y in 0..pm.height() {
        for x in 0..pm.width() {
            let c = pm.pixel(x, y).unwrap().demultiply();
            let d = [c.red(), c.green(), c.blue()]
                .iter()
                .zip(rgb)
                .map(|(&a, b)| (i32::from(a) - i32::from(b)).abs())
                .max()
                .unwrap();
            if d <= tol {
                v.push((x, y));
            }
        }
    }
    v
}

fn lobe(g: f64) -> f64 {
    let a = g.abs().to_radians();
    if a < std::f64::consts::FRAC_PI_2 {
        1000.0 * a.cos() * (0.6 + 0.8 * a.sin().powi(2))
    } else {
        0.0
    }
}

/// 721 measured points (0.5° steps, as a 361-angle file gives) on the curve
/// of a reconstruction: most of the curve's pixels stay visible.
#[test]
fn dense_measured_points_leave_the_curves_visible() {
    let gammas: Vec<f64> = (-360..=360).map(|k| f64::from(k) * 0.5).collect();
    let line = Series {
        label: "bilinear".into(),
        points: gammas.iter().map(|&g| (g, lobe(g))).collect(),
        color: palette(1),
        style: SeriesStyle::Line,
    };
    let measured = Series {
        label: "measured".into(),
        points: line.points.clone(),
        color: [0, 0, 0],
        style: SeriesStyle::Markers,
    };
    let alone = Pixmap::decode_png(
        &polar_diagram(&PolarSpec {
            title: "t",
            left: "C180",
            right: "C0",
            unit: "cd",
            series: std::slice::from_ref(&line),
            ..PolarSpec::default()
        })
        .unwrap(),
    )
    .unwrap();
    let both = Pixmap::decode_png(
        &polar_diagram(&PolarSpec {
            title: "t",
            left: "C180",
            right: "C0",
            unit: "cd",
            series: &[line, measured],
            ..PolarSpec::default()
        })
        .unwrap(),
    )
    .unwrap();
    let (n_alone, n_both) = (
        pixels_like(&alone, palette(1), 40).len(),
        pixels_like(&both, palette(1), 40).len(),
    );
    assert!(n_alone > 500, "{n_alone}");
    assert!(
        n_both as f64 >= 0.8 * n_alone as f64,
        "the markers hide the curve: {n_both} of {n_alone} curve pixels visible"
    );
}

/// Connected blobs of `pixels` (8-neighbourhood): their centres (x, y).
fn blobs(pixels: &[(u32, u32)]) -> Vec<(f64, f64)> {
    let set: std::collections::HashSet<(u32, u32)> = pixels.iter().copied().collect();
    let mut seen = std::collections::HashSet::new();
    let mut out = Vec::new();
    for &p in pixels {
        if !seen.insert(p) {
            continue;
        }
        let (mut stack, mut sum, mut n) = (vec![p], (0.0, 0.0), 0.0);
        while let Some((x, y)) = stack.pop() {
            sum = (sum.0 + f64::from(x), sum.1 + f64::from(y));
            n += 1.0;
            for dx in -1i64..=1 {
                for dy in -1i64..=1 {
                    let q = ((x as i64 + dx) as u32, (y as i64 + dy) as u32);
                    if set.contains(&q) && seen.insert(q) {
                        stack.push(q);
                    }
                }
            }
        }
        out.push((sum.0 / n, sum.1 / n));
    }
    out
}

/// Errors of 0.5, 1 and 2 % next to one of 80 %: on a linear axis the three
/// small ones sit within a few pixels of each other; they must be apart.
#[test]
fn errors_spanning_decades_are_spread_out() {
    let pts: Vec<ScatterPoint> = [(10.0, 0.5, "a"), (20.0, 1.0, "b"), (40.0, 2.0, "c"), (80.0, 80.0, "d")]
        .iter()
        .map(|&(x, y, l)| ScatterPoint {
            label: l.into(),
            x,
            y,
            pareto: false,
        })
        .collect();
    let pm = Pixmap::decode_png(
        &scatter(&ScatterSpec {
            title: "t",
            x_label: "ns",
            y_label: "%",
            points: &pts,
            log_x: true,
            ..ScatterSpec::default()
        })
        .unwrap(),
    )
    .unwrap();
    // The points' blue discs, below the legend row at the top.
    let mut centres: Vec<(f64, f64)> = blobs(&pixels_like(&pm, [70, 120, 180], 10))
        .into_iter()
        .filter(|c| c.1 > 64.0)
        .collect();
    centres.sort_by(|a, b| a.0.total_cmp(&b.0));
    assert_eq!(centres.len(), 4, "{centres:?}");
    for k in 0..2 {
        let dy = centres[k].1 - centres[k + 1].1;
        assert!(dy > 30.0, "points {k} and {} are {dy} px apart: {centres:?}", k + 1);
    }
}
