//! Render throughput of the light distribution texture (samples per second),
//! next to a naive per-sample baseline measured in the same run: every output
//! texel looked up on its own through the f64 reference `Sampler` (taps and
//! weights found per sample, no tables, one core), as a straightforward
//! implementation would.
//!
//! Run briefly: `cargo bench --bench reconstruct -- --warm-up-time 1 --measurement-time 2`.
#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    reason = "in a benchmark a panic is the failure report"
)]

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use photosolid::reconstruct::{render_with, Filter, LightTexture, RenderOptions};
use photosolid::{Distribution, Symmetry};

/// A road-luminaire-sized grid: 72 planes (5°) x 361 γ (0.5°), no symmetry.
fn roadway() -> Distribution {
    let c: Vec<f64> = (0..72).map(|k| k as f64 * 5.0).collect();
    let g: Vec<f64> = (0..=360).map(|k| k as f64 * 0.5).collect();
    let cd = c
        .iter()
        .flat_map(|&c| g.iter().map(move |&g| (c, g)))
        .map(|(c, g): (f64, f64)| {
            let (c, g) = (c.to_radians(), g.to_radians());
            1000.0 * g.cos().max(0.0).powi(2) * (1.0 + 0.5 * c.cos() * g.sin()) + 5.0
        })
        .collect();
    Distribution::new(c, g, cd, Symmetry::None).unwrap()
}

fn bench(cr: &mut Criterion) {
    let tex = LightTexture::new(&roadway()).unwrap();
    let mut group = cr.benchmark_group("render-5x");
    for filter in [Filter::Bilinear, Filter::CatmullRom, Filter::Pchip] {
        for parallel in [true, false] {
            let opts = RenderOptions {
                filter,
                factor: 5,
                clamp: true,
                parallel,
            };
            let n = render_with(&tex, &opts).unwrap().data.len();
            group.throughput(Throughput::Elements(n as u64));
            let id = BenchmarkId::new(filter.to_string(), if parallel { "parallel" } else { "serial" });
            group.bench_with_input(id, &opts, |b, o| b.iter(|| render_with(&tex, o).unwrap()));
        }
        let mapping = render_with(
            &tex,
            &RenderOptions {
                filter,
                ..RenderOptions::default()
            },
        )
        .unwrap()
        .mapping;
        let sampler = tex.sampler(filter);
        group.bench_function(BenchmarkId::new(filter.to_string(), "naive-per-sample-baseline"), |b| {
            b.iter(|| {
                let mut acc = 0.0f64;
                for i in 0..mapping.height {
                    let g = mapping.gamma_of_row(i);
                    for j in 0..mapping.width {
                        acc += sampler.normalized(mapping.c_of_column(j), g);
                    }
                }
                std::hint::black_box(acc)
            })
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
