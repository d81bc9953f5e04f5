//! What every reader target checks on one input (shared by the targets).
// Each target includes this module and calls one of its checks.
#![allow(dead_code)]

use std::path::Path;

use photosolid::formats::roundtrip::{check, non_finite_in_debug};
use photosolid::model::distribution::MAX_CD;
use photosolid::model::Format;
use photosolid::ReadOptions;

/// The path every target reads its input as: a directory that does not
/// exist, so `TILT=<file>` cannot reach real files.
fn fuzz_path(format: Format) -> std::path::PathBuf {
    let name = match format {
        Format::Ies => "fuzz.ies",
        Format::Ldt => "fuzz.ldt",
        Format::Tm33 => "fuzz.xml",
    };
    Path::new("/nonexistent-fuzz-dir").join(name)
}

/// Parse `data` as `format`, both leniently and with the repair option. On
/// success: the photometric summary holds only finite numbers, and writing
/// both formats and reading them back gives the same distribution
/// ([`photosolid::formats::roundtrip::check`]). Any failure panics, which
/// libFuzzer records as a crash with the input.
pub fn reader(data: &[u8], format: Format) {
    let path = fuzz_path(format);
    for repair in [false, true] {
        let opts = ReadOptions {
            repair,
            ..ReadOptions::default()
        };
        let Ok(lum) = photosolid::formats::parse(data, &path, format, &opts) else {
            continue;
        };
        let summary = photosolid::photometry::summary(&lum);
        let bad = non_finite_in_debug(&format!("{summary:?}"));
        assert!(bad.is_empty(), "non-finite numbers in the summary: {bad:?}");
        let bad = non_finite_in_debug(&format!("{:?}", lum.distribution()));
        assert!(bad.is_empty(), "non-finite numbers in the distribution: {bad:?}");
        if let Err(e) = check(&lum) {
            panic!("round trip failed: {e}");
        }
    }
}

/// Parse `data` as `format`, leniently and with the repair option, and
/// nothing else: the fast target per format (issue 26: the round trip runs
/// at tens to thousands of executions a second, the parse alone at thousands).
/// On success the model's invariant holds: every stored angle is finite and
/// every intensity finite within [`photosolid::model::distribution::MAX_CD`];
/// a reader failing must be an `Err`, never a panic.
pub fn parse_only(data: &[u8], format: Format) {
    let path = fuzz_path(format);
    for repair in [false, true] {
        let opts = ReadOptions {
            repair,
            ..ReadOptions::default()
        };
        let Ok(lum) = photosolid::formats::parse(data, &path, format, &opts) else {
            continue;
        };
        let d = lum.distribution();
        assert!(d.c_angles_deg().iter().all(|v| v.is_finite()), "non-finite C angle");
        assert!(
            d.gamma_angles_deg().iter().all(|v| v.is_finite()),
            "non-finite gamma angle"
        );
        assert!(
            d.intensities_cd().iter().all(|v| v.is_finite() && v.abs() <= MAX_CD),
            "intensity outside the model's range"
        );
        assert!(d.max_cd().is_finite(), "non-finite peak");
    }
}
