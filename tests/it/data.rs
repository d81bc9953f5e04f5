//! The project's own analytic files in data/ (written by scripts/make-data.sh):
//! both formats load, agree with each other, and integrate to their closed forms.

use std::f64::consts::PI;
use std::path::Path;

use photosolid::photometry::{beam_angles, flux};

/// (file stem, exact flux in lm, relative tolerance, why that tolerance).
/// The tolerance is the piecewise-linear interpolant's error on that grid:
/// O(h²) for smooth kinds, O(h) for the spot's cut-off jump (one ramp of one
/// step, 2π I(c) sin(c) h/2 relative to the flux).
fn cases() -> Vec<(&'static str, Option<f64>, f64)> {
    let spot = {
        let (p, c) = (8.0, 40f64.to_radians());
        2.0 * PI * 5000.0 * (1.0 - c.cos().powf(p + 1.0)) / (p + 1.0)
    };
    let spot_ramp =
        2.0 * PI * 5000.0 * 40f64.to_radians().cos().powi(8) * 40f64.to_radians().sin() * 0.5f64.to_radians();
    vec![
        // LDT keeps 8 significant digits: 1e-7 is the printed precision.
        ("isotropic", Some(4000.0 * PI), 1e-7),
        ("lambertian", Some(1000.0 * PI), 2e-4),
        ("cosine_p5", Some(2.0 * PI * 1000.0 / 6.0), 2e-4),
        ("spot_p8_c40", Some(spot), 1.1 * spot_ramp / spot),
        ("batwing", None, 0.0),
        ("roadway", None, 0.0),
        // Coarse non-uniform knots (up to 15°) on a narrow lobe: checked below
        // against an independent quadrature of the same interpolant instead.
        ("cosine_p20_nonuniform", None, 0.0),
    ]
}

/// The exact-integral rule on non-uniform knots equals a fine Simpson
/// quadrature of the same piecewise-linear interpolant (an independent path).
#[test]
fn nonuniform_knots_integrate_exactly() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("data");
    let lum = photosolid::load(dir.join("cosine_p20_nonuniform.ldt")).unwrap();
    let d = lum.distribution();
    let (g, v) = (d.gamma_angles_deg(), d.plane_cd(0));
    let interp = |x: f64| {
        let i = g.partition_point(|&k| k <= x).clamp(1, g.len() - 1) - 1;
        let t = ((x - g[i]) / (g[i + 1] - g[i])).clamp(0.0, 1.0);
        v[i] + t * (v[i + 1] - v[i])
    };
    let n = 200_000; // even
    let (a, b) = (0.0f64, 90.0f64);
    let h = (b - a) / n as f64;
    let f = |k: usize| {
        let x = a + k as f64 * h;
        interp(x) * x.to_radians().sin()
    };
    let mut s = f(0) + f(n);
    for k in 1..n {
        s += if k % 2 == 1 { 4.0 } else { 2.0 } * f(k);
    }
    let simpson = 2.0 * PI * s * h.to_radians() / 3.0;
    let ours = flux(d).total_lm;
    // Simpson on a kinked integrand converges as h² per kink: 1e-6 relative is ample.
    assert_close!(ours, simpson, rel = 1e-6, "{ours} vs {simpson}");
    // And the coarse grid really is coarse: several percent above the closed form.
    let exact = 2.0 * PI * 2000.0 / 21.0;
    assert!(ours > exact * 1.01);
}

#[test]
fn data_files_integrate_to_closed_forms_in_both_formats() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("data");
    for (stem, exact, tol) in cases() {
        let ldt = photosolid::load(dir.join(format!("{stem}.ldt"))).unwrap();
        let ies = photosolid::load(dir.join(format!("{stem}.ies"))).unwrap();
        let (fl, fi) = (flux(ldt.distribution()).total_lm, flux(ies.distribution()).total_lm);
        // The two formats hold the same numbers to their printed precision (8 significant digits in LDT).
        assert_close!(fi, fl, rel = 1e-7, "{stem}: ldt {fl} vs ies {fi}");
        assert_eq!(ldt.distribution().symmetry(), ies.distribution().symmetry(), "{stem}");
        if let Some(x) = exact {
            assert_close!(fl, x, abs = tol * x, "{stem}: {fl} vs exact {x} (tol {tol})");
        }
        assert!(
            ldt.warnings().is_empty() && ies.warnings().is_empty(),
            "{stem}: {:?} {:?}",
            ldt.warnings(),
            ies.warnings()
        );
    }
}

#[test]
fn data_beam_angles_match_closed_forms() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("data");
    let lam = photosolid::load(dir.join("lambertian.ldt")).unwrap();
    let b = beam_angles(lam.distribution());
    // 2.5° grid, linear crossing: cos is nearly linear over one step near 60°.
    assert_close!(b.ies_beam_deg[0].unwrap(), 120.0, abs = 0.05);
    let cos5 = photosolid::load(dir.join("cosine_p5.ies")).unwrap();
    let exact = 2.0 * 0.5f64.powf(1.0 / 5.0).acos().to_degrees();
    assert_close!(
        beam_angles(cos5.distribution()).ies_beam_deg[1].unwrap(),
        exact,
        abs = 0.05
    );
}
