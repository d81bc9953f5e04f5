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
        .map(|&(x, y, l)| ScatterPoint { label: l.into(), x, y })
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
    // The points' discs, below the legend row at the top: blue, and the Pareto
    // front's red ring (here "a", lowest on both axes, is on it).
    let mut centres: Vec<(f64, f64)> = blobs(&pixels_like(&pm, [70, 120, 180], 10))
        .into_iter()
        .chain(blobs(&pixels_like(&pm, [214, 39, 40], 10)))
        .filter(|c| c.1 > 64.0)
        .collect();
    centres.sort_by(|a, b| a.0.total_cmp(&b.0));
    assert_eq!(centres.len(), 4, "{centres:?}");
    for k in 0..2 {
        let dy = centres[k].1 - centres[k + 1].1;
        assert!(dy > 30.0, "points {k} and {} are {dy} px apart: {centres:?}", k + 1);
    }
}

// Issue 27 item 6: maps and plots that can be read.

use photosolid::report::plot::{
    contour_levels, isolux_plot, line_chart_plot, scatter_plot, texture_preview_plot, IsoluxSpec, LineSpec, MapAxis,
    MapQuantity, Plot, TexturePreview,
};

/// Every text box inside the image and clear of every other one.
fn assert_legible(plot: &Plot, what: &str) {
    let pm = Pixmap::decode_png(&plot.png).unwrap();
    let (w, h) = (pm.width() as f32, pm.height() as f32);
    assert!(!plot.texts.is_empty(), "{what}: no texts recorded");
    for t in &plot.texts {
        let r = t.rect;
        assert!(
            r[0] >= 0.0 && r[1] >= 0.0 && r[2] <= w && r[3] <= h,
            "{what}: {:?} at {r:?} leaves the {w} x {h} image",
            t.text
        );
    }
    for (i, a) in plot.texts.iter().enumerate() {
        for b in &plot.texts[i + 1..] {
            let (p, q) = (a.rect, b.rect);
            let apart = p[2] <= q[0] || q[2] <= p[0] || p[3] <= q[1] || q[3] <= p[1];
            assert!(apart, "{what}: {:?} at {p:?} overlaps {:?} at {q:?}", a.text, b.text);
        }
    }
}

fn is_1_2_5(v: f64) -> bool {
    let e = v.log10().floor();
    let m = v / 10f64.powf(e);
    [1.0, 2.0, 5.0, 10.0].iter().any(|x| (m - x).abs() < 1e-9)
}

/// A wall (12 × 3 m, u along x, v along z) lit by four luminaires in two
/// pairs that project onto the same two spots, and a road (40 x 7 m): texts
/// apart and inside, axes in metres, a colour bar in lx, E_avg, 1-2-5 contours.
#[test]
fn isolux_maps_are_legible() {
    let (nu, nv) = (24, 6);
    let values: Vec<f64> = (0..nu * nv)
        .map(|k| {
            let (i, j) = ((k % nu) as f64, (k / nu) as f64);
            5.0 + 90.0 * (-((i - 6.0).powi(2) + (j - 2.0).powi(2)) / 20.0).exp()
                + 40.0 * (-((i - 18.0).powi(2)) / 10.0).exp()
        })
        .collect();
    let emax = values.iter().copied().fold(0.0, f64::max);
    let emin = values.iter().copied().fold(f64::INFINITY, f64::min);
    let marks = [(0.25, 0.9), (0.25, 0.9), (0.75, 0.9), (0.751, 0.9), (2.0, 0.5)];
    let wall = isolux_plot(&IsoluxSpec {
        quantity: MapQuantity::ILLUMINANCE,
        name: "a wall with a long name, facing the four wall washers of the test",
        values: &values,
        grid: (nu, nv),
        size_m: (12.0, 3.0),
        e_avg_lux: values.iter().sum::<f64>() / values.len() as f64,
        u_axis: MapAxis {
            start: -6.0,
            end: 6.0,
            title: "x (m)".into(),
        },
        v_axis: MapAxis {
            start: 0.0,
            end: 3.0,
            title: "z (m)".into(),
        },
        marks: &marks,
        limits: &[],
    })
    .unwrap();
    std::fs::write(std::env::temp_dir().join("photosolid_isolux_wall.png"), &wall.png).unwrap();
    assert_legible(&wall, "wall map");
    let texts: Vec<&str> = wall.texts.iter().map(|t| t.text.as_str()).collect();
    for want in ["x (m)", "z (m)", "lx", "L1/L2", "L3/L4", "-6", "6"] {
        assert!(texts.contains(&want), "{want:?} missing from {texts:?}");
    }
    assert!(texts.iter().any(|t| t.contains("E_avg")), "{texts:?}");
    assert!(texts.iter().any(|t| t.contains("beyond the map: L5")), "{texts:?}");
    let levels = contour_levels(emin, emax);
    assert!(
        !levels.is_empty() && levels.iter().all(|&v| is_1_2_5(v) && v > emin && v < emax),
        "{levels:?}"
    );
    let footer = texts.iter().find(|t| t.starts_with("contours")).unwrap();
    assert!(footer.contains("10, 20, 50 lx"), "{footer}");
    // A road, as in data/road_scene.toml: 40 x 7 m, 16 x 3 points.
    let road: Vec<f64> = (0..48).map(|k| 1.0 + f64::from(k % 16) * 1.7).collect();
    let plot = isolux_plot(&IsoluxSpec {
        quantity: MapQuantity::ILLUMINANCE,
        name: "road",
        values: &road,
        grid: (16, 3),
        size_m: (40.0, 7.0),
        e_avg_lux: 13.75,
        u_axis: MapAxis {
            start: -20.0,
            end: 20.0,
            title: "x (m)".into(),
        },
        v_axis: MapAxis {
            start: 0.0,
            end: 7.0,
            title: "y (m)".into(),
        },
        marks: &[(0.125, -1.0 / 7.0), (0.875, -1.0 / 7.0)],
        limits: &[],
    })
    .unwrap();
    assert_legible(&plot, "road map");
    for l in [1.0, 2.0, 5.0, 10.0, 20.0, 50.0, 100.0] {
        assert_eq!(contour_levels(0.5, 26.5).contains(&l), l < 26.5, "{l}");
    }
}

/// The memory-vs-accuracy scatter of a trade table with many close points:
/// the names never pile on each other and stay in the image.
#[test]
fn crowded_scatter_names_do_not_overlap() {
    let filters = ["nearest", "bilinear", "catmull-rom", "mitchell", "bspline", "pchip"];
    let mut pts = Vec::new();
    for (i, f) in filters.iter().enumerate() {
        for (j, x) in [1, 2, 5].iter().enumerate() {
            for (k, lookup) in ["bilinear", "nearest"].iter().enumerate() {
                pts.push(ScatterPoint {
                    label: format!("{f}@x{x}/{lookup}"),
                    x: 40_000.0 * f64::from(*x).powi(2) * (1.0 + 0.01 * k as f64),
                    y: 0.5 + 0.02 * i as f64 + 0.01 * j as f64 + 0.005 * k as f64,
                });
            }
        }
    }
    let plot = scatter_plot(&ScatterSpec {
        title: "Memory vs accuracy",
        x_label: "bytes held",
        y_label: "Hausdorff distance (% of I_max)",
        points: &pts,
        log_x: true,
        ..ScatterSpec::default()
    })
    .unwrap();
    std::fs::write(std::env::temp_dir().join("photosolid_scatter_crowded.png"), &plot.png).unwrap();
    assert_legible(&plot, "scatter");
    let names = plot.texts.iter().filter(|t| t.text.contains('@')).count();
    assert!(names >= pts.len() / 2, "only {names} of {} names shown", pts.len());
}

/// The texture preview says what its exposure does, and its colour bar's
/// candela ticks sit where the tone curve puts them.
#[test]
fn texture_preview_explains_its_exposure() {
    use photosolid::reconstruct::{render, Filter, LightTexture};
    let lum = photosolid::load(std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("data/roadway.ldt")).unwrap();
    let tex = LightTexture::new(lum.distribution()).unwrap();
    let r = render(&tex, Filter::CatmullRom, 5).unwrap();
    let plot = texture_preview_plot(&TexturePreview::new(&r)).unwrap();
    assert_legible(&plot, "texture preview");
    assert!(
        plot.texts
            .iter()
            .any(|t| t.text.contains("exposure k = 4") && t.text.contains("1-exp(-k I/I_max)")),
        "{:?}",
        plot.texts
    );
    // The tick "2000" (cd) is at tone_map(2000 / I_max) up the bar (rows 56 .. h - 62).
    let pm = Pixmap::decode_png(&plot.png).unwrap();
    let (top, bottom) = (56.0, pm.height() as f64 - 62.0);
    let tick = plot.texts.iter().find(|t| t.text == "2000").expect("a 2000 cd tick");
    let yc = f64::from(tick.rect[1] + tick.rect[3]) / 2.0;
    let want = bottom - photosolid::report::plot::tone_map(2000.0 / r.i_max_cd, 4.0) * (bottom - top);
    assert!((yc - want).abs() <= 2.0, "tick at {yc}, the curve puts it at {want}");
}

/// Values against a parameter (the error-vs-L figure): six series whose
/// legend wraps, every text inside and apart, 1-2-5 ticks on the log axis
/// their span asks for, each series drawn in its colour; empty and
/// non-finite input says "no data" instead of failing.
#[test]
fn line_chart_is_legible() {
    let degrees = [2.0, 4.0, 8.0, 16.0];
    let mut series = Vec::new();
    for (k, what) in ["radial max", "radial RMS", "Hausdorff H"].iter().enumerate() {
        for half in [false, true] {
            series.push(Series {
                label: format!("{what}{}", if half { " (+f16)" } else { "" }),
                points: degrees
                    .iter()
                    .map(|&l| (l, 60.0 / (1.0 + k as f64) / l * if half { 1.05 } else { 1.0 }))
                    .collect(),
                color: palette(k),
                style: if half { SeriesStyle::Dashed } else { SeriesStyle::Line },
            });
        }
    }
    let plot = line_chart_plot(&LineSpec {
        title: "Spherical harmonics: error against degree L (truth)",
        x_label: "degree L",
        y_label: "error (% of I_max)",
        series: &series,
        ..LineSpec::default()
    })
    .unwrap();
    std::fs::write(std::env::temp_dir().join("photosolid_line_chart.png"), &plot.png).unwrap();
    assert_legible(&plot, "line chart");
    for s in &series {
        assert!(
            plot.texts.iter().any(|t| t.text == s.label),
            "legend lacks {:?}",
            s.label
        );
    }
    // 1.25 ... 31.5 spans more than 20x: a log axis, labelled at the powers of ten
    // (the linear x axis has 0, 5, 10, 15, 20; a linear y axis would have no 1).
    let ticks: Vec<f64> = plot.texts.iter().filter_map(|t| t.text.parse::<f64>().ok()).collect();
    assert!(ticks.contains(&1.0) && ticks.contains(&10.0), "{ticks:?}");
    let pm = Pixmap::decode_png(&plot.png).unwrap();
    for k in 0..3 {
        let rgb = palette(k);
        let n = pm
            .pixels()
            .iter()
            .filter(|p| [p.red(), p.green(), p.blue()] == rgb)
            .count();
        assert!(n > 20, "series {k}: {n} px of {rgb:?}");
    }
    for (what, points) in [
        ("empty", vec![]),
        ("non-finite", vec![(f64::NAN, 1.0), (1.0, f64::INFINITY)]),
    ] {
        let s = [Series {
            label: what.into(),
            points,
            color: palette(0),
            style: SeriesStyle::Line,
        }];
        let plot = line_chart_plot(&LineSpec {
            series: &s,
            ..LineSpec::default()
        })
        .unwrap();
        assert!(plot.texts.iter().any(|t| t.text == "no data"), "{what}");
    }
}
