#![no_main]
//! The pipeline on any file that loads (format sniffed from the content):
//! a texture at factor 2 with each filter, the solid of each texture plus its
//! sanity check, a one-light fit, and a compare of the file with itself at a
//! coarse tolerance. Errors are fine; panics, NaN or infinity in any result are not.

use std::path::Path;

use libfuzzer_sys::fuzz_target;
use photosolid::compare::{compare, CompareOptions};
use photosolid::fit::{fit, FitOptions};
use photosolid::formats::roundtrip::non_finite_in_debug;
use photosolid::reconstruct::{render, Filter, LightTexture};
use photosolid::solid::{grid_solid, SolidGrid, Units};

fn finite(what: &str, debug: String) {
    let bad = non_finite_in_debug(&debug);
    assert!(bad.is_empty(), "{what}: non-finite numbers {bad:?}");
}

fuzz_target!(|data: &[u8]| {
    let format = photosolid::formats::sniff(data);
    let path = Path::new("/nonexistent-fuzz-dir/pipeline.ies");
    let Ok(lum) = photosolid::formats::parse(data, path, format, &Default::default()) else {
        return;
    };
    let d = lum.distribution();
    // Keep one execution short: the grids fuzzing finds are small anyway.
    if d.n_c() * d.n_gamma() > 4096 {
        return;
    }
    if let Ok(tex) = LightTexture::new(d) {
        for f in Filter::ALL {
            let Ok(r) = render(&tex, f, 2) else { continue };
            assert!(r.data.iter().all(|v| v.is_finite()), "{f}: non-finite texel");
            if let Ok(grid) = SolidGrid::of_texture(&r) {
                if let Ok(mesh) = grid_solid(&r, &grid, Units::Peak) {
                    let report = mesh.sanity_check();
                    assert!(report.is_ok(), "{f}: solid fails its sanity check: {report:?}");
                }
            }
        }
    }
    let opts = FitOptions {
        max_lights: 1,
        parallel: false,
        ..FitOptions::default()
    };
    if let Ok(fitted) = fit(d, &opts) {
        let e = fitted.error();
        assert!(e.is_finite(), "fit error {e}");
    }
    let copts = CompareOptions {
        tolerance: 0.05,
        // A fixed, coarse grid keeps one execution short (adaptive solids at
        // the default tolerance can refine a tiny grid for seconds).
        factor: 1,
        solid_tolerance: None,
        timing_samples: 16,
        timing_repeats: 1,
        ..CompareOptions::default()
    };
    if let Ok(c) = compare(d, Some(d), &copts) {
        finite("compare", format!("{:?}", c.results));
    }
});
