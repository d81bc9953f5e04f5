//! Photometric-solid build and export speed.
//!
//! The target: a 5x Catmull-Rom solid of a 361 x 73 file (about 660 k
//! vertices) built and written as binary PLY in under 0.5 s. With no filter
//! in this tree, the solid is built from a cheap closure on a grid of
//! 365 C x 1805 γ angles (the 5x refinement of 73 x 361), so `build`
//! measures the mesh builder itself (sampling, vertices, triangles,
//! normals); `write_ply` measures encoding plus the atomic write (with its
//! fsync) to a temporary file; `measured` the spade triangulation of the
//! 73 x 361 file's own directions.
#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    reason = "in a benchmark a panic is the failure report"
)]

use std::time::Instant;

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use photosolid::model::{Distribution, Symmetry};
use photosolid::solid::export::{self, MeshFormat};
use photosolid::solid::{grid_solid, measured_solid, SolidGrid, Units};

fn field(c: f64, g: f64) -> f64 {
    // A cheap asymmetric beam with some up-light: non-zero everywhere, so
    // every grid point is a vertex (the full ~660 k).
    let (c, g) = (c.to_radians(), g.to_radians());
    let u = g.cos().max(0.0);
    100.0 + 1000.0 * u * (1.0 + 0.3 * c.cos() * g.sin())
}

fn bench(cr: &mut Criterion) {
    let grid = SolidGrid::uniform(365, 1804).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("solid.ply");

    // One timed pass, printed, so the numbers are visible without criterion's report.
    let t = Instant::now();
    let mesh = grid_solid(&field, &grid, Units::Candela).unwrap();
    let build = t.elapsed();
    let t = Instant::now();
    export::write_as(&mesh, &path, MeshFormat::Ply).unwrap();
    let write = t.elapsed();
    println!(
        "grid solid {} vertices, {} triangles: build {:.1} ms, write PLY ({:.1} MB) {:.1} ms",
        mesh.n_vertices(),
        mesh.n_triangles(),
        build.as_secs_f64() * 1e3,
        std::fs::metadata(&path).unwrap().len() as f64 / 1e6,
        write.as_secs_f64() * 1e3
    );

    let mut g = cr.benchmark_group("solid");
    g.sample_size(10);
    g.measurement_time(std::time::Duration::from_secs(4));
    g.bench_function("build 365x1805", |b| {
        b.iter(|| grid_solid(black_box(&field), &grid, Units::Candela).unwrap())
    });
    g.bench_function("encode ply", |b| {
        b.iter(|| export::encode(black_box(&mesh), MeshFormat::Ply))
    });
    g.bench_function("write ply (encode + atomic write)", |b| {
        b.iter(|| export::write_as(black_box(&mesh), &path, MeshFormat::Ply).unwrap())
    });
    let c: Vec<f64> = (0..72).map(|k| k as f64 * 5.0).collect();
    let gamma: Vec<f64> = (0..=360).map(|k| k as f64 * 0.5).collect();
    let cd: Vec<f64> = c
        .iter()
        .flat_map(|&c| gamma.iter().map(move |&gg| field(c, gg)))
        .collect();
    let d = Distribution::new(c, gamma, cd, Symmetry::None).unwrap();
    g.bench_function("measured 72x361 (spade)", |b| {
        b.iter(|| measured_solid(black_box(&d), Units::Candela).unwrap())
    });
    // The case: a 5x Catmull-Rom solid of a real 361 x 73 file built
    // and written as binary PLY (texture and solid built inside the loop).
    let road = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../shared/corpus/eulumdat-rs/OutdoorRoadway IES OS 8988-2022 03 AM01 60W 4000K.ies");
    if let Ok(lum) = photosolid::load(&road) {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("road.ply");
        g.bench_function("catmull-rom x5 solid of the 361x73 roadway + binary PLY", |b| {
            b.iter(|| {
                let d = lum.distribution();
                let tex = photosolid::reconstruct::LightTexture::new(d).unwrap();
                let grid = photosolid::solid::SolidGrid::refined(d, 5).unwrap();
                let mesh = photosolid::solid::grid_solid(
                    &tex.sampler(photosolid::reconstruct::Filter::CatmullRom),
                    &grid,
                    Units::Candela,
                )
                .unwrap();
                photosolid::solid::export::write(&mesh, &out).unwrap();
            })
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
