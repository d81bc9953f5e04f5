//! A damaged-file corpus generated from the project's own `data/` files:
//! truncation at every line, bit flips, huge counts, NaN / infinity / 1e400
//! text, UTF-16, mixed line endings, and TILT= pointing at a directory, a
//! FIFO and /dev/zero. Every case either fails with an error naming the file
//! and a line, or loads (possibly with warnings) into a luminaire whose
//! summary is finite and which round-trips through both writers. No case may
//! panic, hang (each runs under a deadline) or make one allocation over the
//! cap (a counting allocator watches the largest request).

use std::alloc::{GlobalAlloc, Layout, System};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Duration;

use crate::common;

use photosolid::formats::roundtrip::{check, non_finite_in_debug};
use photosolid::model::Format;
use photosolid::{Error, ReadOptions};

/// Largest single allocation any damaged input may cause (bytes). The data
/// files are below 200 kB; a reader that trusts a huge count asks for GBs.
const ALLOCATION_CAP: usize = 64 << 20;

struct Watch;
static LARGEST: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Watch {
    unsafe fn alloc(&self, l: Layout) -> *mut u8 {
        LARGEST.fetch_max(l.size(), Ordering::Relaxed);
        unsafe { System.alloc(l) }
    }
    unsafe fn dealloc(&self, p: *mut u8, l: Layout) {
        unsafe { System.dealloc(p, l) }
    }
    unsafe fn realloc(&self, p: *mut u8, l: Layout, new: usize) -> *mut u8 {
        LARGEST.fetch_max(new, Ordering::Relaxed);
        unsafe { System.realloc(p, l, new) }
    }
}

#[global_allocator]
static GLOBAL: Watch = Watch;

fn data_files() -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("data");
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| Format::from_extension(p).is_some())
        .collect();
    v.sort();
    assert!(v.len() >= 10, "data/ holds the generated files");
    v
}

/// Outcome counts of a batch of damaged inputs.
#[derive(Default, Debug)]
struct Tally {
    loaded: usize,
    refused: usize,
}

/// Parse one damaged input under a deadline and check the outcome.
fn judge(bytes: Vec<u8>, path: &Path, format: Format, what: &str, tally: &mut Tally) {
    let p = path.to_path_buf();
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        let r = photosolid::formats::parse(&bytes, &p, format, &ReadOptions::default());
        let _ = tx.send(r);
    });
    let r = rx
        .recv_timeout(Duration::from_secs(20))
        .unwrap_or_else(|_| panic!("{what}: no answer within 20 s (hang or panic)"));
    match r {
        Ok(lum) => {
            tally.loaded += 1;
            let s = photosolid::photometry::summary(&lum);
            let bad = non_finite_in_debug(&format!("{s:?}"));
            assert!(bad.is_empty(), "{what}: loads but its summary holds {bad:?}");
            check(&lum).unwrap_or_else(|e| panic!("{what}: loads but does not round-trip: {e}"));
        }
        Err(e) => {
            tally.refused += 1;
            assert_eq!(e.path, path, "{what}: the error names the file");
            assert!(e.location.line >= 1, "{what}: the error names a line: {e}");
            assert!(!e.expected.is_empty() && !e.found.is_empty(), "{what}: {e}");
        }
    }
    let largest = LARGEST.load(Ordering::Relaxed);
    assert!(largest <= ALLOCATION_CAP, "{what}: an allocation of {largest} bytes");
}

fn line_ends(b: &[u8]) -> Vec<usize> {
    b.iter()
        .enumerate()
        .filter(|(_, &c)| c == b'\n')
        .map(|(i, _)| i + 1)
        .collect()
}

#[test]
fn truncation_at_every_line() {
    for f in data_files() {
        let bytes = std::fs::read(&f).unwrap();
        let format = Format::from_extension(&f).unwrap();
        let mut t = Tally::default();
        for end in std::iter::once(0).chain(line_ends(&bytes)) {
            if end == bytes.len() {
                continue;
            }
            judge(
                bytes[..end].to_vec(),
                &f,
                format,
                &format!("{} cut at byte {end}", f.display()),
                &mut t,
            );
        }
        // Cut in the middle of the last line too.
        judge(bytes[..bytes.len() - 3].to_vec(), &f, format, "cut mid-line", &mut t);
        assert!(t.refused > 0, "{}: {t:?}", f.display());
    }
}

#[test]
fn bit_flips() {
    let mut rng = common::Rng(0x5eed_1234_abcd_0001);
    for f in data_files() {
        let bytes = std::fs::read(&f).unwrap();
        let format = Format::from_extension(&f).unwrap();
        let mut t = Tally::default();
        for case in 0..150 {
            let mut b = bytes.clone();
            let flips = 1 + (rng.next() % 4) as usize;
            for _ in 0..flips {
                let i = (rng.next() as usize) % b.len();
                b[i] ^= 1 << (rng.next() % 8);
            }
            judge(b, &f, format, &format!("{} flip case {case}", f.display()), &mut t);
        }
        assert!(t.loaded + t.refused == 150);
    }
}

/// Replace the `k`-th whitespace-separated token (0-based) of `line` (1-based) by `with`.
fn replace_token(text: &str, line: usize, k: usize, with: &str) -> String {
    let mut out = String::new();
    for (i, l) in text.split_inclusive('\n').enumerate() {
        if i + 1 == line {
            let body = l.trim_end_matches(['\r', '\n']);
            let end = &l[body.len()..];
            let mut toks: Vec<&str> = body.split_whitespace().collect();
            toks[k] = with;
            out.push_str(&toks.join(" "));
            out.push_str(end);
        } else {
            out.push_str(l);
        }
    }
    out
}

/// Line (1-based) of `TILT=` in an IES text: the counts follow on the next line.
fn tilt_line(text: &str) -> usize {
    text.lines().position(|l| l.starts_with("TILT=")).unwrap() + 1
}

#[test]
fn huge_counts_and_non_finite_numbers() {
    let mut t = Tally::default();
    let values = [
        "99999999999",
        "18446744073709551617",
        "-99999999999",
        "1e400",
        "-1e400",
        "NaN",
        "inf",
        "-inf",
        "1e308",
        "4.9e-324",
    ];
    for f in data_files() {
        let text = std::fs::read_to_string(&f).unwrap();
        let format = Format::from_extension(&f).unwrap();
        // Count and number positions: (line, token).
        let places: Vec<(usize, usize)> = match format {
            Format::Ies => {
                let h = tilt_line(&text) + 1;
                // lamps, lm/lamp, multiplier, #vertical, #horizontal, type, units, width, ...
                let mut p: Vec<(usize, usize)> = (0..10).map(|k| (h, k)).collect();
                // ballast factor, future use, watts; the first angle; a candela value.
                p.extend([(h + 1, 0), (h + 1, 1), (h + 2, 0), (h + 2, 3), (h + 4, 0)]);
                p
            }
            // Isym, Mc, Dc, Ng, Dg; dimensions; lamp sets count; flux of set 1; an angle; an intensity.
            Format::Ldt => {
                let mut p: Vec<(usize, usize)> = [3, 4, 5, 6, 7, 13, 22, 23, 24, 26, 27, 29]
                    .iter()
                    .map(|&l| (l, 0))
                    .collect();
                let n = text.lines().count();
                p.extend([(n - 1, 0), (n, 0), (45, 0)]);
                p
            }
            Format::Tm33 => panic!("{}: data/ holds .ies and .ldt files only", f.display()),
        };
        for &(line, k) in &places {
            for v in values {
                let damaged = replace_token(&text, line, k, v);
                judge(
                    damaged.into_bytes(),
                    &f,
                    format,
                    &format!("{} line {line} token {k} = {v}", f.display()),
                    &mut t,
                );
            }
        }
    }
    assert!(t.refused > 0 && t.loaded > 0, "{t:?}");
}

#[test]
fn utf16_and_mixed_line_endings() {
    for f in data_files() {
        let text = std::fs::read_to_string(&f).unwrap();
        let format = Format::from_extension(&f).unwrap();
        let mut t = Tally::default();
        // UTF-16 LE with a byte-order mark: refused with a clear message, never misread.
        let mut utf16 = vec![0xFF, 0xFE];
        utf16.extend(text.encode_utf16().flat_map(|u| u.to_le_bytes()));
        judge(utf16, &f, format, &format!("{} as UTF-16", f.display()), &mut t);
        assert_eq!(t.refused, 1, "{}: UTF-16 is refused", f.display());
        // Mixed line endings load into the very same distribution.
        let plain = photosolid::formats::parse(text.as_bytes(), &f, format, &ReadOptions::default()).unwrap();
        let mut mixed = String::new();
        for (i, l) in text.lines().enumerate() {
            mixed.push_str(l);
            mixed.push_str(["\r\n", "\n", "\r"][i % 3]);
        }
        let m = photosolid::formats::parse(mixed.as_bytes(), &f, format, &ReadOptions::default())
            .unwrap_or_else(|e| panic!("{}: mixed line endings: {e}", f.display()));
        assert_eq!(m.distribution(), plain.distribution(), "{}", f.display());
    }
}

/// An IES text (from data/) whose TILT line names `target`.
fn with_tilt(target: &str) -> String {
    let f = Path::new(env!("CARGO_MANIFEST_DIR")).join("data/batwing.ies");
    let text = std::fs::read_to_string(f).unwrap();
    text.replace("TILT=NONE", &format!("TILT={target}"))
}

fn mkfifo(p: &Path) {
    let ok = std::process::Command::new("mkfifo").arg(p).status().unwrap().success();
    assert!(ok, "mkfifo {}", p.display());
}

#[test]
fn tilt_and_photometric_paths_that_are_not_regular_files() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("adir")).unwrap();
    mkfifo(&dir.path().join("fifo"));
    let main = dir.path().join("lum.ies");
    let mut t = Tally::default();
    for target in ["adir", "fifo", "/dev/zero", "/dev/stdin", "missing.dat"] {
        judge(
            with_tilt(target).into_bytes(),
            &main,
            Format::Ies,
            &format!("TILT={target}"),
            &mut t,
        );
    }
    assert_eq!(t.refused, 5, "{t:?}");
    // A tilt file over the cap is refused before it is parsed.
    let big = dir.path().join("big.dat");
    std::fs::write(
        &big,
        vec![b'1'; photosolid::formats::ies::MAX_TILT_FILE_BYTES as usize + 1],
    )
    .unwrap();
    judge(
        with_tilt("big.dat").into_bytes(),
        &main,
        Format::Ies,
        "TILT=big.dat",
        &mut t,
    );
    assert_eq!(t.refused, 6);
    // The photometric file itself: a directory, a FIFO, /dev/zero.
    for p in [
        dir.path().join("adir"),
        dir.path().join("fifo"),
        PathBuf::from("/dev/zero"),
    ] {
        let (tx, rx) = std::sync::mpsc::channel();
        let q = p.clone();
        std::thread::spawn(move || {
            let _ = tx.send(photosolid::load_with(&q, &ReadOptions::default()).map(|_| ()));
        });
        let r = rx.recv_timeout(Duration::from_secs(20)).expect("no hang");
        let e = r.expect_err("not a regular file");
        assert!(matches!(e, Error::Parse(_) | Error::Io { .. }), "{e}");
        let e = photosolid::load(&p).unwrap_err().to_string();
        assert!(e.contains(&*p.to_string_lossy()), "{e}");
    }
    assert!(LARGEST.load(Ordering::Relaxed) <= ALLOCATION_CAP);
}

#[test]
fn user_controlled_sizes_and_iterations_are_bounded() {
    use photosolid::solid::{measured_solid, SolidGrid, Units};
    let lum = photosolid::load(Path::new(env!("CARGO_MANIFEST_DIR")).join("data/batwing.ldt")).unwrap();
    // `mesh --factor 3000` asked for a 373 GB allocation: refused before allocating.
    let e = SolidGrid::refined(lum.distribution(), 3000).unwrap_err().to_string();
    assert!(e.contains("factor") && e.contains("at most"), "{e}");
    assert!(LARGEST.load(Ordering::Relaxed) <= ALLOCATION_CAP);
    assert!(SolidGrid::refined(lum.distribution(), 2).is_ok());
    // A Hausdorff tolerance of 0 is reached only when the bound closes exactly;
    // otherwise refinement stops at its cap and says so, in bounded time.
    let cap = photosolid::metrics::hausdorff::MAX_REFINEMENT_QUERIES;
    let load = |n: &str| photosolid::load(Path::new(env!("CARGO_MANIFEST_DIR")).join("data").join(n)).unwrap();
    let mut partial = 0;
    for (x, y) in [("batwing.ldt", "cosine_p5.ldt")] {
        // A filtered solid on a refined grid against a measured one, as `compare` does.
        let d = load(x).distribution().clone();
        let tex = photosolid::reconstruct::LightTexture::new(&d).unwrap();
        let sampler = tex.sampler(photosolid::reconstruct::Filter::CatmullRom);
        let grid = SolidGrid::refined(&d, 3).unwrap();
        let a = photosolid::solid::grid_solid(&sampler, &grid, Units::Peak).unwrap();
        let b = measured_solid(load(y).distribution(), Units::Peak).unwrap();
        // Bounded by MAX_REFINEMENT_QUERIES (checked below through
        // `converged`), not by a wall-clock assertion; benches/metrics.rs
        // times the mesh Hausdorff distance it refines.
        let h = photosolid::compare::solid_hausdorff(&a, &b, 0.0);
        assert!(h.bound.is_finite() && h.value.is_finite());
        for side in [h.a_to_b, h.b_to_a] {
            if side.converged {
                assert_eq!(
                    side.bound, 0.0,
                    "{x} {y}: converged at tolerance 0 means a closed bound"
                );
            } else {
                partial += 1;
                assert!(side.bound > 0.0 && side.queries >= cap, "{x} {y}: {side:?}");
            }
        }
    }
    // The pairs tried here close their bound exactly at tolerance 0 (`partial` stays 0):
    // the cap itself is not exercised by this test (RELIABILITY.md, "Left open").
    eprintln!("tolerance-0 sides stopped at the cap: {partial}");
}

/// Byte ranges of the numbers in `text`: maximal runs of digits, signs, dots
/// and exponents that parse as a number and do not sit inside a word
/// (`IESTM33-22` and dates are skipped).
fn number_spans(text: &str) -> Vec<(usize, usize)> {
    let b = text.as_bytes();
    let in_number = |c: u8| c.is_ascii_digit() || matches!(c, b'.' | b'+' | b'-' | b'e' | b'E');
    let word = |c: u8| c.is_ascii_alphanumeric() || c == b'_';
    let mut spans = Vec::new();
    let mut i = 0;
    while i < b.len() {
        let starts = (b[i].is_ascii_digit() || matches!(b[i], b'.' | b'+' | b'-')) && (i == 0 || !word(b[i - 1]));
        if !starts {
            i += 1;
            continue;
        }
        let mut j = i;
        while j < b.len() && in_number(b[j]) {
            j += 1;
        }
        let s = &text[i..j];
        let after_ok = j == b.len() || !word(b[j]);
        if after_ok && s.bytes().any(|c| c.is_ascii_digit()) && s.parse::<f64>().is_ok() {
            spans.push((i, j));
        }
        i = j.max(i + 1);
    }
    spans
}

/// The longest run of digits (a decimal point inside it counted) in `s`.
fn longest_digit_run(s: &str) -> usize {
    let (mut best, mut run) = (0, 0);
    for c in s.chars() {
        run = if c.is_ascii_digit() || (c == '.' && run > 0) {
            run + 1
        } else {
            0
        };
        best = best.max(run);
    }
    best
}

/// The texts a reader gives back for `bytes`: the error's expected and found
/// texts, or every warning's message.
fn messages(bytes: &[u8], path: &Path, format: Format, repair: bool) -> Vec<String> {
    let opts = ReadOptions {
        repair,
        ..ReadOptions::default()
    };
    match photosolid::formats::parse(bytes, path, format, &opts) {
        Ok(doc) => doc.warnings().iter().map(|w| w.message.clone()).collect(),
        Err(e) => vec![e.expected, e.found],
    }
}

/// Every number of every reader's input set, one at a time, to magnitudes
/// whose plain decimal form runs to hundreds of digits: no error or warning
/// message may print one that way (a ballast factor of 1e-200 printed 200
/// digits). Inputs: the data/ files, a TM-33-23 document written from one,
/// and the generated fixtures with an inline TILT table and a Type B grid.
#[test]
fn extreme_numbers_print_short_in_every_message() {
    use common::fixtures::{tm33_points, tm33_text, IesFile, IesTilt, IesVersion, LdtFile};
    let mut inputs: Vec<(PathBuf, Format, String)> = data_files()
        .into_iter()
        .map(|f| {
            let text = std::fs::read_to_string(&f).unwrap();
            (f.clone(), Format::from_extension(&f).unwrap(), text)
        })
        .collect();
    let road = photosolid::formats::load_document_with(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("data/roadway.ldt"),
        &ReadOptions::default(),
    )
    .unwrap();
    inputs.push(("road.xml".into(), Format::Tm33, photosolid::formats::tm33::write(&road)));
    inputs.push(("fixture.xml".into(), Format::Tm33, tm33_text(&tm33_points())));
    let mut tilted = IesFile::type_c(IesVersion::Lm1986);
    tilted.tilt = IesTilt::Include(1, vec![0.0, 45.0, 90.0], vec![1.0, 0.9, 0.7]);
    inputs.push(("tilted.ies".into(), Format::Ies, tilted.text()));
    inputs.push((
        "type_b.ies".into(),
        Format::Ies,
        IesFile::type_ab(IesVersion::Lm2002, 2).text(),
    ));
    inputs.push(("isym3.ldt".into(), Format::Ldt, LdtFile::isym(3).text()));
    let values = ["1e-200", "-1e-200", "1e300", "4e-320", "123456789012345678901234567890"];
    // One example per message template (digits collapsed), so each site shows once.
    let (mut cases, mut failures) = (0usize, std::collections::BTreeMap::new());
    for (path, format, text) in &inputs {
        let spans = number_spans(text);
        // Every number in the header part, then every k-th (at most ~100 per file).
        let head = text.lines().take(60).map(|l| l.len() + 1).sum::<usize>();
        let stride = (spans.len() / 100).max(1);
        for (k, &(a, b)) in spans.iter().enumerate() {
            if a >= head && k % stride != 0 {
                continue;
            }
            for v in values {
                let damaged = format!("{}{v}{}", &text[..a], &text[b..]);
                for repair in [false, true] {
                    cases += 1;
                    for m in messages(damaged.as_bytes(), path, *format, repair) {
                        // Quoting the file's own text is fine: only numbers the reader formats count.
                        if longest_digit_run(&m.replace(v, "")) > 24 {
                            let template: String = m
                                .chars()
                                .filter(|c| !c.is_ascii_digit() && *c != '.' && *c != '-')
                                .collect();
                            let short: String = m.chars().take(300).collect();
                            failures
                                .entry(template)
                                .or_insert_with(|| format!("{} `{}` -> {v}: {short}", path.display(), &text[a..b]));
                        }
                    }
                }
            }
        }
    }
    assert!(cases > 1000, "{cases} cases");
    assert!(
        failures.is_empty(),
        "{} message kinds (of {cases} cases) print a number at full length:\n{}",
        failures.len(),
        failures.values().cloned().collect::<Vec<_>>().join("\n")
    );
}
