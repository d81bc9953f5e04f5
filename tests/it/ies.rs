//! IES LM-63 reader and writer against the shared corpus and synthetic files.

use std::path::{Path, PathBuf};
use std::time::Instant;

use photosolid::formats::ies::{self, IesWriteVersion};
use photosolid::formats::{Handedness, ReadOptions};
use photosolid::model::{PhotometricType, Symmetry, Tilt};
use photosolid::{Distribution, Luminaire};

use crate::common;

/// (path, malformed) of every .ies file of the corpus manifest (the shared
/// manifest reader of `tests/common`); None when the corpus is missing.
fn corpus() -> Option<Vec<(PathBuf, bool)>> {
    let root = common::corpus()?;
    let out: Vec<(PathBuf, bool)> = common::manifest(&root)
        .into_iter()
        .filter(|e| e.format == "ies")
        .map(|e| {
            let m = e.malformed();
            (e.path, m)
        })
        .collect();
    assert!(!out.is_empty(), "no .ies files in the manifest");
    Some(out)
}

fn read_path(p: &Path) -> Result<photosolid::formats::Document, photosolid::ParseError> {
    let bytes = std::fs::read(p).unwrap();
    ies::read(&bytes, p, &ReadOptions::default())
}

fn read_str(s: &str) -> Result<photosolid::formats::Document, photosolid::ParseError> {
    ies::read(s.as_bytes(), Path::new("mem.ies"), &ReadOptions::default())
}

/// Same angles exactly, same symmetry, values within `rel` of the peak.
fn assert_same(a: &Distribution, b: &Distribution, rel: f64, what: &str) {
    assert_eq!(a.symmetry(), b.symmetry(), "{what}: symmetry");
    assert_eq!(a.c_angles_deg(), b.c_angles_deg(), "{what}: C angles");
    assert_eq!(a.gamma_angles_deg(), b.gamma_angles_deg(), "{what}: gamma angles");
    let tol = rel * a.max_cd().abs().max(1e-300);
    for (i, (x, y)) in a.intensities_cd().iter().zip(b.intensities_cd()).enumerate() {
        assert_close!(*x, *y, abs = tol.max(rel * x.abs()), "{what}: value #{i}: {x} vs {y}");
    }
}

#[test]
fn corpus_loads_or_fails_as_the_manifest_says() {
    let Some(files) = corpus() else { return };
    let mut report = String::new();
    let mut bad = Vec::new();
    for (p, malformed) in &files {
        match (read_path(p), malformed) {
            (Ok(l), false) => report.push_str(&format!(
                "OK   {} ({}, {:?}, {:?}, {} warnings)\n",
                p.display(),
                l.version(),
                l.photometric_type(),
                l.distribution().symmetry(),
                l.warnings().len()
            )),
            (Err(e), true) => {
                let s = e.to_string();
                report.push_str(&format!("FAIL {s}\n"));
                let name = p.file_name().unwrap().to_string_lossy().into_owned();
                if !s.contains(&name) || e.location.line == 0 {
                    bad.push(format!("error does not name file and line: {s}"));
                }
            }
            (Ok(_), true) => bad.push(format!("MALFORMED file loaded: {}", p.display())),
            (Err(e), false) => bad.push(format!("valid file failed: {e}")),
        }
    }
    eprintln!("{report}");
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}

#[test]
fn corpus_round_trips_through_the_writer() {
    let Some(files) = corpus() else { return };
    for (p, malformed) in &files {
        if *malformed {
            continue;
        }
        let Ok(a) = read_path(p) else { continue };
        for version in [IesWriteVersion::Lm63_2002, IesWriteVersion::Lm63_2019] {
            let text = ies::write(&a, version);
            for (i, l) in text.split("\r\n").enumerate() {
                assert!(l.len() + 2 <= 256, "{}: line {} too long", p.display(), i + 1);
            }
            let b = ies::read(text.as_bytes(), p, &ReadOptions::default())
                .unwrap_or_else(|e| panic!("{}: re-read failed: {e}\n{text}", p.display()));
            // The writer's precision contract: exact without multipliers, else 1e-14 relative.
            assert_same(a.distribution(), b.distribution(), 1e-13, &p.display().to_string());
            assert_eq!(a.photometric_type(), b.photometric_type());
            assert_eq!(a.tilt().table(), b.tilt().table());
            assert_eq!(a.metadata().manufacturer, b.metadata().manufacturer);
            assert_eq!(a.metadata().catalogue, b.metadata().catalogue);
            for k in ["[TEST]", "[TESTLAB]", "[ISSUEDATE]", "[MANUFAC]"] {
                assert!(text.contains(k), "{}: {k} missing", p.display());
            }
        }
    }
}

#[test]
fn no_panic_on_truncated_flipped_or_random_input() {
    let Some(files) = corpus() else { return };
    let mut rng = common::Rng(0x9E37_79B9_7F4A_7C15);
    let opts_all = [
        ReadOptions::default(),
        ReadOptions {
            repair: true,
            ..ReadOptions::default()
        },
    ];
    let picks: Vec<&PathBuf> = files.iter().map(|f| &f.0).step_by(6).collect();
    for p in picks {
        let bytes = std::fs::read(p).unwrap();
        // Truncation: every prefix for small files, a stride through big ones.
        let step = (bytes.len() / 400).max(1);
        for n in (0..bytes.len()).step_by(step) {
            let _ = ies::read(&bytes[..n], p, &opts_all[n % 2]);
        }
        // Bit flips and byte substitutions.
        for k in 0..200 {
            let mut b = bytes.clone();
            for _ in 0..1 + k % 4 {
                let i = (rng.next() as usize) % b.len().max(1);
                if let Some(x) = b.get_mut(i) {
                    if k % 2 == 0 {
                        *x ^= 1 << (rng.next() % 8);
                    } else {
                        *x = b"0123456789-.,e \n[]TILT=NONE"[(rng.next() % 27) as usize];
                    }
                }
            }
            let _ = ies::read(&b, p, &opts_all[k % 2]);
        }
    }
    // Multi-byte text where a tilt file name or keyword is expected.
    for t in ["TILT=€€€", "TILT=FILE€", "TILT=FILE ", "TILT=F€LE x", "TILT="] {
        let s = SIMPLE.replace("TILT=NONE", t);
        let _ = read_str(&s);
    }
    // Random bytes, and random bytes after a valid prefix.
    let base = "IESNA:LM-63-2002\nTILT=NONE\n";
    for k in 0..2000 {
        let n = (rng.next() % 300) as usize;
        let mut b: Vec<u8> = if k % 2 == 0 {
            Vec::new()
        } else {
            base.as_bytes().to_vec()
        };
        for _ in 0..n {
            b.push(if k % 3 == 0 {
                rng.next() as u8
            } else {
                b"0123456789 -.\n"[(rng.next() % 14) as usize]
            });
        }
        let _ = ies::read(&b, Path::new("random.ies"), &opts_all[k % 2]);
    }
}

#[test]
fn huge_header_counts_error_quickly() {
    // Counts far beyond the values present are refused from the header; how
    // fast is a benchmark's business (benches/parse.rs times the reader), not
    // a wall-clock assertion in a test.
    let e = read_str("IESNA:LM-63-2002\nTILT=NONE\n1 -1 1 1000000000 1 1 2 0 0 0\n1 1 0\n0 90\n0\n1 2\n").unwrap_err();
    assert_eq!(e.location.line, 3, "{e}");
    assert!(e.to_string().contains("1000000000"), "{e}");
    let e = read_str("IESNA:LM-63-2002\nTILT=NONE\n1 -1 1 1000000000 1000000000 1 2 0 0 0\n1 1 0\n").unwrap_err();
    assert_eq!(e.location.line, 3, "{e}");
    let e = read_str("IESNA:LM-63-2002\nTILT=INCLUDE\n1 1000000000\n0 1\n").unwrap_err();
    assert_eq!(e.location.line, 3, "{e}");
}

const SIMPLE: &str =
    "IESNA:LM-63-2002\n[TEST] T1\n[MANUFAC] Acme\nTILT=NONE\n1 -1 1 3 1 1 2 0 0 0\n1 1 10\n0 45 90\n0\n100 50 0\n";

#[test]
fn reads_a_simple_file() {
    let l = read_str(SIMPLE).unwrap();
    assert_eq!(l.version(), "LM-63-2002");
    assert_eq!(l.metadata().manufacturer, "Acme");
    assert_eq!(l.metadata().test_report, "T1");
    assert!(l.declared().absolute);
    assert_eq!(l.distribution().symmetry(), Symmetry::Rotational);
    assert_eq!(l.distribution().intensities_cd(), &[100.0, 50.0, 0.0]);
    assert!(l.warnings().is_empty(), "{:?}", l.warnings());
}

#[test]
fn tilt_include_is_parsed_not_applied() {
    let s = "IESNA:LM-63-2002\nTILT=INCLUDE\n1\n3\n0 15 30\n1.0 0.95 0.9\n1 -1 1 2 1 1 2 0 0 0\n1 1 0\n0 90\n0\n10 5\n";
    let l = read_str(s).unwrap();
    let Tilt::Include { table } = l.tilt() else {
        panic!("{:?}", l.tilt())
    };
    assert_eq!(table.geometry, 1);
    assert_eq!(table.angles, vec![0.0, 15.0, 30.0]);
    assert_eq!(table.multipliers, vec![1.0, 0.95, 0.9]);
    assert_eq!(l.distribution().intensities_cd(), &[10.0, 5.0]);
    let t = l.tilted_distribution(30.0).unwrap();
    assert_close!(t.intensities_cd()[0], 9.0, abs = 1e-12);
}

#[test]
fn tilt_file_is_resolved_next_to_the_file() {
    let Some(root) = common::corpus() else { return };
    let p = root.join("luxera/tilt_file_variant.ies");
    let l = read_path(&p).unwrap();
    let Tilt::File { name, table } = l.tilt() else {
        panic!("{:?}", l.tilt())
    };
    assert_eq!(name, "tilt_factor.dat");
    assert_eq!(table.angles, vec![0.0, 15.0, 30.0]);
    assert_eq!(table.multipliers, vec![1.0, 0.9, 0.8]);
    assert!(l.warnings().iter().any(|w| w.code == "tilt-file-keyword"));
    // Written back inline.
    let text = ies::write(&l, IesWriteVersion::Lm63_2002);
    assert!(
        text.contains("TILT=INCLUDE\r\n1\r\n3\r\n0 15 30\r\n1 0.9 0.8\r\n"),
        "{text}"
    );

    let p = root.join("luxera/tilt_file_missing.ies");
    let e = read_path(&p).unwrap_err();
    assert!(e.to_string().contains("does_not_exist.dat"), "{e}");
    assert_eq!(e.location.line, 4);
}

#[test]
fn tilt_file_in_a_temp_dir() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("t.tlt"), "3 2\n0 90\n1 0.5\n").unwrap();
    let p = dir.path().join("lum.ies");
    let s = "IESNA:LM-63-2002\nTILT=t.tlt\n1 -1 1 2 1 1 2 0 0 0\n1 1 0\n0 90\n0\n10 5\n";
    let l = ies::read(s.as_bytes(), &p, &ReadOptions::default()).unwrap();
    let table = l.tilt().table().unwrap();
    assert_eq!(table.geometry, 3);
    assert_eq!(table.multipliers, vec![1.0, 0.5]);
    let s = "IESNA:LM-63-2002\nTILT=nope.tlt\n1 -1 1 2 1 1 2 0 0 0\n1 1 0\n0 90\n0\n10 5\n";
    let e = ies::read(s.as_bytes(), &p, &ReadOptions::default()).unwrap_err();
    assert!(
        e.to_string().contains("nope.tlt") && e.to_string().contains("lum.ies:2"),
        "{e}"
    );
}

/// Type B file with one bright direction at H = 30 (towards +y), V = 40.
fn type_b_spot() -> String {
    let v: Vec<f64> = (-18..=18).map(|i| i as f64 * 5.0).collect();
    let h: Vec<f64> = (-18..=18).map(|i| i as f64 * 5.0).collect();
    let mut s = format!(
        "IESNA:LM-63-2002\n[TEST] B\nTILT=NONE\n1 -1 1 {} {} 2 2 0 0 0\n1 1 0\n",
        v.len(),
        h.len()
    );
    let join = |a: &[f64]| a.iter().map(|x| x.to_string()).collect::<Vec<_>>().join(" ");
    s += &join(&v);
    s += "\n";
    s += &join(&h);
    s += "\n";
    for &hh in &h {
        let row: Vec<f64> = v
            .iter()
            .map(|&vv| {
                if (hh - 30.0).abs() <= 5.0 && (vv - 40.0).abs() <= 5.0 {
                    1000.0
                } else {
                    0.0
                }
            })
            .collect();
        s += &join(&row);
        s += "\n";
    }
    s
}

#[test]
fn type_b_bright_direction_lands_at_the_expected_c_gamma() {
    let s = type_b_spot();
    for (hand, sign) in [(Handedness::CounterClockwise, 1.0), (Handedness::Clockwise, -1.0)] {
        let opts = ReadOptions {
            handedness: hand,
            ..ReadOptions::default()
        };
        let l = ies::read(s.as_bytes(), Path::new("b.ies"), &opts).unwrap();
        assert_eq!(l.photometric_type(), PhotometricType::B);
        assert_eq!(l.distribution().symmetry(), Symmetry::None);
        // d = (cosH sinV, sinH, -cosH cosV) for H = 30, V = 40.
        let (h, v) = (30f64.to_radians(), 40f64.to_radians());
        let d = [h.cos() * v.sin(), sign * h.sin(), -h.cos() * v.cos()];
        let gamma = (-d[2]).acos().to_degrees();
        let c = d[1].atan2(d[0]).to_degrees().rem_euclid(360.0);
        let (peak, _, _) = l.distribution().max_cd_at_deg();
        assert_close!(peak, 1000.0, abs = 1e-9, "{peak}");
        // The grid point nearest the bright direction lies inside the lit patch.
        let d2 = l.distribution();
        let near = |a: &[f64], x: f64| {
            (0..a.len())
                .min_by(|&i, &j| (a[i] - x).abs().total_cmp(&(a[j] - x).abs()))
                .unwrap()
        };
        let (ic, ig) = (near(d2.c_angles_deg(), c), near(d2.gamma_angles_deg(), gamma));
        assert!(
            d2.value_cd(ic, ig) > 999.0,
            "dark at C {c} gamma {gamma}: {}",
            d2.value_cd(ic, ig)
        );
        // Mirror image is dark.
        let mirror_c = (360.0 - c).rem_euclid(360.0);
        let ic = d2
            .c_angles_deg()
            .iter()
            .position(|&x| (x - mirror_c).abs() < 2.6)
            .unwrap();
        let ig = d2
            .gamma_angles_deg()
            .iter()
            .position(|&x| (x - gamma).abs() < 2.6)
            .unwrap();
        assert!(d2.value_cd(ic, ig) < 1e-9, "mirror lit: {}", d2.value_cd(ic, ig));
        // The source grid is kept and written back as Type B.
        let sg = l.source_grid().unwrap();
        assert_eq!(sg.kind, PhotometricType::B);
        let text = ies::write(&l, IesWriteVersion::Lm63_2002);
        let back = ies::read(text.as_bytes(), Path::new("b.ies"), &opts).unwrap();
        assert_eq!(back.source_grid(), l.source_grid());
    }
}

#[test]
fn type_b_half_grid_is_c0c180() {
    let s = "IESNA:LM-63-2002\nTILT=NONE\n1 -1 1 3 3 2 2 0 0 0\n1 1 0\n-90 0 90\n0 45 90\n1 2 3 4 5 6 7 8 9\n";
    let l = read_str(s).unwrap();
    assert_eq!(l.distribution().symmetry(), Symmetry::C0C180);
    // Nadir = H0 V0 = 2.
    assert_close!(l.distribution().value_cd(0, 0), 2.0, abs = 1e-9);
}

#[test]
fn comma_separated_values() {
    let s = "IESNA:LM-63-2002\nTILT=NONE\n1,-1,1,3,1,1,2,0,0,0\n1,1,0\n0,45,90\n0\n100,50.5,0\n";
    let l = read_str(s).unwrap();
    assert_eq!(l.distribution().intensities_cd(), &[100.0, 50.5, 0.0]);
}

#[test]
fn file_1986_without_keyword_line_and_blpf() {
    let s = "ACME LIGHTING\nSome luminaire\nTILT=NONE\n2 1000 2 2 1 1 1 1 2 0\n0.5 0.8 100\n0 90\n0\n100 50\n";
    let l = read_str(s).unwrap();
    assert_eq!(l.version(), "LM-63-1986");
    // 100 x multiplier 2 x ballast 0.5 x BLPF 0.8 = 80.
    assert_eq!(l.distribution().intensities_cd(), &[80.0, 40.0]);
    assert_eq!(l.declared().lamp_flux_lm, Some(2000.0));
    assert_close!(l.luminous_opening().length_m, 2.0 * 0.3048, abs = 1e-12);
    assert_close!(l.luminous_opening().width_m, 0.3048, abs = 1e-12);
    assert_eq!(l.metadata().luminaire, "ACME LIGHTING Some luminaire");
    // From 1995 the BLPF field is unused.
    let s95 = s.replace("ACME LIGHTING\n", "IESNA:LM-63-1995\n");
    assert_eq!(read_str(&s95).unwrap().distribution().intensities_cd(), &[100.0, 50.0]);
    // Written as 2002 the BLPF is folded into the values.
    let l2 = read_str(&ies::write(&l, IesWriteVersion::Lm63_2002)).unwrap();
    assert_same(l.distribution(), l2.distribution(), 1e-14, "1986 rewrite");
}

#[test]
fn ctrl_z_cr_only_bom_and_blank_lines() {
    let cr = SIMPLE.replace('\n', "\r");
    assert_eq!(
        read_str(&cr).unwrap().distribution().intensities_cd(),
        &[100.0, 50.0, 0.0]
    );
    let z = format!("\u{feff}{}\x1a", SIMPLE.replace('\n', "\r\n"));
    assert_eq!(
        read_str(&z).unwrap().distribution().intensities_cd(),
        &[100.0, 50.0, 0.0]
    );
    let blank = SIMPLE.replace("TILT=NONE\n", &format!("TILT=NONE\n{}", "\n".repeat(1000)));
    let l = read_str(&blank).unwrap();
    assert_eq!(l.distribution().intensities_cd(), &[100.0, 50.0, 0.0]);
    let one_per_line = SIMPLE.replace(' ', "\n");
    assert!(read_str(&one_per_line).is_ok());
}

#[test]
fn keywords_more_user_and_version_spellings() {
    let s = "IESNA: LM-63-2002 \n[TEST]T9\n[MANUFAC] Big\n[MORE] Company\n[_Electric Parameters] 230 V\nTILT=NONE\n1 -1 1 2 1 1 2 0 0 0\n1 1 0\n0 90\n0\n1 2\n";
    let l = read_str(s).unwrap();
    assert_eq!(l.version(), "LM-63-2002");
    assert_eq!(l.metadata().test_report, "T9");
    assert_eq!(l.metadata().manufacturer, "Big Company");
    let h = l.ies_header().unwrap();
    assert_eq!(h.keyword("_Electric Parameters").as_deref(), Some("230 V"));
    let text = ies::write(&l, IesWriteVersion::Lm63_2019);
    assert!(text.starts_with("IES:LM-63-2019\r\n"));
    assert!(
        text.contains("[MANUFAC] Big\r\n[MORE] Company\r\n[_Electric Parameters] 230 V\r\n"),
        "{text}"
    );
    for (line, v) in [
        ("IESNA:LM-63-2019", "LM-63-2019"),
        ("IES:LM-63-2019", "LM-63-2019"),
        ("IESNA91", "LM-63-1991"),
        ("IESNA94", "IESNA94"),
        ("IESNA:LM-63-1995", "LM-63-1995"),
    ] {
        let s2 = s.replacen("IESNA: LM-63-2002 ", line, 1);
        assert_eq!(read_str(&s2).unwrap().version(), v);
    }
    // A long value is split into [MORE] lines and read back whole.
    let mut l2 = l.clone();
    let long = "x".repeat(600);
    if let Some(photosolid::formats::ies::IesLabel::Keyword { value, .. }) = match &mut l2.header {
        photosolid::formats::Header::Ies(h) => h.labels.get_mut(1),
        _ => None,
    } {
        *value = long.clone();
    }
    let text = ies::write(&l2, IesWriteVersion::Lm63_2002);
    assert!(text.split("\r\n").all(|x| x.len() <= 254));
    let back = read_str(&text).unwrap();
    assert_eq!(
        back.ies_header().unwrap().keyword("MANUFAC").unwrap().replace(' ', ""),
        format!("{long}Company")
    );
}

#[test]
fn errors_name_line_column_expected_found() {
    let s = SIMPLE.replace("100 50 0", "100 abc 0");
    let e = read_str(&s).unwrap_err();
    assert_eq!((e.location.line, e.location.column), (9, Some(5)), "{e}");
    assert!(e.found.contains("abc") && e.expected.contains("candela"), "{e}");
    let e = read_str(&SIMPLE.replace("0 45 90", "0 90 45")).unwrap_err();
    assert_eq!(e.location.line, 7, "{e}");
    assert!(e.expected.contains("ascending"), "{e}");
    let e = read_str("IESNA:LM-63-2002\n[TEST] x\n").unwrap_err();
    assert!(e.expected.contains("TILT"), "{e}");
    let e = read_str("").unwrap_err();
    assert!(e.to_string().starts_with("mem.ies:1"), "{e}");
}

#[test]
fn warnings_extra_negative_pole_missing_ballast() {
    let s = "IESNA:LM-63-2002\nTILT=NONE\n1 -1 1 2 2 1 2 0 0 0\n1 1 0\n0 90\n0 180\n10 -1\n12 3\nEND\n";
    let l = read_str(s).unwrap();
    let codes: Vec<&str> = l.warnings().iter().map(|w| w.code.as_str()).collect();
    assert!(codes.contains(&"extra-values"), "{codes:?}");
    assert!(codes.contains(&"negative-intensity"), "{codes:?}");
    assert!(codes.contains(&"pole-mismatch"), "{codes:?}");
    assert_eq!(l.distribution().intensities_cd(), &[10.0, -1.0, 12.0, 3.0]);
    let s = "IESNA:LM-63-2002\nTILT=NONE\n1 -1 1 2 1 1 2 0 0 0\n0 90\n0\n10 5\n";
    let l = read_str(s).unwrap();
    assert!(l.warnings().iter().any(|w| w.code == "missing-ballast-line"));
    assert_eq!(l.distribution().intensities_cd(), &[10.0, 5.0]);
}

#[test]
fn symmetry_from_horizontal_angles() {
    let mk = |h: &str, n: usize| {
        let vals = vec!["1 2"; n].join("\n");
        format!("IESNA:LM-63-2002\nTILT=NONE\n1 -1 1 2 {n} 1 2 0 0 0\n1 1 0\n0 90\n{h}\n{vals}\n")
    };
    let sym = |h: &str, n| {
        read_str(&mk(h, n)).map(|l| (l.distribution().symmetry(), l.distribution().c_angles_deg().to_vec()))
    };
    assert_eq!(sym("0 45 90", 3).unwrap().0, Symmetry::Quadrant);
    assert_eq!(sym("0 90 180", 3).unwrap().0, Symmetry::C0C180);
    assert_eq!(sym("90 180 270", 3).unwrap().0, Symmetry::C90C270);
    assert_eq!(sym("0 180 360", 3).unwrap(), (Symmetry::None, vec![0.0, 180.0]));
    assert_eq!(sym("0 120 240 355", 4).unwrap().0, Symmetry::None);
    assert_eq!(sym("45", 1).unwrap(), (Symmetry::Rotational, vec![0.0]));
    assert!(sym("0 45", 2).is_err());
    assert!(sym("90 270", 2).is_err());
    // Repair of unsorted / duplicate planes.
    let opts = ReadOptions {
        repair: true,
        ..ReadOptions::default()
    };
    let s = "IESNA:LM-63-2002\nTILT=NONE\n1 -1 1 2 4 1 2 0 0 0\n1 1 0\n90 0\n180 0 90 90\n1 10\n3 30\n2 20\n9 9\n";
    assert!(read_str(s).is_err());
    let l = ies::read(s.as_bytes(), Path::new("r.ies"), &opts).unwrap();
    assert_eq!(l.distribution().c_angles_deg(), &[0.0, 90.0, 180.0]);
    assert_eq!(l.distribution().gamma_angles_deg(), &[0.0, 90.0]);
    assert_eq!(l.distribution().intensities_cd(), &[30.0, 3.0, 20.0, 2.0, 10.0, 1.0]);
    assert!(l.warnings().iter().any(|w| w.code == "angles-repaired"));
}

#[test]
fn synthetic_luminaire_writes_and_reads_back() {
    let d = Distribution::new(
        vec![30.0, 150.0, 270.0],
        vec![0.0, 60.0, 120.0],
        vec![5.0, 4.0, 1e-7, 6.0, 3.0, 0.0, 7.0, 2.0, 5e11],
        Symmetry::None,
    )
    .unwrap();
    let mut l = Luminaire::from_distribution(d);
    l.metadata_mut().manufacturer = "Synth".into();
    let text = ies::write(&l.clone().into(), IesWriteVersion::Lm63_2002);
    let back = read_str(&text).unwrap();
    assert_eq!(back.distribution().c_angles_deg(), &[0.0, 30.0, 150.0, 270.0]);
    assert_eq!(back.distribution().plane_cd(1), l.distribution().plane_cd(0));
    assert_eq!(back.distribution().plane_cd(3), l.distribution().plane_cd(2));
    assert_eq!(back.metadata().manufacturer, "Synth");
    assert!(back.declared().absolute);
}

/// Parse speed on a large synthetic file (run with `--ignored --nocapture`).
#[test]
#[ignore = "a timing run that checks nothing (benches/parse.rs measures parsing): run with --ignored --nocapture"]
fn parse_speed() {
    let nv = 721;
    let nh = 1441;
    let mut s = format!("IESNA:LM-63-2002\nTILT=NONE\n1 -1 1 {nv} {nh} 1 2 0 0 0\n1 1 0\n");
    for i in 0..nv {
        s += &format!("{} ", i as f64 * 0.25);
    }
    s += "\n";
    for i in 0..nh {
        s += &format!("{} ", i as f64 * 0.25);
    }
    s += "\n";
    for i in 0..nv * nh {
        s += &format!("{:.2} ", 1000.0 + (i % 997) as f64 * 1.37);
        if i % 10 == 9 {
            s += "\n";
        }
    }
    let t = Instant::now();
    let n = photosolid::formats::scan::Scanner::new(
        s.as_bytes(),
        0,
        1,
        photosolid::formats::scan::Separators::BlanksAndCommas,
    )
    .count_remaining();
    eprintln!("count_remaining: {n} tokens in {:.3} s", t.elapsed().as_secs_f64());
    let t = Instant::now();
    let l = read_str(&s).unwrap();
    let dt = t.elapsed().as_secs_f64();
    eprintln!(
        "{} MB in {dt:.3} s: {:.0} MB/s",
        s.len() / 1_000_000,
        s.len() as f64 / dt / 1e6
    );
    assert_eq!(l.distribution().n_c(), nh - 1);
}
