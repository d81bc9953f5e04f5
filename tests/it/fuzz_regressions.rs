//! Regression tests: every input the fuzz targets (fuzz/) found, minimised,
//! as bytes. Each is checked the way the fuzz target checks it (see
//! `fuzz/fuzz_targets/common.rs`): parse plainly and with the repair option;
//! whatever loads must have a finite summary and round-trip through both
//! writers. RELIABILITY.md lists the findings.

use std::path::Path;

use photosolid::formats::roundtrip::{check, non_finite_in_debug};
use photosolid::model::Format;
use photosolid::ReadOptions;

/// The fuzz targets' check of one input; returns how many of the two parses loaded.
fn reader_check(data: &[u8], format: Format) -> usize {
    let mut loaded = 0;
    for repair in [false, true] {
        let opts = ReadOptions {
            repair,
            ..ReadOptions::default()
        };
        let path = Path::new("/nonexistent-fuzz-dir/regression").with_extension(match format {
            Format::Ies => "ies",
            Format::Ldt => "ldt",
            Format::Tm33 => "xml",
        });
        let Ok(lum) = photosolid::formats::parse(data, &path, format, &opts) else {
            continue;
        };
        loaded += 1;
        let s = format!("{:?}", photosolid::photometry::summary(&lum));
        assert!(non_finite_in_debug(&s).is_empty(), "{s}");
        check(&lum).unwrap_or_else(|e| panic!("repair = {repair}: {e}"));
    }
    loaded
}

/// ldt_reader, run 1: an Isym 1 file whose line-28 C-angles repeat (0, 0, 0,
/// 15) loads with the repair option; the writer reused the header's angle
/// list and wrote the duplicates back, which the reader then refused.
/// Fixed: the writer derives the grid when the header's lists are not in order.
const LDT_REPAIRED_C_ANGLES: &[u8] = b"\n\n1\n4\n90\n5\n\n n\n\n\n\n\n50\n\n\n4\n\n\n\n\n0\n0\n\n\n0\n1\n0\n\n1\nD\n3\n\n0\n1\n0\n0\n0\n0\n0\n0\n0\n0\n0\n0\n0\n15\n0\n4\n6\n7\n90\n5\n12\n30\n5\n29";

#[test]
fn ldt_repaired_angle_list_is_not_written_back() {
    assert_eq!(reader_check(LDT_REPAIRED_C_ANGLES, Format::Ldt), 1);
}

/// ldt_reader, run 2 (found after 298,634 executions; the 8 kB crash input
/// minimised by hand to the same defect): a first C-plane at 2.8e-8 degrees,
/// within the 1e-6 duplicate tolerance of 0. The IES writer inserted an
/// interpolated C0 plane in front of it, a duplicate the IES reader refused.
/// Fixed: the writer treats a first plane within `ANGLE_EPS` of 0 as C0.
const LDT_FIRST_PLANE_NEAR_ZERO: &[u8] = b"m\n1\n0\n2\n0\n2\n0\n\n\n\n\n\n0\n0\n0\n0\n0\n0\n0\n0\n0\n100\n100\n1\n0\n1\n-1\nL\n1000\n\n\n0\n0\n0\n0\n0\n0\n0\n0\n0\n0\n0\n0.000000028\n180\n0\n90\n100\n10\n50\n5\n";

#[test]
fn ies_writer_does_not_duplicate_a_near_zero_first_plane() {
    assert_eq!(reader_check(LDT_FIRST_PLANE_NEAR_ZERO, Format::Ldt), 2);
}

/// pipeline (and `photosolid compare FILE` with its defaults): a 2 x 5 Type B
/// file took over 20 s. Its reconstructions jump (the fit's spot cone, the
/// converted grid at γ = 90°), and the adaptive solids refined whole rows and
/// columns down to the 0.05° minimum step: the fitted-gl solid alone had
/// 1,274,976 triangles. Fixed: a halving that leaves an interval's deviation
/// where it was stops (twice in a row), every solid has a point budget, and each
/// row says whether its tolerance was reached.
const IES_TYPE_B_2X5: &[u8] = b"IESNA91\r\nTILT=NONE\r\n1 0 1 2 5 2 1 0 0 0\r\n1 1 0\r\n-90 90\r\n-90 -45 0 45 90\r\n0.1 0.2\r\n0.3 0.4\r\n0.5 0.6\r\n0.7 0.8\r\n0.9 1.0\r\n";

#[test]
fn compare_with_defaults_does_bounded_work_and_says_what_it_reached() {
    use photosolid::compare::{compare, CompareOptions, SOLID_MAX_POINTS};
    assert_eq!(reader_check(IES_TYPE_B_2X5, Format::Ies), 2);
    let lum = photosolid::formats::parse(
        IES_TYPE_B_2X5,
        Path::new("/nonexistent-fuzz-dir/regression.ies"),
        Format::Ies,
        &ReadOptions::default(),
    )
    .unwrap();
    let opts = CompareOptions {
        timing_samples: 100,
        timing_repeats: 1,
        ..CompareOptions::default()
    };
    let c = compare(lum.distribution(), None, &opts).unwrap();
    assert_eq!(c.reference_kind, "withheld");
    let tol = c.solid_tolerance_cd.expect("adaptive solids by default");
    let json = serde_json::to_value(&c).unwrap();
    for (row, value) in c.results.iter().zip(json["results"].as_array().unwrap()) {
        assert!(non_finite_in_debug(&format!("{row:?}")).is_empty(), "{row:?}");
        assert!(
            row.triangles <= 2 * SOLID_MAX_POINTS + 2,
            "{}: {}",
            row.name,
            row.triangles
        );
        // Continuous fields are measured on their surface: no solid, no deviation.
        let method = row.withheld_distance.as_deref();
        assert_eq!(
            method == Some("surface"),
            !["measured", "nearest", "fitted-gl"].contains(&row.name.as_str()),
            "{}: {method:?}",
            row.name
        );
        match row.solid_deviation_cd {
            None => assert!(row.name == "measured" || method == Some("surface"), "{}", row.name),
            // Honest: reached exactly when the deviation reached is within the tolerance.
            Some(dev) => {
                assert_eq!(row.solid_tolerance_reached, Some(dev <= tol), "{}", row.name);
                assert_eq!(value["solid_tolerance_reached"], dev <= tol, "{}", row.name);
                assert_eq!(value["solid_deviation_cd"], dev, "{}", row.name);
            }
        }
    }
    // The fit's cone is a jump: not reached, said so, and refined only a little.
    let fit = c.results.iter().find(|r| r.name == "fitted-gl").unwrap();
    assert_eq!(fit.solid_tolerance_reached, Some(false), "{fit:?}");
    assert!(fit.solid_deviation_cd.unwrap() > 10.0 * tol, "{fit:?}");
    assert!(
        fit.triangles < 100_000,
        "{} triangles (1,274,976 before the fix)",
        fit.triangles
    );
}

/// ldt_reader, run of 2026-12-01: text fields whose bytes decode to the
/// noncharacter U+FFFF; the TM-33 writer put it into the XML, which no XML
/// 1.0 parser (ours included) reads back. Fixed: the XML escaper drops the
/// characters XML 1.0 cannot hold (U+FFFE, U+FFFF, C0 controls).
#[test]
fn tm33_writer_drops_characters_xml_cannot_hold() {
    let input = b"ACME Lighting\n\
      1\n\
      0\n\
      2\n\
      180\n\
      3\n\
      45\n\
      \xfe\xff\xff\xff-001\n\
      Synthetic LDT\n\
      LDT-001\n\
      synthetic_b\x9f\x8c\x96\x9c\xd1\x93\x9b\x93\n\
      2026-02-10 test\n\
      100\n\
      100\n\
      50\n\
      60\n\
      90\n\
      0\n\
      0\n\
      0\n\
      0\n\
      100\n\
      100\n\
      1.0\n\
      0\n\
      1\n\
      1\n\
      L\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff5.00001\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xffED\n\
      2000\n\
      4000K\n\
      80\n\
      20\n\
      0\n\
      0\n\
      0\n\
      0\n\
      0\n\
      0\n\
      0\n\
      0\n\
      0\n\
      0\n\
      0\n\
      180\n\
      0\n\
      45\n\
      90\n\
      1000 800 100\n\
      1000 700 50\n\
      ";
    assert!(
        reader_check(input, Format::Ldt) > 0,
        "the input must load to check its round trip"
    );
}

/// ldt_reader, run of 2026-12-01: a lamp count of 1.7976931348623157e308
/// (f64::MAX) written to IES as its 15-digit rounding, which reads back as
/// infinity ("expected number of lamps, found `inf`"). Fixed: a rounding that
/// overflows keeps the exact value.
#[test]
fn ies_writer_keeps_a_lamp_count_near_f64_max() {
    let lum = photosolid::synth::Synth::Lambertian
        .build(&photosolid::synth::GridSpec::uniform(15.0, 5.0).unwrap(), 1000.0)
        .unwrap();
    let text = photosolid::formats::ldt::write(&lum.into());
    let mut lines: Vec<&str> = text.split("\r\n").collect();
    // Line 27: the first lamp set's number of lamps.
    lines[26] = "1.7976931348623157e308";
    let input = lines.join("\r\n");
    assert_eq!(reader_check(input.as_bytes(), Format::Ldt), 2);
}

/// ldt_reader run 5 (finding 9): a declared flux so small that the flux ratio,
/// finite, overflows as a percentage; the warning printed "inf %". Fixed: the
/// warning gives the ratio as "N times" then.
#[test]
fn flux_mismatch_warning_never_prints_inf() {
    let mut lum = photosolid::synth::Synth::Lambertian
        .build(&photosolid::synth::GridSpec::uniform(15.0, 5.0).unwrap(), 1000.0)
        .unwrap();
    lum.declared_mut().luminaire_flux_lm = Some(1e-303);
    let s = photosolid::photometry::summary(&lum);
    let text = format!("{s:?}");
    assert!(non_finite_in_debug(&text).is_empty(), "{text}");
    assert!(text.contains("times of the declared"), "{text}");
}
