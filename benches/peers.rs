//! photosolid against its peer eulumdat-rs (`eulumdat = "=0.7.1"`, a dev-dependency only)
//! on the real-file corpus (`../shared/corpus`; third-party files, never copied into the
//! repository). Without the corpus it prints one line and measures nothing.
//!
//! Per file class (IES Type C, IES Type A/B, EULUMDAT, TM-33 XML): criterion groups
//! `peers-parse/<class>` (every file of the class parsed from its bytes, once per
//! iteration; photosolid's Type A/B parse includes the conversion to Type C) and
//! `peers-sample/<class>` (parse, then 9,180 intensities on a 2° x 3.6° (C, γ) grid:
//! photosolid's bilinear `Sampler` over a `LightTexture` built from the distribution,
//! eulumdat-rs's `Eulumdat::sample`). Before the criterion groups, a table of every
//! file's parse time (best of repeated runs, µs) for both and their ratio is printed,
//! slowest first, to stderr; for Type A/B files also "cold": the conversion's
//! per-process caches (target-grid geometry, tap tables) cleared before each run,
//! what the first file of its angle grid costs.
//!
//! Only files both readers accept take part (the corpus has deliberately broken
//! files). eulumdat-rs 0.7.1 does not convert Type A/B to Type C: it keeps the
//! angles as they are, so its Type B "parse" is less work than ours.
//!
//! Run: `cargo bench --bench peers -- --warm-up-time 1 --measurement-time 3`.
#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    reason = "in a benchmark a panic is the failure report"
)]

use std::path::{Path, PathBuf};
use std::time::Instant;

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use photosolid::formats::{parse, ReadOptions};
use photosolid::model::{Format, PhotometricType};
use photosolid::reconstruct::{Filter, LightTexture};

/// File classes the report groups by.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
enum Class {
    IesTypeC,
    IesTypeAB,
    Ldt,
    Tm33,
}

impl Class {
    fn name(self) -> &'static str {
        match self {
            Class::IesTypeC => "ies-type-c",
            Class::IesTypeAB => "ies-type-ab",
            Class::Ldt => "ldt",
            Class::Tm33 => "tm33",
        }
    }
}

struct File {
    path: PathBuf,
    rel: String,
    bytes: Vec<u8>,
    format: Format,
    class: Class,
}

fn corpus_root() -> Option<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/corpus");
    root.is_dir().then_some(root)
}

fn walk(root: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut stack = vec![root.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).into_iter().flatten().flatten() {
            let p = e.path();
            if p.is_dir() {
                stack.push(p);
            } else if matches!(
                Format::from_extension(&p),
                Some(Format::Ies | Format::Ldt | Format::Tm33)
            ) {
                out.push(p);
            }
        }
    }
    out.sort();
    out
}

/// The bytes as text the way a caller of eulumdat-rs would hand them over (UTF-8, else Latin-1).
fn text(bytes: &[u8]) -> std::borrow::Cow<'_, str> {
    match std::str::from_utf8(bytes) {
        Ok(s) => std::borrow::Cow::Borrowed(s),
        Err(_) => std::borrow::Cow::Owned(bytes.iter().map(|&b| b as char).collect()),
    }
}

/// eulumdat-rs's reader for the format (TM-33 through its ATLA module, converted to its model).
fn peer_parse(f: &File) -> Option<eulumdat::Eulumdat> {
    let t = text(&f.bytes);
    match f.format {
        Format::Ies => eulumdat::IesParser::parse(&t).ok(),
        Format::Ldt => eulumdat::Eulumdat::parse(&t).ok(),
        Format::Tm33 => eulumdat::atla::parse(&t).ok().map(|d| d.to_eulumdat()),
    }
}

fn ours_parse(f: &File, opts: &ReadOptions) -> Option<photosolid::formats::Document> {
    parse(&f.bytes, &f.path, f.format, opts).ok()
}

fn files(root: &Path, opts: &ReadOptions) -> Vec<File> {
    walk(root)
        .into_iter()
        .filter_map(|path| {
            let bytes = std::fs::read(&path).ok()?;
            let format = Format::from_extension(&path)?;
            let rel = path.strip_prefix(root).ok()?.display().to_string();
            let mut f = File {
                path,
                rel,
                bytes,
                format,
                class: Class::Ldt,
            };
            let doc = ours_parse(&f, opts)?;
            peer_parse(&f)?;
            f.class = match (format, doc.luminaire.photometric_type()) {
                (Format::Ldt, _) => Class::Ldt,
                (Format::Tm33, _) => Class::Tm33,
                (_, PhotometricType::C) => Class::IesTypeC,
                _ => Class::IesTypeAB,
            };
            Some(f)
        })
        .collect()
}

/// Best time of `f` over repeated runs (at least 20 runs and 20 ms), seconds.
fn best_of(mut f: impl FnMut()) -> f64 {
    let mut best = f64::INFINITY;
    let start = Instant::now();
    let mut n = 0;
    while n < 20 || start.elapsed().as_secs_f64() < 0.02 {
        let t = Instant::now();
        f();
        best = best.min(t.elapsed().as_secs_f64());
        n += 1;
    }
    best
}

/// The (C, γ) grid both sample: 2° in C over 0..358, 3.6° in γ over 0..180 (180 x 51 = 9,180 directions).
fn sample_grid() -> Vec<(f64, f64)> {
    let mut g = Vec::new();
    for i in 0..180 {
        for j in 0..=50 {
            g.push((2.0 * f64::from(i), 3.6 * f64::from(j)));
        }
    }
    g
}

fn bench(c: &mut Criterion) {
    let Some(root) = corpus_root() else {
        println!("peers: skipped, no corpus at ../shared/corpus (the peer benchmark needs the real files)");
        return;
    };
    let opts = ReadOptions::default();
    let set = files(&root, &opts);

    // Per-file table (stderr), slowest of ours first.
    let mut rows: Vec<(f64, f64, &File, Option<f64>)> = set
        .iter()
        .map(|f| {
            let ours = best_of(|| {
                black_box(ours_parse(f, &opts));
            });
            let peer = best_of(|| {
                black_box(peer_parse(f));
            });
            // Type A/B: also the first file of its grid in a process (the conversion's caches empty).
            let cold = (f.class == Class::IesTypeAB).then(|| {
                best_of(|| {
                    photosolid::formats::ies::type_ab::clear_caches();
                    black_box(ours_parse(f, &opts));
                })
            });
            (ours, peer, f, cold)
        })
        .collect();
    rows.sort_by(|a, b| b.0.total_cmp(&a.0));
    eprintln!("peers: {} files both read; per file, best of >= 20 runs:", set.len());
    eprintln!(
        "{:<56} {:>12} {:>12} {:>12} {:>8} {:>14}",
        "file", "class", "ours µs", "eulumdat µs", "ratio", "ours cold µs"
    );
    for (ours, peer, f, cold) in &rows {
        eprintln!(
            "{:<56} {:>12} {:>12.1} {:>12.1} {:>8.2} {:>14}",
            f.rel,
            f.class.name(),
            ours * 1e6,
            peer * 1e6,
            ours / peer,
            cold.map_or("-".to_string(), |c| format!("{:.1}", c * 1e6))
        );
    }

    let grid = sample_grid();
    for class in [Class::IesTypeC, Class::IesTypeAB, Class::Ldt, Class::Tm33] {
        let of: Vec<&File> = set.iter().filter(|f| f.class == class).collect();
        if of.is_empty() {
            eprintln!("peers: no {} file that both read", class.name());
            continue;
        }
        let sum = |k: usize| {
            rows.iter()
                .filter(|r| r.2.class == class)
                .map(|r| [r.0, r.1][k])
                .sum::<f64>()
        };
        eprintln!(
            "peers: {:<12} {:>3} files, sum of best times: ours {:.1} µs, eulumdat-rs {:.1} µs, ratio {:.2}",
            class.name(),
            of.len(),
            sum(0) * 1e6,
            sum(1) * 1e6,
            sum(0) / sum(1)
        );
        let mut group = c.benchmark_group(format!("peers-parse/{}", class.name()));
        group.bench_function("photosolid", |b| {
            b.iter(|| {
                for f in &of {
                    black_box(ours_parse(f, &opts));
                }
            })
        });
        group.bench_function("eulumdat-rs", |b| {
            b.iter(|| {
                for f in &of {
                    black_box(peer_parse(f));
                }
            })
        });
        group.finish();

        let mut group = c.benchmark_group(format!("peers-sample/{}", class.name()));
        group.bench_function("photosolid", |b| {
            b.iter(|| {
                let mut acc = 0.0;
                for f in &of {
                    let Some(doc) = ours_parse(f, &opts) else { continue };
                    let Ok(tex) = LightTexture::new(doc.luminaire.distribution()) else {
                        continue;
                    };
                    let s = tex.sampler(Filter::Bilinear);
                    for &(cc, g) in &grid {
                        acc += s.cd(cc, g);
                    }
                }
                black_box(acc)
            })
        });
        group.bench_function("eulumdat-rs", |b| {
            b.iter(|| {
                let mut acc = 0.0;
                for f in &of {
                    let Some(l) = peer_parse(f) else { continue };
                    for &(cc, g) in &grid {
                        acc += l.sample(cc, g);
                    }
                }
                black_box(acc)
            })
        });
        group.finish();
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
