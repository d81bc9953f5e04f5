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
