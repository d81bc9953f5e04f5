//! PNG plots of reports: valid PNGs for all inputs, geometry, font, data URIs.

use photosolid::report::font;
use std::path::Path;

use photosolid::reconstruct::{render, Filter, LightTexture};
use photosolid::report::plot::{
    heatmap, palette, png_data_uri, polar_diagram, scatter, texture_preview, tone_map, ColorScale, HeatmapSpec,
    PolarSpec, ScatterPoint, ScatterSpec, Series, SeriesStyle, TexturePreview, DEFAULT_EXPOSURE, HEATMAP_SIZE,
    POLAR_SIZE, SCATTER_SIZE, TEXTURE_SIZE,
};
use photosolid::solid::ColorMap;
use tiny_skia::Pixmap;

/// Checks the PNG signature and IHDR; returns (width, height).
fn png_size(png: &[u8]) -> (u32, u32) {
    assert!(png.len() > 33, "PNG too short");
    assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n", "PNG signature");
    assert_eq!(&png[12..16], b"IHDR");
    let w = u32::from_be_bytes(png[16..20].try_into().unwrap());
    let h = u32::from_be_bytes(png[20..24].try_into().unwrap());
    (w, h)
}

/// Writes the PNG to $PLOTS_OUT/name when that variable is set (to look at).
fn keep(name: &str, png: &[u8]) {
    if let Ok(dir) = std::env::var("PLOTS_OUT") {
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(std::path::Path::new(&dir).join(name), png).unwrap();
    }
}

fn rgb_at(pm: &Pixmap, x: u32, y: u32) -> [u8; 3] {
    let c = pm.pixel(x, y).unwrap().demultiply();
    [c.red(), c.green(), c.blue()]
}

/// A batwing-ish distribution: (signed gamma, cd) from -180 to 180.
fn curve(scale: f64, f: impl Fn(f64) -> f64) -> Vec<(f64, f64)> {
    (-36..=36)
        .map(|k| f64::from(k) * 5.0)
        .map(|g| (g, scale * f(g)))
        .collect()
}

fn batwing(g: f64) -> f64 {
    let a = g.abs().to_radians();
    if a >= std::f64::consts::FRAC_PI_2 {
        0.05 * (1.0 + a.cos())
    } else {
        a.cos() * (0.6 + 0.8 * a.sin().powi(2))
    }
}

fn series_set(scale: f64) -> Vec<Series> {
    vec![
        Series {
            label: "measured".into(),
            points: curve(scale, batwing),
            color: palette(0),
            style: SeriesStyle::Markers,
        },
        Series {
            label: "reconstructed (bilinear)".into(),
            points: curve(scale, |g| 0.97 * batwing(g + 2.0)),
            color: palette(1),
            style: SeriesStyle::Line,
        },
        Series {
            label: "fitted lobes".into(),
            points: curve(scale, |g| g.to_radians().cos().max(0.0).powf(1.5)),
            color: palette(2),
            style: SeriesStyle::Dashed,
        },
    ]
}

/// A C0-C180 polar diagram (cd) of `series` titled `title`.
fn c0_c180_polar(title: &str, series: &[Series]) -> Vec<u8> {
    polar_diagram(&PolarSpec {
        title,
        left: "C180",
        right: "C0",
        unit: "cd",
        series,
        ..PolarSpec::default()
    })
    .unwrap()
}

#[test]
fn polar_renders_for_all_inputs() {
    let typical = series_set(420.0);
    let png = c0_c180_polar("C0-C180: luminaire X", &typical);
    assert_eq!(png_size(&png), (800, 800));
    keep("polar_typical.png", &png);

    let cases: Vec<(&str, Vec<Series>)> = vec![
        ("empty", vec![]),
        (
            "empty_points",
            vec![Series {
                label: "nothing".into(),
                points: vec![],
                color: palette(0),
                style: SeriesStyle::Line,
            }],
        ),
        (
            "nonfinite",
            vec![Series {
                label: "nan".into(),
                points: vec![
                    (f64::NAN, 1.0),
                    (0.0, f64::INFINITY),
                    (10.0, f64::NEG_INFINITY),
                    (20.0, 5.0),
                    (30.0, 4.0),
                ],
                color: palette(3),
                style: SeriesStyle::Line,
            }],
        ),
        (
            "single",
            vec![Series {
                label: "one".into(),
                points: vec![(0.0, 100.0)],
                color: palette(4),
                style: SeriesStyle::Line,
            }],
        ),
        ("huge", series_set(1e6)),
        ("tiny", series_set(1e-6)),
        (
            "negative",
            vec![Series {
                label: "neg".into(),
                points: vec![(-10.0, -5.0), (0.0, -1.0), (10.0, -3.0)],
                color: palette(5),
                style: SeriesStyle::Dashed,
            }],
        ),
    ];
    for (name, s) in cases {
        let png = c0_c180_polar(name, &s);
        assert_eq!(png_size(&png), (800, 800), "{name}");
        assert!(Pixmap::decode_png(&png).is_ok(), "{name}");
        keep(&format!("polar_{name}.png"), &png);
    }
}

#[test]
fn polar_nadir_points_down() {
    let color = [200, 0, 200];
    let points = (-36..=36)
        .map(|k| f64::from(k) * 5.0)
        .map(|g: f64| (g, if g.abs() <= 5.0 { 1000.0 } else { 0.0 }))
        .collect();
    let s = [Series {
        label: "down".into(),
        points,
        color,
        style: SeriesStyle::Line,
    }];
    let png = c0_c180_polar("down", &s);
    keep("polar_down.png", &png);
    let pm = Pixmap::decode_png(&png).unwrap();
    let (w, h) = (pm.width(), pm.height());
    let cy = h / 2;
    let (mut below, mut above) = (0usize, 0usize);
    for y in 0..h {
        for x in 0..w {
            let c = rgb_at(&pm, x, y);
            let close = c
                .iter()
                .zip(color)
                .all(|(a, b)| (i32::from(*a) - i32::from(b)).abs() <= 30);
            if close {
                if y > cy + 60 {
                    below += 1;
                } else if y + 60 < cy {
                    above += 1;
                }
            }
        }
    }
    assert!(below > 100, "series pixels below the centre: {below}");
    assert_eq!(above, 0, "series pixels above the centre");
}

fn grid() -> (Vec<f64>, Vec<f64>) {
    let xs: Vec<f64> = (0..24).map(|k| f64::from(k) * 15.0).collect();
    let ys: Vec<f64> = [
        0.0, 2.5, 5.0, 10.0, 20.0, 30.0, 45.0, 60.0, 75.0, 90.0, 120.0, 150.0, 180.0,
    ]
    .to_vec();
    (xs, ys)
}

#[test]
fn heatmap_renders_for_all_inputs() {
    let (xs, ys) = grid();
    let mut vals = Vec::new();
    for &g in &ys {
        for &c in &xs {
            vals.push(100.0 * (g.to_radians().cos().max(0.0)) * (0.8 + 0.2 * (2.0 * f64::to_radians(c)).cos()));
        }
    }
    let png = heatmap(&HeatmapSpec {
        title: "I / I_max",
        xs: &xs,
        ys: &ys,
        values: &vals,
        unit: "% of I_max",
        scale: ColorScale::Sequential,
        ..HeatmapSpec::default()
    })
    .unwrap();
    assert_eq!(png_size(&png), (900, 500));
    keep("heat_typical.png", &png);
    let signed: Vec<f64> = vals
        .iter()
        .enumerate()
        .map(|(k, v)| (v - 50.0) * 0.1 * ((k % 7) as f64 - 3.0))
        .collect();
    let png = heatmap(&HeatmapSpec {
        title: "signed error",
        xs: &xs,
        ys: &ys,
        values: &signed,
        unit: "% of I_max",
        scale: ColorScale::Diverging,
        ..HeatmapSpec::default()
    })
    .unwrap();
    keep("heat_diverging.png", &png);

    let nanvals: Vec<f64> = vals
        .iter()
        .enumerate()
        .map(|(k, &v)| {
            if k % 5 == 0 {
                f64::NAN
            } else if k % 7 == 0 {
                f64::INFINITY
            } else {
                v
            }
        })
        .collect();
    let huge: Vec<f64> = vals.iter().map(|v| v * 1e6).collect();
    let tiny: Vec<f64> = vals.iter().map(|v| v * 1e-8).collect();
    let all_nan = vec![f64::NAN; vals.len()];
    let mut bad_xs = xs.clone();
    bad_xs[3] = f64::NAN;
    // (name, xs, ys, values, diverging)
    type Case<'a> = (&'a str, Vec<f64>, Vec<f64>, Vec<f64>, bool);
    let cases: Vec<Case> = vec![
        ("empty", vec![], vec![], vec![], false),
        ("empty_div", vec![], vec![], vec![], true),
        ("nan", xs.clone(), ys.clone(), nanvals, false),
        ("all_nan", xs.clone(), ys.clone(), all_nan, true),
        ("single", vec![90.0], vec![45.0], vec![3.0], false),
        ("huge", xs.clone(), ys.clone(), huge, false),
        ("tiny", xs.clone(), ys.clone(), tiny, true),
        ("constant", xs.clone(), ys.clone(), vec![7.0; vals.len()], false),
        ("nan_axis", bad_xs, ys.clone(), vals.clone(), false),
    ];
    for (name, x, y, v, div) in cases {
        let png = heatmap(&HeatmapSpec {
            title: name,
            xs: &x,
            ys: &y,
            values: &v,
            unit: "cd",
            scale: if div {
                ColorScale::Diverging
            } else {
                ColorScale::Sequential
            },
            ..HeatmapSpec::default()
        })
        .unwrap();
        assert_eq!(png_size(&png), (900, 500), "{name}");
        keep(&format!("heat_{name}.png"), &png);
    }
    assert!(heatmap(&HeatmapSpec {
        title: "mismatch",
        xs: &xs,
        ys: &ys,
        values: &vals[1..],
        unit: "cd",
        scale: ColorScale::Sequential,
        ..HeatmapSpec::default()
    })
    .is_err());
}

/// Top-left cell colour of the default-size heat map (plot area starts at x = 92, y = 56;
/// the first gamma row, 0..1.25 deg, is under 3 px high).
fn top_left(png: &[u8]) -> [u8; 3] {
    let pm = Pixmap::decode_png(png).unwrap();
    rgb_at(&pm, 95, 57)
}

#[test]
fn heatmap_top_left_is_value_zero() {
    let (xs, ys) = grid();
    let n = xs.len() * ys.len();
    let corner = |values: &[f64], scale: ColorScale| {
        top_left(
            &heatmap(&HeatmapSpec {
                title: "t",
                xs: &xs,
                ys: &ys,
                values,
                unit: "cd",
                scale,
                ..HeatmapSpec::default()
            })
            .unwrap(),
        )
    };
    // values[0] is the minimum: colour map at 0.
    let v: Vec<f64> = (0..n).map(|k| k as f64).collect();
    assert_eq!(corner(&v, ColorScale::Sequential), ColorMap::Viridis.rgb8(0.0));
    // values[0] is the maximum: colour map at 1.
    let v: Vec<f64> = (0..n).map(|k| (n - k) as f64).collect();
    assert_eq!(corner(&v, ColorScale::Sequential), ColorMap::Viridis.rgb8(1.0));
    // Diverging: 0 is the middle of the map; -max is its low end.
    let mut v: Vec<f64> = (0..n).map(|k| k as f64 - 40.0).collect();
    v[0] = 0.0;
    assert_eq!(corner(&v, ColorScale::Diverging), ColorMap::RdBu.rgb8(0.5));
    let v: Vec<f64> = (0..n).map(|k| -(((k + 1) % 9) as f64)).collect();
    // values[0] = -1, range ±8: t = 7/16.
    assert_eq!(corner(&v, ColorScale::Diverging), ColorMap::RdBu.rgb8(7.0 / 16.0));
    // Exposure: values[0] = 1 of range 0..4 is at tone_map(0.25, k) on viridis.
    let mut v = vec![0.0; n];
    v[0] = 1.0;
    v[1] = 4.0;
    assert_eq!(
        corner(&v, ColorScale::Exposure(3.0)),
        ColorMap::Viridis.rgb8(tone_map(0.25, 3.0))
    );
}

fn methods() -> Vec<ScatterPoint> {
    [
        ("nearest", 3.0, 4.1, true),
        ("bilinear", 6.0, 1.9, true),
        ("bicubic", 14.0, 1.2, true),
        ("lanczos3", 40.0, 1.25, false),
        ("spline", 90.0, 0.8, true),
        ("rbf", 1500.0, 0.85, false),
        ("sh-16", 25.0, 3.3, false),
        ("texture 64", 2.0, 5.8, false),
    ]
    .into_iter()
    .map(|(l, x, y, _)| ScatterPoint { label: l.into(), x, y })
    .collect()
}

#[test]
fn scatter_renders_for_all_inputs() {
    let pts = methods();
    let png = scatter(&ScatterSpec {
        title: "cost vs error",
        x_label: "time per sample (ns)",
        y_label: "RMS error (% of I_max)",
        points: &pts,
        log_x: true,
        ..ScatterSpec::default()
    })
    .unwrap();
    assert_eq!(png_size(&png), (800, 550));
    keep("scatter_typical.png", &png);
    let png = scatter(&ScatterSpec {
        title: "linear x",
        x_label: "time per sample (ns)",
        y_label: "RMS error (% of I_max)",
        points: &pts,
        log_x: false,
        ..ScatterSpec::default()
    })
    .unwrap();
    keep("scatter_linear.png", &png);

    let p = |x: f64, y: f64, _pareto: bool| ScatterPoint {
        label: format!("p{x}"),
        x,
        y,
    };
    let cases: Vec<(&str, Vec<ScatterPoint>, bool)> = vec![
        ("empty", vec![], true),
        ("empty_lin", vec![], false),
        (
            "nonfinite",
            vec![
                p(f64::NAN, 1.0, true),
                p(1.0, f64::INFINITY, false),
                p(-3.0, 2.0, true),
                p(5.0, 1.0, true),
            ],
            true,
        ),
        ("single", vec![p(10.0, 1.0, true)], true),
        ("single_lin", vec![p(10.0, 1.0, true)], false),
        (
            "huge",
            vec![p(1e6, 1e6, true), p(3e7, 2e5, true), p(5e6, 5e6, false)],
            true,
        ),
        (
            "tiny",
            vec![p(1e-6, 1e-6, true), p(3e-6, 5e-7, true), p(2e-6, 2e-6, false)],
            false,
        ),
        ("zero_y", vec![p(1.0, 0.0, true), p(2.0, 0.0, false)], true),
        ("negative_y", vec![p(1.0, -2.0, true), p(2.0, 3.0, false)], false),
    ];
    for (name, pts, log) in cases {
        let png = scatter(&ScatterSpec {
            title: name,
            x_label: "x (ns)",
            y_label: "y (%)",
            points: &pts,
            log_x: log,
            ..ScatterSpec::default()
        })
        .unwrap();
        assert_eq!(png_size(&png), (800, 550), "{name}");
        keep(&format!("scatter_{name}.png"), &png);
    }
}

/// An independent RFC 4648 decoder (the `base64` crate, not our encoder run backwards).
fn b64_decode(s: &str) -> Vec<u8> {
    use base64::Engine as _;
    base64::engine::general_purpose::STANDARD
        .decode(s)
        .expect("valid base64")
}

#[test]
fn data_uri_round_trips() {
    for len in 0..8 {
        let data: Vec<u8> = (0..len).map(|k| (k * 37 + 200) as u8).collect();
        let uri = png_data_uri(&data);
        let b64 = uri.strip_prefix("data:image/png;base64,").unwrap();
        assert_eq!(b64_decode(b64), data, "len {len}");
    }
    assert_eq!(png_data_uri(b"Man"), "data:image/png;base64,TWFu");
    assert_eq!(png_data_uri(b"Ma"), "data:image/png;base64,TWE=");
    let png = scatter(&ScatterSpec {
        title: "s",
        x_label: "x",
        y_label: "y",
        points: &methods(),
        log_x: true,
        ..ScatterSpec::default()
    })
    .unwrap();
    let uri = png_data_uri(&png);
    assert_eq!(b64_decode(uri.strip_prefix("data:image/png;base64,").unwrap()), png);
}

#[test]
fn font_covers_printable_ascii() {
    for c in (32u8..=126).map(char::from) {
        let mut pm = Pixmap::new(20, 20).unwrap();
        let w = font::draw_text(&mut pm, 2, 2, &c.to_string(), 2, [0, 0, 0]);
        assert_eq!(w, font::text_width(&c.to_string(), 2));
        let lit = pm.pixels().iter().filter(|p| p.alpha() > 0).count();
        if c == ' ' {
            assert_eq!(lit, 0, "space draws nothing");
        } else {
            assert!(lit > 0, "{c:?} draws nothing");
        }
    }
    // Distinct glyphs for distinct characters.
    let all: std::collections::HashSet<[u8; font::ROWS]> = (32u8..=126).map(|b| font::glyph(char::from(b))).collect();
    assert_eq!(all.len(), 95);
    assert_eq!(font::glyph('\u{1F600}'), font::glyph('?'));
}

#[test]
fn font_width_is_monotonic() {
    let mut s = String::new();
    let mut last = font::text_width(&s, 1);
    assert_eq!(last, 0);
    for k in 0..40 {
        s.push(char::from(b'a' + (k % 26) as u8));
        for scale in 1..=3 {
            assert!(font::text_width(&s, scale) > font::text_width(&s[..s.len() - 1], scale));
        }
        let w = font::text_width(&s, 1);
        assert!(w > last);
        last = w;
    }
    assert_eq!(font::text_width("ab", 3), 3 * font::text_width("ab", 1));
}

fn decoded_size(png: &[u8]) -> (u32, u32) {
    let pm = Pixmap::decode_png(png).expect("our PNG decodes");
    (pm.width(), pm.height())
}

/// Every plot kind drawn from its spec's `Default` (plus the texture's
/// `new`) is a PNG of the stated size that tiny-skia's decoder (the `png`
/// crate) reads back; a spec's size is honoured and a bad one refused.
#[test]
fn spec_defaults_give_decodable_pngs_of_the_stated_size() {
    assert_eq!(POLAR_SIZE, (800, 800));
    assert_eq!(HEATMAP_SIZE, (900, 500));
    assert_eq!(SCATTER_SIZE, (800, 550));
    assert_eq!(decoded_size(&polar_diagram(&PolarSpec::default()).unwrap()), POLAR_SIZE);
    assert_eq!(decoded_size(&heatmap(&HeatmapSpec::default()).unwrap()), HEATMAP_SIZE);
    assert_eq!(decoded_size(&scatter(&ScatterSpec::default()).unwrap()), SCATTER_SIZE);
    let lum = photosolid::load(Path::new(env!("CARGO_MANIFEST_DIR")).join("data/roadway.ldt")).unwrap();
    let tex = LightTexture::new(lum.distribution()).unwrap();
    let r = render(&tex, Filter::Bilinear, 2).unwrap();
    assert_eq!(
        decoded_size(&texture_preview(&TexturePreview::new(&r)).unwrap()),
        TEXTURE_SIZE
    );

    for size in [(320, 200), (1203, 911)] {
        let s = (size.0.max(300), size.1.max(240));
        assert_eq!(
            decoded_size(
                &polar_diagram(&PolarSpec {
                    size: s,
                    ..PolarSpec::default()
                })
                .unwrap()
            ),
            s
        );
        assert_eq!(
            decoded_size(
                &heatmap(&HeatmapSpec {
                    size: s,
                    ..HeatmapSpec::default()
                })
                .unwrap()
            ),
            s
        );
        assert_eq!(
            decoded_size(
                &scatter(&ScatterSpec {
                    size: s,
                    ..ScatterSpec::default()
                })
                .unwrap()
            ),
            s
        );
        let t = TexturePreview {
            size: s,
            ..TexturePreview::new(&r)
        };
        assert_eq!(decoded_size(&texture_preview(&t).unwrap()), s);
    }
    assert!(polar_diagram(&PolarSpec {
        size: (100, 800),
        ..PolarSpec::default()
    })
    .is_err());
    assert!(heatmap(&HeatmapSpec {
        size: (900, 9000),
        ..HeatmapSpec::default()
    })
    .is_err());
    assert!(scatter(&ScatterSpec {
        size: (0, 0),
        ..ScatterSpec::default()
    })
    .is_err());
    assert!(texture_preview(&TexturePreview {
        size: (119, 478),
        ..TexturePreview::new(&r)
    })
    .is_err());
    // A bad colour range or exposure is an error, not a blank map.
    let bad_range = HeatmapSpec {
        range: Some((1.0, 1.0)),
        ..HeatmapSpec::default()
    };
    assert!(heatmap(&bad_range).is_err());
    let bad_k = HeatmapSpec {
        scale: ColorScale::Exposure(f64::NAN),
        ..HeatmapSpec::default()
    };
    assert!(heatmap(&bad_k).is_err());
}

/// The texture preview's colour bar (x = width - 124 .. width - 102, rows
/// 56 .. height - 62, as in every heat map) runs from viridis(0) at 0 cd to
/// viridis(1) at I_max, and the texel at the roadway's peak is its brightest
/// colour: the preview shows the texture, in candela.
#[test]
fn texture_preview_bar_and_peak() {
    let lum = photosolid::load(Path::new(env!("CARGO_MANIFEST_DIR")).join("data/roadway.ldt")).unwrap();
    let tex = LightTexture::new(lum.distribution()).unwrap();
    let r = render(&tex, Filter::CatmullRom, 5).unwrap();
    let png = texture_preview(&TexturePreview::new(&r)).unwrap();
    keep("texture_roadway.png", &png);
    let pm = Pixmap::decode_png(&png).unwrap();
    let (w, h) = (pm.width(), pm.height());
    let near = |a: [u8; 3], b: [u8; 3]| a.iter().zip(b).all(|(x, y)| (i32::from(*x) - i32::from(y)).abs() <= 3);
    let top = rgb_at(&pm, w - 113, 57);
    let bottom = rgb_at(&pm, w - 113, h - 63);
    assert!(near(top, ColorMap::Viridis.rgb8(1.0)), "bar top {top:?}");
    assert!(near(bottom, ColorMap::Viridis.rgb8(0.0)), "bar bottom {bottom:?}");
    // The brightest texel, at its pixel in the plot (C across 92 .. w - 150,
    // gamma down 56 .. h - 62), has the colour of I_max.
    let m = &r.mapping;
    let k = (0..r.data.len())
        .max_by(|&a, &b| r.data[a].total_cmp(&r.data[b]))
        .unwrap();
    let (c, g) = (m.c_of_column(k % m.width), m.gamma_of_row(k / m.width));
    let x = 92.0 + c / 360.0 * f64::from(w - 150 - 92);
    let y = 56.0 + g / 180.0 * f64::from(h - 62 - 56);
    let peak = rgb_at(&pm, x as u32, y as u32);
    let want = ColorMap::Viridis.rgb8(tone_map(f64::from(r.data[k]), DEFAULT_EXPOSURE));
    assert!(near(peak, want), "peak at C{c:.1} gamma {g:.1}: {peak:?} vs {want:?}");
}
