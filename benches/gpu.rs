//! GPU resampling phases next to the CPU reference, for one 5x texture of a
//! 73 x 181 grid (gamma x C; output 365 x 905) and for a batch of 100 such.
//!
//! `cargo bench --bench gpu` (honours `WGPU_BACKEND=vulkan|gl`). Without an
//! adapter only the CPU benchmarks run.

use std::time::Duration;

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use photosolid::gpu::{resample_cpu, AxisTaps, GpuContext, ResampleJob};
use rayon::prelude::*;

const DATA_ROWS: usize = 73; // gamma 0..180 by 2.5
const DATA_COLS: usize = 181; // C 0..360 by 2
const FACTOR: usize = 5;

/// Catmull-Rom taps over data padded with one ghost sample on each side.
fn catmull_rom(n_data: usize, n_out: usize) -> AxisTaps {
    let (mut idx, mut w) = (vec![], vec![]);
    for k in 0..n_out {
        let x = k as f64 * (n_data - 1) as f64 / (n_out - 1) as f64;
        let i = (x.floor() as usize).min(n_data - 2);
        let t = (x - i as f64) as f32;
        let (t2, t3) = (t * t, t * t * t);
        w.push([
            0.5 * (-t3 + 2.0 * t2 - t),
            0.5 * (3.0 * t3 - 5.0 * t2 + 2.0),
            0.5 * (-3.0 * t3 + 4.0 * t2 + t),
            0.5 * (t3 - t2),
        ]);
        let b = i as u32;
        idx.push([b, b + 1, b + 2, b + 3]);
    }
    AxisTaps::Weights { idx, w }
}

fn grid(seed: usize) -> Vec<f32> {
    let (rows, cols) = (DATA_ROWS + 2, DATA_COLS + 2);
    (0..rows * cols)
        .map(|i| {
            let (r, c) = ((i / cols) as f32 / rows as f32, (i % cols) as f32 / cols as f32);
            (1000 + seed) as f32 * (0.5 + 0.45 * (3.0 * r).cos() * (std::f32::consts::TAU * c + seed as f32).cos())
        })
        .collect()
}

fn bench(c: &mut Criterion) {
    let rt = catmull_rom(DATA_ROWS, DATA_ROWS * FACTOR);
    let ct = catmull_rom(DATA_COLS, DATA_COLS * FACTOR);
    let grids: Vec<Vec<f32>> = (0..100).map(grid).collect();
    let jobs: Vec<ResampleJob<'_>> = grids
        .iter()
        .map(|g| ResampleJob {
            src: g,
            rows: DATA_ROWS + 2,
            cols: DATA_COLS + 2,
            row_taps: &rt,
            col_taps: &ct,
            clamp_negative: true,
        })
        .collect();
    let one = &jobs[..1];

    let mut g = c.benchmark_group("gpu");
    g.sample_size(10)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(3));

    g.bench_function("cpu/single 365x905", |b| b.iter(|| resample_cpu(black_box(&one[0]))));
    g.bench_function("cpu/batch100 serial", |b| {
        b.iter(|| jobs.iter().map(|j| resample_cpu(black_box(j))).collect::<Vec<_>>())
    });
    g.bench_function("cpu/batch100 rayon", |b| {
        b.iter(|| jobs.par_iter().map(|j| resample_cpu(black_box(j))).collect::<Vec<_>>())
    });

    let ctx = match GpuContext::global() {
        Ok(ctx) => ctx,
        Err(e) => {
            eprintln!("no GPU adapter, GPU benchmarks skipped: {e}");
            return;
        }
    };
    eprintln!("gpu adapter: {} (set-up {:.0?})", ctx.adapter(), ctx.setup_time());
    let (_, t) = ctx.render_batch_timed(&jobs).unwrap();
    eprintln!("batch100 phases (one run): {t:?}, total {:?}", t.total());

    g.bench_function("gpu/setup (instance+adapter+device+pipeline)", |b| {
        b.iter(|| GpuContext::new().unwrap())
    });
    for (name, set) in [("single 365x905", one), ("batch100", &jobs[..])] {
        g.bench_function(format!("gpu/{name}/upload"), |b| {
            b.iter(|| ctx.upload(black_box(set)).unwrap())
        });
        let batch = ctx.upload(set).unwrap();
        g.bench_function(format!("gpu/{name}/dispatch"), |b| {
            b.iter(|| ctx.dispatch(&batch).unwrap())
        });
        g.bench_function(format!("gpu/{name}/read-back"), |b| {
            b.iter(|| ctx.read_back(&batch).unwrap())
        });
        g.bench_function(format!("gpu/{name}/end-to-end"), |b| {
            b.iter(|| ctx.render_batch(black_box(set)).unwrap())
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
