//! Symmetric Hausdorff distance between two real photometric solids of about
//! 200 k triangles each, with a certified bound under 0.1 % of I_max
//! (goal: under 1 s). Catmull-Rom vs bilinear solids of the corpus file
//! `eulumdat-rs/OutdoorRoadway IES OS 8988-2022 03 AM01 60W 4000K.ies` at
//! factor 2 (~207 k triangles each); two synthetic roadway solids
//! (5° x 2.5° grid, factor 5) when the corpus is absent. Measured here:
//! ~0.81 s median, bound 3.2 cd against a tolerance of 5.9 cd.
#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    reason = "in a benchmark a panic is the failure report"
)]

use criterion::{criterion_group, criterion_main, Criterion};
use photosolid::compare::solid_hausdorff;
use photosolid::reconstruct::Filter;
use photosolid::registry::{Recon, Reconstructions};

fn input() -> (String, photosolid::Distribution, usize) {
    let p = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../shared/corpus/eulumdat-rs/OutdoorRoadway IES OS 8988-2022 03 AM01 60W 4000K.ies");
    match photosolid::load(&p) {
        Ok(l) => ("OutdoorRoadway IES (corpus)".into(), l.into_distribution(), 2),
        Err(_) => {
            eprintln!("notice: corpus file absent; synthetic roadway instead");
            let g = photosolid::synth::GridSpec::uniform(5.0, 2.5).unwrap();
            let l = photosolid::synth::Synth::Roadway.build(&g, 12_000.0).unwrap();
            ("synthetic roadway".into(), l.into_distribution(), 5)
        }
    }
}

fn bench(c: &mut Criterion) {
    let (name, d, factor) = input();
    let p = Reconstructions::new(d.clone(), &[]).unwrap();
    let a = p.solid(Recon::Filter(Filter::CatmullRom), factor).unwrap();
    let b = p.solid(Recon::Filter(Filter::Bilinear), factor).unwrap();
    let tol = 1e-3 * d.max_cd();
    let t0 = std::time::Instant::now();
    let h = solid_hausdorff(&a, &b, tol);
    eprintln!(
        "{name}: catmull-rom ({} tris) vs bilinear ({} tris): H = {:.3} cd (+{:.3}, tolerance {:.3} = 0.1 % of I_max), \
         queries {} + {}, one run {:.3} s",
        a.n_triangles(),
        b.n_triangles(),
        h.value,
        h.bound,
        tol,
        h.a_to_b.queries,
        h.b_to_a.queries,
        t0.elapsed().as_secs_f64()
    );
    let mut g = c.benchmark_group("compare");
    g.sample_size(10);
    g.bench_function("hausdorff_200k_catmull-rom_vs_bilinear", |bn| {
        bn.iter(|| solid_hausdorff(&a, &b, tol))
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
