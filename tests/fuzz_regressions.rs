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
