//! The GPU render against the CPU reference `reconstruct::render_planned`,
//! from the same plans, on whatever adapter exists (CI: Mesa lavapipe via
//! `WGPU_BACKEND=vulkan`, llvmpipe via `WGPU_BACKEND=gl`).
//!
//! Without an adapter the tests print why and pass, unless
//! `PHOTOSOLID_REQUIRE_GPU=1`, which turns a missing adapter into a failure.
#![cfg(feature = "gpu")]

use std::path::{Path, PathBuf};
use std::sync::Once;

use crate::common;

use photosolid::gpu::{self, Backend, GpuContext, GpuError, RenderJob, RenderKernel, Resolved};
use photosolid::reconstruct::{render_with, Filter, LightTexture, RenderOptions, Rendered};
use photosolid::synth::{GridSpec, Synth};

/// Largest allowed |gpu − cpu| per texel (texels are I / I_max).
const TOL: f32 = 1e-5;

fn require_gpu() -> bool {
    std::env::var("PHOTOSOLID_REQUIRE_GPU").is_ok_and(|v| v == "1")
}

/// The process-wide context, or `None` (test skipped) when there is no adapter.
fn ctx(test: &str) -> Option<&'static GpuContext> {
    static PRINT: Once = Once::new();
    match GpuContext::global() {
        Ok(c) => {
            PRINT.call_once(|| {
                eprintln!(
                    "gpu adapter: {} (WGPU_BACKEND={}, set-up {:.0?})",
                    c.adapter(),
                    std::env::var("WGPU_BACKEND").unwrap_or_else(|_| "unset".into()),
                    c.setup_time()
                )
            });
            Some(c)
        }
        Err(e) if require_gpu() => panic!("PHOTOSOLID_REQUIRE_GPU=1 but: {e}"),
        Err(e) => {
            eprintln!("SKIPPED {test}: {e}");
            None
        }
    }
}

/// Every filter of the contract: the defaults plus a Mitchell with other B, C.
fn filters() -> Vec<Filter> {
    let mut f = Filter::ALL.to_vec();
    f.push(Filter::Mitchell { b: 0.0, c: 0.75 });
    f
}

/// Max |gpu − cpu| over the texels; panics on a size or metadata mismatch.
fn max_diff(gpu: &Rendered, cpu: &Rendered, what: &str) -> f32 {
    assert_eq!(gpu.mapping, cpu.mapping, "{what}: mapping");
    assert_eq!(gpu.data.len(), cpu.data.len(), "{what}: length");
    assert_eq!(
        (gpu.filter, gpu.factor, gpu.i_max_cd, gpu.measured_gamma),
        (cpu.filter, cpu.factor, cpu.i_max_cd, cpu.measured_gamma),
        "{what}: metadata"
    );
    let (k, err) = gpu
        .data
        .iter()
        .zip(&cpu.data)
        .map(|(g, c)| {
            if g.is_nan() || c.is_nan() {
                f32::INFINITY
            } else {
                (g - c).abs()
            }
        })
        .enumerate()
        .fold((0, 0.0f32), |a, b| if b.1 > a.1 { b } else { a });
    assert!(
        err <= TOL,
        "{what}: texel {k} (row {}, col {}): gpu {} cpu {} (|diff| {err:e} > {TOL:e})",
        k / gpu.mapping.width,
        k % gpu.mapping.width,
        gpu.data[k],
        cpu.data[k]
    );
    err
}

/// The GPU's clamped-texel count is the CPU's, or differs from it only by
/// texels whose value lies within [`TOL`] of 0 ([`gpu::clamp_count_range`]):
/// an overshoot that ends within rounding of 0 takes either sign under FMA
/// contraction (an NVIDIA H200 clamps 2 of the corpus subset's renders
/// differently from the CPU; lavapipe matches it).
fn assert_clamped(job: &RenderJob<'_>, gpu_count: usize, cpu_count: usize, what: &str) {
    if gpu_count == cpu_count {
        return;
    }
    let range = gpu::clamp_count_range(job, TOL);
    assert!(
        range.contains(&gpu_count),
        "{what}: clamped texels gpu {gpu_count} cpu {cpu_count}; a device within {TOL:e} of the CPU clamps {range:?}"
    );
    eprintln!("{what}: clamped texels gpu {gpu_count} cpu {cpu_count}, within rounding of 0 ({range:?})");
}

/// The range of clamped counts: exactly the CPU's count at tolerance 0, wider
/// (and containing it) at a positive tolerance, `0..=0` for a job that does
/// not clamp. CPU only: runs without an adapter.
#[test]
fn clamp_count_range_brackets_the_cpu_count() {
    let tex = texture(Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/data/spot_p8_c40.ldt")));
    let mut wider = 0;
    for filter in [Filter::CatmullRom, Filter::Mitchell { b: 0.0, c: 0.75 }] {
        let plan = tex.render_plan(filter, 5).unwrap();
        for clamp in [true, false] {
            let job = RenderJob {
                texture: &tex,
                plan: &plan,
                clamp,
            };
            let cpu = gpu::render_cpu(&job);
            let exact = gpu::clamp_count_range(&job, 0.0);
            assert_eq!(exact, cpu.clamped..=cpu.clamped, "[{filter}] clamp {clamp}");
            let range = gpu::clamp_count_range(&job, 1e-3);
            assert!(range.contains(&cpu.clamped), "[{filter}] {range:?}");
            if !clamp {
                assert_eq!(range, 0..=0);
            } else {
                assert!(
                    cpu.clamped > 0,
                    "[{filter}]: the spot's cut-off makes the cubic overshoot"
                );
                wider += range.end() - range.start();
            }
        }
    }
    assert!(wider > 0, "overshoots within 1e-3 of 0 widen the range");
}

/// Compare GPU renders (both kernels) and CPU renders of the same jobs;
/// returns the max difference.
fn check_jobs(c: &GpuContext, jobs: &[RenderJob<'_>], names: &[String]) -> f32 {
    let mut worst = 0.0f32;
    for kernel in RenderKernel::ALL {
        let out = c.render_jobs_with(jobs, kernel).unwrap();
        assert_eq!(out.len(), jobs.len());
        for ((job, g), name) in jobs.iter().zip(&out).zip(names) {
            let cpu = gpu::render_cpu(job);
            let name = format!("{name} ({} kernel)", kernel.name());
            worst = worst.max(max_diff(g, &cpu, &name));
            assert_clamped(job, g.clamped, cpu.clamped, &name);
        }
    }
    worst
}

/// The two-pass kernel (the default) against the fused one and the CPU on
/// the generated data/ files, every filter, factors 1, 5 and 12.
#[test]
fn two_pass_matches_fused_and_cpu_on_data_files() {
    let Some(c) = ctx("two_pass_matches_fused_and_cpu_on_data_files") else {
        return;
    };
    assert_eq!(RenderKernel::default(), RenderKernel::TwoPass);
    let dir = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/data"));
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "ldt"))
        .collect();
    files.sort();
    assert!(files.len() >= 5, "data/ holds the generated .ldt files");
    let mut worst = 0.0f32;
    for path in &files {
        let tex = texture(path);
        let mut items = Vec::new();
        for factor in [1, 5, 12] {
            for filter in filters() {
                items.push((
                    &tex,
                    RenderOptions {
                        filter,
                        factor,
                        ..RenderOptions::default()
                    },
                ));
            }
        }
        let plans = gpu::plans(&items).unwrap();
        let jobs = gpu::jobs(&items, &plans);
        let fused = c.render_jobs_with(&jobs, RenderKernel::Fused).unwrap();
        let two = c.render_jobs_with(&jobs, RenderKernel::TwoPass).unwrap();
        for (k, ((job, f), t)) in jobs.iter().zip(&fused).zip(&two).enumerate() {
            let name = format!("{} [{}] x{}", path.display(), items[k].1.filter, items[k].1.factor);
            worst = worst.max(max_diff(t, f, &format!("{name}: two-pass vs fused")));
            worst = worst.max(max_diff(t, &gpu::render_cpu(job), &format!("{name}: two-pass vs cpu")));
            let cpu = gpu::render_cpu(job).clamped;
            assert_clamped(job, t.clamped, cpu, &format!("{name}: two-pass"));
            assert_clamped(job, f.clamped, cpu, &format!("{name}: fused"));
        }
    }
    println!(
        "two-pass kernel: {} data files x {} filters x 3 factors, max |diff| = {worst:.3e} (of I_max)",
        files.len(),
        filters().len()
    );
}

/// The representative subset: full sphere, Isym 3, Isym 4, lower hemisphere,
/// non-uniform γ, single-plane rotational, Type B, partial γ range.
const CORPUS_SUBSET: [&str; 8] = [
    "eulumdat-rs/OutdoorRoadway IES OS 8988-2022 03 AM01 60W 4000K.ies",
    "eulumdat-plot/sample_01_isym3.ldt",
    "eulumdat-plot/sample_02_isym4.ldt",
    "cl-ies/test.ies",
    "rpr-sdk/ies_light_1.ies",
    "ils20/NDNN74022.ies",
    "cu-ies/flood_2.1.IES",
    "eulumdat-rs/demo_two_lamp_sets.ldt",
];

fn texture(path: &Path) -> LightTexture {
    let lum = photosolid::load(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    LightTexture::new(lum.distribution()).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

fn synth_textures() -> Vec<(String, LightTexture)> {
    let grids = [
        ("uniform 15/5", GridSpec::uniform(15.0, 5.0).unwrap()),
        (
            "non-uniform",
            GridSpec::explicit(
                vec![0.0, 10.0, 25.0, 90.0, 135.0, 180.0, 200.0, 300.0],
                vec![0.0, 2.0, 5.0, 15.0, 30.0, 60.0, 75.0, 90.0],
            ),
        ),
    ];
    let shapes = [
        Synth::Batwing,
        Synth::Roadway,
        Synth::Spot {
            p: 20.0,
            cutoff_deg: 40.0,
        },
    ];
    let mut out = Vec::new();
    for (gname, g) in &grids {
        for s in &shapes {
            let lum = s.build(g, 1000.0).unwrap();
            out.push((
                format!("{} on {gname}", s.name()),
                LightTexture::new(lum.distribution()).unwrap(),
            ));
        }
    }
    out
}

#[test]
fn adapter_is_reported() {
    let Some(c) = ctx("adapter_is_reported") else { return };
    let a = c.adapter();
    assert!(!a.name.is_empty());
    println!(
        "adapter: {a}; software: {}; max binding {} B",
        a.software,
        c.max_binding_bytes()
    );
    if let Ok(b) = std::env::var("WGPU_BACKEND") {
        let want = if b.eq_ignore_ascii_case("vulkan") || b == "vk" {
            "Vulkan"
        } else {
            "Gl"
        };
        assert_eq!(a.backend, want, "WGPU_BACKEND={b} must select that backend");
    }
}

/// The acceptance criterion on a representative subset: every filter at factor 5.
#[test]
fn corpus_subset_every_filter_matches_cpu() {
    let Some(c) = ctx("corpus_subset_every_filter_matches_cpu") else {
        return;
    };
    let Some(root) = common::corpus() else { return };
    let mut worst = 0.0f32;
    for rel in CORPUS_SUBSET {
        let tex = texture(&root.join(rel));
        // One plan per filter, shared by both renders; one submission per file.
        let items: Vec<(&LightTexture, RenderOptions)> = filters()
            .into_iter()
            .map(|filter| {
                (
                    &tex,
                    RenderOptions {
                        filter,
                        ..RenderOptions::default()
                    },
                )
            })
            .collect();
        let plans = gpu::plans(&items).unwrap();
        let jobs = gpu::jobs(&items, &plans);
        let names: Vec<String> = filters().iter().map(|f| format!("{rel} [{f}]")).collect();
        let d = check_jobs(c, &jobs, &names);
        println!("{rel}: max |gpu - cpu| = {d:.3e}");
        worst = worst.max(d);
    }
    println!(
        "corpus subset: {} files x {} filters, max |gpu - cpu| = {worst:.3e}",
        8,
        filters().len()
    );
}

/// `render_gpu` / `render_batch` equal `render_with` (plans built separately, same tables).
#[test]
fn public_api_matches_render_with() {
    let Some(c) = ctx("public_api_matches_render_with") else {
        return;
    };
    let texs = synth_textures();
    for (name, tex) in &texs {
        let o = RenderOptions {
            filter: Filter::Pchip,
            ..RenderOptions::default()
        };
        let g = gpu::render_gpu(c, tex, &o).unwrap();
        let cpu = render_with(tex, &o).unwrap();
        max_diff(&g, &cpu, name);
        let plan = tex.render_plan(o.filter, o.factor).unwrap();
        let job = RenderJob {
            texture: tex,
            plan: &plan,
            clamp: o.clamp,
        };
        assert_clamped(&job, g.clamped, cpu.clamped, name);
    }
    let items: Vec<(&LightTexture, RenderOptions)> = texs
        .iter()
        .flat_map(|(_, t)| {
            filters().into_iter().map(move |filter| {
                (
                    t,
                    RenderOptions {
                        filter,
                        factor: 3,
                        clamp: true,
                        parallel: false,
                    },
                )
            })
        })
        .collect();
    let out = gpu::render_batch(c, &items).unwrap();
    let plans = gpu::plans(&items).unwrap();
    for ((job, (t, o)), g) in gpu::jobs(&items, &plans).iter().zip(&items).zip(&out) {
        let cpu = render_with(t, o).unwrap();
        let what = format!("batch [{}]", o.filter);
        max_diff(g, &cpu, &what);
        assert_clamped(job, g.clamped, cpu.clamped, &what);
    }
}

/// Factors 1–32, clamping on and off (negative overshoot kept), every filter.
#[test]
fn factors_1_to_32_and_clamping() {
    let Some(c) = ctx("factors_1_to_32_and_clamping") else {
        return;
    };
    let lum = Synth::Spot {
        p: 8.0,
        cutoff_deg: 35.0,
    }
    .build(&GridSpec::uniform(30.0, 10.0).unwrap(), 500.0)
    .unwrap();
    let tex = LightTexture::new(lum.distribution()).unwrap();
    let mut items = Vec::new();
    for factor in 1..=32 {
        for (k, filter) in filters().into_iter().enumerate() {
            // Every factor with clamping; every filter unclamped at a few factors.
            items.push((
                &tex,
                RenderOptions {
                    filter,
                    factor,
                    clamp: !(factor % 8 == 1 || (factor as usize + k).is_multiple_of(11)),
                    parallel: true,
                },
            ));
        }
    }
    let plans = gpu::plans(&items).unwrap();
    let jobs = gpu::jobs(&items, &plans);
    let names: Vec<String> = items
        .iter()
        .map(|(_, o)| format!("factor {} [{}] clamp={}", o.factor, o.filter, o.clamp))
        .collect();
    check_jobs(c, &jobs, &names);
    let out = c.render_jobs(&jobs).unwrap();
    let negatives = out
        .iter()
        .zip(&items)
        .filter(|(r, (_, o))| !o.clamp && r.data.iter().any(|&v| v < 0.0));
    assert!(negatives.count() > 0, "unclamped cubics keep their negative overshoot");
    let clamped: usize = out.iter().map(|r| r.clamped).sum();
    assert!(clamped > 0, "the spot's cut-off makes cubics overshoot below 0");
    // Out-of-range factors are errors, as on the CPU.
    for factor in [0, 33] {
        let o = RenderOptions {
            factor,
            ..RenderOptions::default()
        };
        let e = gpu::render_gpu(c, &tex, &o).unwrap_err();
        assert!(matches!(e, GpuError::InvalidJob { index: 0, .. }), "{e}");
        assert!(e.to_string().contains("factor"), "{e}");
    }
}

/// A batch of 100 luminaires in one submission; chunked; upload once, dispatch twice.
#[test]
fn batch_of_100_in_one_submission() {
    let Some(c) = ctx("batch_of_100_in_one_submission") else {
        return;
    };
    let texs = synth_textures();
    let items: Vec<(&LightTexture, RenderOptions)> = (0..100)
        .map(|k| {
            let f = filters();
            (
                &texs[k % texs.len()].1,
                RenderOptions {
                    filter: f[k % f.len()],
                    factor: 1 + (k % 7) as u32,
                    clamp: k % 5 != 0,
                    parallel: true,
                },
            )
        })
        .collect();
    let plans = gpu::plans(&items).unwrap();
    let jobs = gpu::jobs(&items, &plans);
    let (out, t) = c.render_jobs_timed(&jobs).unwrap();
    println!("batch of 100: {t:?}");
    assert_eq!(out.len(), 100);
    for (k, (job, g)) in jobs.iter().zip(&out).enumerate() {
        let cpu = gpu::render_cpu(job);
        max_diff(g, &cpu, &format!("batch item {k}"));
        assert_clamped(job, g.clamped, cpu.clamped, &format!("batch item {k}"));
    }
    assert_eq!(c.render_jobs(&jobs).unwrap(), out);
    for kernel in RenderKernel::ALL {
        let whole = c.render_jobs_with(&jobs, kernel).unwrap();
        // Split into many chunks (small binding limit): same numbers again.
        let chunked = c.render_jobs_chunked(&jobs, 1 << 20, kernel).unwrap();
        assert_eq!(chunked, whole, "{} kernel", kernel.name());
        // Upload once, dispatch twice (counters are reset), read back.
        let batch = c.upload_with(&jobs, kernel).unwrap();
        assert!(batch.chunks() >= 1);
        assert_eq!(batch.kernel(), kernel);
        c.dispatch(&batch).unwrap();
        c.dispatch(&batch).unwrap();
        assert_eq!(c.read_back(&batch).unwrap(), whole, "{} kernel", kernel.name());
    }
}

#[test]
fn empty_batch_and_invalid_job() {
    let Some(c) = ctx("empty_batch_and_invalid_job") else {
        return;
    };
    assert!(gpu::render_batch(c, &[]).unwrap().is_empty());
    let texs = synth_textures();
    let (a, b) = (&texs[0].1, &texs[3].1);
    let plan_b = b.render_plan(Filter::Bilinear, 2).unwrap();
    let plan_a = a.render_plan(Filter::Bilinear, 2).unwrap();
    let ok = RenderJob {
        texture: a,
        plan: &plan_a,
        clamp: true,
    };
    let bad = RenderJob {
        texture: a,
        plan: &plan_b,
        clamp: true,
    };
    let err = c.render_jobs(&[ok, bad]).unwrap_err();
    assert!(err.to_string().contains("render job 1"), "{err}");
}

#[test]
fn backend_resolution() {
    match gpu::resolve(Backend::Cpu).unwrap() {
        Resolved::Cpu { notice } => assert!(notice.is_none()),
        Resolved::Gpu(_) => panic!("cpu resolved to gpu"),
    }
    let auto = gpu::resolve(Backend::Auto).unwrap();
    let forced = gpu::resolve(Backend::Gpu);
    match (auto, forced) {
        (Resolved::Gpu(a), Ok(Resolved::Gpu(b))) => assert!(std::ptr::eq(a, b)),
        (Resolved::Cpu { notice: Some(n) }, Err(e)) => {
            assert!(!require_gpu(), "PHOTOSOLID_REQUIRE_GPU=1 but: {e}");
            assert!(n.contains("CPU"), "{n}");
            assert!(e.to_string().contains("backends tried"), "{e}");
            eprintln!("SKIPPED gpu half of backend_resolution: {e}");
        }
        other => panic!("inconsistent resolution: {other:?}"),
    }
}
