//! Parse throughput on real files: the largest corpus files and the whole corpus.
//!
//! Reads `../shared/corpus` (third-party files, never copied into the
//! repository); without it, benchmarks the project's own `data/` files.
//! Throughput is reported in bytes/s by criterion; values/s is printed once
//! per file set. The baseline in the same run is `std::fs::read` plus
//! `str::split_ascii_whitespace` + `str::parse::<f64>` over the same bytes:
//! the cost of merely tokenising every number with the standard library.
#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    reason = "in a benchmark a panic is the failure report"
)]

use std::path::{Path, PathBuf};

use criterion::{black_box, criterion_group, criterion_main, Criterion, Throughput};
use photosolid::formats::{parse, ReadOptions};
use photosolid::model::Format;

fn corpus_files() -> Vec<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/corpus");
    let root = if root.is_dir() {
        root
    } else {
        Path::new(env!("CARGO_MANIFEST_DIR")).join("data")
    };
    let mut out = Vec::new();
    let mut stack = vec![root];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).into_iter().flatten().flatten() {
            let p = e.path();
            if p.is_dir() {
                stack.push(p);
            } else if Format::from_extension(&p).is_some() {
                out.push(p);
            }
        }
    }
    out.sort();
    out
}

fn baseline(bytes: &[u8]) -> f64 {
    let s = String::from_utf8_lossy(bytes);
    let mut acc = 0.0;
    for t in s.split(|c: char| c.is_ascii_whitespace() || c == ',') {
        if let Ok(v) = t.parse::<f64>() {
            acc += v;
        }
    }
    acc
}

fn bench(c: &mut Criterion) {
    let opts = ReadOptions::default();
    let files: Vec<(PathBuf, Vec<u8>, Format)> = corpus_files()
        .into_iter()
        .filter_map(|p| {
            let b = std::fs::read(&p).ok()?;
            let f = Format::from_extension(&p)?;
            // Only files that load take part: a failing file is measured by its error path elsewhere.
            parse(&b, &p, f, &opts).ok()?;
            Some((p, b, f))
        })
        .collect();
    let mut largest = files.clone();
    largest.sort_by_key(|f| std::cmp::Reverse(f.1.len()));
    largest.truncate(3);

    let mut group = c.benchmark_group("parse");
    for (name, set) in [("largest-3", &largest), ("corpus", &files)] {
        let bytes: usize = set.iter().map(|f| f.1.len()).sum();
        let values: usize = set
            .iter()
            .map(|f| {
                parse(&f.1, &f.0, f.2, &opts)
                    .map(|l| l.distribution().intensities_cd().len())
                    .unwrap_or(0)
            })
            .sum();
        eprintln!("{name}: {} files, {bytes} bytes, {values} intensity values", set.len());
        group.throughput(Throughput::Bytes(bytes as u64));
        group.bench_function(format!("photosolid/{name}"), |b| {
            b.iter(|| {
                for (p, data, f) in set.iter() {
                    black_box(parse(black_box(data), p, *f, &opts).ok());
                }
            })
        });
        group.bench_function(format!("baseline-std-split-parse/{name}"), |b| {
            b.iter(|| {
                for (_, data, _) in set.iter() {
                    black_box(baseline(black_box(data)));
                }
            })
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
