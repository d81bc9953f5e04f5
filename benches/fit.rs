//! Fit time per luminaire for the fitted OpenGL lights (Zotti et al. 2005
//! report "a few seconds on a 2 GHz Athlon"; the target here is a median
//! under 50 ms).
//!
//! Synthetic luminaires on realistic grids (rotational 1°, asymmetric
//! 5° × 2.5°), fitted in parallel (rayon over combinations) and serially;
//! then every loadable file of `../shared/corpus` (when it exists and the
//! readers load it). A median over the set is printed once per set.
#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    reason = "in a benchmark a panic is the failure report"
)]

use std::path::{Path, PathBuf};
use std::time::Instant;

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use photosolid::fit::{fit, FitOptions, FittedLights, Hemisphere, Light, Spot};
use photosolid::model::Distribution;

fn spot(h: Hemisphere, w: f64, p: f64, cut: f64, tilt: f64, az: f64) -> Light {
    Light::Spot(Spot {
        hemisphere: h,
        weight_cd: w,
        exponent: p,
        cutoff_deg: cut,
        tilt_deg: tilt,
        azimuth_deg: az,
    })
}

fn synthetic() -> Vec<(&'static str, Distribution)> {
    use Hemisphere::*;
    let c5: Vec<f64> = (0..72).map(|k| k as f64 * 5.0).collect();
    let g1: Vec<f64> = (0..=180).map(f64::from).collect();
    let g25: Vec<f64> = (0..=72).map(|k| k as f64 * 2.5).collect();
    let make = |l: Vec<Light>, g: &[f64]| FittedLights::new(l).sample(&c5, g).unwrap();
    vec![
        (
            "rot-spot-1deg",
            make(vec![spot(Down, 1000.0, 6.5, 37.3, 0.0, 0.0)], &g1),
        ),
        (
            "rot-spot+point-1deg",
            make(
                vec![
                    spot(Down, 900.0, 12.0, 60.2, 0.0, 0.0),
                    Light::Point { weight_cd: 60.0 },
                ],
                &g1,
            ),
        ),
        (
            "rot-two-spots-1deg",
            make(
                vec![
                    spot(Down, 1000.0, 4.0, 75.4, 0.0, 0.0),
                    spot(Up, 300.0, 20.0, 30.6, 0.0, 0.0),
                ],
                &g1,
            ),
        ),
        (
            "tilted-spot-5x2.5",
            make(vec![spot(Down, 1000.0, 10.0, 35.0, 25.0, 60.0)], &g25),
        ),
        (
            "tilted-spot+point-5x2.5",
            make(
                vec![
                    spot(Down, 1000.0, 30.0, 20.0, 40.0, 300.0),
                    Light::Point { weight_cd: 80.0 },
                ],
                &g25,
            ),
        ),
        (
            "tilted-two-spots-5x2.5",
            make(
                vec![
                    spot(Down, 1000.0, 8.0, 50.0, 15.0, 200.0),
                    spot(Up, 400.0, 3.0, 40.0, 30.0, 45.0),
                ],
                &g25,
            ),
        ),
        (
            "roadway-5x2.5",
            photosolid::synth::Synth::Roadway
                .build(&photosolid::synth::GridSpec::uniform(5.0, 2.5).unwrap(), 1000.0)
                .unwrap()
                .into_distribution(),
        ),
    ]
}

fn corpus() -> Vec<(String, Distribution)> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/corpus");
    let mut files: Vec<PathBuf> = Vec::new();
    let mut stack = vec![root];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).into_iter().flatten().flatten() {
            let p = e.path();
            if p.is_dir() {
                stack.push(p);
            } else if matches!(
                p.extension()
                    .and_then(|e| e.to_str())
                    .map(|e| e.to_ascii_lowercase())
                    .as_deref(),
                Some("ies" | "ldt")
            ) {
                files.push(p);
            }
        }
    }
    files.sort();
    files
        .into_iter()
        .filter_map(|p| {
            if let Ok(lum) = photosolid::load(&p) {
                Some((
                    p.file_name().unwrap().to_string_lossy().into_owned(),
                    lum.into_distribution(),
                ))
            } else {
                None
            }
        })
        .collect()
}

/// Median wall time (ms) of one fit of each distribution (best of 3 runs each).
fn median_ms(set: &[(impl AsRef<str>, Distribution)], opts: &FitOptions) -> f64 {
    let mut t: Vec<f64> = set
        .iter()
        .map(|(_, d)| {
            (0..3)
                .map(|_| {
                    let s = Instant::now();
                    black_box(fit(d, opts).unwrap());
                    s.elapsed().as_secs_f64() * 1e3
                })
                .fold(f64::INFINITY, f64::min)
        })
        .collect();
    t.sort_by(f64::total_cmp);
    t[t.len() / 2]
}

/// True under `cargo bench` (cargo passes `--bench`); under `cargo test` criterion runs each
/// benchmark once as a check that it runs, and the medians (six more fits of every file,
/// about 10 s of the test command) would measure nothing.
fn measuring() -> bool {
    std::env::args().any(|a| a == "--bench")
}

/// Print the median fit times of `set` (parallel and serial), when measuring.
fn print_medians(label: &str, set: &[(impl AsRef<str>, Distribution)], par: &FitOptions, serial: &FitOptions) {
    if measuring() {
        eprintln!(
            "{label} ({}): median fit {:.2} ms parallel, {:.2} ms serial",
            set.len(),
            median_ms(set, par),
            median_ms(set, serial)
        );
    } else {
        eprintln!("{label} ({}): medians only under cargo bench", set.len());
    }
}

fn bench(c: &mut Criterion) {
    let synth = synthetic();
    let serial = FitOptions {
        parallel: false,
        ..Default::default()
    };
    let par = FitOptions::default();
    print_medians("synthetic set", &synth, &par, &serial);
    let mut g = c.benchmark_group("fit");
    g.sample_size(10);
    for (name, d) in &synth {
        g.bench_function(format!("{name}/parallel"), |b| {
            b.iter(|| fit(black_box(d), &par).unwrap())
        });
        g.bench_function(format!("{name}/serial"), |b| {
            b.iter(|| fit(black_box(d), &serial).unwrap())
        });
    }
    g.finish();
    let corpus = corpus();
    if corpus.is_empty() {
        eprintln!("corpus: no loadable files (readers missing or ../shared/corpus absent)");
    } else {
        print_medians("corpus files", &corpus, &par, &serial);
        let mut g = c.benchmark_group("fit-corpus");
        g.sample_size(10);
        g.bench_function("all-files/parallel", |b| {
            b.iter(|| {
                for (_, d) in &corpus {
                    black_box(fit(d, &par).unwrap());
                }
            })
        });
        // What `batch` runs per file.
        g.bench_function("all-files/serial", |b| {
            b.iter(|| {
                for (_, d) in &corpus {
                    black_box(fit(d, &serial).unwrap());
                }
            })
        });
        g.finish();
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
