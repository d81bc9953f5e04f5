//! The compact representations on the GPU (`photosolid::gpu::compact`):
//! spherical harmonics and lobe mixtures evaluated by the compute shader in
//! f32 against the CPU's f64 evaluation of the same stored parameters, the
//! field interface, and their rows in the trade table, on whatever adapter
//! exists (CI: Mesa lavapipe / llvmpipe). Without an adapter the tests
//! print why and pass, unless `PHOTOSOLID_REQUIRE_GPU=1`.
#![cfg(feature = "gpu")]

use crate::common;

use std::path::Path;

use glam::DVec3;
use photosolid::gpu::compact::{compact_row, GpuCompact};
use photosolid::metrics::random_directions;
use photosolid::model::{frame, IntensityField};
use photosolid::reconstruct::sh::sh_index;
use photosolid::reconstruct::{Compact, Filter, LightTexture, Lobe, Lobes, Precision, ShField, ShWindow};

use common::gpu::ctx;

const EPS32: f64 = f32::EPSILON as f64 / 2.0; // unit roundoff 2^-24

/// Test directions: random ones, the poles, the 0/360 seam, the horizon.
fn directions() -> Vec<DVec3> {
    let mut d = random_directions(3000, 0xc0ffee);
    for (c, g) in [
        (0.0, 0.0),
        (0.0, 180.0),
        (0.0, 90.0),
        (359.999, 45.0),
        (180.0, 90.0),
        (90.0, 179.9),
    ] {
        d.push(frame::direction(c, g));
    }
    d
}

/// An f32 bound on |shader − f64| for a series (cd): the Legendre
/// recurrence and the (x + iy)^m powers take at most 4L + 8 roundings per
/// term (Holmes and Featherstone (2002): the normalised recurrence does not
/// amplify them), each term at most |b_lm| · √(2(2l + 1)) (the largest
/// |√(4π) Y_lm|), summed over the terms, times the scale.
fn sh_bound(s: &ShField) -> f64 {
    let l_max = s.degree();
    let b = s.stored_coefficients();
    let terms: f64 = (0..=l_max)
        .map(|l| {
            let norm = (2.0 * (2 * l + 1) as f64).sqrt();
            (0..2 * l + 1).map(|k| b[l * l + k].abs()).sum::<f64>() * norm
        })
        .sum();
    (4 * l_max + 8) as f64 * EPS32 * terms * s.scale_cd()
}

/// An f32 bound for a lobe mixture (cd): per lobe, the dot product of f32
/// vectors (8 roundings of a cosine), times p (t^p's sensitivity), and
/// exp2(p log2 t) with log2's absolute error 2^-21 (WGSL's accuracy near 1)
/// times p ln 2, plus exp2's few ulps.
fn lobes_bound(m: &Lobes) -> f64 {
    m.lobes
        .iter()
        .map(|l| l.weight_cd * (l.exponent * (8.0 * EPS32 + 2f64.powi(-21) * std::f64::consts::LN_2) + 8.0 * EPS32))
        .sum()
}

fn check(gpu: &GpuCompact<'_>, dirs: &[DVec3], bound: f64, what: &str) {
    let got = gpu.sample_dirs_cd(dirs).unwrap();
    let mut worst = 0.0f64;
    for (d, g) in dirs.iter().zip(&got) {
        let e = gpu.exact().intensity_dir_cd(*d);
        assert!(g.is_finite() && *g >= 0.0, "{what}: {g} at {d}");
        worst = worst.max((g - e).abs());
    }
    let peak = dirs
        .iter()
        .map(|d| gpu.exact().intensity_dir_cd(*d))
        .fold(0.0, f64::max);
    eprintln!("{what}: largest |gpu - cpu| {worst:.3e} cd, bound {bound:.3e} cd, peak {peak:.3e} cd");
    assert!(peak > 0.0, "{what}: the test saw no light");
    assert!(worst <= bound, "{what}: {worst} cd over the bound {bound} cd");
}

/// Spherical harmonics of the roadway (L = 0 to 32, f32 and f16
/// coefficients) and of an isotropic source: the shader's f32 evaluation
/// agrees with the CPU's f64 within the rounding bound.
#[test]
fn sh_on_the_gpu_matches_the_cpu() {
    let Some(c) = ctx("sh_on_the_gpu_matches_the_cpu") else {
        return;
    };
    let lum = photosolid::load(Path::new(env!("CARGO_MANIFEST_DIR")).join("data/roadway.ldt")).unwrap();
    let tex = LightTexture::new(lum.distribution()).unwrap();
    let source = tex.sampler(Filter::CatmullRom);
    let dirs = directions();
    for degree in [0, 2, 8, 16, 32] {
        for precision in [Precision::F32, Precision::F16] {
            let s = ShField::new(&source, degree, ShWindow::Lanczos, precision).unwrap();
            let bound = sh_bound(&s);
            let gpu = GpuCompact::new(c, Compact::Sh(s)).unwrap();
            check(&gpu, &dirs, bound, &format!("roadway sh:{degree} {precision:?}"));
        }
    }
    // One harmonic at a time (l ≤ 6, every m): a coefficient stored at the
    // wrong index, or a sine taken for a cosine, would give another function.
    for l in 0..=6usize {
        for m in -(l as isize)..=l as isize {
            let mut coeffs = vec![0.0; 49];
            coeffs[sh_index(l, m)] = 100.0;
            let s = ShField::from_coefficients(&coeffs, 100.0, 6, ShWindow::None, Precision::F32);
            let bound = sh_bound(&s);
            let gpu = GpuCompact::new(c, Compact::Sh(s)).unwrap();
            check(&gpu, &dirs, bound, &format!("Y_{l},{m}"));
        }
    }
    let iso = photosolid::synth::Synth::Isotropic
        .build(&photosolid::synth::GridSpec::uniform(15.0, 5.0).unwrap(), 1000.0)
        .unwrap();
    let iso_tex = LightTexture::new(iso.distribution()).unwrap();
    let s = ShField::new(
        &iso_tex.sampler(Filter::CatmullRom),
        8,
        ShWindow::Lanczos,
        Precision::F32,
    )
    .unwrap();
    let gpu = GpuCompact::new(c, Compact::Sh(s)).unwrap();
    let i0 = iso_tex.sampler(Filter::CatmullRom).intensity_cd(0.0, 0.0);
    for v in gpu.sample_dirs_cd(&dirs).unwrap() {
        assert!((v - i0).abs() <= 1e-5 * i0, "isotropic: {v} vs {i0}");
    }
}

/// Lobe mixtures, including the extremes (p = 0, a hemisphere's step;
/// p = 128 and 1024, delta-like spots; a tilted axis): within the bound, finite.
#[test]
fn lobes_on_the_gpu_match_the_cpu() {
    let Some(c) = ctx("lobes_on_the_gpu_match_the_cpu") else {
        return;
    };
    let lobe = |axis: DVec3, exponent, weight_cd| Lobe {
        axis: axis.normalize(),
        exponent,
        weight_cd,
    };
    let dirs = directions();
    for (name, lobes) in [
        ("cosine", vec![lobe(DVec3::NEG_Z, 1.0, 1000.0)]),
        ("step p=0", vec![lobe(DVec3::NEG_Z, 0.0, 10.0)]),
        (
            "batwing-like",
            vec![
                lobe(DVec3::new(0.6, 0.0, -0.8), 12.0, 800.0),
                lobe(DVec3::new(-0.6, 0.0, -0.8), 12.0, 800.0),
                lobe(DVec3::NEG_Z, 2.0, 300.0),
            ],
        ),
        ("spot p=128", vec![lobe(DVec3::new(0.1, 0.2, -1.0), 128.0, 1e6)]),
        ("spot p=1024", vec![lobe(DVec3::NEG_Z, 1024.0, 1e-6)]),
    ] {
        // The same lobes as rings about the vertical (rotational data) as well.
        for m in [Lobes::new(lobes.clone()), Lobes::rings(lobes)] {
            let name = &format!("{name}{}", if m.rings { " (rings)" } else { "" });
            let bound = lobes_bound(&m);
            let gpu = GpuCompact::new(c, Compact::Lobes(m)).unwrap();
            check(&gpu, &dirs, bound, name);
            // On the first lobe's axis every lobe adds its share: the CPU's value, within the bound.
            let axis = lobes_axis(&gpu);
            let on_axis = gpu.sample_dirs_cd(&[axis]).unwrap()[0];
            let want = gpu.exact().intensity_dir_cd(axis);
            assert!(
                (on_axis - want).abs() <= bound && want > 0.0,
                "{name}: {on_axis} vs {want} on the axis"
            );
        }
    }
}

/// The field interface: names, bytes, batches equal to single lookups, zero
/// and non-finite directions give 0; the row's difference is the same bound.
#[test]
fn compact_gpu_as_field() {
    let Some(c) = ctx("compact_gpu_as_field") else {
        return;
    };
    let lum = photosolid::load(Path::new(env!("CARGO_MANIFEST_DIR")).join("data/roadway.ldt")).unwrap();
    let tex = LightTexture::new(lum.distribution()).unwrap();
    let s = ShField::new(&tex.sampler(Filter::CatmullRom), 8, ShWindow::Lanczos, Precision::F16).unwrap();
    let (cpu_name, cpu_bytes) = (s.name(), s.bytes());
    let gpu = GpuCompact::new(c, Compact::Sh(s)).unwrap();
    assert_eq!(gpu.name(), format!("{cpu_name}+gpu"));
    assert_eq!(gpu.bytes(), cpu_bytes);
    assert_eq!(gpu.bytes(), 81 * 2);
    let cs = [0.0, 33.3, 359.9];
    let gs = [0.0, 60.0, 180.0];
    let mut grid = vec![0.0; cs.len() * gs.len()];
    gpu.sample_grid(&cs, &gs, &mut grid);
    for (ic, &cc) in cs.iter().enumerate() {
        for (ig, &g) in gs.iter().enumerate() {
            assert_eq!(gpu.intensity_cd(cc, g), grid[ic * gs.len() + ig], "({cc}, {g})");
        }
    }
    assert_eq!(gpu.intensity_dir_cd(DVec3::ZERO), 0.0);
    assert_eq!(gpu.intensity_cd(f64::NAN, 3.0), 0.0);
    assert!(gpu.sample_dirs_cd(&[]).unwrap().is_empty());
    let row = compact_row(&gpu, &directions(), 1).unwrap();
    assert!(
        row.ns_per_sample_dispatch > 0.0 && row.vs_exact_max_cd < 1e-4 * lum.distribution().max_cd(),
        "{row:?}"
    );
}

/// The axis of the first lobe of a mixture on the device.
fn lobes_axis(gpu: &GpuCompact<'_>) -> DVec3 {
    match gpu.compact() {
        Compact::Lobes(m) => m.lobes[0].axis,
        Compact::Sh(_) => DVec3::NEG_Z,
    }
}

/// A rotationally symmetric series is stored zonal on the device as on the
/// CPU: L + 1 coefficients (68 bytes for `sh:16`), the m = 0 sum only, the
/// same values within the rounding bound.
#[test]
fn zonal_series_on_the_gpu() {
    let Some(c) = ctx("zonal_series_on_the_gpu") else {
        return;
    };
    let lum = photosolid::synth::Synth::Batwing
        .build(&photosolid::synth::GridSpec::uniform(5.0, 2.5).unwrap(), 1000.0)
        .unwrap();
    let tex = LightTexture::new(lum.distribution()).unwrap();
    let s = ShField::new(&tex.sampler(Filter::CatmullRom), 16, ShWindow::Lanczos, Precision::F32).unwrap();
    assert!(s.is_zonal());
    let bound = sh_bound(&s);
    let gpu = GpuCompact::new(c, Compact::Sh(s)).unwrap();
    assert_eq!(gpu.bytes(), 17 * 4);
    check(&gpu, &directions(), bound, "batwing sh:16 zonal");
}
