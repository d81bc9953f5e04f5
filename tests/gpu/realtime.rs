//! The real-time lookup path (`photosolid::gpu::realtime`): hardware
//! filtering against the exact filter on the same texels, the adapter's
//! sub-texel precision, and the field interface, on whatever adapter exists
//! (CI: Mesa lavapipe / llvmpipe). Without an adapter the tests print why
//! and pass, unless `PHOTOSOLID_REQUIRE_GPU=1`.
#![cfg(feature = "gpu")]

use crate::common;

use std::path::Path;

use glam::DVec3;
use photosolid::gpu::precision::subtexel_precision;
use photosolid::gpu::realtime::{HardwareLookup, RealtimeTexture};
use photosolid::metrics::random_directions;
use photosolid::model::IntensityField;
use photosolid::reconstruct::{render, Filter, LightTexture, Lookup, Precision, Rendered, StoredTexture};
use photosolid::report::shading::{self, PlaneView};

use common::gpu::ctx;

fn rendered(file: &str, factor: u32) -> (Rendered, photosolid::model::Symmetry) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("data").join(file);
    let lum = photosolid::load(&path).unwrap();
    let tex = LightTexture::new(lum.distribution()).unwrap();
    (render(&tex, Filter::CatmullRom, factor).unwrap(), tex.symmetry())
}

/// Largest difference between neighbouring texels (I / I_max), both axes,
/// C periodic: what a weight error of one unit moves a bilinear result by.
fn max_step(r: &Rendered) -> f64 {
    let (h, w) = (r.mapping.height, r.mapping.width);
    let v = |i: usize, j: usize| f64::from(r.data[i * w + j % w]);
    let mut d = 0.0f64;
    for i in 0..h {
        for j in 0..w {
            d = d.max((v(i, j + 1) - v(i, j)).abs());
            if i + 1 < h {
                d = d.max((v(i + 1, j) - v(i, j)).abs());
            }
        }
    }
    d
}

/// The largest |hardware − exact| lookup (fraction of I_max) that a
/// weight error `eps` (texels, measured by the probe) allows on `r`.
/// Bilinear: one weight error per axis moves the result by at most
/// eps * step each; Catmull-Rom's merged middle fetch (weight <= 1.25) per
/// axis, summed with |weights| <= 1.3 over the other axis: under 3 eps step.
/// Plus f32 coordinates: s and t carry about 8 ulps (2^-20) after atan2 and
/// scaling, times the texels per unit coordinate; and f32 arithmetic.
fn lookup_tolerance(r: &Rendered, lookup: HardwareLookup, eps: f64) -> f64 {
    let k = if lookup == HardwareLookup::Linear { 2.0 } else { 3.0 };
    let texels = r.mapping.height.max(r.mapping.width) as f64;
    (k * eps + k * texels * 2f64.powi(-20)) * max_step(r) + 1e-6
}

/// Hardware lookups against the exact lookups on the same texels (whole and
/// symmetry-reduced storage), within what the measured sub-texel precision allows.
#[test]
fn hardware_lookups_match_exact_within_weight_precision() {
    let Some(c) = ctx("hardware_lookups_match_exact_within_weight_precision") else {
        return;
    };
    let p = subtexel_precision(c, 4097).unwrap();
    let eps = p.max_weight_error;
    println!(
        "{}: {} sub-texel weight levels ({:.1} bits), max weight error {eps:.2e}",
        p.adapter, p.distinct_weights, p.bits
    );
    let mut dirs = random_directions(20_000, 7);
    dirs.extend(seam_and_pole_directions());
    dirs.push(DVec3::new(1.0, -1e-9, 0.3));
    for file in [
        "roadway.ldt",
        "batwing.ldt",
        "spot_p8_c40.ldt",
        "cosine_p20_nonuniform.ldt",
    ] {
        let (r, sym) = rendered(file, 5);
        for lookup in HardwareLookup::ALL {
            if lookup == HardwareLookup::Nearest {
                continue; // ties at texel edges make nearest ill-posed at the probe points
            }
            for reduced in [None, Some(sym)] {
                let t = RealtimeTexture::new(c, &r, reduced, Precision::F32, lookup).unwrap();
                let hw = t.sample_dirs_cd(&dirs).unwrap();
                let ex = t.exact();
                let worst = dirs
                    .iter()
                    .zip(&hw)
                    .map(|(d, g)| (g - ex.intensity_dir_cd(*d)).abs() / r.i_max_cd)
                    .fold(0.0, f64::max);
                let tol = lookup_tolerance(&r, lookup, eps);
                println!(
                    "{file} {lookup:?} reduced={} ({:?}): max |hw - exact| = {worst:.3e} of I_max (tol {tol:.2e})",
                    reduced.is_some(),
                    t.format()
                );
                assert!(
                    worst <= tol,
                    "{file} {lookup:?} reduced={reduced:?}: {worst:e} > {tol:e}"
                );
                assert!(hw.iter().all(|v| v.is_finite() && *v >= 0.0));
            }
        }
    }
}

/// 16- and 8-bit normalised-integer textures on the GPU (`R16Unorm`,
/// `R8Unorm`): the hardware reads the same steps the exact lookup reads,
/// within the weight precision plus one step (the filtered value may be
/// rounded to the format); without `TEXTURE_FORMAT_16BIT_NORM` the
/// 16-bit texture falls back to f16 and says so.
#[test]
fn quantised_textures_match_exact_on_the_gpu() {
    let Some(c) = ctx("quantised_textures_match_exact_on_the_gpu") else {
        return;
    };
    let eps = subtexel_precision(c, 4097).unwrap().max_weight_error;
    let dirs = random_directions(20_000, 11);
    for file in ["roadway.ldt", "spot_p8_c40.ldt"] {
        let (r, _) = rendered(file, 5);
        for precision in [Precision::U16, Precision::U8] {
            let t = RealtimeTexture::new(c, &r, None, precision, HardwareLookup::Linear).unwrap();
            if t.precision() != precision {
                println!(
                    "{file}: {precision:?} not on this adapter (no TEXTURE_FORMAT_16BIT_NORM): {:?}",
                    t.format()
                );
                assert_eq!((precision, t.precision()), (Precision::U16, Precision::F16));
                continue;
            }
            let want = if precision == Precision::U8 {
                photosolid::gpu::TextureFormat::R8Unorm
            } else {
                photosolid::gpu::TextureFormat::R16Unorm
            };
            assert_eq!(t.format(), want);
            assert_eq!(t.bytes(), precision.bytes() * r.data.len());
            let hw = t.sample_dirs_cd(&dirs).unwrap();
            let ex = t.exact();
            let worst = dirs
                .iter()
                .zip(&hw)
                .map(|(d, g)| (g - ex.intensity_dir_cd(*d)).abs() / r.i_max_cd)
                .fold(0.0, f64::max);
            // A texture unit may return a filtered 8-bit texel at the format's own precision
            // (llvmpipe filters UNORM8 in 8-bit fixed point): one step of the scale on top.
            let steps = if precision == Precision::U8 { 255.0 } else { 65_535.0 };
            let tol = lookup_tolerance(&r, HardwareLookup::Linear, eps) + f64::from(ex.unorm_scale()) / steps;
            println!("{file} {precision:?}: max |hw - exact| = {worst:.3e} of I_max (tol {tol:.2e})");
            assert!(worst <= tol, "{file} {precision:?}: {worst:e} > {tol:e}");
            assert!(hw.iter().all(|v| v.is_finite() && *v >= 0.0));
        }
    }
}

/// BC6H on the GPU (`Bc6hRgbUfloat`, where the adapter has
/// `TEXTURE_COMPRESSION_BC`): the texture unit's own decoder reads the
/// blocks the encoder wrote, whole 4 x 4 blocks or padded to them (the shader
/// addresses the stored texels and never reads the padding), whole circle or
/// a symmetry's sector. At texel centres a nearest lookup returns exactly the
/// texel bcdec decoded (BC6H decodes to half floats bit for bit); bilinear and
/// Catmull-Rom lookups, the 0/360 seam, the poles and the sector edges
/// included, stay within the weight-precision tolerance of the exact lookup on
/// those texels, plus half an f16 step per unit of summed |weight| (a texture
/// unit may filter a half-float format in half floats).
#[test]
fn bc6h_textures_are_decoded_by_the_gpu() {
    let Some(c) = ctx("bc6h_textures_are_decoded_by_the_gpu") else {
        return;
    };
    if !photosolid::reconstruct::bc6h::available() {
        println!("SKIPPED bc6h_textures_are_decoded_by_the_gpu: built without the bc6h feature");
        return;
    }
    if !c.bc_compression() {
        let (r, _) = rendered("roadway.ldt", 3);
        let t = RealtimeTexture::new(c, &r, None, Precision::Bc6h, HardwareLookup::Nearest).unwrap();
        println!(
            "{}: no TEXTURE_COMPRESSION_BC, BC6H stored as {:?}",
            c.adapter(),
            t.format()
        );
        assert_eq!(
            (t.precision(), t.format()),
            (Precision::F16, photosolid::gpu::TextureFormat::R16Float)
        );
        return;
    }
    let eps = subtexel_precision(c, 4097).unwrap().max_weight_error;
    let mut dirs = random_directions(20_000, 13);
    dirs.extend(seam_and_pole_directions());
    let mut padded = 0;
    // Whole blocks (the roadway at x5 and x3: 360 x 360, 216 x 216) and not
    // (the spot, 5 x 900; the batwing's sector and the cosine's nonuniform grid).
    let cases = [
        ("roadway.ldt", 5),
        ("roadway.ldt", 3),
        ("spot_p8_c40.ldt", 5),
        ("batwing.ldt", 5),
        ("cosine_p20_nonuniform.ldt", 3),
    ];
    for (file, factor) in cases {
        let (r, sym) = rendered(file, factor);
        for reduced in [None, Some(sym)] {
            let t = RealtimeTexture::new(c, &r, reduced, Precision::Bc6h, HardwareLookup::Nearest).unwrap();
            let (h, (first, w)) = (t.exact().height(), t.exact().stored_columns());
            let full = t.exact().full_width();
            let whole_blocks = h % 4 == 0 && w % 4 == 0;
            padded += usize::from(!whole_blocks);
            let name = format!("{file} x{factor} reduced={} ({w} x {h} texels)", reduced.is_some());
            assert_eq!(
                (t.precision(), t.format()),
                (Precision::Bc6h, photosolid::gpu::TextureFormat::Bc6hRgbUfloat),
                "{name}"
            );
            assert_eq!(t.bytes(), w.div_ceil(4) * h.div_ceil(4) * 16, "{name}");
            // Texel centres, through the nearest sampler: the hardware's decode against bcdec's.
            let centres: Vec<(f64, f64)> = (0..h)
                .flat_map(|i| {
                    (0..w).map(move |j| {
                        let c_deg = 360.0 * ((first + j) as f64 + 0.5) / full as f64;
                        (c_deg, 180.0 * (i as f64 + 0.5) / h as f64)
                    })
                })
                .collect();
            let hw = t.sample_angles_cd(&centres).unwrap();
            let worst = hw
                .iter()
                .zip(t.exact().texels())
                .map(|(g, &x)| (g / r.i_max_cd - f64::from(x)).abs())
                .fold(0.0, f64::max);
            println!("{name}: BC6H texel centres, max |gpu - bcdec| = {worst:.3e} of I_max");
            assert!(worst <= 1e-6, "{name}: {worst:e}");
            for (lookup, weights) in [
                (HardwareLookup::Linear, 1.0),
                (HardwareLookup::CatmullRomLinearFetch, 1.7),
            ] {
                let t = RealtimeTexture::new(c, &r, reduced, Precision::Bc6h, lookup).unwrap();
                let hw = t.sample_dirs_cd(&dirs).unwrap();
                let worst = dirs
                    .iter()
                    .zip(&hw)
                    .map(|(d, g)| (g - t.exact().intensity_dir_cd(*d)).abs() / r.i_max_cd)
                    .fold(0.0, f64::max);
                let tol = lookup_tolerance(&r, lookup, eps) + weights * 2f64.powi(-11);
                println!("{name}: BC6H {lookup:?}, max |hw - exact| = {worst:.3e} of I_max (tol {tol:.2e})");
                assert!(worst <= tol, "{name} {lookup:?}: {worst:e} > {tol:e}");
                assert!(hw.iter().all(|v| v.is_finite() && *v >= 0.0), "{name} {lookup:?}");
            }
        }
    }
    assert!(
        padded >= 2,
        "the cases include textures padded to whole blocks ({padded})"
    );
}

/// The poles, the 0/360 seam and C-sector edges, approached from both sides.
fn seam_and_pole_directions() -> Vec<DVec3> {
    let mut dirs = vec![DVec3::NEG_Z, DVec3::Z, DVec3::X, DVec3::Y, DVec3::NEG_Y, DVec3::NEG_X];
    for k in 0..64 {
        let z = -1.0 + 2.0 * (k as f64 + 0.5) / 64.0;
        for e in [-1e-3, -1e-6, 0.0, 1e-6, 1e-3] {
            dirs.push(DVec3::new(1.0, e, z)); // C = 0 / 360
            dirs.push(DVec3::new(-1.0, e, z)); // C = 180
            dirs.push(DVec3::new(e, 1.0, z)); // C = 90
            dirs.push(DVec3::new(e, -1.0, z)); // C = 270
        }
    }
    dirs
}

/// The probe sees monotone weights from 0 to 1 and at least 4 bits.
#[test]
fn subtexel_precision_probe() {
    let Some(c) = ctx("subtexel_precision_probe") else {
        return;
    };
    let p = subtexel_precision(c, 65_537).unwrap();
    println!("{p:?}");
    assert!(p.distinct_weights >= 17, "{p:?}");
    assert!(p.bits <= 16.0 + 1e-9, "the probe resolves at most 16 bits: {p:?}");
    // The weight error of b-bit weights is at most one level.
    assert!(p.max_weight_error <= 2f64.powf(-p.bits.floor()) + 1e-6, "{p:?}");
    assert!(subtexel_precision(c, 1).is_err());
}

/// The field interface: batch, grid and single lookups agree; zero and
/// non-finite input give 0.
#[test]
fn realtime_texture_as_field() {
    let Some(c) = ctx("realtime_texture_as_field") else {
        return;
    };
    let (r, _) = rendered("roadway.ldt", 2);
    let t = RealtimeTexture::new(c, &r, None, Precision::F16, HardwareLookup::CatmullRomLinearFetch).unwrap();
    assert_eq!(t.precision(), Precision::F16);
    assert_eq!(t.bytes(), 2 * r.data.len());
    assert!(t.name().ends_with("+f16+gpu"), "{}", t.name());
    let cs = [0.0, 33.3, 90.0, 359.9];
    let gs = [0.0, 12.5, 60.0, 89.0, 180.0];
    let mut grid = vec![0.0; cs.len() * gs.len()];
    t.sample_grid(&cs, &gs, &mut grid);
    for (ic, &cc) in cs.iter().enumerate() {
        for (ig, &g) in gs.iter().enumerate() {
            let one = t.intensity_cd(cc, g);
            assert_close!(one, grid[ic * gs.len() + ig], abs = 1e-9 * r.i_max_cd, "({cc}, {g})");
        }
    }
    assert_eq!(t.intensity_dir_cd(DVec3::ZERO), 0.0);
    assert_eq!(t.intensity_cd(f64::NAN, 3.0), 0.0);
    let b = t.intensity_batch_cd(&[(f64::INFINITY, 1.0), (10.0, 45.0)]);
    assert_eq!(b[0], 0.0);
    assert_close!(b[1], t.intensity_cd(10.0, 45.0), abs = 1e-9 * r.i_max_cd);
    assert!(t.sample_dirs_cd(&[]).unwrap().is_empty());
}

/// The shaded plane (Wallner's (2008) Figure 5 setting): GPU and CPU images agree
/// within the lookup tolerance times the largest cos/d² (1/h²); bilinear and
/// Catmull-Rom differ; the EXR reads back with the same values.
#[test]
fn shaded_plane_gpu_matches_cpu() {
    let Some(c) = ctx("shaded_plane_gpu_matches_cpu") else {
        return;
    };
    let eps = subtexel_precision(c, 4097).unwrap().max_weight_error;
    let (r, _) = rendered("roadway.ldt", 5);
    let view = PlaneView {
        pixels: 96,
        ..PlaneView::default()
    };
    let mut images = Vec::new();
    let device = photosolid::device::device().unwrap();
    for lookup in [Lookup::Bilinear, Lookup::CatmullRom] {
        let shaded = shading::shade_gpu(device, &r, lookup, &view).unwrap();
        assert_eq!(shaded.store.adapter, c.adapter().to_string());
        // f32 where the adapter filters it (lavapipe), else f16 (llvmpipe's GL).
        let (format, precision) = if c.float32_filterable() {
            ("R32Float", Precision::F32)
        } else {
            ("R16Float", Precision::F16)
        };
        assert_eq!(
            (shaded.store.texture_format.as_str(), shaded.store.precision),
            (format, precision)
        );
        let exact = StoredTexture::new(&r, None, precision, lookup);
        let cpu = shading::shade_cpu(&exact, &view).unwrap();
        let gpu = shaded.lux;
        let worst = gpu.iter().zip(&cpu).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
        let hardware = HardwareLookup::for_lookup(lookup);
        let tol = lookup_tolerance(&r, hardware, eps) * r.i_max_cd / (view.height_m * view.height_m);
        let e_max = cpu.iter().copied().fold(0.0, f64::max);
        println!("{lookup:?}: E max {e_max:.1} lx, max |gpu - cpu| = {worst:.3e} lx (tol {tol:.2e})");
        assert!(e_max > 0.0);
        assert!(worst <= tol, "{lookup:?}: {worst} > {tol}");
        images.push(gpu);
    }
    let diff: Vec<f64> = images[0].iter().zip(&images[1]).map(|(a, b)| a - b).collect();
    assert!(
        diff.iter().any(|d| d.abs() > 1e-3),
        "bilinear and Catmull-Rom shade differently"
    );
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("diff.exr");
    shading::write_exr(&path, &view, &diff, "bilinear - catmull-rom").unwrap();
    let img = exr::prelude::read_first_flat_layer_from_file(&path).unwrap();
    let back = img.layer_data.channel_data.list[0]
        .sample_data
        .values_as_f32()
        .collect::<Vec<f32>>();
    assert_eq!(back.len(), diff.len());
    for (a, b) in back.iter().zip(&diff) {
        assert_eq!(*a, *b as f32);
    }
    let png = shading::png(&view, &diff, shading::Tone::Diverging).unwrap();
    assert_eq!(&png[1..4], b"PNG");
    assert!(shading::shade_gpu(device, &r, Lookup::Bilinear, &PlaneView { pixels: 0, ..view }).is_err());
}

/// A quick `tradeoff --gpu` of `lum` against `against` (2,000 dense
/// directions, x2 solids, 500 timing samples once), textures at `factor`.
fn gpu_trade(
    lum: &photosolid::Luminaire,
    against: photosolid::compare::Against,
    factor: u32,
) -> photosolid::compare::trade::TradeOptions {
    use photosolid::compare::{CompareOptions, Directions};
    photosolid::compare::trade::TradeOptions {
        factors: vec![factor],
        compare: CompareOptions {
            against: Some(against),
            truth: photosolid::synth::Truth::of_luminaire(lum),
            directions: Directions::Dense(2000),
            factor: 2,
            tolerance: 0.01,
            timing_samples: 500,
            timing_repeats: 1,
            ..CompareOptions::default()
        },
        gpu: true,
        ..Default::default()
    }
}

/// The trade table's `+gpu` rows: measured like the CPU rows (truth and
/// withheld), naming the adapter; their errors match the exact lookup of the
/// same texture to within the hardware's difference.
#[test]
fn trade_table_gpu_rows() {
    use photosolid::compare::trade::trade_table;
    use photosolid::compare::Against;
    let Some(c) = ctx("trade_table_gpu_rows") else {
        return;
    };
    let lum = photosolid::load(Path::new(env!("CARGO_MANIFEST_DIR")).join("data/batwing.ldt")).unwrap();
    for against in [Against::Truth, Against::Withheld] {
        let t = trade_table(lum.distribution(), None, &gpu_trade(&lum, against, 5), &|_, _, _| {}).unwrap();
        let row = |name: &str| t.rows.iter().find(|r| r.representation == name).unwrap();
        for (gpu, cpu) in [
            ("catmull-rom@x5/bilinear+gpu", "catmull-rom@x5/bilinear"),
            ("catmull-rom@x5/catmull-rom+gpu", "catmull-rom@x5/catmull-rom"),
        ] {
            let (g, e) = (row(gpu), row(cpu));
            println!("{against}: {gpu}: {g:?}");
            assert_eq!(g.adapter.as_deref(), Some(c.adapter().to_string().as_str()));
            assert!(g.ns_per_sample_gpu.is_some_and(|v| v > 0.0) && g.ns_per_sample > 0.0);
            assert!(g.subtexel_bits.is_some_and(|b| b >= 4.0));
            let d = g.hardware_vs_exact_max_pct.unwrap();
            assert!(d < 0.01, "{gpu}: {d} % of I_max from the exact lookup");
            assert!(e.ns_per_sample_gpu.is_none() && e.adapter.is_none());
            // Same texels, same metrics: the radial maximum moves by at most
            // the hardware difference, plus f16 rounding (half an ulp, 2^-11
            // of I_max) where the adapter cannot filter R32Float.
            let f16 = if g.texture_format.as_deref() == Some("R16Float") {
                100.0 * 2f64.powi(-11)
            } else {
                0.0
            };
            assert_close!(
                g.radial_max_pct,
                e.radial_max_pct,
                abs = d + f16 + 1e-6,
                "{gpu}: {g:?} vs {e:?}"
            );
        }
        // The compute shader's series and mixture: the same stored parameters in f32.
        for (gpu, cpu) in [("sh:16+gpu", "sh:16"), ("lobes:4+gpu", "lobes:4")] {
            let (g, e) = (row(gpu), row(cpu));
            println!("{against}: {gpu}: {g:?}");
            assert_eq!(g.adapter.as_deref(), Some(c.adapter().to_string().as_str()));
            assert!(g.ns_per_sample_gpu.is_some_and(|v| v > 0.0) && g.ns_per_sample > 0.0);
            assert!(g.texture_format.is_none() && g.subtexel_bits.is_none());
            assert_eq!((g.bytes, g.window.as_deref()), (e.bytes, e.window.as_deref()));
            let d = g.hardware_vs_exact_max_pct.unwrap();
            assert!(d < 1e-3, "{gpu}: {d} % from the CPU evaluation");
            // Relative to the row's own peak, which is at most about I_max: a margin of 2.
            assert_close!(g.radial_max_pct, e.radial_max_pct, abs = 2.0 * d + 1e-6, "{gpu}");
        }
    }
}

/// A built-in representation on the open trait evaluated by the GPU
/// (`c-mean+gpu`, `Representation::build_gpu`). batwing.ldt is the same in
/// every plane, so its mean profile is the file (to rounding): the GPU reads
/// the texels of `catmull-rom@x5/bilinear+gpu`, and stays within the
/// hardware lookup's difference (the trade table's bound, 0.01 % of I_max)
/// of the CPU's exact lookup of the same texture.
#[test]
fn an_open_representation_on_the_gpu() {
    use photosolid::registry::{Recon, Reconstructions};
    let Some(_) = ctx("an_open_representation_on_the_gpu") else {
        return;
    };
    let lum = photosolid::load(Path::new(env!("CARGO_MANIFEST_DIR")).join("data/batwing.ldt")).unwrap();
    let names = ["c-mean+gpu", "catmull-rom@x5/bilinear+gpu", "catmull-rom@x5/bilinear"];
    let recons: Vec<Recon> = names.iter().map(|n| n.parse().unwrap()).collect();
    assert!(recons[0].on_gpu() && !recons[2].on_gpu());
    assert_eq!(recons[0].to_string(), "c-mean+gpu");
    let recs = Reconstructions::new(lum.distribution().clone(), &recons).unwrap();
    let dirs: Vec<(f64, f64)> = (0..50)
        .flat_map(|i| (0..59).map(move |j| (7.3 * f64::from(i), 3.1 * f64::from(j))))
        .collect();
    let values: Vec<Vec<f64>> = recons
        .iter()
        .map(|r| recs.field(*r).unwrap().intensity_batch_cd(&dirs))
        .collect();
    let i_max = lum.distribution().max_cd();
    // Where the adapter cannot filter R32Float (llvmpipe GL) the texels are half floats: half an
    // ulp, 2^-11 of I_max, more from the CPU's f32 texels.
    let gpu_name = recs.field(recons[0]).unwrap().name();
    let f16 = if gpu_name.contains("+f16") { 2f64.powi(-11) } else { 0.0 };
    for (k, dir) in dirs.iter().enumerate() {
        assert_close!(values[0][k], values[1][k], abs = 1e-6 * i_max, "{dir:?}");
        assert_close!(
            values[0][k],
            values[2][k],
            abs = (1e-4 + f16) * i_max,
            "{gpu_name} {dir:?}"
        );
    }
}

/// `tradeoff --gpu` lists the GPU's evaluation of a representation on the
/// open trait after its CPU row: `c-mean+gpu` names the adapter and its
/// largest difference from `c-mean`, which on a profile this smooth is the
/// x5 texture's bilinear reading (under 0.1 % of I_max).
#[test]
fn trade_table_lists_open_gpu_twins() {
    use photosolid::compare::trade::trade_table;
    use photosolid::compare::Against;
    use photosolid::synth::{GridSpec, Synth};
    let Some(c) = ctx("trade_table_lists_open_gpu_twins") else {
        return;
    };
    let grid = GridSpec::uniform(15.0, 5.0).unwrap();
    let mut lum = Synth::CosinePower { p: 5.0 }.build(&grid, 1000.0).unwrap();
    lum.set_distribution(lum.distribution().expand(24));
    let t = trade_table(
        lum.distribution(),
        None,
        &gpu_trade(&lum, Against::Truth, 1),
        &|_, _, _| {},
    )
    .unwrap();
    let at = |name: &str| t.rows.iter().position(|r| r.representation == name).expect(name);
    assert_eq!(at("c-mean+gpu"), at("c-mean") + 1);
    let g = &t.rows[at("c-mean+gpu")];
    assert_eq!(g.adapter.as_deref(), Some(c.adapter().to_string().as_str()));
    assert!(g.ns_per_sample_gpu.is_none() && g.ns_per_sample > 0.0);
    let d = g.hardware_vs_exact_max_pct.unwrap();
    assert!(d > 0.0 && d < 0.1, "{d} % of I_max");
    assert!(t.rows[at("c-mean")].adapter.is_none());
}
