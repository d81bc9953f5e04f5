//! EULUMDAT reader and writer: the corpus, round trips, damaged input, and
//! the format's corner cases on small files built here.

use std::path::{Path, PathBuf};
use std::time::Instant;

use photosolid::formats::ldt::{self, LampSetLayout, SIGNIFICANT_DIGITS};
use photosolid::formats::{LampSetFlux, ReadOptions};
use photosolid::model::{Distribution, Luminaire, Symmetry};

use crate::common;

/// (path, malformed) of every .ldt file of the corpus manifest (the shared
/// manifest reader of `tests/common`); None when the corpus is missing.
fn corpus() -> Option<Vec<(PathBuf, bool)>> {
    let root = common::corpus()?;
    let out: Vec<(PathBuf, bool)> = common::manifest(&root)
        .into_iter()
        .filter(|e| e.format == "ldt")
        .map(|e| {
            let m = e.malformed();
            (e.path, m)
        })
        .collect();
    assert!(!out.is_empty(), "no .ldt files in the manifest");
    Some(out)
}

fn read_file(p: &Path) -> Result<photosolid::formats::Document, photosolid::ParseError> {
    let bytes = std::fs::read(p).unwrap();
    ldt::read(&bytes, p, &ReadOptions::default())
}

fn read_str(s: &str) -> Result<photosolid::formats::Document, photosolid::ParseError> {
    ldt::read(s.as_bytes(), Path::new("test.ldt"), &ReadOptions::default())
}

/// Relative tolerance that follows from the writer's precision: half a unit
/// in the last of SIGNIFICANT_DIGITS digits, plus float noise.
fn tolerance(v: f64) -> f64 {
    0.5 * 10f64.powi(1 - SIGNIFICANT_DIGITS as i32) * v.abs() * 1.000001 + 1e-12
}

fn assert_same_distribution(a: &Distribution, b: &Distribution, what: &str) {
    assert_eq!(a.symmetry(), b.symmetry(), "{what}: symmetry");
    assert_eq!(a.c_angles_deg(), b.c_angles_deg(), "{what}: C angles");
    assert_eq!(a.gamma_angles_deg(), b.gamma_angles_deg(), "{what}: gamma angles");
    for (i, (x, y)) in a.intensities_cd().iter().zip(b.intensities_cd()).enumerate() {
        let g = a.n_gamma();
        assert_close!(
            *x,
            *y,
            abs = tolerance(*x),
            "{what}: C = {} > gamma = {}: {x} vs {y}",
            a.c_angles_deg()[i / g],
            a.gamma_angles_deg()[i % g]
        );
    }
}

#[test]
fn corpus_loads_unless_malformed() {
    let Some(files) = corpus() else { return };
    let mut report = Vec::new();
    for (p, malformed) in &files {
        match read_file(p) {
            Ok(l) => {
                assert!(!malformed, "{} is MALFORMED but loaded", p.display());
                let d = l.distribution();
                report.push(format!(
                    "ok   {} isym {} planes {} x {} warnings {:?}",
                    p.display(),
                    d.symmetry().isym(),
                    d.n_c(),
                    d.n_gamma(),
                    l.warnings().iter().map(|w| w.code).collect::<Vec<_>>()
                ));
            }
            Err(e) => {
                assert!(*malformed, "{} failed: {e}", p.display());
                assert_eq!(e.path, *p, "error names the file");
                assert!(e.location.line >= 1, "error names a line: {e}");
                report.push(format!("fail {e}"));
            }
        }
    }
    for r in report {
        println!("{r}");
    }
}

#[test]
fn corpus_round_trips_through_the_writer() {
    let Some(files) = corpus() else { return };
    for (p, malformed) in files {
        if malformed {
            continue;
        }
        let a = read_file(&p).unwrap();
        let text = ldt::write(&a);
        assert!(text.ends_with("\r\n") && !text.contains("\n\n"));
        let b = ldt::read(text.as_bytes(), &p, &ReadOptions::default())
            .unwrap_or_else(|e| panic!("{}: written file does not read back: {e}\n{text}", p.display()));
        let what = p.display().to_string();
        assert_same_distribution(a.distribution(), b.distribution(), &what);
        assert_eq!(a.metadata(), b.metadata(), "{what}");
        assert_eq!(a.lamp_sets().len(), b.lamp_sets().len(), "{what}");
        assert_eq!(a.declared().absolute, b.declared().absolute, "{what}");
        let (ha, hb) = (a.ldt_header().unwrap(), b.ldt_header().unwrap());
        assert_eq!(ha.c_angles, hb.c_angles, "{what}");
        assert_eq!(ha.mc, hb.mc, "{what}");
        assert_eq!(ha.direct_ratios, hb.direct_ratios, "{what}");
        // Written from a read file, the raw numbers come back as they were.
        assert_eq!(ha.cd_per_cdklm, hb.cd_per_cdklm, "{what}");
        // And a second trip is stable text.
        assert_eq!(ldt::write(&b), text, "{what}");
    }
}

#[test]
fn corpus_special_files() {
    let Some(root) = common::corpus() else { return };
    let root = root.as_path();
    // ~1000 blank lines and 259 extra values after the data.
    let l = read_file(&root.join("r-lighting/0_CIE-2010-Table7.ldt")).unwrap();
    let w = l
        .warnings()
        .iter()
        .find(|w| w.code == "extra-values")
        .expect("extra-values warning");
    assert!(w.message.starts_with("259 "), "{}", w.message);
    // Block-layout lamp sets, detected.
    let l = read_file(&root.join("photometric-viewer/multiple_lamp_sets.ldt")).unwrap();
    assert_eq!(l.ldt_header().unwrap().lamp_set_layout, LampSetLayout::Blocks);
    assert_eq!(l.lamp_sets().len(), 3);
    assert_eq!(l.lamp_sets()[1].lamp_type, "Double Lamp");
    assert_eq!(l.lamp_sets()[1].flux_lm, 1200.0);
    assert!(l.warnings().iter().any(|w| w.code == "lamp-set-layout"));
    // Isym 3 with Mc = 36: C270 ... C350, C0 ... C90 = 19 planes, model C90 ... C270.
    let l = read_file(&root.join("photometric-viewer/symmetry_to_c90c270.ldt")).unwrap();
    let d = l.distribution();
    assert_eq!(d.symmetry(), Symmetry::C90C270);
    assert_eq!(d.n_c(), 19);
    assert_eq!((d.c_angles_deg()[0], d.c_angles_deg()[18]), (90.0, 270.0));
    // Several values per line in the data block.
    let l = read_file(&root.join("luxera/synthetic_basic.ldt")).unwrap();
    assert_eq!(l.distribution().n_c(), 2);
    assert_eq!(l.distribution().plane_cd(1), &[2000.0, 1400.0, 100.0]);
}

/// A small xorshift PRNG: fixed seed, no dependency.
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

#[test]
fn damaged_input_never_panics() {
    let Some(files) = corpus() else { return };
    let mut rng = Rng(0x5eed_1dea_2024_0001);
    let opts = [
        ReadOptions::default(),
        ReadOptions {
            repair: true,
            lamp_set_flux: LampSetFlux::Sum,
            ..ReadOptions::default()
        },
    ];
    let path = Path::new("fuzz.ldt");
    let check = |bytes: &[u8], o: &ReadOptions| {
        if let Ok(l) = ldt::read(bytes, path, o) {
            assert!(l.distribution().intensities_cd().iter().all(|v| v.is_finite()));
            // Whatever loads can be written and read again.
            let _ = ldt::read(ldt::write(&l).as_bytes(), path, o);
        }
    };
    for (p, _) in &files {
        let bytes = std::fs::read(p).unwrap();
        for o in &opts {
            // Truncated prefixes.
            for k in 0..24 {
                let cut = if k < 8 { k * 7 } else { rng.below(bytes.len() + 1) };
                check(&bytes[..cut.min(bytes.len())], o);
            }
            // Bit flips and byte substitutions with format-relevant bytes.
            for _ in 0..40 {
                let mut b = bytes.clone();
                for _ in 0..1 + rng.below(4) {
                    if b.is_empty() {
                        break;
                    }
                    let i = rng.below(b.len());
                    const SUBST: &[u8] = b"0123456789-.,\n\r e9";
                    b[i] = match rng.below(4) {
                        0 => b[i] ^ (1 << rng.below(8)),
                        1 => SUBST[rng.below(SUBST.len())],
                        2 => b'9',
                        _ => rng.next() as u8,
                    };
                }
                check(&b, o);
            }
        }
    }
    for _ in 0..200 {
        let n = rng.below(3000);
        let b: Vec<u8> = (0..n).map(|_| rng.next() as u8).collect();
        check(&b, &opts[0]);
        // Random digits and line breaks: gets deep into the header.
        const DIGITS: &[u8] = b"0123456789\n\n\n .,-";
        let b: Vec<u8> = (0..n).map(|_| DIGITS[rng.below(DIGITS.len())]).collect();
        check(&b, &opts[1]);
    }
}

/// An EULUMDAT file with the given grid; `sets` are six lines per set in field-group order.
fn ldt_text(isym: u8, c: &[f64], gamma: &[f64], sets: &[&str], values: &[f64]) -> String {
    let mut s = String::new();
    let mut line = |x: &dyn std::fmt::Display| s.push_str(&format!("{x}\r\n"));
    line(&"Test company");
    line(&3);
    line(&isym);
    line(&c.len());
    line(&if c.len() > 1 { c[1] - c[0] } else { 0.0 });
    line(&gamma.len());
    line(&if gamma.len() > 1 { gamma[1] - gamma[0] } else { 0.0 });
    for t in ["R1", "Lum", "L-1", "test.ldt", "2024"] {
        line(&t);
    }
    for v in [600, 300, 50, 500, 0, 40, 40, 40, 40] {
        line(&v);
    }
    line(&"80");
    line(&"90");
    line(&"1");
    line(&"0");
    line(&(sets.len() / 6));
    for t in sets {
        line(t);
    }
    for _ in 0..10 {
        line(&"0.5");
    }
    for v in c.iter().chain(gamma).chain(values) {
        line(v);
    }
    s
}

const ONE_SET: [&str; 6] = ["1", "LED", "2000", "3000K", "80", "25"];

#[test]
fn isym3_planes_are_mirrored_into_c90_c270() {
    let c: Vec<f64> = (0..24).map(|i| i as f64 * 15.0).collect();
    let gamma = [0.0, 45.0, 90.0];
    // Stored file planes in file order: C270, C285, ..., C345, C0, ..., C90.
    let file_planes: Vec<f64> = (18..24).chain(0..7).map(|i| i as f64 * 15.0).collect();
    let mut values = Vec::new();
    for &fc in &file_planes {
        // Distinct per plane so that every value tells where it came from.
        values.extend([100.0, 50.0 + fc / 10.0, 10.0 + fc / 100.0]);
    }
    let l = read_str(&ldt_text(3, &c, &gamma, &ONE_SET, &values)).unwrap();
    let d = l.distribution();
    assert_eq!(d.symmetry(), Symmetry::C90C270);
    assert_eq!(d.c_angles_deg().first(), Some(&90.0));
    assert_eq!(d.c_angles_deg().last(), Some(&270.0));
    let scale = 2.0; // 2000 lm / 1000
                     // File plane C0 is model C180; C270 stays; C90 stays; C300 is model C240.
    let at = |c: f64, g: usize| d.value_cd(d.find_plane(c).unwrap(), g) / scale;
    assert_eq!(at(180.0, 1), 50.0);
    assert_eq!(at(270.0, 1), 50.0 + 27.0);
    assert_eq!(at(90.0, 1), 50.0 + 9.0);
    assert_eq!(at(240.0, 1), 50.0 + 30.0);
    // Expansion reproduces the file's stored planes at their own angles.
    let full = d.expand(1);
    for &fc in &file_planes {
        let ic = full.find_plane(fc).unwrap();
        assert_eq!(full.value_cd(ic, 1) / scale, 50.0 + fc / 10.0, "file plane C{fc}");
        assert_eq!(full.value_cd(ic, 2) / scale, 10.0 + fc / 100.0, "file plane C{fc}");
    }
    // Written back, the same planes sit at the same file positions.
    let text = ldt::write(&l);
    assert_eq!(text, ldt::write(&read_str(&text).unwrap()));
    let back = read_str(&text).unwrap();
    assert_same_distribution(d, back.distribution(), "isym 3");
}

#[test]
fn decimal_commas_are_read() {
    let text = ldt_text(1, &[0.0], &[0.0, 45.0, 90.0], &ONE_SET, &[100.0, 50.0, 0.0])
        .replace("\r\n0.5\r\n", "\r\n0,5\r\n")
        .replace("\r\n50\r\n", "\r\n12,5\r\n")
        .replace("\r\n45\r\n", "\r\n45,0\r\n");
    let l = read_str(&text).unwrap();
    assert_eq!(l.distribution().gamma_angles_deg(), &[0.0, 45.0, 90.0]);
    assert_eq!(l.distribution().plane_cd(0), &[200.0, 25.0, 0.0]);
    assert_eq!(l.ldt_header().unwrap().direct_ratios[0], 0.5);
}

#[test]
fn two_lamp_sets_in_field_groups() {
    let sets = [
        "1", "2", "LED A", "LED B", "1000", "3000", "830", "840", "1B", "1A", "10", "30",
    ];
    let text = ldt_text(1, &[0.0], &[0.0, 90.0], &sets, &[100.0, 10.0]);
    let l = read_str(&text).unwrap();
    let h = l.ldt_header().unwrap();
    assert_eq!(h.lamp_set_layout, LampSetLayout::FieldGroups);
    assert_eq!(l.lamp_sets()[1].lamp_type, "LED B");
    assert_eq!(l.lamp_sets()[1].flux_lm, 3000.0);
    assert_eq!(l.lamp_sets()[1].color, "840");
    assert!(l.warnings().iter().any(|w| w.code == "lamp-set-layout"));
    // Set 1 is the reference by default.
    assert_eq!(l.distribution().plane_cd(0), &[100.0, 10.0]);
    assert_eq!(l.declared().lamp_flux_lm, Some(1000.0));
    // The input power is the luminaire's: every set's wattage, whichever set the cd/klm
    // refer to (`info`'s `input_watts`, and what a conversion writes).
    assert_eq!(l.declared().input_watts, Some(40.0));
    let sum = ReadOptions {
        lamp_set_flux: LampSetFlux::Sum,
        ..ReadOptions::default()
    };
    let l = ldt::read(text.as_bytes(), Path::new("t.ldt"), &sum).unwrap();
    assert_eq!(l.distribution().plane_cd(0), &[400.0, 40.0]);
    assert_eq!(l.declared().lamp_flux_lm, Some(4000.0));
    assert_eq!(l.declared().input_watts, Some(40.0));
    // The same sets in blocks of six are detected too.
    let blocks = [
        "1", "LED A", "1000", "830", "1B", "10", "2", "LED B", "3000", "840", "1A", "30",
    ];
    let l = read_str(&ldt_text(1, &[0.0], &[0.0, 90.0], &blocks, &[100.0, 10.0])).unwrap();
    assert_eq!(l.ldt_header().unwrap().lamp_set_layout, LampSetLayout::Blocks);
    assert_eq!(l.lamp_sets()[1].flux_lm, 3000.0);
}

#[test]
fn absolute_photometry() {
    let set = ["-1", "LED module", "1500", "4000K", "80", "12"];
    let l = read_str(&ldt_text(1, &[0.0], &[0.0, 90.0], &set, &[200.0, 20.0])).unwrap();
    assert!(l.declared().absolute);
    assert_eq!(l.declared().lamp_flux_lm, None);
    assert_eq!(l.declared().luminaire_flux_lm, Some(1500.0));
    assert_eq!(l.distribution().plane_cd(0), &[300.0, 30.0]);
    let back = read_str(&ldt::write(&l)).unwrap();
    assert!(back.declared().absolute);
    assert_same_distribution(l.distribution(), back.distribution(), "absolute");
}

#[test]
fn relative_photometry_fills_declared() {
    let l = read_str(&ldt_text(1, &[0.0], &[0.0, 90.0], &ONE_SET, &[200.0, 20.0])).unwrap();
    assert!(!l.declared().absolute);
    assert_eq!(l.declared().lamp_flux_lm, Some(2000.0));
    assert_eq!(l.declared().luminaire_flux_lm, Some(1800.0));
    assert_eq!(l.declared().lor, Some(0.9));
    assert_eq!(l.declared().dff, Some(0.8));
    assert_eq!(l.declared().input_watts, Some(25.0));
    assert_eq!(l.dimensions().length_m, 0.6);
    assert_eq!(l.luminous_opening().width_m, 0.0);
    assert_eq!(l.metadata().lamp, "LED");
}

#[test]
fn huge_counts_fail_fast_without_allocating() {
    // Counts beyond the values present are refused; the reader's speed is
    // measured by benches/parse.rs, not asserted against the wall clock here.
    let text = ldt_text(0, &[0.0], &[0.0], &ONE_SET, &[1.0]);
    // Mc and Ng at their bounds but the file holds a handful of values.
    let big = text.replacen("\r\n1\r\n0\r\n1\r\n", "\r\n3600\r\n0\r\n1801\r\n", 1);
    assert_ne!(big, text);
    let e = read_str(&big).unwrap_err();
    assert!(e.to_string().contains("values"), "{e}");
    // Beyond the bounds.
    let e = read_str(&text.replacen("\r\n1\r\n0\r\n1\r\n", "\r\n99999999999\r\n0\r\n1\r\n", 1)).unwrap_err();
    assert_eq!(e.location.line, 4, "{e}");
    // A huge lamp-set count.
    let e = read_str(&text.replacen("\r\n0\r\n1\r\n1\r\n", "\r\n0\r\n10000\r\n1\r\n", 1)).unwrap_err();
    assert!(e.to_string().contains("lamp-set lines"), "{e}");
}

#[test]
fn truncated_intensities_report_expected_and_found() {
    let c: Vec<f64> = (0..4).map(|i| i as f64 * 90.0).collect();
    let text = ldt_text(0, &c, &[0.0, 45.0, 90.0], &ONE_SET, &[1.0; 10]);
    let e = read_str(&text).unwrap_err();
    let s = e.to_string();
    assert!(s.contains("12 intensities") && s.contains("found 10 values"), "{s}");
    assert!(s.starts_with("test.ldt:"), "{s}");
}

#[test]
fn unsorted_angles_fail_or_are_repaired() {
    let text = ldt_text(1, &[0.0], &[0.0, 90.0, 45.0], &ONE_SET, &[3.0, 1.0, 2.0]);
    let e = read_str(&text).unwrap_err();
    assert!(e.to_string().contains("strictly ascending gamma"), "{e}");
    let line = text.split("\r\n").position(|l| l == "45").unwrap() + 1;
    assert_eq!((e.location.line, e.location.column), (line, Some(1)), "{e}");
    let repair = ReadOptions {
        repair: true,
        ..ReadOptions::default()
    };
    let l = ldt::read(text.as_bytes(), Path::new("t.ldt"), &repair).unwrap();
    assert_eq!(l.distribution().gamma_angles_deg(), &[0.0, 45.0, 90.0]);
    assert_eq!(l.distribution().plane_cd(0), &[6.0, 4.0, 2.0]);
    assert!(l.warnings().iter().any(|w| w.code == "unsorted-angles"));
}

#[test]
fn poles_and_negative_values_are_kept_with_warnings() {
    let c: Vec<f64> = (0..4).map(|i| i as f64 * 90.0).collect();
    let values = [10.0, 5.0, 11.0, 5.0, 10.0, -1.0, 10.0, 5.0];
    let l = read_str(&ldt_text(0, &c, &[0.0, 90.0], &ONE_SET, &values)).unwrap();
    let codes: Vec<_> = l.warnings().iter().map(|w| w.code.as_str()).collect();
    assert!(
        codes.contains(&"pole-mismatch") && codes.contains(&"negative-intensity"),
        "{codes:?}"
    );
    assert_eq!(l.distribution().value_cd(1, 0), 22.0);
    assert_eq!(l.distribution().value_cd(2, 1), -2.0);
}

#[test]
fn text_encodings_line_ends_and_padding() {
    let text = ldt_text(1, &[0.0], &[0.0, 90.0], &ONE_SET, &[100.0, 10.0]);
    let mut latin1 = text.replace("Test company", "Soci\u{e9}t\u{e9}").into_bytes();
    // Re-encode the two é as Latin-1.
    let mut b = Vec::new();
    let mut i = 0;
    while i < latin1.len() {
        if latin1[i] == 0xC3 && latin1.get(i + 1) == Some(&0xA9) {
            b.push(0xE9);
            i += 2;
        } else {
            b.push(latin1[i]);
            i += 1;
        }
    }
    b.extend_from_slice(b"\x1A");
    latin1 = b;
    let l = ldt::read(&latin1, Path::new("t.ldt"), &ReadOptions::default()).unwrap();
    assert_eq!(l.metadata().manufacturer, "Soci\u{e9}t\u{e9}");
    for eol in ["\n", "\r"] {
        let t = text.replace("\r\n", eol);
        let t = t.trim_end();
        let l = read_str(t).unwrap();
        assert_eq!(l.distribution().plane_cd(0), &[200.0, 20.0]);
    }
    // Integers written as 1.0, trailing blanks, junk after a header number.
    let t = text
        .replacen("\r\n1\r\n1\r\n", "\r\n1.0  \r\n1.0\r\n", 1)
        .replacen("\r\n80\r\n", "\r\n80 % dff\r\n", 1);
    let l = read_str(&t).unwrap();
    assert!(l.warnings().iter().any(|w| w.code == "header-junk"));
}

#[test]
fn synthetic_distributions_are_written_with_derived_headers() {
    let g: Vec<f64> = vec![0.0, 10.0, 30.0, 90.0];
    let c = vec![0.0, 30.0, 90.0];
    let cd: Vec<f64> = (0..12).map(|i| 1000.0 / (1.0 + i as f64) + 0.123456789).collect();
    for sym in [Symmetry::Quadrant, Symmetry::None, Symmetry::C0C180] {
        let c = match sym {
            Symmetry::C0C180 => vec![0.0, 60.0, 180.0],
            _ => c.clone(),
        };
        let d = Distribution::new(c, g.clone(), cd.clone(), sym).unwrap();
        let lum = Luminaire::from_distribution(d.clone());
        let text = ldt::write(&lum.clone().into());
        let back = read_str(&text).unwrap_or_else(|e| panic!("{sym:?}: {e}\n{text}"));
        assert!(back.declared().absolute);
        assert_same_distribution(&d, back.distribution(), &format!("{sym:?}"));
        let h = back.ldt_header().unwrap();
        assert_eq!(h.dc, 0.0, "non-uniform C");
        assert_eq!(h.dg, 0.0, "non-uniform gamma");
    }
    // Rotational: Mc = 24, Dc = 15, one stored plane.
    let d = Distribution::new(vec![0.0], g.clone(), cd[..4].to_vec(), Symmetry::Rotational).unwrap();
    let back = read_str(&ldt::write(&Luminaire::from_distribution(d.clone()).into())).unwrap();
    let h = back.ldt_header().unwrap();
    assert_eq!((h.isym, h.mc, h.dc), (1, 24, 15.0));
    assert_same_distribution(&d, back.distribution(), "rotational");
}

/// Throughput of the reader on a large file (run with `--ignored --nocapture`).
#[test]
#[ignore = "a timing run that checks nothing (benches/parse.rs measures parsing): run with --ignored --nocapture"]
fn parse_speed() {
    let c: Vec<f64> = (0..720).map(|i| i as f64 * 0.5).collect();
    let g: Vec<f64> = (0..=1800).map(|i| i as f64 * 0.1).collect();
    // Real files print a few decimals: keep the values short, as they are.
    let values: Vec<f64> = (0..c.len() * g.len())
        .map(|i| ((i % 9973) as f64 * 37.0).round() / 100.0)
        .collect();
    let text = ldt_text(0, &c, &g, &ONE_SET, &values);
    let start = Instant::now();
    let runs = 5;
    for _ in 0..runs {
        read_str(&text).unwrap();
    }
    let s = start.elapsed().as_secs_f64() / runs as f64;
    println!(
        "{:.1} MB in {:.3} s: {:.0} MB/s",
        text.len() as f64 / 1e6,
        s,
        text.len() as f64 / 1e6 / s
    );
}
