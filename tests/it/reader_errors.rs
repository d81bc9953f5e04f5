//! Every reader's error paths on files the tests build (tests/common/fixtures.rs),
//! so they run without ../shared/corpus: IES LM-63 of each edition with each
//! TILT form and photometric type, EULUMDAT of each symmetry with several
//! lamp sets, TM-33 and GLDF; then one damaged variant per error site of the
//! readers (truncation in each section, bad numbers, NaN, huge counts,
//! encodings, bad angles). Each refusal is checked for the file, the line and
//! the expected/found text.

use crate::common;

use std::path::{Path, PathBuf};

use common::fixtures::{
    distribution, first_lines, gldf_bytes, gldf_product, grid_values, lamp_set_count, read, replace_line,
    replace_token, tilt_table, tm33_points, tm33_text, IesFile, IesTilt, IesVersion, LampSet, LdtFile,
};
use photosolid::model::{Format, Symmetry};
use photosolid::ParseError;

/// Reading `bytes` as `format` (named `name`) fails at line `line` of that
/// file, the error's expected and found texts containing `expected` and
/// `found`; otherwise a description of what happened instead.
fn check_refused(
    format: Format,
    name: &str,
    bytes: &[u8],
    line: usize,
    expected: &str,
    found: &str,
) -> Result<ParseError, String> {
    let path = Path::new(name);
    let e = match read(format, path, bytes) {
        Ok(_) => return Err(format!("loads, but should fail at line {line} expecting {expected:?}")),
        Err(e) => e,
    };
    let ok = e.path == path && e.location.line == line && e.expected.contains(expected) && e.found.contains(found);
    if ok {
        Ok(e)
    } else {
        Err(format!(
            "want line {line}, expected ~ {expected:?}, found ~ {found:?}; got line {}: {e}",
            e.location.line
        ))
    }
}

#[track_caller]
fn refused(format: Format, name: &str, bytes: &[u8], line: usize, expected: &str, found: &str) -> ParseError {
    check_refused(format, name, bytes, line, expected, found).unwrap_or_else(|m| panic!("{name}: {m}"))
}

#[track_caller]
fn ies_refused(text: &str, line: usize, expected: &str, found: &str) -> ParseError {
    refused(Format::Ies, "fixture.ies", text.as_bytes(), line, expected, found)
}

#[track_caller]
fn ldt_refused(text: &str, line: usize, expected: &str, found: &str) -> ParseError {
    refused(Format::Ldt, "fixture.ldt", text.as_bytes(), line, expected, found)
}

#[test]
fn ies_every_edition_and_tilt_form_loads_type_c() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("lamp.tlt"), "1\n3\n0 45 90\n1 0.9 0.7\n").unwrap();
    for version in IesVersion::ALL {
        for tilt in [
            IesTilt::None,
            IesTilt::Include(1, vec![0.0, 45.0, 90.0], vec![1.0, 0.9, 0.7]),
            IesTilt::File("lamp.tlt".into()),
        ] {
            let mut f = IesFile::type_c(version);
            f.tilt = tilt.clone();
            f.multiplier = 2.0;
            // The ballast-lamp factor multiplies the values in 1986 and 1991 only.
            f.ballast[1] = 0.5;
            let what = format!("{version:?} {tilt:?}");
            let path = dir.path().join("lum.ies");
            let l = read(Format::Ies, &path, f.text().as_bytes()).unwrap_or_else(|e| panic!("{what}: {e}"));
            let d = distribution(&l);
            assert_eq!(d.symmetry(), Symmetry::Quadrant, "{what}");
            assert_eq!(d.c_angles_deg(), &f.horizontal[..], "{what}");
            assert_eq!(d.gamma_angles_deg(), &f.vertical[..], "{what}");
            let scale = if version.ballast_lamp_factor_applies() {
                1.0
            } else {
                2.0
            };
            for (ic, row) in f.cd.chunks(f.vertical.len()).enumerate() {
                for (ig, cd) in row.iter().enumerate() {
                    assert_close!(
                        d.value_cd(ic, ig),
                        cd * scale,
                        rel = 1e-12,
                        "{what}: C #{ic} gamma #{ig}"
                    );
                }
            }
            let table = tilt_table(&l);
            match tilt {
                IesTilt::None => assert!(table.is_none(), "{what}"),
                _ => {
                    let t = table.unwrap_or_else(|| panic!("{what}: tilt table"));
                    assert_eq!(t.angles, vec![0.0, 45.0, 90.0], "{what}");
                    assert_eq!(t.multipliers, vec![1.0, 0.9, 0.7], "{what}");
                }
            }
        }
    }
}

#[test]
fn ies_type_a_and_b_load_in_every_edition() {
    for version in IesVersion::ALL {
        for ptype in [2, 3] {
            let f = IesFile::type_ab(version, ptype);
            let what = format!("{version:?} type {ptype}");
            let l =
                read(Format::Ies, Path::new("ab.ies"), f.text().as_bytes()).unwrap_or_else(|e| panic!("{what}: {e}"));
            let d = distribution(&l);
            // H = 0, V = 0 and H = 45, V = 0 are unambiguous directions (Type B: nadir and
            // C90 gamma 45; Type A: C0 and C45 at gamma 90) on the converted grid's points.
            let at = |c: f64, g: f64| {
                let ig = d.gamma_angles_deg().iter().position(|&x| x == g).unwrap();
                d.value_at_plane_cd(c, ig)
                    .unwrap_or_else(|| panic!("{what}: no plane C {c}"))
            };
            let (first, second) = if ptype == 2 {
                ((0.0, 0.0), (90.0, 45.0))
            } else {
                ((0.0, 90.0), (45.0, 90.0))
            };
            assert_close!(at(first.0, first.1), 100.0, rel = 1e-12, "{what}: H 0 V 0");
            assert_close!(
                at(second.0, second.1),
                100.0 + 0.5 * 45.0,
                rel = 1e-12,
                "{what}: H 45 V 0"
            );
            // Interpolation never exceeds the source's peak.
            let peak = f.cd.iter().cloned().fold(0.0, f64::max);
            assert!(d.max_cd() <= peak, "{what}: {} > {peak}", d.max_cd());
            assert!(d.intensities_cd().iter().all(|v| v.is_finite() && *v >= 0.0), "{what}");
        }
    }
}

/// One damaged file: its text, the line the error must name, and texts the
/// error's expected and found parts must contain.
type Case = (String, usize, &'static str, &'static str);

/// Every case refused as it says; all mismatches are listed together.
#[track_caller]
fn all_refused(format: Format, name: &str, cases: &[Case]) {
    let wrong: Vec<String> = cases
        .iter()
        .enumerate()
        .filter_map(|(k, (text, line, expected, found))| {
            check_refused(format, name, text.as_bytes(), *line, expected, found)
                .err()
                .map(|m| format!("case #{k}: {m}"))
        })
        .collect();
    assert!(
        wrong.is_empty(),
        "{name}: {} of {} cases:\n{}",
        wrong.len(),
        cases.len(),
        wrong.join("\n")
    );
}

#[test]
fn ies_header_errors_name_the_line() {
    let f = IesFile::type_c(IesVersion::Lm2002);
    let (text, at) = (f.text(), f.lines());
    let counts = |k: usize, v: &str| replace_token(&text, at.counts, k, v);
    let mut cases: Vec<Case> = vec![
        // Truncated before the TILT line, after it, after the counts, inside the candela block.
        (
            first_lines(&text, 2),
            2,
            "a `TILT=` line",
            "end of file after 2 lines of text",
        ),
        // (The end of a file whose last line ends is the start of the next line.)
        (
            first_lines(&text, at.tilt),
            at.tilt + 1,
            "number of lamps",
            "end of file",
        ),
        // The counts are checked against the numbers there before any is read.
        (
            first_lines(&text, at.counts),
            at.counts,
            "angle counts that fit the data",
            "",
        ),
        (
            first_lines(&text, at.cd + 1),
            at.counts,
            "angle counts that fit the data: 7 vertical x 3 horizontal angles need 31 numbers",
            "only 27 numbers after the first header record",
        ),
        // Each field of the first record.
        (counts(2, "0"), at.counts, "candela multiplier (> 0)", "0"),
        (
            counts(3, "0"),
            at.counts,
            "number of vertical angles (integer 1..=",
            "0",
        ),
        (
            counts(4, "2.5"),
            at.counts,
            "number of horizontal angles (integer 1..=",
            "2.5",
        ),
        (
            counts(5, "4"),
            at.counts,
            "photometric type (1 = C, 2 = B, 3 = A) (integer 1..=3)",
            "4",
        ),
        (
            counts(6, "3"),
            at.counts,
            "units type (1 = feet, 2 = metres) (integer 1..=2)",
            "3",
        ),
        // The ballast record: a product that is no positive normal number.
        // (A ballast factor <= 0 is replaced by 1 with a warning; an underflowing product is refused.)
        (
            replace_token(&counts(2, "1e-200"), at.ballast, 0, "1e-200"),
            at.ballast,
            "candela multiplier x ballast factor x ballast-lamp factor a positive normal number",
            " x 1 = 0",
        ),
        // Candela values beyond the model's range once scaled.
        (
            replace_token(&counts(2, "1e300"), at.cd, 0, "1e300"),
            at.cd,
            "candela values in the model's range",
            "",
        ),
        // A value that is no number, NaN in the data.
        (replace_token(&text, at.cd, 3, "NaN"), at.cd, "candela", "NaN"),
        (
            replace_token(&text, at.vertical, 1, "3O"),
            at.vertical,
            "vertical angle",
            "3O",
        ),
    ];
    cases.push((
        counts(3, "99999999999"),
        at.counts,
        "angle counts that fit the data",
        "numbers after the first header record",
    ));
    cases.push((
        counts(3, "18446744073709551617"),
        at.counts,
        "number of vertical angles (integer 1..=9223372036854775807)",
        "`18446744073709551617`",
    ));
    for bad in ["NaN", "inf", "1e400", "x"] {
        cases.push((counts(2, bad), at.counts, "candela multiplier", bad));
    }
    all_refused(Format::Ies, "fixture.ies", &cases);
}

#[test]
fn ies_angle_errors_name_the_line() {
    let f = IesFile::type_c(IesVersion::Lm1995);
    let (text, at) = (f.text(), f.lines());
    let vertical = |k: usize, v: &str| replace_token(&text, at.vertical, k, v);
    let horizontal = |k: usize, v: &str| replace_token(&text, at.horizontal, k, v);
    // 90..270 with only those two planes.
    let mut two = IesFile::type_c(IesVersion::Lm2002);
    two.horizontal = vec![90.0, 270.0];
    two.cd = grid_values(&two.horizontal, &two.vertical);
    all_refused(
        Format::Ies,
        "fixture.ies",
        &[
            (
                vertical(2, "20"),
                at.vertical,
                "vertical angles in strictly ascending order",
                "",
            ),
            (
                horizontal(1, "0"),
                at.horizontal,
                "horizontal angles in strictly ascending order",
                "",
            ),
            (
                vertical(0, "-30"),
                at.vertical,
                "Type C vertical angles within 0..180 degrees",
                "-30",
            ),
            (
                horizontal(2, "400"),
                at.horizontal,
                "Type C horizontal angles within 0..360 degrees",
                "400",
            ),
            // A horizontal set that is none of LM-63's Type C layouts.
            (
                horizontal(2, "120"),
                at.horizontal,
                "a horizontal angle set of LM-63 Type C",
                "0..120",
            ),
            (
                two.text(),
                two.lines().horizontal,
                "a 90-270 horizontal angle set",
                "`270` only",
            ),
        ],
    );
    // Type B whose horizontal angles start above 0.
    let mut b = IesFile::type_ab(IesVersion::Lm2002, 2);
    b.horizontal = vec![10.0, 45.0, 90.0];
    b.cd = grid_values(&b.horizontal, &b.vertical);
    let e = ies_refused(
        &b.text(),
        b.lines().horizontal,
        "a Type B grid that converts to Type C",
        "start at 10",
    );
    assert_eq!(e.kind, photosolid::ErrorKind::Unsupported);
}

#[test]
fn ies_tilt_errors_name_the_line() {
    let mut f = IesFile::type_c(IesVersion::Lm2002);
    f.tilt = IesTilt::Include(1, vec![0.0, 45.0, 90.0], vec![1.0, 0.9, 0.7]);
    let (text, t) = (f.text(), f.lines().tilt);
    all_refused(
        Format::Ies,
        "fixture.ies",
        &[
            (
                replace_line(&text, t + 1, "4"),
                t + 1,
                "tilt lamp-to-luminaire geometry (1, 2 or 3)",
                "4",
            ),
            (
                replace_line(&text, t + 2, "0"),
                t + 2,
                "number of tilt angle / multiplier pairs",
                "0",
            ),
            (
                replace_line(&text, t + 2, "99999999"),
                t + 2,
                "a number of tilt pairs that fits the file",
                "99999999",
            ),
            (replace_token(&text, t + 3, 1, "x"), t + 3, "tilt angle #2 of 3", "x"),
            (
                replace_token(&text, t + 4, 2, "NaN"),
                t + 4,
                "tilt multiplier #3 of 3",
                "NaN",
            ),
            (
                replace_token(&text, t + 3, 1, "0"),
                t + 3,
                "tilt angles in strictly ascending order",
                "",
            ),
            // Truncated after the tilt angles: the pair count no longer fits.
            (
                first_lines(&text, t + 3),
                t + 2,
                "a number of tilt pairs that fits the file (at most 1)",
                "`3`",
            ),
        ],
    );
    // TILT=<file>: missing, or damaged inside (the error names the tilt file and its line).
    let dir = tempfile::tempdir().unwrap();
    let main = dir.path().join("lum.ies");
    let mut g = IesFile::type_c(IesVersion::Lm2002);
    g.tilt = IesTilt::File("gone.tlt".into());
    let gt = g.lines().tilt;
    let e = read(Format::Ies, &main, g.text().as_bytes()).unwrap_err();
    assert_eq!((e.path.as_path(), e.location.line), (main.as_path(), gt), "{e}");
    assert!(
        e.expected.contains("gone.tlt") && e.found.contains("cannot be read"),
        "{e}"
    );
    std::fs::write(dir.path().join("bad.tlt"), "1\n3\n0 45 x\n1 0.9 0.7\n").unwrap();
    g.tilt = IesTilt::File("bad.tlt".into());
    let e = read(Format::Ies, &main, g.text().as_bytes()).unwrap_err();
    assert_eq!(
        (e.path, e.location.line),
        (dir.path().join("bad.tlt"), 3),
        "tilt file line"
    );
    assert!(e.expected.contains("tilt angle #3 of 3") && e.found.contains('x'));
}

#[test]
fn ies_and_ldt_encoding_and_padding_errors() {
    let ies = IesFile::type_c(IesVersion::Lm2019).text();
    let ldt = LdtFile::isym(1).text();
    for (format, name, text) in [(Format::Ies, "e.ies", &ies), (Format::Ldt, "e.ldt", &ldt)] {
        let mut utf16 = vec![0xFF, 0xFE];
        utf16.extend(text.encode_utf16().flat_map(|u| u.to_le_bytes()));
        refused(format, name, &utf16, 1, "an 8-bit text file", "UTF-16 byte-order mark");
        refused(format, name, b"", 1, "a photometric file", "an empty file");
        refused(
            format,
            name,
            b"\x1a\0\0 \n",
            1,
            "a photometric file",
            "5 bytes of padding",
        );
        let mut nul = text.clone().into_bytes();
        let at = text.find('\n').unwrap() + 1;
        nul[at] = 0;
        refused(format, name, &nul, 2, "text", "a NUL byte");
    }
}

#[test]
fn ldt_every_symmetry_and_several_lamp_sets_load() {
    for isym in 0..=4u8 {
        for sets in [1usize, 2, 3] {
            let mut f = LdtFile::isym(isym);
            f.lamp_sets = (0..sets)
                .map(|k| LampSet::new(1 + k as i32, 1000.0 * (k + 1) as f64, 10.0))
                .collect();
            let what = format!("Isym {isym}, {sets} lamp sets");
            let l =
                read(Format::Ldt, Path::new("sym.ldt"), f.text().as_bytes()).unwrap_or_else(|e| panic!("{what}: {e}"));
            assert_eq!(lamp_set_count(&l), sets, "{what}");
            let d = distribution(&l);
            assert_eq!(d.gamma_angles_deg(), &f.gamma[..], "{what}");
            // Every stored value comes back (cd/klm x the first set's 1000 lm / 1000), at its plane.
            let stored: Vec<f64> = f.stored_planes().iter().map(|&i| f.c_angles[i]).collect();
            for (k, &c) in stored.iter().enumerate() {
                for (ig, &g) in f.gamma.iter().enumerate() {
                    let want = f.cd_per_klm[k * f.ng + ig];
                    let got = d
                        .value_at_plane_cd(c, ig)
                        .unwrap_or_else(|| panic!("{what}: no plane C {c}"));
                    assert_close!(got, want, rel = 1e-9, "{what}: C {c} gamma {g}");
                }
            }
        }
    }
}

#[test]
fn ldt_header_errors_name_the_line() {
    let f = LdtFile::isym(0);
    let (text, at) = (f.text(), f.lines());
    // Truncated in each section: header lines, lamp sets (the next line is missing).
    for cut in [1, 2, at.isym, at.mc, at.ng, 12, 20] {
        let e = ldt_refused(&first_lines(&text, cut), cut + 1, "", "end of file");
        assert!(!e.expected.is_empty(), "{e}");
    }
    let line = |l: usize, v: &str| replace_line(&text, l, v);
    all_refused(
        Format::Ldt,
        "fixture.ldt",
        &[
            // Truncated in the lamp sets, the direct ratios and the intensities.
            (
                first_lines(&text, at.n_sets),
                at.n_sets,
                "6 lamp-set lines (6 per set) after line 26",
                "1 sets but only 0 lines left",
            ),
            (
                first_lines(&text, at.sets + 3),
                at.n_sets,
                "6 lamp-set lines (6 per set) after line 26",
                "1 sets but only 4 lines left",
            ),
            (first_lines(&text, at.ratios + 4), at.ratios + 4, "at least", ""),
            (
                first_lines(&text, at.cd + 3),
                at.cd + 3,
                "intensities (8 C-planes × 7 gamma angles",
                "values before the end of the file",
            ),
            (
                line(at.isym, "5"),
                at.isym,
                "Isym (symmetry indicator) (integer 0..=4)",
                "`5`",
            ),
            (line(at.isym, "x"), at.isym, "Isym", "x"),
            (
                line(at.mc, "0"),
                at.mc,
                "Mc (number of C-planes) (integer 1..=3600)",
                "`0`",
            ),
            (
                line(at.mc, "99999999999"),
                at.mc,
                "Mc (number of C-planes) (integer 1..=3600)",
                "99999999999",
            ),
            (line(at.ng, "NaN"), at.ng, "Ng (number of gamma angles)", "NaN"),
            (
                line(at.ng, "1802"),
                at.ng,
                "Ng (number of gamma angles) (integer 1..=1801)",
                "`1802`",
            ),
            (
                line(at.n_sets, "10000"),
                at.n_sets,
                "lamp-set lines (6 per set)",
                "10000 sets but only",
            ),
            (line(at.n_sets, "-1"), at.n_sets, "lamp sets", "-1"),
        ],
    );
}

#[test]
fn ldt_angle_and_value_errors_name_the_line() {
    let f = LdtFile::isym(0);
    let (text, at) = (f.text(), f.lines());
    let line = |l: usize, v: &str| replace_line(&text, l, v);
    // Isym 4 stores C0..C90: planes all outside that quarter leave none to read.
    let q = LdtFile::isym(4);
    let qa = q.lines();
    let shifted = (0..q.mc).fold(q.text(), |t, k| {
        replace_line(&t, qa.c_angles + k, &(100 + 10 * k).to_string())
    });
    all_refused(
        Format::Ldt,
        "fixture.ldt",
        &[
            (
                line(at.c_angles + 2, "30"),
                at.c_angles + 2,
                "strictly ascending C angles",
                "C angle #3 = 30 after 45",
            ),
            (
                line(at.gamma + 1, "0"),
                at.gamma + 1,
                "strictly ascending gamma angles",
                "",
            ),
            (
                line(at.c_angles + 7, "400"),
                at.c_angles + 7,
                "C angles in [0, ",
                "C angle #8 = 400",
            ),
            (
                line(at.gamma + 6, "190"),
                at.gamma + 6,
                "gamma angles in [0, 180] degrees",
                "#7 = 190",
            ),
            (line(at.cd + 5, "abc"), at.cd + 5, "intensit", "abc"),
            (line(at.cd + 5, "1e400"), at.cd + 5, "intensit", "1e400"),
            // Values beyond the model's range once scaled by the flux.
            (
                replace_line(&line(at.sets + 2, "1e300"), at.cd, "1e300"),
                at.cd,
                "intensities whose candela values",
                "",
            ),
            (
                shifted,
                qa.c_angles,
                "C-angles in [0, 90] for Isym 4",
                "none in line 28",
            ),
        ],
    );
}

#[test]
fn tm33_and_gldf_fixtures_load_and_fail_clearly() {
    let good = tm33_text(&tm33_points());
    let l = read(Format::Tm33, Path::new("t.xml"), good.as_bytes()).unwrap();
    assert_eq!(distribution(&l).symmetry(), Symmetry::Quadrant);
    assert_close!(distribution(&l).max_cd(), 100.0 + 45.0 + 45.0, rel = 1e-12);
    // Damaged: truncated XML, a bad number, NaN, Latin-1 bytes in a UTF-8 document.
    let cut = first_lines(&good, 12);
    let e = read(Format::Tm33, Path::new("t.xml"), cut.as_bytes()).unwrap_err();
    assert_eq!(e.path, Path::new("t.xml"));
    assert!(e.location.line >= 1 && !e.expected.is_empty(), "{e}");
    for bad in ["x", "NaN", "1e400"] {
        let text = good.replacen(">100<", &format!(">{bad}<"), 1);
        assert_ne!(text, good);
        let e = read(Format::Tm33, Path::new("t.xml"), text.as_bytes()).unwrap_err();
        let line = text.lines().position(|l| l.contains(&format!(">{bad}<"))).unwrap() + 1;
        assert_eq!(e.location.line, line, "{bad}: {e}");
        assert!(e.found.contains(bad), "{bad}: {e}");
    }
    let latin1: Vec<u8> = good
        .replacen("photosolid", "photos\u{f6}lid", 1)
        .chars()
        .map(|c| c as u32 as u8)
        .collect();
    let e = read(Format::Tm33, Path::new("t.xml"), &latin1).unwrap_err();
    assert!(e.location.line >= 1 && e.to_string().contains("UTF-8"), "{e}");
    // GLDF: a container around a generated EULUMDAT file; then a damaged member, a missing one, not a zip.
    let dir = tempfile::tempdir().unwrap();
    let ldt = LdtFile::isym(2);
    let write = |name: &str, member: &[u8]| -> PathBuf {
        let p = dir.path().join(name);
        let zip = gldf_bytes(
            &gldf_product("p1", "lum.ldt", "ldc/eulumdat"),
            &[("ldc/lum.ldt", member.to_vec())],
        );
        std::fs::write(&p, zip).unwrap();
        p
    };
    let ok = write("ok.gldf", ldt.text().as_bytes());
    let l = photosolid::load(&ok).unwrap();
    assert_eq!(distribution(&l).symmetry(), Symmetry::C0C180);
    let at = ldt.lines();
    let broken = write("broken.gldf", replace_line(&ldt.text(), at.isym, "7").as_bytes());
    let e = photosolid::load(&broken).unwrap_err().to_string();
    assert!(
        e.contains("broken.gldf#p1") && e.contains(&format!(":{}", at.isym)) && e.contains("Isym"),
        "{e}"
    );
    let p = dir.path().join("missing.gldf");
    std::fs::write(&p, gldf_bytes(&gldf_product("p1", "gone.ldt", "ldc/eulumdat"), &[])).unwrap();
    let e = photosolid::load(&p).unwrap_err().to_string();
    assert!(e.contains("missing.gldf") && e.contains("gone.ldt"), "{e}");
    // An id the container does not hold, a file it only links to, no photometry at all.
    let e = photosolid::load(format!("{}#nope", ok.display()))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("ok.gldf") && e.contains("a photometry id of the container: p1") && e.contains("`nope`"),
        "{e}"
    );
    let p = dir.path().join("remote.gldf");
    let remote = gldf_product("p1", "https://example.invalid/lum.ldt", "ldc/eulumdat").replace("localFileName", "url");
    std::fs::write(&p, gldf_bytes(&remote, &[])).unwrap();
    let e = photosolid::load(&p).unwrap_err().to_string();
    assert!(e.contains("remote.gldf#p1") && e.contains("does not download"), "{e}");
    let p = dir.path().join("empty.gldf");
    let none = "<?xml version=\"1.0\"?>\n<Root><Header/><GeneralDefinitions/></Root>\n";
    std::fs::write(&p, gldf_bytes(none, &[])).unwrap();
    let e = photosolid::load(&p).unwrap_err().to_string();
    assert!(
        e.contains("empty.gldf") && e.contains("a GLDF container with a photometry"),
        "{e}"
    );
    let p = dir.path().join("notzip.gldf");
    std::fs::write(&p, b"PK\x03\x04 truncated").unwrap();
    let e = photosolid::load(&p).unwrap_err().to_string();
    assert!(e.contains("notzip.gldf") && e.contains("zip archive"), "{e}");
}

/// A negative intensity (-5) is kept as it is, with one `negative-intensity`
/// warning of one wording, in every reader: IES and EULUMDAT did so, and the
/// TM-33 reader accepted it silently.
#[test]
fn a_negative_intensity_is_kept_and_warned_alike_by_every_reader() {
    use photosolid::error::WarningCode;
    let mut ies = IesFile::type_c(IesVersion::Lm2002);
    ies.cd[1] = -5.0;
    let mut ldt = LdtFile::isym(4);
    ldt.cd_per_klm[1] = -5.0;
    let mut points = tm33_points();
    points[1].2 = -5.0;
    let tm33 = tm33_text(&points);
    let tm33_line = tm33.lines().position(|l| l.contains(">-5<")).unwrap() + 1;
    let cases = [
        (Format::Ies, ies.text(), "cd", None),
        (Format::Ldt, ldt.text(), "cd/klm", Some(ldt.lines().cd)),
        (Format::Tm33, tm33, "cd", Some(tm33_line)),
    ];
    for (format, text, unit, line) in cases {
        let what = format!("{format:?}");
        let doc = read(format, Path::new("neg"), text.as_bytes()).unwrap_or_else(|e| panic!("{what}: {e}"));
        // Plane C0, gamma 30: the value the file holds (x 1 multiplier, 1000 lm / 1000 for cd/klm).
        assert_eq!(distribution(&doc).value_cd(0, 1), -5.0, "{what}: kept as it is");
        let w: Vec<_> = doc
            .warnings()
            .iter()
            .filter(|w| w.code == WarningCode::NegativeIntensity)
            .collect();
        assert_eq!(w.len(), 1, "{what}: {:?}", doc.warnings());
        assert_eq!(
            w[0].message,
            format!("1 negative intensities kept as they are (lowest -5 {unit})"),
            "{what}"
        );
        assert_eq!(w[0].line, line, "{what}");
    }
}
