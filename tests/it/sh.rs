//! Compact representations (issue 30): spherical harmonics `sh:L` and lobe
//! mixtures `lobes:K` against closed forms, synthetic truths, the corpus and
//! numerical extremes; the trade table's bytes front.

use std::f64::consts::PI;

use photosolid::fit::lobes::{fit_lobes, Lobe, Lobes};
use photosolid::metrics::{radial_errors, DirectionSet};
use photosolid::model::frame::{cos_deg, direction};
use photosolid::model::{Distribution, IntensityField, Symmetry};
use photosolid::reconstruct::sh::{gauss_legendre, project, sh_index};
use photosolid::reconstruct::{
    eval_all, Filter, LightTexture, Precision, ShField, ShWindow, MAX_SH_DEGREE, MAX_ZONAL_SH_DEGREE,
};
use photosolid::registry::{Recon, Reconstructions};
use photosolid::synth::{GridSpec, Synth, Truth};

use crate::common;

/// The rule of n points integrates z^k exactly for k ≤ 2n − 1.
#[test]
fn gauss_legendre_is_exact_to_degree_2n_minus_1() {
    for n in [1, 2, 5, 17, 90] {
        let rule = gauss_legendre(n);
        for k in 0..2 * n {
            let q: f64 = rule.iter().map(|&(x, w)| w * x.powi(k as i32)).sum();
            let exact = if k % 2 == 1 { 0.0 } else { 2.0 / (k + 1) as f64 };
            assert!((q - exact).abs() < 1e-13, "n {n} k {k}: {q} vs {exact}");
        }
    }
}

/// Projecting a basis function returns its unit coefficient and nothing
/// else: the basis is orthonormal and the evaluation is the projection's.
#[test]
fn basis_is_orthonormal() {
    let degree = 6;
    for l in 0..=degree {
        for m in -(l as isize)..=l as isize {
            let mut c = vec![0.0; (degree + 1) * (degree + 1)];
            c[sh_index(l, m)] = 1.0;
            // Relative to 1/√(4π) the stored coefficient is exactly 1 (no f32 rounding).
            let y = ShField::from_coefficients(&c, 1.0 / (4.0 * PI).sqrt(), degree, ShWindow::None, Precision::F32);
            let f = |cd: f64, g: f64| y.unclamped_cd(direction(cd, g));
            let (back, _) = project(&f, degree).unwrap();
            for (i, b) in back.iter().enumerate() {
                let want = if i == sh_index(l, m) { 1.0 } else { 0.0 };
                assert!((b - want).abs() < 1e-12, "Y({l},{m}) coefficient {i}: {b}");
            }
        }
    }
}

/// An isotropic source is exact at any degree, in f32 and f16, and through
/// the registry from an isotropic file (Catmull-Rom of constant data).
#[test]
fn isotropic_is_exact_at_any_degree() {
    let f = |_c: f64, _g: f64| 1234.5;
    for degree in [0, 1, 2, 4, 8, 16, MAX_SH_DEGREE] {
        for precision in [Precision::F32, Precision::F16] {
            let s = ShField::new(&f, degree, ShWindow::Lanczos, precision).unwrap();
            for (c, g) in [(0.0, 0.0), (17.0, 33.0), (200.0, 90.0), (359.0, 180.0), (45.0, 123.4)] {
                let v = s.intensity_cd(c, g);
                assert!((v - 1234.5).abs() <= 1e-10 * 1234.5, "L {degree} {precision:?}: {v}");
            }
        }
    }
    let lum = photosolid::load(concat!(env!("CARGO_MANIFEST_DIR"), "/data/isotropic.ldt")).unwrap();
    let d = lum.distribution();
    let set = DirectionSet::fibonacci(2000);
    for degree in [2, 16] {
        let r = Recon::Sh {
            degree,
            f16: false,
            gpu: false,
        };
        let recs = Reconstructions::new(d.clone(), &[r]).unwrap();
        let v = eval_all(&*recs.field(r).unwrap(), &set.directions);
        let truth = vec![d.max_cd(); v.len()];
        let e = radial_errors(&set, &truth, &v, d.max_cd(), 0.02);
        assert!(e.rms_cd <= 1e-9 * d.max_cd(), "sh:{degree}: rms {} cd", e.rms_cd);
    }
}

/// Zonal closed forms: `c_00 = 2π/(p+1)/√(4π)` (the flux) and
/// `c_10 = √(3π)/(p+2)` for `max(0, cos γ)^p`; the clamped cosine's
/// `c_20 = √(5π)/8` and its odd bands above 1 vanish (Ramamoorthi and Hanrahan 2001).
#[test]
fn cosine_lobes_match_closed_forms() {
    for p in [0.0, 1.0, 2.0, 5.0, 20.0] {
        let f = move |_c: f64, g: f64| if cos_deg(g) > 0.0 { cos_deg(g).powf(p) } else { 0.0 };
        let (c, scale) = project(&f, 8).unwrap();
        assert!(scale > 0.99 && scale <= 1.0, "{scale}");
        let c00 = 2.0 * PI / (p + 1.0) / (4.0 * PI).sqrt();
        let c10 = (3.0 * PI).sqrt() / (p + 2.0);
        assert!((c[0] - c00).abs() < 1e-12, "p {p}: c00 {} vs {c00}", c[0]);
        assert!((c[sh_index(1, 0)] - c10).abs() < 1e-12, "p {p}: c10");
        for (i, x) in c.iter().enumerate() {
            let zonal = (0..=8).any(|l| i == sh_index(l, 0));
            assert!(zonal || x.abs() < 1e-13, "p {p}: non-zonal {i} = {x}");
        }
        if p == 1.0 {
            assert!((c[sh_index(2, 0)] - (5.0 * PI).sqrt() / 8.0).abs() < 1e-12);
            for l in [3, 5, 7] {
                assert!(c[sh_index(l, 0)].abs() < 1e-12, "l {l}");
            }
        }
    }
}

/// Against analytic truths (`synth`): the error falls with L, the series of
/// the Catmull-Rom field is near the series of the truth, f16 costs at most
/// its rounding bound.
#[test]
fn sh_against_synthetic_truths() {
    for kind in [
        Synth::Lambertian,
        Synth::CosinePower { p: 5.0 },
        Synth::Batwing,
        Synth::Roadway,
    ] {
        let lum = kind.build(&GridSpec::uniform(5.0, 2.5).unwrap(), 1000.0).unwrap();
        let truth = Truth::of_luminaire(&lum).unwrap();
        let tex = LightTexture::new(lum.distribution()).unwrap();
        let cr = tex.sampler(Filter::CatmullRom);
        let set = DirectionSet::fibonacci(4000);
        let t = eval_all(&truth, &set.directions);
        let i_max = lum.distribution().max_cd();
        let mut last = f64::INFINITY;
        for degree in [2, 4, 8, 16] {
            let s = ShField::new(&cr, degree, ShWindow::Lanczos, Precision::F32).unwrap();
            let e = radial_errors(&set, &t, &eval_all(&s, &set.directions), i_max, 0.02);
            eprintln!("{kind:?} sh:{degree}: rms {:.4} % max {:.4} %", e.rms_pct, e.max_pct);
            assert!(e.rms_pct.is_finite() && e.max_pct.is_finite());
            assert!(
                e.rms_pct <= last * 1.0001 + 1e-9,
                "{kind:?} sh:{degree}: {} after {last}",
                e.rms_pct
            );
            last = e.rms_pct;
            let h = ShField::new(&cr, degree, ShWindow::Lanczos, Precision::F16).unwrap();
            // |Δf| ≤ ‖Δc‖ · ‖Y‖ with ‖Y‖² = (L+1)²/(4π) (the addition theorem) and each
            // stored coefficient off by ≤ 2^-11 of itself, or 2^-25 of √(4π)·scale when subnormal.
            let c = s.coefficients_cd();
            let sub = (4.0 * PI).sqrt() * s.scale_cd() / 33_554_432.0;
            let dc: f64 = c.iter().map(|x| (x.abs() / 2040.0 + sub).powi(2)).sum::<f64>().sqrt();
            let bound = dc * ((degree + 1) as f64) / (4.0 * PI).sqrt();
            let worst = set
                .directions
                .iter()
                .map(|&(c, g)| (h.intensity_cd(c, g) - s.intensity_cd(c, g)).abs())
                .fold(0.0, f64::max);
            assert!(worst <= bound, "{kind:?} sh:{degree}+f16: {worst} > {bound}");
            assert_eq!(2 * h.bytes(), s.bytes());
            // A rotationally symmetric truth stores only its L + 1 zonal coefficients.
            let rotational = lum.distribution().symmetry() == Symmetry::Rotational;
            assert_eq!(s.is_zonal(), rotational, "{kind:?} sh:{degree}");
            let n = if rotational {
                degree + 1
            } else {
                (degree + 1) * (degree + 1)
            };
            assert_eq!(s.bytes(), n * 4, "{kind:?} sh:{degree}");
        }
    }
}

/// Zonal series reach L = 128 (`MAX_ZONAL_SH_DEGREE`): on a narrow spot
/// (cos^128, half width about 6°) the radial max error falls from L = 32 to
/// L = 128, to under a tenth of L = 32's (29.1, 8.8, 2.3 %), and
/// every value is finite and >= 0; an isotropic source is exact; 129
/// coefficients are stored. A field that depends on C is refused above
/// L = 32 with a reason, and the recon name parses to L = 128, not beyond.
#[test]
fn zonal_series_reach_degree_128() {
    assert_eq!(MAX_ZONAL_SH_DEGREE, 128);
    let spot = |_c: f64, g: f64| 1000.0 * cos_deg(g).max(0.0).powf(128.0);
    let set = DirectionSet::fibonacci(20_000);
    let truth = eval_all(&spot, &set.directions);
    let mut errors = Vec::new();
    for degree in [32, 64, 128] {
        let s = ShField::new(&spot, degree, ShWindow::Lanczos, Precision::F32).unwrap();
        assert!(s.is_zonal() && s.degree() == degree, "sh:{degree}");
        assert_eq!(s.bytes(), (degree + 1) * 4);
        let v = eval_all(&s, &set.directions);
        assert!(v.iter().all(|x| x.is_finite() && *x >= 0.0), "sh:{degree}");
        let e = radial_errors(&set, &truth, &v, 1000.0, 0.02);
        eprintln!("cos^128 sh:{degree}: rms {:.4} % max {:.4} %", e.rms_pct, e.max_pct);
        errors.push(e.max_pct);
    }
    assert!(errors[2] < errors[1] && errors[1] < errors[0], "{errors:?}");
    assert!(errors[2] < 0.1 * errors[0], "{errors:?}");
    let flat = |_c: f64, _g: f64| 250.0;
    let iso = ShField::new(&flat, 128, ShWindow::Lanczos, Precision::F32).unwrap();
    for &(c, g) in set.directions.iter().step_by(97) {
        assert!((iso.intensity_cd(c, g) - 250.0).abs() < 1e-9, "({c}, {g})");
    }
    let lum = Synth::Roadway
        .build(&GridSpec::uniform(15.0, 5.0).unwrap(), 1000.0)
        .unwrap();
    let tex = LightTexture::new(lum.distribution()).unwrap();
    let err = ShField::new(&tex.sampler(Filter::CatmullRom), 64, ShWindow::Lanczos, Precision::F32)
        .unwrap_err()
        .to_string();
    assert!(err.contains("rotationally symmetric"), "{err}");
    assert_eq!(
        "sh:128".parse::<Recon>().unwrap(),
        Recon::Sh {
            degree: 128,
            f16: false,
            gpu: false
        }
    );
    assert!("sh:129".parse::<Recon>().is_err());
}

/// Zonal storage loses nothing: the batwing's series (rotational, stored
/// zonal) evaluates as the full series of the same coefficients with one
/// non-zonal coefficient raised by δ = 1e-9 of the scale (stored full) to
/// within δ·max|Y_11| ≤ 0.5 δ; the perturbed series is no longer zonal.
#[test]
fn zonal_storage_is_exact() {
    let lum = Synth::Batwing
        .build(&GridSpec::uniform(5.0, 2.5).unwrap(), 1000.0)
        .unwrap();
    let tex = LightTexture::new(lum.distribution()).unwrap();
    let (c, scale) = project(&tex.sampler(Filter::CatmullRom), 16).unwrap();
    let zonal = ShField::from_coefficients(&c, scale, 16, ShWindow::None, Precision::F32);
    let mut bumped = c.clone();
    let delta = 1e-9 * scale;
    bumped[sh_index(1, 1)] += delta;
    let full = ShField::from_coefficients(&bumped, scale, 16, ShWindow::None, Precision::F32);
    assert!(zonal.is_zonal() && !full.is_zonal());
    assert_eq!((zonal.bytes(), full.bytes()), (17 * 4, 289 * 4));
    for &(cc, g) in &DirectionSet::fibonacci(3000).directions {
        let u = direction(cc, g);
        let d = (zonal.unclamped_cd(u) - full.unclamped_cd(u)).abs();
        assert!(d <= 0.5 * delta + 1e-12 * scale, "({cc}, {g}): {d}");
    }
}

/// Numerical extremes: a delta-like spot (p = 128) rings below zero before
/// clamping and every value is finite and ≥ 0; all-zero data is an honest
/// typed error from the file and a zero series from a zero field.
#[test]
fn sh_extremes() {
    let f = |_c: f64, g: f64| cos_deg(g).max(0.0).powf(128.0);
    for window in [ShWindow::None, ShWindow::Lanczos] {
        let s = ShField::new(&f, 4, window, Precision::F32).unwrap();
        let mut negative = 0;
        for k in 0..=1800 {
            let g = k as f64 / 10.0;
            let v = s.intensity_cd(30.0, g);
            assert!(v >= 0.0 && v.is_finite(), "{window:?} {g}: {v}");
            negative += usize::from(s.unclamped_cd(direction(30.0, g)) < 0.0);
        }
        if window == ShWindow::None {
            assert!(negative > 0, "cos^128 at L = 4 rings below zero before clamping");
        }
    }
    let lum = Synth::CosinePower { p: 128.0 }
        .build(&GridSpec::uniform(15.0, 1.0).unwrap(), 1000.0)
        .unwrap();
    for degree in [2, 16, MAX_SH_DEGREE] {
        let r = Recon::Sh {
            degree,
            f16: true,
            gpu: false,
        };
        let recs = Reconstructions::new(lum.distribution().clone(), &[r]).unwrap();
        let v = eval_all(&*recs.field(r).unwrap(), &DirectionSet::fibonacci(3000).directions);
        assert!(v.iter().all(|x| x.is_finite() && *x >= 0.0), "sh:{degree}+f16");
    }
    let zero = ShField::new(&|_c: f64, _g: f64| 0.0, 8, ShWindow::Lanczos, Precision::F16).unwrap();
    assert_eq!((zero.intensity_cd(0.0, 0.0), zero.scale_cd()), (0.0, 0.0));
    let g: Vec<f64> = (0..=18).map(|k| 10.0 * k as f64).collect();
    let dark = Distribution::new(vec![0.0], g.clone(), vec![0.0; g.len()], Symmetry::Rotational).unwrap();
    let err = Reconstructions::new(
        dark.clone(),
        &[Recon::Sh {
            degree: 4,
            f16: false,
            gpu: false,
        }],
    )
    .unwrap_err()
    .to_string();
    assert!(err.contains("I_max"), "{err}");
    assert!(fit_lobes(&dark, 2).is_err());
    assert!(ShField::new(&f, MAX_ZONAL_SH_DEGREE + 1, ShWindow::None, Precision::F32).is_err());
    for bad in ["sh:", "sh:x", "sh:129", "sh:4+f32", "lobes:0", "lobes:17", "lobes:"] {
        assert!(bad.parse::<Recon>().is_err(), "{bad}");
    }
    for good in ["sh:0", "sh:8", "sh:16+f16", "lobes:1", "lobes:8"] {
        assert_eq!(good.parse::<Recon>().unwrap().to_string(), good);
    }
}

/// Every good corpus file: sh:16 has a lower radial RMS error than sh:4
/// against the Catmull-Rom field it approximates (solid-angle weighted, 4000
/// Fibonacci directions), and both are finite and ≥ 0.
#[test]
fn sh16_beats_sh4_on_every_corpus_file() {
    let Some(root) = common::corpus() else { return };
    let set = DirectionSet::fibonacci(4000);
    let mut n = 0;
    for e in common::manifest(&root) {
        if e.malformed() || !e.photometric() {
            continue;
        }
        let Ok(lum) = photosolid::load(&e.path) else { continue };
        let Ok(tex) = LightTexture::new(lum.distribution()) else {
            continue;
        };
        let cr = tex.sampler(Filter::CatmullRom);
        let reference = eval_all(&cr, &set.directions);
        let rms = |degree: usize| {
            let s = ShField::new(&cr, degree, ShWindow::Lanczos, Precision::F32).unwrap();
            let v = eval_all(&s, &set.directions);
            assert!(v.iter().all(|x| x.is_finite() && *x >= 0.0), "{}", e.rel);
            radial_errors(&set, &reference, &v, tex.i_max_cd(), 0.02).rms_pct
        };
        let (r4, r16) = (rms(4), rms(16));
        eprintln!("{}: sh:4 rms {r4:.3} %, sh:16 rms {r16:.3} %", e.rel);
        assert!(r16 < r4 || r4 < 1e-9, "{}: sh:16 {r16} vs sh:4 {r4}", e.rel);
        n += 1;
    }
    assert!(n >= 20, "only {n} corpus files");
}

/// Fitted lobes never rise far above the data between measured directions
/// (a lobe's half-maximum cone must hold three measured directions,
/// `fit::lobes`): on every loadable corpus file and each of its 2-fold
/// hold-outs, the mixtures of 1 to 4 lobes stay below 2 I_max over 20,000
/// directions. The cone bounds one lobe's peak to twice its value at a
/// measured direction, where the fit holds the mixture near the data. (Before
/// that rule: up to 10.4 I_max, the weight cap, on 8 files; after: 1.84 at most.)
#[test]
fn lobes_do_not_spike_between_samples() {
    let Some(root) = common::corpus() else { return };
    let dirs = photosolid::metrics::random_directions(20_000, 7);
    let mut n = 0;
    let mut worst = (0.0f64, String::new());
    for e in common::manifest(&root) {
        if e.malformed() || !e.photometric() {
            continue;
        }
        let Ok(lum) = photosolid::load(&e.path) else { continue };
        let d = lum.distribution();
        let Ok(folds) = photosolid::reconstruct::kfold(d, 2) else {
            continue;
        };
        for dist in std::iter::once(d.clone()).chain(folds.into_iter().map(|f| f.kept)) {
            let Ok(stages) = fit_lobes(&dist, 4) else { continue };
            for m in &stages {
                let peak = dirs.iter().map(|u| m.intensity_dir_cd(*u)).fold(0.0, f64::max);
                let ratio = peak / dist.max_cd();
                if ratio > worst.0 {
                    worst = (ratio, format!("{} {}", e.rel, m.name()));
                }
                assert!(ratio < 2.0, "{}: {} peaks at {ratio} I_max", e.rel, m.name());
            }
        }
        n += 1;
    }
    eprintln!("largest lobe-mixture peak: {:.3} I_max ({})", worst.0, worst.1);
    assert!(n >= 50, "only {n} corpus files");
}

fn lobe_truth(lobes: &[(f64, f64, f64, f64)]) -> Lobes {
    Lobes::new(
        lobes
            .iter()
            .map(|&(c, g, p, w)| Lobe {
                axis: direction(c, g),
                exponent: p,
                weight_cd: w,
            })
            .collect(),
    )
}

/// A synthetic K-lobe truth sampled on a 5° x 2.5° grid is recovered: axes
/// within 1°, exponents and weights within 3 %.
#[test]
fn lobes_recover_a_synthetic_truth() {
    let cases = [
        vec![(0.0, 0.0, 20.0, 1000.0), (90.0, 60.0, 8.0, 400.0)],
        vec![
            (0.0, 30.0, 30.0, 800.0),
            (180.0, 35.0, 30.0, 800.0),
            (90.0, 150.0, 4.0, 200.0),
        ],
    ];
    for truth in cases {
        let t = lobe_truth(&truth);
        let c: Vec<f64> = (0..72).map(|k| 5.0 * k as f64).collect();
        let g: Vec<f64> = (0..=72).map(|k| 2.5 * k as f64).collect();
        let v: Vec<f64> = c
            .iter()
            .flat_map(|&c| g.iter().map(move |&g| (c, g)))
            .map(|(c, g)| t.intensity_cd(c, g))
            .collect();
        let d = Distribution::new(c, g, v, Symmetry::None).unwrap();
        let stages = fit_lobes(&d, truth.len()).unwrap();
        let fit = &stages[truth.len() - 1];
        for want in &t.lobes {
            let got = fit
                .lobes
                .iter()
                .min_by(|a, b| {
                    a.axis
                        .angle_between(want.axis)
                        .total_cmp(&b.axis.angle_between(want.axis))
                })
                .unwrap();
            let angle = got.axis.angle_between(want.axis).to_degrees();
            eprintln!("truth {want:?} fit {got:?}: {angle:.3} deg");
            assert!(angle < 1.0, "axis {angle} deg off");
            assert_close!(got.exponent, want.exponent, rel = 0.03);
            assert_close!(got.weight_cd, want.weight_cd, rel = 0.03);
        }
    }
}

/// Rotationally symmetric data is fitted with rings (`Lobes::rings`): a
/// batwing of two rings (γ 40°, p 40, and a plain downward lobe, p 20) sampled on
/// one plane, 2.5° steps, is recovered: the ring's polar angle within 1°,
/// its exponent and weight within 3 %, the mixture within 1 % of I_max
/// beyond 5° of the nadir (0.88 %) and within 0.5 % in weighted RMS (0.23 %); the truth is rotational (every C gives
/// the same intensity) and ring lobes add what no vertical lobe can (the
/// vertical-only fit of earlier rounds, 46 % radial max on wiki-batwing, is in
/// docs/compact.md).
#[test]
fn rings_recover_a_rotational_batwing() {
    let ring = |gamma: f64, p: f64, w: f64| Lobe {
        axis: direction(0.0, gamma),
        exponent: p,
        weight_cd: w,
    };
    let truth = Lobes::rings(vec![ring(40.0, 40.0, 900.0), ring(0.0, 20.0, 400.0)]);
    let g: Vec<f64> = (0..=72).map(|k| 2.5 * k as f64).collect();
    let v: Vec<f64> = g.iter().map(|&g| truth.intensity_cd(0.0, g)).collect();
    // Rotational: the same at every C, and not what the plain lobes give.
    for gamma in [20.0, 40.0, 50.0] {
        let at0 = truth.intensity_cd(0.0, gamma);
        for c in [45.0, 90.0, 180.0, 271.0] {
            assert_close!(truth.intensity_cd(c, gamma), at0, rel = 1e-6);
        }
    }
    assert!(Lobes::new(truth.lobes.clone()).intensity_cd(180.0, 40.0) < 0.5 * truth.intensity_cd(180.0, 40.0));
    let d = Distribution::new(vec![0.0], g, v, Symmetry::Rotational).unwrap();
    let fit = &fit_lobes(&d, 2).unwrap()[1];
    assert!(fit.rings, "rotational data is fitted with rings");
    let polar = |l: &Lobe| l.axis.truncate().length().atan2(-l.axis.z).to_degrees();
    // The ring: polar angle within 1°, exponent and weight within 3 %.
    let (want, got) = (&truth.lobes[0], &fit.lobes[0]);
    assert!(
        (polar(got) - polar(want)).abs() < 1.0,
        "ring at {} deg, want {}",
        polar(got),
        polar(want)
    );
    assert_close!(got.exponent, want.exponent, rel = 0.03);
    assert_close!(got.weight_cd, want.weight_cd, rel = 0.03);
    // The whole mixture within 1 % of I_max at every γ (0.1° steps) and C
    // beyond 5° of the nadir. Nearer, a ring of a few degrees' tilt and a
    // plain lobe differ by little solid angle, which the fit's
    // solid-angle-weighted error barely sees (the fit puts the second lobe
    // on a ring of 2.5° there, 3.3 % below the truth at the nadir), so the
    // second lobe's parameters are not pinned; its solid-angle-weighted RMS
    // difference is.
    let i_max = d.max_cd();
    let diff = |c: f64, g: f64| (fit.intensity_cd(c, g) - truth.intensity_cd(c, g)).abs() / i_max;
    let gammas = (0..=1800).map(|k| 0.1 * k as f64);
    let worst = gammas
        .clone()
        .filter(|&g| g > 5.0)
        .map(|g| diff(137.0, g))
        .fold(0.0, f64::max);
    let (sq, omega) = gammas.fold((0.0, 0.0), |(sq, om), g| {
        let w = g.to_radians().sin();
        (sq + w * diff(0.0, g).powi(2), om + w)
    });
    let rms = (sq / omega).sqrt();
    eprintln!(
        "largest difference beyond 5 deg: {:.3} %, weighted rms {:.4} % of I_max",
        100.0 * worst,
        100.0 * rms
    );
    assert!(worst < 0.01 && rms < 0.005, "{worst} {rms}");
}

/// K up to 8 on real and extreme data: finite, ≥ 0, 20 bytes a lobe, and
/// more lobes never fit the data worse (beyond the search's tolerance).
#[test]
fn lobes_up_to_eight_are_finite() {
    let spot = Synth::CosinePower { p: 128.0 }
        .build(&GridSpec::uniform(15.0, 1.0).unwrap(), 1000.0)
        .unwrap();
    let roadway = Synth::Roadway
        .build(&GridSpec::uniform(5.0, 2.5).unwrap(), 1000.0)
        .unwrap();
    let set = DirectionSet::fibonacci(2000);
    for lum in [spot, roadway] {
        let d = lum.distribution();
        let stages = fit_lobes(d, 8).unwrap();
        let tex = LightTexture::new(d).unwrap();
        let reference = eval_all(&tex.sampler(Filter::CatmullRom), &set.directions);
        let mut last = f64::INFINITY;
        for (k, s) in stages.iter().enumerate() {
            assert_eq!(s.lobes.len(), k + 1);
            assert_eq!(s.bytes(), 20 * (k + 1));
            let v = eval_all(s, &set.directions);
            assert!(v.iter().all(|x| x.is_finite() && *x >= 0.0), "lobes:{}", k + 1);
            let e = radial_errors(&set, &reference, &v, d.max_cd(), 0.02);
            eprintln!("lobes:{}: rms {:.3} % max {:.3} %", k + 1, e.rms_pct, e.max_pct);
            assert!(
                e.rms_pct <= last * 1.05 + 1e-3,
                "lobes:{}: {} after {last}",
                k + 1,
                e.rms_pct
            );
            last = last.min(e.rms_pct);
        }
    }
}
