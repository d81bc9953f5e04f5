//! What one lookup costs a renderer: ns per intensity from a unit direction
//! vector, one thread, for each representation of the trade table, on the
//! synthetic roadway (5° x 2.5°). Baseline in the same run: the direction →
//! (C, γ) conversion alone (an `acos` and an `atan2`), the floor of every
//! angle-indexed lookup.
#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    reason = "in a benchmark a panic is the failure report"
)]

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use photosolid::compare::trade::representations;
use photosolid::metrics::random_directions;
use photosolid::model::frame;
use photosolid::registry::Reconstructions;
use photosolid::synth::{GridSpec, Synth};

fn bench(c: &mut Criterion) {
    let lum = Synth::Roadway
        .build(&GridSpec::uniform(5.0, 2.5).unwrap(), 12_000.0)
        .unwrap();
    let d = lum.distribution();
    let dirs = random_directions(4096, 11);
    let mut g = c.benchmark_group("lookup");
    g.throughput(Throughput::Elements(dirs.len() as u64));
    g.bench_function("angles-only-baseline", |b| {
        b.iter(|| {
            let mut acc = 0.0;
            for &u in &dirs {
                let (cc, gg) = frame::unit_angles(std::hint::black_box(u));
                acc += cc + gg;
            }
            acc
        })
    });
    let reps = representations(d.symmetry(), &[1, 5]);
    let recs = Reconstructions::new(d.clone(), &reps).unwrap();
    for r in reps {
        let field = recs.field(r).unwrap();
        g.bench_function(BenchmarkId::new("representation", r.to_string()), |b| {
            b.iter(|| {
                let mut acc = 0.0;
                for &u in &dirs {
                    acc += field.intensity_dir_cd(std::hint::black_box(u));
                }
                acc
            })
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
