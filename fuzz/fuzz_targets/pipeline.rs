#![no_main]
//! The pipeline on any file that loads (format sniffed from the content),
//! thinned to a small grid ([`small_grid`]): a texture at factor 2 with each
//! filter, the solid of each texture plus its sanity check, the fit of up to
//! two lights, and a compare of the file with itself (measured solid and
//! filters; the fit is checked once, above) at a coarse tolerance on a few
//! hundred directions. Errors are fine; panics, NaN or infinity in any result
//! are not.

use std::path::Path;

use libfuzzer_sys::fuzz_target;
use photosolid::compare::{compare, CompareOptions, Directions};
use photosolid::fit::{fit, FitOptions};
use photosolid::formats::roundtrip::non_finite_in_debug;
use photosolid::model::Distribution;
use photosolid::reconstruct::{render, Filter, LightTexture};
use photosolid::registry::Recon;
use photosolid::solid::{grid_solid, SolidGrid, Units};

fn finite(what: &str, debug: String) {
    let bad = non_finite_in_debug(&debug);
    assert!(bad.is_empty(), "{what}: non-finite numbers {bad:?}");
}

/// Axis length of the thinned grid at most: 12 x 12 values keep one
/// execution in milliseconds, where a 37 x 73 grid took seconds.
const MAX_AXIS: usize = 12;

/// `d` with every k-th plane and angle kept (both ends always), so that each
/// axis holds at most [`MAX_AXIS`] angles: a large seed still exercises the
/// pipeline on its own values instead of being turned away. `None` when the
/// thinned grid is refused (the model's own checks), which is fine.
fn small_grid(d: &Distribution) -> Option<Distribution> {
    if d.n_c() <= MAX_AXIS && d.n_gamma() <= MAX_AXIS {
        return Some(d.clone());
    }
    let keep = |n: usize| -> Vec<usize> {
        let k = n.div_ceil(MAX_AXIS - 1).max(1);
        (0..n).filter(|&i| i % k == 0 || i + 1 == n).collect()
    };
    let (cs, gs) = (keep(d.n_c()), keep(d.n_gamma()));
    let c = cs.iter().map(|&i| d.c_angles_deg()[i]).collect();
    let gamma = gs.iter().map(|&j| d.gamma_angles_deg()[j]).collect();
    let cd = cs
        .iter()
        .flat_map(|&i| gs.iter().map(move |&j| d.value_cd(i, j)))
        .collect();
    Distribution::new(c, gamma, cd, d.symmetry()).ok()
}

fuzz_target!(|data: &[u8]| {
    let format = photosolid::formats::sniff(data);
    let path = Path::new("/nonexistent-fuzz-dir/pipeline.ies");
    let Ok(lum) = photosolid::formats::parse(data, path, format, &Default::default()) else {
        return;
    };
    let Some(small) = small_grid(lum.distribution()) else {
        return;
    };
    let d = &small;
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
        parallel: false,
        ..FitOptions::default()
    };
    if let Ok(fitted) = fit(d, &opts) {
        let e = fitted.error();
        assert!(e.is_finite(), "fit error {e}");
    }
    let copts = CompareOptions {
        recons: CompareOptions::default()
            .recons
            .into_iter()
            .filter(|r| *r != Recon::FittedGl)
            .collect(),
        tolerance: 0.05,
        // A fixed, coarse grid keeps one execution short (adaptive solids at
        // the default tolerance can refine a tiny grid for seconds).
        factor: 1,
        solid_tolerance: None,
        directions: Directions::Dense(400),
        timing_samples: 16,
        timing_repeats: 1,
        ..CompareOptions::default()
    };
    if let Ok(c) = compare(d, Some(d), &copts) {
        finite("compare", format!("{:?}", c.results));
    }
});
