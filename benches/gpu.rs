//! The GPU render next to the CPU render of the same plans: adapter/device
//! set-up, upload, dispatch and read-back separately, for one texture and for
//! a batch of 100, at factor 5 with Catmull-Rom.
//!
//! Textures: the loadable files of ../shared/corpus (cycled to 100; the
//! single texture is the 361 x 73 roadway file when present), else synthetic
//! ones from `photosolid::synth`.
//!
//! Both render kernels (`RenderKernel::TwoPass`, the default, and the fused
//! one) in the same run; and the real-time lookups (`gpu::realtime`,
//! hardware bilinear and Catmull-Rom from linear fetches) over 1,048,576
//! random directions on the single texture; on a hardware adapter, 1,000
//! textures at 5x from tap tables to read-back. Throughput (criterion's
//! `thrpt`) is texels or samples per second; `scripts/bench-gpu.sh` prints it.
//!
//! `cargo bench --bench gpu` (honours `WGPU_BACKEND=vulkan|gl`). Without an
//! adapter only the CPU benchmarks run.
#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    reason = "in a benchmark a panic is the failure report"
)]

use std::path::Path;
use std::time::Duration;

use criterion::{black_box, criterion_group, criterion_main, Criterion, Throughput};
use photosolid::gpu::realtime::{HardwareLookup, RealtimeTexture};
use photosolid::gpu::{self, GpuContext, RenderJob, RenderKernel};
use photosolid::metrics::random_directions;
use photosolid::reconstruct::{render_planned, Filter, LightTexture, Precision, RenderOptions};
use photosolid::synth::{GridSpec, Synth};

const ROADWAY: &str = "eulumdat-rs/OutdoorRoadway IES OS 8988-2022 03 AM01 60W 4000K.ies";

fn corpus_textures() -> Vec<LightTexture> {
    let root = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../shared/corpus"));
    let Ok(manifest) = std::fs::read_to_string(root.join("MANIFEST.tsv")) else {
        return Vec::new();
    };
    let mut rels: Vec<&str> = manifest
        .lines()
        .skip(1)
        .filter_map(|l| l.split('\t').next())
        .filter(|r| {
            let r = r.to_ascii_lowercase();
            r.ends_with(".ies") || r.ends_with(".ldt")
        })
        .collect();
    // The roadway file first: it is the single-texture case.
    rels.sort_by_key(|r| *r != ROADWAY);
    rels.iter()
        .filter_map(|r| photosolid::load(root.join(r)).ok())
        .filter_map(|l| LightTexture::new(l.distribution()).ok())
        .collect()
}

fn synth_textures() -> Vec<LightTexture> {
    let shapes = [
        Synth::Roadway,
        Synth::Batwing,
        Synth::Spot {
            p: 20.0,
            cutoff_deg: 40.0,
        },
        Synth::CosinePower { p: 3.0 },
    ];
    let grids = [(5.0, 2.5), (15.0, 5.0), (10.0, 1.0)];
    let mut out = Vec::new();
    for (i, s) in shapes.iter().enumerate() {
        for (j, &(c, g)) in grids.iter().enumerate() {
            let lum = s
                .build(&GridSpec::uniform(c, g).unwrap(), 1000.0 + (i * 3 + j) as f64)
                .unwrap();
            out.push(LightTexture::new(lum.distribution()).unwrap());
        }
    }
    out
}

fn bench(c: &mut Criterion) {
    let mut texs = corpus_textures();
    let source = if texs.is_empty() {
        texs = synth_textures();
        "synthetic"
    } else {
        "corpus"
    };
    let opts = RenderOptions {
        filter: Filter::CatmullRom,
        ..RenderOptions::default()
    };
    let items: Vec<(&LightTexture, RenderOptions)> = (0..100).map(|k| (&texs[k % texs.len()], opts)).collect();
    let plans = gpu::plans(&items).unwrap();
    let jobs: Vec<RenderJob<'_>> = gpu::jobs(&items, &plans);
    let texels = |js: &[RenderJob<'_>]| js.iter().map(|j| j.height() * j.width()).sum::<usize>();
    let one = &jobs[..1];
    eprintln!(
        "{source} textures ({} distinct): single {} x {} texels; batch of 100: {} texels",
        texs.len(),
        one[0].height(),
        one[0].width(),
        texels(&jobs)
    );

    let mut g = c.benchmark_group("gpu");
    g.sample_size(10)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(3));

    for (name, set) in [("single", one), ("batch100", &jobs[..])] {
        g.throughput(Throughput::Elements(texels(set) as u64));
        g.bench_function(format!("cpu/{name}/render (rayon rows)"), |b| {
            b.iter(|| {
                set.iter()
                    .map(|j| render_planned(j.texture, j.plan, j.clamp, true))
                    .collect::<Vec<_>>()
            })
        });
    }
    g.throughput(Throughput::Elements(1));
    g.bench_function("cpu/batch100/plans (tap tables)", |b| {
        b.iter(|| gpu::plans(black_box(&items)).unwrap())
    });

    let ctx = match GpuContext::global() {
        Ok(ctx) => ctx,
        Err(e) => {
            eprintln!("no GPU adapter, GPU benchmarks skipped: {e}");
            return;
        }
    };
    eprintln!("gpu adapter: {} (set-up {:.0?})", ctx.adapter(), ctx.setup_time());
    for kernel in RenderKernel::ALL {
        let (_, t) = ctx.render_jobs_timed_with(&jobs, kernel).unwrap();
        eprintln!(
            "batch100 phases, {} kernel (one run): {t:?}, total {:?}",
            kernel.name(),
            t.total()
        );
    }

    g.bench_function("gpu/setup (instance+adapter+device+pipeline)", |b| {
        b.iter(|| GpuContext::new().unwrap())
    });
    for (name, set) in [("single", one), ("batch100", &jobs[..])] {
        g.throughput(Throughput::Elements(texels(set) as u64));
        for kernel in RenderKernel::ALL {
            let k = kernel.name();
            g.bench_function(format!("gpu/{k}/{name}/upload"), |b| {
                b.iter(|| ctx.upload_with(black_box(set), kernel).unwrap())
            });
            let batch = ctx.upload_with(set, kernel).unwrap();
            g.bench_function(format!("gpu/{k}/{name}/dispatch"), |b| {
                b.iter(|| ctx.dispatch(&batch).unwrap())
            });
            g.bench_function(format!("gpu/{k}/{name}/read-back"), |b| {
                b.iter(|| ctx.read_back(&batch).unwrap())
            });
            g.bench_function(format!("gpu/{k}/{name}/end-to-end"), |b| {
                b.iter(|| ctx.render_jobs_with(black_box(set), kernel).unwrap())
            });
        }
    }

    // The goal's case: 1,000 luminaires at 5x end to end, tap tables to read-back
    // (textures cycled). Hardware adapters only: a software driver needs about 20 s an iteration.
    if ctx.adapter().software {
        eprintln!(
            "gpu/two-pass/batch1000 skipped: {} is a software adapter",
            ctx.adapter()
        );
    } else {
        let items: Vec<(&LightTexture, RenderOptions)> = (0..1000).map(|k| (&texs[k % texs.len()], opts)).collect();
        let total: usize = gpu::plans(&items)
            .unwrap()
            .iter()
            .map(|p| p.mapping.height * p.mapping.width)
            .sum();
        g.throughput(Throughput::Elements(total as u64));
        g.bench_function("gpu/two-pass/batch1000/plans + end-to-end", |b| {
            b.iter(|| {
                let plans = gpu::plans(black_box(&items)).unwrap();
                ctx.render_jobs(&gpu::jobs(&items, &plans)).unwrap().len()
            })
        });
        eprintln!("batch1000: {total} texels");
    }

    // Real-time lookups: the single texture's render, read by the texture hardware.
    let rendered = gpu::render_cpu(&one[0]);
    let dirs = random_directions(1 << 20, 11);
    g.throughput(Throughput::Elements(dirs.len() as u64));
    for lookup in [HardwareLookup::Linear, HardwareLookup::CatmullRomLinearFetch] {
        let t = RealtimeTexture::new(ctx, &rendered, None, Precision::F32, lookup).unwrap();
        let batch = t.prepare(&dirs).unwrap();
        let name = format!("{lookup:?}").to_lowercase();
        g.bench_function(
            format!("gpu/realtime/{name}/dispatch ({:?}, 1M directions)", t.format()),
            |b| b.iter(|| t.run(&batch).unwrap()),
        );
        g.bench_function(format!("gpu/realtime/{name}/end-to-end (1M directions)"), |b| {
            b.iter(|| t.sample_dirs_cd(black_box(&dirs)).unwrap())
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
