//! Reconstruction on the sphere: filters, light distribution textures, render, files, hold-out.

use glam::DVec3;
use photosolid::model::frame::{angles, direction};
use photosolid::reconstruct::{exr_io, holdout, render, render_with, Filter, HoldoutSpec, LightTexture, RenderOptions};
use photosolid::report::plot;
use photosolid::{Distribution, ModelError, Symmetry};
use proptest::prelude::*;

const INTERPOLATING: [Filter; 4] = [Filter::Nearest, Filter::Bilinear, Filter::CatmullRom, Filter::Pchip];

/// A smooth asymmetric test solid (cd): a tilted lobe plus a weak uplight.
fn solid(c: f64, g: f64) -> f64 {
    let (c, g) = (c.to_radians(), g.to_radians());
    // The C modulation fades out at the poles, where one direction has one value.
    let down = (g.cos().max(0.0)).powi(3) * (1.0 + (0.4 * c.cos() + 0.2 * (2.0 * c).sin()) * g.sin());
    let up = 0.1 * (-g.cos()).max(0.0);
    1000.0 * (down + up)
}

fn grid(c: &[f64], g: &[f64], sym: Symmetry, f: impl Fn(f64, f64) -> f64) -> Distribution {
    let cd = c
        .iter()
        .flat_map(|&c| g.iter().map(move |&g| (c, g)))
        .map(|(c, g)| f(c, g))
        .collect();
    Distribution::new(c.to_vec(), g.to_vec(), cd, sym).unwrap()
}

fn steps(from: f64, to: f64, step: f64) -> Vec<f64> {
    let n = ((to - from) / step).round() as usize;
    (0..=n).map(|k| from + k as f64 * step).collect()
}

/// Non-uniform C (no symmetry) and γ grids, full sphere, poles consistent.
fn nonuniform() -> Distribution {
    let c = [0.0, 10.0, 25.0, 60.0, 90.0, 150.0, 180.0, 200.0, 270.0, 300.0, 345.0];
    let g = [
        0.0, 2.5, 5.0, 10.0, 20.0, 35.0, 50.0, 65.0, 80.0, 90.0, 120.0, 150.0, 175.0, 180.0,
    ];
    grid(&c, &g, Symmetry::None, solid)
}

#[test]
fn interpolating_filters_return_measured_values_at_their_directions() {
    let d = nonuniform();
    let tex = LightTexture::new(&d).unwrap();
    for f in INTERPOLATING {
        let s = tex.sampler(f);
        for (ic, &c) in d.c_angles_deg().iter().enumerate() {
            for (ig, &g) in d.gamma_angles_deg().iter().enumerate() {
                let want = d.value_cd(ic, ig);
                assert_eq!(s.cd(c, g), want, "{f} at C {c} gamma {g}");
                // by direction: acos/atan2 round trip costs a few ulps of the angle
                let got = s.cd_dir(direction(c, g));
                assert_close!(
                    got,
                    want,
                    abs = 1e-9 * d.max_cd(),
                    "{f} dir at C {c} gamma {g}: {got} vs {want}"
                );
            }
        }
    }
}

#[test]
fn c_is_periodic_whatever_the_symmetry() {
    let g = steps(0.0, 180.0, 5.0);
    let cases = [
        grid(&steps(0.0, 345.0, 15.0), &g, Symmetry::None, solid),
        grid(&steps(0.0, 180.0, 15.0), &g, Symmetry::C0C180, |c, g| {
            solid(c.min(360.0 - c), g)
        }),
        grid(&steps(0.0, 90.0, 15.0), &g, Symmetry::Quadrant, solid),
        grid(&steps(90.0, 270.0, 15.0), &g, Symmetry::C90C270, solid),
    ];
    for d in &cases {
        let tex = LightTexture::new(d).unwrap();
        for f in Filter::ALL {
            let s = tex.sampler(f);
            for g in [3.0, 47.5, 91.0, 178.0] {
                let at0 = s.cd(0.0, g);
                assert_eq!(s.cd(360.0, g), at0, "{f} {:?}", d.symmetry());
                assert_eq!(s.cd(-360.0, g), at0);
                assert_eq!(s.cd(720.0, g), at0);
                for e in [1e-12, 1e-9] {
                    // continuity across the seam, from both sides
                    assert_close!(s.cd(360.0 - e, g), at0, abs = 1e-6 * tex.i_max_cd());
                    assert_close!(s.cd(e, g), at0, abs = 1e-6 * tex.i_max_cd());
                }
                let d0 = s.cd_dir(DVec3::new(1.0, 0.0, -g.to_radians().cos() / g.to_radians().sin()));
                let dm = s.cd_dir(DVec3::new(1.0, -1e-12, -g.to_radians().cos() / g.to_radians().sin()));
                assert_close!(d0, at0, abs = 1e-6 * tex.i_max_cd(), "{f}: {d0} vs {at0}");
                assert_close!(dm, at0, abs = 1e-6 * tex.i_max_cd(), "{f}: {dm} vs {at0}");
            }
        }
    }
}

#[test]
fn poles_are_continuous_and_independent_of_c() {
    // Non-uniform: 0 + 180 = 180 is a plane, 10 + 180 = 190 is not (ghost interpolated in C).
    // Uniform: every C + 180 is a plane.
    let uniform = grid(&steps(0.0, 330.0, 30.0), &steps(0.0, 180.0, 7.5), Symmetry::None, solid);
    for (d, closed) in [(nonuniform(), false), (uniform, true)] {
        let tex = LightTexture::new(&d).unwrap();
        let tol = 1e-9 * tex.i_max_cd();
        for f in Filter::ALL {
            let s = tex.sampler(f);
            for (pole, sign) in [(0.0, -1.0), (180.0, 1.0)] {
                let at = s.cd_dir(DVec3::new(0.0, 0.0, sign));
                assert!(at.is_finite() && at >= 0.0);
                for k in 0..24 {
                    let c = k as f64 * 15.0 + 0.3;
                    let (cc, sc) = (c.to_radians().cos(), c.to_radians().sin());
                    let near = s.cd_dir(DVec3::new(1e-12 * cc, 1e-12 * sc, sign));
                    let by_angle = s.cd(c, pole);
                    if f.is_interpolating() {
                        // Exactly one value at the pole, whatever C.
                        assert_close!(near, at, abs = tol, "{f} pole {pole} C {c}: {near} vs {at}");
                        assert_close!(by_angle, at, abs = tol, "{f} pole {pole} C {c}");
                    }
                    // Continuous through the pole along every meridian: C and C + 180 meet
                    // (approximating filters: on grids closed under C + 180).
                    if f.is_interpolating() || closed {
                        let g = if pole == 0.0 { 1e-7 } else { 180.0 - 1e-7 };
                        let (a, b) = (s.cd(c, g), s.cd(c + 180.0, g));
                        assert_close!(a, b, abs = 1e-6 * tex.i_max_cd(), "{f} meridian C {c}: {a} vs {b}");
                    }
                }
            }
        }
    }
}

#[test]
fn zero_outside_the_measured_band_without_ringing() {
    // Lower hemisphere, ending with a jump at 90 (cubics would ring past it if they extrapolated).
    let g = steps(0.0, 90.0, 10.0);
    let d = grid(&[0.0, 90.0], &g, Symmetry::Quadrant, |_, g| {
        if g < 75.0 {
            100.0
        } else {
            500.0
        }
    });
    let tex = LightTexture::new(&d).unwrap();
    for f in Filter::ALL {
        let s = tex.sampler(f).unclamped();
        for g in [90.0 + 1e-5, 90.5, 100.0, 135.0, 179.9, 180.0] {
            for c in [0.0, 33.0, 200.0] {
                assert_eq!(s.cd(c, g), 0.0, "{f} at {g}");
            }
        }
        assert!(s.cd(10.0, 90.0) > 0.0, "{f}: the band end itself is measured");
        assert!(s.cd(10.0, 90.0 - 1e-9) > 0.0);
    }
    // An upper-hemisphere file: 0 below 90.
    let d = grid(&[0.0], &steps(90.0, 180.0, 15.0), Symmetry::Rotational, |_, g| g - 80.0);
    let tex = LightTexture::new(&d).unwrap();
    for f in Filter::ALL {
        assert_eq!(tex.sampler(f).cd(0.0, 89.999), 0.0);
        assert!(tex.sampler(f).cd(0.0, 90.0) > 0.0);
    }
}

#[test]
fn cubic_overshoot_is_clamped_and_counted_unless_unclamped() {
    // A spike next to zeros: Catmull–Rom dips below zero beside it.
    let g = steps(0.0, 180.0, 10.0);
    let d = grid(&steps(0.0, 330.0, 30.0), &g, Symmetry::None, |c, g| {
        if (g - 60.0).abs() < 1.0 && c == 90.0 {
            1000.0
        } else {
            0.0
        }
    });
    let tex = LightTexture::new(&d).unwrap();
    let s = tex.sampler(Filter::CatmullRom);
    assert!(s.unclamped().cd(90.0, 72.0) < 0.0);
    assert_eq!(s.cd(90.0, 72.0), 0.0);
    let r = render(&tex, Filter::CatmullRom, 5).unwrap();
    assert!(r.clamped > 0);
    assert!(r.data.iter().all(|&v| v >= 0.0));
    let opts = RenderOptions {
        filter: Filter::CatmullRom,
        clamp: false,
        ..RenderOptions::default()
    };
    let u = render_with(&tex, &opts).unwrap();
    assert_eq!(u.clamped, 0);
    assert!(u.data.iter().any(|&v| v < 0.0));
    // PCHIP and the B-spline never go below zero here.
    for f in [Filter::Pchip, Filter::BSpline, Filter::Bilinear] {
        let r = render(&tex, f, 5).unwrap();
        assert_eq!(r.clamped, 0, "{f}");
    }
}

fn assert_same_lookups(a: &LightTexture, b: &LightTexture, tol: f64, what: &str) {
    for f in Filter::ALL {
        let (sa, sb) = (a.sampler(f), b.sampler(f));
        for i in 0..=72 {
            for j in 0..=37 {
                let (c, g) = (i as f64 * 5.0 + 0.7, j as f64 * 4.87);
                let (x, y) = (sa.cd(c, g), sb.cd(c, g));
                assert_close!(
                    x,
                    y,
                    abs = tol * a.i_max_cd(),
                    "{what} {f} at C {c} gamma {g}: {x} vs {y}"
                );
            }
        }
    }
}

#[test]
fn compact_storage_gives_the_same_values_as_the_full_grid() {
    let g = [0.0, 5.0, 10.0, 20.0, 30.0, 45.0, 60.0, 75.0, 90.0, 105.0, 135.0, 180.0];
    let cases = [
        (
            grid(&[0.0], &g, Symmetry::Rotational, |_, g| solid(0.0, g)),
            (g.len(), 1),
        ),
        (
            grid(&[0.0, 20.0, 45.0, 90.0], &g, Symmetry::Quadrant, solid),
            (g.len(), 4),
        ),
        (
            grid(&steps(0.0, 180.0, 30.0), &g, Symmetry::C0C180, solid),
            (g.len(), 7),
        ),
        (
            grid(&[90.0, 135.0, 150.0, 180.0, 270.0], &g, Symmetry::C90C270, solid),
            (g.len(), 5),
        ),
    ];
    for (d, stored) in &cases {
        let compact = LightTexture::new(d).unwrap();
        assert_eq!(compact.stored_size(), *stored, "{:?}", d.symmetry());
        let full = LightTexture::new(&d.expand(24)).unwrap();
        assert_same_lookups(&compact, &full, 1e-12, &format!("{:?}", d.symmetry()));
    }
}

#[test]
fn an_empty_hemisphere_is_not_stored_and_changes_nothing() {
    let g = steps(0.0, 180.0, 5.0);
    let lower = |c: f64, g: f64| if g <= 80.0 { solid(c, g) + 1.0 } else { 0.0 };
    let d = grid(&steps(0.0, 90.0, 15.0), &g, Symmetry::Quadrant, lower);
    let tex = LightTexture::new(&d).unwrap();
    // 0..80 holds data, plus two zero rows of margin: up to 90.
    assert_eq!(tex.gamma_rows().first(), Some(&0.0));
    assert_eq!(tex.gamma_rows().last(), Some(&90.0));
    // The same data with a (tiny) zenith value is stored whole; below 170 nothing can differ.
    let d2 = grid(&steps(0.0, 90.0, 15.0), &g, Symmetry::Quadrant, |c, g| {
        if g == 180.0 {
            1e-3
        } else {
            lower(c, g)
        }
    });
    let tex2 = LightTexture::new(&d2).unwrap();
    assert_eq!(tex2.gamma_rows().len(), 37);
    for f in Filter::ALL {
        for c in [0.0, 12.0, 100.0, 222.0] {
            for k in 0..=160 {
                let gq = k as f64 * 1.0625;
                assert_eq!(tex.sampler(f).cd(c, gq), tex2.sampler(f).cd(c, gq), "{f} {c} {gq}");
            }
        }
    }
}

#[test]
fn f32_render_matches_the_f64_sampler() {
    // Stated bound: 2e-6 of I_max (f32 rounding of values, weights and sums).
    let d = nonuniform();
    let tex = LightTexture::new(&d).unwrap();
    for f in Filter::ALL.into_iter().chain([Filter::Mitchell { b: 0.0, c: 0.75 }]) {
        let r = render(&tex, f, 3).unwrap();
        let m = r.mapping;
        let s = tex.sampler(f);
        let mut worst = 0.0f64;
        for i in 0..m.height {
            for j in 0..m.width {
                let want = s.normalized(m.c_of_column(j), m.gamma_of_row(i));
                worst = worst.max((f64::from(r.data[i * m.width + j]) - want).abs());
            }
        }
        assert!(worst <= 2e-6, "{f}: worst {worst}");
        let serial = render_with(
            &tex,
            &RenderOptions {
                filter: f,
                factor: 3,
                parallel: false,
                ..RenderOptions::default()
            },
        )
        .unwrap();
        assert_eq!(serial, r, "{f}: parallel and serial renders agree bit for bit");
    }
}

#[test]
fn render_size_mapping_and_factor_domain() {
    let d = grid(&steps(0.0, 345.0, 15.0), &steps(0.0, 90.0, 5.0), Symmetry::None, solid);
    let tex = LightTexture::new(&d).unwrap();
    let r = render(&tex, Filter::Bilinear, 5).unwrap();
    assert_eq!((r.mapping.height, r.mapping.width), (36 * 5, 24 * 5));
    assert_eq!(r.mapping.gamma_of_row(0), 0.5);
    assert_eq!(r.mapping.c_of_column(119), 358.5);
    // rows beyond the measured band are zero
    assert!(r.data[100 * r.mapping.width..].iter().all(|&v| v == 0.0));
    for bad in [0, 33, 1000] {
        assert!(matches!(
            render(&tex, Filter::Bilinear, bad),
            Err(ModelError::Parameter { name: "factor", .. })
        ));
    }
    assert!(render(&tex, Filter::Bilinear, 1).is_ok());
    assert!(render(&tex, Filter::Bilinear, 32).is_ok());
}

#[test]
fn all_zero_data_is_a_clear_error() {
    let d = grid(&[0.0, 90.0], &steps(0.0, 90.0, 10.0), Symmetry::Quadrant, |_, _| 0.0);
    let e = LightTexture::new(&d).unwrap_err();
    assert!(matches!(e, ModelError::AllZero(_)), "{e}");
    assert!(e.to_string().contains("I_max"));
    let e = holdout(
        &d,
        HoldoutSpec {
            c_step: 1,
            gamma_step: 2,
        },
        &[Filter::Bilinear],
    )
    .unwrap_err();
    assert!(matches!(e, ModelError::AllZero(_)));
}

#[test]
fn degenerate_axes() {
    // One C-plane (rotational): constant in C, exact at the knots.
    let d = grid(&[0.0], &steps(0.0, 180.0, 30.0), Symmetry::Rotational, |_, g| 10.0 + g);
    let tex = LightTexture::new(&d).unwrap();
    assert_eq!(tex.stored_size(), (7, 1));
    for f in Filter::ALL {
        for c in [0.0, 77.0, 359.9999999] {
            assert_eq!(tex.sampler(f).cd(c, 13.0), tex.sampler(f).cd(0.0, 13.0));
        }
    }
    // One γ row: defined only at that γ.
    let d = grid(&steps(0.0, 270.0, 90.0), &[90.0], Symmetry::None, |c, _| 1.0 + c);
    let tex = LightTexture::new(&d).unwrap();
    for f in Filter::ALL {
        let s = tex.sampler(f);
        assert!(s.cd(45.0, 90.0).is_finite() && s.cd(45.0, 90.0) >= 0.0);
        assert_eq!(s.cd(45.0, 89.0), 0.0);
        assert_eq!(s.cd(45.0, 91.0), 0.0);
        assert_eq!(s.cd_dir(DVec3::new(0.0, 1.0, 0.0)), s.cd(90.0, 90.0));
        if f.is_interpolating() {
            assert_eq!(s.cd(180.0, 90.0), 181.0);
        }
        let r = render(&tex, f, 2).unwrap();
        assert!(r.data.iter().all(|v| v.is_finite()));
    }
    // Two γ samples, both band edges: every cubic degrades to linear.
    let d = grid(&[0.0], &[10.0, 80.0], Symmetry::Rotational, |_, g| g);
    let tex = LightTexture::new(&d).unwrap();
    for f in [Filter::CatmullRom, Filter::Pchip, Filter::BSpline, Filter::MITCHELL] {
        for g in [10.0, 20.0, 45.0, 79.0, 80.0] {
            assert_close!(tex.sampler(f).cd(0.0, g), g, abs = 1e-9, "{f} at {g}");
        }
    }
    // Two C-planes: no overshoot along C.
    let d = grid(&[0.0, 180.0], &steps(0.0, 90.0, 45.0), Symmetry::None, |c, _| {
        if c == 0.0 {
            1.0
        } else {
            3.0
        }
    });
    let tex = LightTexture::new(&d).unwrap();
    for f in Filter::ALL {
        for k in 0..36 {
            let v = tex.sampler(f).cd(k as f64 * 10.0, 45.0);
            assert!((1.0 - 1e-12..=3.0 + 1e-12).contains(&v), "{f}: {v}");
        }
    }
}

#[test]
fn intensities_from_micro_to_mega_candela() {
    let g = steps(0.0, 180.0, 10.0);
    let d = grid(&steps(0.0, 330.0, 30.0), &g, Symmetry::None, |c, g| {
        10f64.powf(-6.0 + 12.0 * ((c / 360.0 + g / 180.0) / 2.0))
    });
    let tex = LightTexture::new(&d).unwrap();
    for f in Filter::ALL {
        let s = tex.sampler(f);
        for (ic, &c) in d.c_angles_deg().iter().enumerate() {
            for (ig, &gg) in g.iter().enumerate() {
                let v = s.cd(c, gg);
                assert!(v.is_finite() && v >= 0.0);
                if f.is_interpolating() && gg != 0.0 && gg != 180.0 {
                    assert_eq!(v, d.value_cd(ic, ig), "{f}");
                }
            }
        }
        let r = render(&tex, f, 2).unwrap();
        assert!(r.data.iter().all(|v| v.is_finite() && *v >= 0.0));
    }
}

#[test]
fn direction_angles_round_trip_and_edge_vectors() {
    for (c, g) in [(0.0, 0.0), (0.0, 180.0), (90.0, 90.0), (271.5, 33.0), (359.0, 179.0)] {
        let (c2, g2) = angles(direction(c, g)).unwrap();
        assert_close!(g2, g, abs = 1e-9);
        if g != 0.0 && g != 180.0 {
            assert_close!(c2, c, abs = 1e-9, "{c} {c2}");
        }
    }
    assert_eq!(angles(DVec3::ZERO), None);
    assert_eq!(angles(DVec3::new(f64::NAN, 0.0, 1.0)), None);
    assert_eq!(angles(DVec3::new(0.0, 0.0, -5.0)), Some((0.0, 0.0)));
    let (c, _) = angles(DVec3::new(1.0, -1e-300, 0.0)).unwrap();
    assert!(c == 0.0 || c > 359.0);
    let tex = LightTexture::new(&nonuniform()).unwrap();
    let s = tex.sampler(Filter::CatmullRom);
    assert_eq!(s.cd_dir(DVec3::ZERO), 0.0);
    let dirs: Vec<DVec3> = (0..1000).map(|k| direction(k as f64 * 7.3, k as f64 * 0.18)).collect();
    let mut out = vec![0.0; dirs.len()];
    s.cd_dirs(&dirs, &mut out);
    for (d, o) in dirs.iter().zip(&out) {
        assert_eq!(*o, s.cd_dir(*d));
    }
}

#[test]
fn exr_round_trip_keeps_numbers_and_metadata() {
    let tex = LightTexture::new(&nonuniform()).unwrap();
    let r = render(&tex, Filter::MITCHELL, 2).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("ldt.exr");
    let meta = exr_io::ExrMeta {
        source: Some("Ünïcode luminaire.ldt".into()),
    };
    exr_io::write_exr(&path, &r, &meta).unwrap();
    // atomic: only the target is left
    let names: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(names, vec![std::ffi::OsString::from("ldt.exr")]);
    let (back, meta2) = exr_io::read_exr(&path).unwrap();
    assert_eq!(back, r);
    assert_eq!(meta2, meta);
    // A non-EXR file is an invalid-file error, not a panic.
    std::fs::write(dir.path().join("bad.exr"), b"not an exr").unwrap();
    assert!(matches!(
        exr_io::read_exr(dir.path().join("bad.exr")),
        Err(photosolid::Error::Parse(_))
    ));
}

#[test]
fn png_preview_is_written() {
    let tex = LightTexture::new(&nonuniform()).unwrap();
    let r = render(&tex, Filter::CatmullRom, 5).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("ldt.png");
    plot::write_texture_preview(&path, &plot::TexturePreview::new(&r)).unwrap();
    let bytes = std::fs::read(&path).unwrap();
    let pm = tiny_skia::Pixmap::decode_png(&bytes).unwrap();
    assert_eq!((pm.width(), pm.height()), plot::texture::TEXTURE_SIZE);
    let bad = plot::TexturePreview {
        exposure: 0.0,
        ..plot::TexturePreview::new(&r)
    };
    assert!(plot::texture_preview(&bad).is_err());
    assert_eq!(plot::tone_map(1.0, 4.0), 1.0);
    assert_eq!(plot::tone_map(0.0, 4.0), 0.0);
}

#[test]
fn holdout_ranks_filters_on_a_smooth_solid() {
    let d = grid(&steps(0.0, 355.0, 5.0), &steps(0.0, 180.0, 1.0), Symmetry::None, solid);
    let reports = holdout(
        &d,
        HoldoutSpec {
            c_step: 4,
            gamma_step: 8,
        },
        &Filter::ALL,
    )
    .unwrap();
    assert_eq!(reports.len(), 6);
    let by = |f: Filter| reports.iter().find(|r| r.filter == f).unwrap();
    let (bl, cr) = (by(Filter::Bilinear), by(Filter::CatmullRom));
    assert!(cr.rms_percent < bl.rms_percent, "{cr:?} vs {bl:?}");
    assert!(by(Filter::Pchip).rms_percent < bl.rms_percent);
    for r in &reports {
        assert!(r.rms_percent.is_finite() && r.max_percent >= r.rms_percent);
        assert_close!(r.flux_error_percent, 0.0, abs = 5.0, "{r:?}");
        assert_eq!(r.kept, (18, 24));
    }
    let json = serde_json::to_string(&reports[2]).unwrap();
    assert!(json.contains("\"filter\":\"catmull-rom\""), "{json}");
    // Nothing to drop is an error.
    assert!(holdout(
        &d,
        HoldoutSpec {
            c_step: 1,
            gamma_step: 1
        },
        &[Filter::Bilinear]
    )
    .is_err());
}

// ---- property tests over random grids ----

/// Random full-sphere or partial grids, no symmetry, non-uniform, non-negative values.
fn arb_distribution() -> impl Strategy<Value = Distribution> {
    (
        prop::collection::btree_set(0u32..3600, 1..9),
        prop::collection::btree_set(0u32..1800, 2..10),
        any::<bool>(),
        any::<bool>(),
    )
        .prop_flat_map(|(cs, gs, pole0, pole180)| {
            let c: Vec<f64> = cs.into_iter().map(|k| k as f64 / 10.0).collect();
            let mut g: Vec<f64> = gs.into_iter().map(|k| k as f64 / 10.0).collect();
            if pole0 {
                g.insert(0, 0.0);
                g.dedup();
            }
            if pole180 {
                g.push(180.0);
                g.dedup();
            }
            let n = c.len() * g.len();
            (Just(c), Just(g), prop::collection::vec(0.0f64..1000.0, n))
        })
        .prop_map(|(c, g, v)| Distribution::new(c, g, v, Symmetry::None).unwrap())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    #[test]
    fn prop_interpolating_filters_hit_the_knots(d in arb_distribution()) {
        let d = d.with_averaged_poles();
        let Ok(tex) = LightTexture::new(&d) else { return Ok(()) };
        for f in INTERPOLATING {
            let s = tex.sampler(f);
            for (ic, &c) in d.c_angles_deg().iter().enumerate() {
                for (ig, &g) in d.gamma_angles_deg().iter().enumerate() {
                    let (got, want) = (s.cd(c, g), d.value_cd(ic, ig));
                    prop_assert!((got - want).abs() <= 1e-9 * tex.i_max_cd(), "{} at ({}, {}): {} vs {}", f, c, g, got, want);
                }
            }
        }
    }

    #[test]
    fn prop_outputs_finite_and_non_negative(d in arb_distribution(), q in prop::collection::vec((-10.0f64..370.0, 0.0f64..180.0), 32)) {
        let Ok(tex) = LightTexture::new(&d) else { return Ok(()) };
        for f in Filter::ALL {
            let s = tex.sampler(f);
            for &(c, g) in &q {
                let v = s.cd(c, g);
                prop_assert!(v.is_finite() && v >= 0.0, "{} {} {} -> {}", f, c, g, v);
            }
        }
    }

    #[test]
    fn prop_bilinear_stays_within_its_four_neighbours(d in arb_distribution(), q in prop::collection::vec((0.0f64..360.0, 0.0f64..180.0), 32)) {
        let d = d.with_averaged_poles();
        let Ok(tex) = LightTexture::new(&d) else { return Ok(()) };
        let s = tex.sampler(Filter::Bilinear);
        let full = d.full_planes();
        let g = d.gamma_angles_deg();
        for &(c, gq) in &q {
            if gq < g[0] || gq > g[g.len() - 1] { continue; }
            let ig = g.partition_point(|&x| x <= gq).clamp(1, g.len() - 1) - 1;
            let jc = full.partition_point(|p| p.0 <= c);
            let planes = [full[(jc + full.len() - 1) % full.len()].1, full[jc % full.len()].1];
            let vals: Vec<f64> = planes.iter().flat_map(|&p| [d.value_cd(p, ig), d.value_cd(p, ig + 1)]).collect();
            let lo = vals.iter().cloned().fold(f64::INFINITY, f64::min);
            let hi = vals.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
            let v = s.cd(c, gq);
            prop_assert!(v >= lo - 1e-9 * hi.abs() && v <= hi + 1e-9 * hi.abs(), "{} not in [{}, {}]", v, lo, hi);
        }
    }

    #[test]
    fn prop_rotating_the_data_by_a_grid_step_rotates_the_result(
        n in 1usize..13, k in 0usize..12,
        g in prop::collection::btree_set(0u32..180, 2..8),
        seed in prop::collection::vec(0.0f64..100.0, 12 * 8),
        q in prop::collection::vec((0.0f64..360.0, 0.0f64..180.0), 16),
    ) {
        let step = 360.0 / n as f64;
        let c: Vec<f64> = (0..n).map(|j| j as f64 * step).collect();
        let g: Vec<f64> = g.into_iter().map(f64::from).collect();
        let ng = g.len();
        let val = |j: usize, i: usize| seed[(j % n) * 8 + i];
        let k = k % n;
        let a = Distribution::new(c.clone(), g.clone(), (0..n).flat_map(|j| (0..ng).map(move |i| (j, i))).map(|(j, i)| val(j, i)).collect(), Symmetry::None).unwrap();
        let b = Distribution::new(c, g, (0..n).flat_map(|j| (0..ng).map(move |i| (j, i))).map(|(j, i)| val((j + n - k) % n, i)).collect(), Symmetry::None).unwrap();
        let (Ok(ta), Ok(tb)) = (LightTexture::new(&a), LightTexture::new(&b)) else { return Ok(()) };
        for f in Filter::ALL {
            for &(cq, gq) in &q {
                let (x, y) = (ta.sampler(f).cd(cq, gq), tb.sampler(f).cd(cq + k as f64 * step, gq));
                prop_assert!((x - y).abs() <= 1e-9 * ta.i_max_cd().max(1.0), "{} {} {}: {} vs {}", f, cq, gq, x, y);
            }
        }
    }
}

/// The knot spacing the surface search samples no coarser than: the
/// smallest step between stored γ rows or full-circle C-planes (the seam
/// included), and what a filter on the texture reports.
#[test]
fn knot_spacing_is_the_smallest_step_between_rows_or_planes() {
    use photosolid::model::IntensityField;
    let full = grid(&steps(0.0, 345.0, 15.0), &steps(0.0, 90.0, 5.0), Symmetry::None, solid);
    let tex = LightTexture::new(&full).unwrap();
    assert_eq!(tex.knot_spacing_deg(), Some(5.0));
    assert_eq!(tex.sampler(Filter::Bilinear).knot_spacing_deg(), Some(5.0));
    // Planes 0-350 every 10° but the seam closes with 350 → 0 (10°); γ every 20°.
    let coarse = grid(
        &steps(0.0, 350.0, 10.0),
        &steps(0.0, 180.0, 20.0),
        Symmetry::None,
        solid,
    );
    assert_eq!(LightTexture::new(&coarse).unwrap().knot_spacing_deg(), Some(10.0));
    // An uneven grid: the narrowest step wins.
    let uneven = nonuniform();
    let g = uneven.gamma_angles_deg();
    let want = g.windows(2).map(|w| w[1] - w[0]).fold(f64::INFINITY, f64::min);
    let got = LightTexture::new(&uneven).unwrap().knot_spacing_deg().unwrap();
    assert!(got <= want + 1e-12 && got > 0.0, "{got} vs {want}");
    // Rotational symmetry: one plane, the γ spacing alone.
    let rot = grid(&[0.0], &steps(0.0, 90.0, 2.5), Symmetry::Rotational, |_, g| {
        solid(0.0, g)
    });
    assert_eq!(LightTexture::new(&rot).unwrap().knot_spacing_deg(), Some(2.5));
}
