//! Hausdorff distance between two solids of about 200 k triangles each.
//!
//! Goal (issue "compare"): symmetric Hausdorff with a certified bound under
//! 0.1 % of I_max in under 1 s on the 2-core machine. The solids here are
//! two UV spheres (radius 1000 "cd", one offset by 30 and squashed) so the
//! supremum lies inside faces. Baseline in the same run: vertex-only
//! sampling (one exact BVH query per vertex of each mesh, no certificate),
//! the method of gpytoolbox's approximate_hausdorff_distance.
#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    reason = "in a benchmark a panic is the failure report"
)]

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use glam::DVec3;
use photosolid::metrics::{hausdorff, hausdorff::distances, Bvh, MeshRef};

fn sphere(r: [f64; 3], c: [f64; 3], n_lat: usize, n_lon: usize) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let mut pos = vec![DVec3::new(c[0], c[1], c[2] - r[2])];
    for i in 1..n_lat {
        let th = std::f64::consts::PI * i as f64 / n_lat as f64;
        for j in 0..n_lon {
            let ph = 2.0 * std::f64::consts::PI * j as f64 / n_lon as f64;
            pos.push(DVec3::new(
                c[0] + r[0] * th.sin() * ph.cos(),
                c[1] + r[1] * th.sin() * ph.sin(),
                c[2] - r[2] * th.cos(),
            ));
        }
    }
    pos.push(DVec3::new(c[0], c[1], c[2] + r[2]));
    let top = (pos.len() - 1) as u32;
    let idx = |i: usize, j: usize| (1 + (i - 1) * n_lon + (j % n_lon)) as u32;
    let mut t = Vec::new();
    for j in 0..n_lon {
        t.push([0, idx(1, j + 1), idx(1, j)]);
        t.push([top, idx(n_lat - 1, j), idx(n_lat - 1, j + 1)]);
    }
    for i in 1..n_lat - 1 {
        for j in 0..n_lon {
            t.push([idx(i, j), idx(i, j + 1), idx(i + 1, j)]);
            t.push([idx(i, j + 1), idx(i + 1, j + 1), idx(i + 1, j)]);
        }
    }
    (pos, t)
}

fn bench(c: &mut Criterion) {
    let (pa, ta) = sphere([1000.0; 3], [0.0; 3], 224, 448);
    let (pb, tb) = sphere([1000.0, 1000.0, 950.0], [30.0, 0.0, 0.0], 230, 436);
    eprintln!("triangles: {} and {}", ta.len(), tb.len());
    let a = MeshRef {
        positions: &pa,
        triangles: &ta,
    };
    let b = MeshRef {
        positions: &pb,
        triangles: &tb,
    };
    let tol = 1.0; // 0.1 % of I_max = 1000
    let h = hausdorff(a, b, tol);
    eprintln!(
        "H = {:.3} (+{:.4}); h(A,B) = {:.3}, h(B,A) = {:.3}; queries {} + {}",
        h.value, h.bound, h.a_to_b.value, h.b_to_a.value, h.a_to_b.queries, h.b_to_a.queries
    );
    let mut g = c.benchmark_group("hausdorff-200k");
    g.sample_size(10);
    g.bench_function("certified-symmetric-0.1pct", |bch| {
        bch.iter(|| black_box(hausdorff(a, b, tol)))
    });
    g.bench_function("baseline-vertex-sampling", |bch| {
        bch.iter(|| {
            let (ba, bb) = (Bvh::build(&pa, &ta), Bvh::build(&pb, &tb));
            let x = distances(&pa, &bb).into_iter().fold(0.0, f64::max);
            let y = distances(&pb, &ba).into_iter().fold(0.0, f64::max);
            black_box(x.max(y))
        })
    });
    g.finish();
}

/// The UGR table (19 rooms × 5 reflectances × 2 views) of a real linear
/// luminaire (`../shared/ugr-reference/sample_10.ldt`, 1395 × 78 mm) at the
/// catalogue spacing 0.25 H (up to 1,536 luminaires a room) and at CIE 190's
/// 1 H, in the same run: what `info` pays for the catalogue spacing.
fn ugr(c: &mut Criterion) {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/ugr-reference/sample_10.ldt");
    let Ok(lum) = photosolid::load(&path) else {
        println!("ugr bench skipped: {} not found", path.display());
        return;
    };
    let mut g = c.benchmark_group("ugr_table");
    g.sample_size(20);
    for spacing in [1.0, 0.25] {
        g.bench_function(format!("spacing {spacing} H"), |b| {
            b.iter(|| black_box(photosolid::photometry::ugr::ugr_table_at(&lum, spacing).map(|t| t.max)))
        });
    }
    g.finish();
}

/// The radial metrics of one comparison row on the demo (`photosolid demo`:
/// the synthetic road luminaire, 5° x 2.5° grid, peak 12,000 cd; Mitchell
/// against the closed form, the truth's values on the 20,000 directions
/// evaluated once as in `compare`): over the set only, and with the maximum
/// refined between the directions (`MAX_REFINEMENT`): what the refinement costs.
fn radial(c: &mut Criterion) {
    use photosolid::metrics::{field_radial_errors, DirectionSet, MAX_REFINEMENT, ZOTTI_C};
    use photosolid::model::IntensityField;
    use photosolid::reconstruct::Filter;
    use photosolid::registry::{Recon, Reconstructions};
    use photosolid::synth::{GridSpec, Synth, Truth};
    let lum = Synth::Roadway
        .build(&GridSpec::uniform(5.0, 2.5).unwrap(), 12_000.0)
        .unwrap();
    let truth = Truth::of_luminaire(&lum).unwrap();
    let r = Recon::Filter(Filter::Mitchell {
        b: 1.0 / 3.0,
        c: 1.0 / 3.0,
    });
    let recs = Reconstructions::new(lum.distribution().clone(), &[r]).unwrap();
    let field = recs.field(r).unwrap();
    let set = DirectionSet::fibonacci(20_000);
    let m = truth.intensity_batch_cd(&set.directions);
    let i_max = lum.distribution().max_cd();
    let run = |refine: bool| {
        field_radial_errors(
            &set,
            &m,
            &truth,
            &*field,
            i_max,
            ZOTTI_C,
            refine.then_some(&MAX_REFINEMENT),
        )
    };
    let e = run(true);
    eprintln!(
        "demo mitchell: sampled max {:.4} %, refined max {:.4} % at C {:.3} gamma {:.3}",
        e.sampled_max_pct, e.max_pct, e.max_at_deg.0, e.max_at_deg.1
    );
    let a = field.intensity_batch_cd(&set.directions);
    let diffs: Vec<f64> = a.iter().zip(&m).map(|(a, m)| (a - m).abs()).collect();
    let eval = |d: &[(f64, f64)]| -> Vec<f64> {
        let (a, m) = (field.intensity_batch_cd(d), truth.intensity_batch_cd(d));
        a.iter().zip(&m).map(|(a, m)| (a - m).abs()).collect()
    };
    let rm = photosolid::metrics::refine_max(&set, &diffs, &eval, &MAX_REFINEMENT);
    eprintln!(
        "refinement: {} seeds, {} directions evaluated (the set: {})",
        rm.seeds,
        rm.evaluations,
        set.len()
    );
    let mut g = c.benchmark_group("radial-demo-mitchell-20000");
    g.sample_size(30);
    g.bench_function("sampled", |b| b.iter(|| black_box(run(false).max_pct)));
    g.bench_function("refined", |b| b.iter(|| black_box(run(true).max_pct)));
    g.finish();
}

criterion_group!(benches, bench, ugr, radial);
criterion_main!(benches);
