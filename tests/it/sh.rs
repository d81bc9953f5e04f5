//! Compact representations (issue 30): spherical harmonics `sh:L` and lobe
//! mixtures `lobes:K` against closed forms, synthetic truths, the corpus and
//! numerical extremes; the trade table's bytes front.

use std::f64::consts::PI;

use photosolid::compare::trade::{mark_pareto_bytes, smallest_within, trade_table, TradeOptions, TradeRow};
use photosolid::compare::{CompareOptions, Directions};
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

fn row(name: &str, bytes: usize, max: f64) -> TradeRow {
    TradeRow {
        representation: name.into(),
        recon: None,
        bytes,
        ns_per_sample: 1.0,
        ns_per_sample_f32: None,
        f32_vs_f64_max_pct: None,
        ns_per_sample_gpu: None,
        adapter: None,
        texture_format: None,
        subtexel_bits: None,
        hardware_vs_exact_max_pct: None,
        hausdorff_pct: max,
        hausdorff_bound_pct: 0.0,
        radial_max_pct: max,
        radial_rms_pct: max,
        flux_error_pct: 0.0,
        window: None,
        form: None,
        pareto: false,
        pareto_bytes: false,
    }
}

/// The bytes front and the smallest row within 1 %, on a hand-made table.
#[test]
fn bytes_front_and_smallest_within() {
    let mut rows = vec![
        row("a", 100, 50.0),
        row("b", 200, 10.0),
        row("c", 300, 20.0),
        row("d", 1000, 0.9),
        row("e", 1000, 0.5),
        row("f", 5000, 0.5),
    ];
    mark_pareto_bytes(&mut rows);
    let front: Vec<&str> = rows
        .iter()
        .filter(|r| r.pareto_bytes)
        .map(|r| r.representation.as_str())
        .collect();
    assert_eq!(front, ["a", "b", "e"]);
    assert_eq!(smallest_within(&rows, 1.0).as_deref(), Some("e"));
    assert_eq!(smallest_within(&rows, 0.1), None);
}

/// Every trade row says how the data shaped it (`form`, a key on every row): the
/// lobes are `rings` exactly when the series are `zonal` (both follow the data's
/// rotational symmetry), every other row has none; the rotational wiki-batwing
/// gets them, the asymmetric ITALO does not.
fn check_forms(name: &str, rows: &[TradeRow], json: &serde_json::Value) {
    for r in json["rows"].as_array().unwrap() {
        assert!(r.get("form").is_some(), "{name}: a row without the form key");
    }
    let form_of = |prefix: &str| -> Vec<Option<&str>> {
        rows.iter()
            .filter(|r| r.representation.starts_with(prefix))
            .map(|r| r.form.as_deref())
            .collect()
    };
    let (sh, lobes) = (form_of("sh:"), form_of("lobes:"));
    let rotational = sh.first().copied().flatten() == Some("zonal");
    assert!(sh.iter().all(|f| *f == rotational.then_some("zonal")), "{name}: {sh:?}");
    assert!(
        lobes.iter().all(|f| *f == rotational.then_some("rings")),
        "{name}: {lobes:?}"
    );
    let others: Vec<_> = rows
        .iter()
        .filter(|r| !(r.representation.starts_with("sh:") || r.representation.starts_with("lobes:")))
        .filter(|r| r.form.is_some())
        .map(|r| r.representation.as_str())
        .collect();
    assert!(others.is_empty(), "{name}: {others:?}");
    match name {
        "eulumdat-rs/wiki-batwing.ldt" => assert!(rotational, "{name}"),
        "eulumdat-rs/ITALO 1 5P5 S05 3.140-3M.IES" => assert!(!rotational, "{name}"),
        _ => {}
    }
}

/// The trade table (fixed x1 solids, 2000 directions) of the synthetic
/// roadway and of a sample of 13 corpus files of every kind (rotational,
/// symmetric, asymmetric, floods, uplights; the whole corpus would take
/// minutes): sh and lobes rows with their costs, `pareto_bytes` on every
/// row, `smallest_within_1pct`. On every corpus file an sh/lobes row lies
/// on the bytes front between 128 bytes and 10 kB, unless a row under 128
/// bytes is already within 1 % of I_max. (The table adds `sh:32`, `lobes:7`
/// and `lobes:8` to the default rows: a rotational file's series are zonal,
/// `sh:16` 68 bytes and `sh:32` 132; on cu-ies 3.IES only `lobes:8`, 160
/// bytes, and on photon-v2's L1768 only `sh:32`, 4,356 bytes, is on the
/// front past the lobes:1-4, which beat every series up to `sh:16`. Data the
/// same in every C-plane adds the zonal `sh:64` and `sh:128`, 260 and 516
/// bytes: photometric-viewer's sphere opening (one plane) needs `sh:64`, and
/// rpr-sdk's ies_light_1 (two equal planes of 269 angles) `sh:128`, past
/// `lobes:3` and `lobes:4`. eulumdat-plot's sample_02 (4 quadrants) needs
/// `lobes:7`, 140 bytes: 4.08 % radial max against `lobes:4`'s 5.29 %, where
/// every series up to `sh:32` and `lobes:8` read worse. On the
/// coarse synthetic roadway against withheld samples the lobes beat every
/// grid representation, so its front ends at `lobes:4`, 80 bytes.)
#[test]
fn trade_table_has_compact_rows_on_the_bytes_front() {
    let opts = TradeOptions {
        factors: vec![1, 2],
        compare: CompareOptions {
            directions: Directions::Dense(2000),
            factor: 1,
            solid_tolerance: None,
            tolerance: 0.01,
            timing_samples: 200,
            timing_repeats: 1,
            ..CompareOptions::default()
        },
        gpu: false,
    };
    let lum = Synth::Roadway
        .build(&GridSpec::uniform(15.0, 5.0).unwrap(), 1000.0)
        .unwrap();
    // (name, distribution, whether the front must reach [128 B, 10 kB])
    let mut files = vec![("roadway (withheld)".to_string(), lum.distribution().clone(), false)];
    if let Some(root) = common::corpus() {
        for rel in [
            "eulumdat-rs/projector.ldt",
            "eulumdat-rs/ITALO 1 5P5 S05 3.140-3M.IES",
            "eulumdat-rs/road_luminaire.ldt",
            "eulumdat-rs/wiki-batwing.ldt",
            "eulumdat-rs/floor_uplight.ldt",
            "eulumdat-rs/ABSOLUTE_LED.ies",
            "cu-ies/flood_2.1.IES",
            "gldf-rs/SLV_Tria2_narrow.ldt",
            "cu-ies/3.IES",
            "photon-v2/L1768-65BR30FL_FL55.ies",
            "photometric-viewer/sphere_opening.ies",
            "rpr-sdk/ies_light_1.ies",
            "eulumdat-plot/sample_02_isym4.ldt",
        ] {
            let d = photosolid::load(root.join(rel)).unwrap().distribution().clone();
            files.push((rel.into(), d, true));
        }
    }
    let mut missing = Vec::new();
    for (name, d, corpus) in files {
        let start = std::time::Instant::now();
        let t = trade_table(&d, None, &opts, &|_, _, _| {}).unwrap();
        eprintln!("{name}: trade table {:.2} s", start.elapsed().as_secs_f64());
        let json = serde_json::to_value(&t).unwrap();
        assert!(json.get("smallest_within_1pct").is_some(), "{name}");
        for r in json["rows"].as_array().unwrap() {
            assert!(r["pareto"].is_boolean() && r["pareto_bytes"].is_boolean(), "{name}");
        }
        for r in &t.rows {
            eprintln!(
                "{name}: {:<28} {:>8} B {:>8.1} ns max {:>8.3} % rms {:>7.3} % {}",
                r.representation,
                r.bytes,
                r.ns_per_sample,
                r.radial_max_pct,
                r.radial_rms_pct,
                if r.pareto_bytes { "front" } else { "" }
            );
            assert!(r.radial_max_pct.is_finite() && r.ns_per_sample.is_finite());
        }
        eprintln!("{name}: smallest within 1 %: {:?}", t.smallest_within_1pct);
        check_forms(&name, &t.rows, &json);
        for want in [
            "sh:2", "sh:4", "sh:8", "sh:16", "sh:32", "lobes:1", "lobes:2", "lobes:3", "lobes:4", "lobes:7", "lobes:8",
        ] {
            let r = t.rows.iter().find(|r| r.representation == want).unwrap();
            assert!(r.ns_per_sample > 0.0, "{name} {want}");
            assert_eq!(r.window.is_some(), want.starts_with("sh:"));
        }
        let on_front = |lo: usize| {
            t.rows.iter().any(|r| {
                (r.representation.starts_with("sh:") || r.representation.starts_with("lobes:"))
                    && r.pareto_bytes
                    && (lo..=10240).contains(&r.bytes)
            })
        };
        // Exempt: a row under 128 bytes already within 1 % (ABSOLUTE_LED: lobes:1, 20 bytes,
        // 0.92 %; only a 5 kB texture at 0.86 % lies below it on the front).
        let served = t
            .rows
            .iter()
            .any(|r| Some(&r.representation) == t.smallest_within_1pct.as_ref() && r.bytes < 128);
        if (corpus && !served && !on_front(128)) || !on_front(0) {
            missing.push(name);
        }
    }
    assert!(
        missing.is_empty(),
        "no sh/lobes row where the bytes front needs one: {missing:?}"
    );
}

/// The report plots error against L (issue 30 item 1): a comparison with
/// `sh:L` rows at several degrees gets `error_vs_degree.png`, drawn from
/// those rows' own errors, and one with a single degree gets none.
#[test]
fn report_plots_error_against_degree() {
    use photosolid::report::compare_report;
    let lum = Synth::Roadway
        .build(&GridSpec::uniform(10.0, 5.0).unwrap(), 1000.0)
        .unwrap();
    let d = lum.distribution();
    let recons: Vec<Recon> = ["sh:2", "sh:4", "sh:8", "sh:8+f16"]
        .iter()
        .map(|s| s.parse().unwrap())
        .collect();
    let opts = CompareOptions {
        recons,
        truth: Truth::of_luminaire(&lum),
        directions: Directions::Dense(2000),
        factor: 1,
        solid_tolerance: None,
        timing_samples: 50,
        timing_repeats: 1,
        plots: true,
        ..Default::default()
    };
    let c = photosolid::compare::compare(d, None, &opts).unwrap();
    // The rows the figure is drawn from: errors that fall with L, as the figure shows them.
    let max_of = |name: &str| c.results.iter().find(|r| r.name == name).unwrap().radial_max_pct;
    assert!(
        max_of("sh:8") < max_of("sh:2"),
        "{} vs {}",
        max_of("sh:8"),
        max_of("sh:2")
    );
    let figs = compare_report::figures(&c).unwrap();
    let fig = figs
        .iter()
        .find(|f| f.file == "error_vs_degree.png")
        .expect("an error-vs-L figure");
    assert!(
        fig.caption.contains("against") && fig.caption.contains(&c.reference),
        "{}",
        fig.caption
    );
    let pm = tiny_skia::Pixmap::decode_png(&fig.png).unwrap();
    // Three metrics, solid for f32 and dashed for f16 coefficients, in the palette's first three colours.
    for k in 0..3 {
        let rgb = photosolid::report::plot::palette(k);
        let n = pm
            .pixels()
            .iter()
            .filter(|p| [p.red(), p.green(), p.blue()] == rgb && p.alpha() == 255)
            .count();
        assert!(n > 20, "series colour {k} ({rgb:?}): {n} px");
    }

    let one = CompareOptions {
        recons: vec!["sh:4".parse().unwrap(), Recon::Filter(Filter::Bilinear)],
        ..opts
    };
    let c = photosolid::compare::compare(d, None, &one).unwrap();
    let figs = compare_report::figures(&c).unwrap();
    assert!(
        figs.iter().all(|f| f.file != "error_vs_degree.png"),
        "one degree is no curve"
    );
}

/// 16- and 8-bit normalised-integer textures (issue 30 item 5): each texel
/// is within half a step of the largest texel of the f32 texel it stores,
/// bilinear lookups (convex weights) within the same bound, bytes 2 and 1
/// per texel; the spelling round-trips; a p = 128 spot (most texels far
/// below one 8-bit step) stays finite and non-negative; the default trade
/// table holds both.
#[test]
fn quantised_textures_keep_half_a_step() {
    use photosolid::compare::trade::representations;
    use photosolid::reconstruct::{render, Lookup, StoredTexture, TextureSpec};
    for (what, synth) in [
        ("roadway", Synth::Roadway),
        (
            "spot p 128",
            Synth::Spot {
                p: 128.0,
                cutoff_deg: 60.0,
            },
        ),
    ] {
        let lum = synth.build(&GridSpec::uniform(5.0, 2.5).unwrap(), 1000.0).unwrap();
        let tex = LightTexture::new(lum.distribution()).unwrap();
        let r = render(&tex, Filter::CatmullRom, 5).unwrap();
        let full = StoredTexture::new(&r, None, Precision::F32, Lookup::Bilinear);
        let dirs = photosolid::metrics::random_directions(5000, 3);
        for (precision, steps, bytes) in [(Precision::U16, 65_535.0, 2), (Precision::U8, 255.0, 1)] {
            let q = StoredTexture::new(&r, None, precision, Lookup::Bilinear);
            let scale = f64::from(q.unorm_scale());
            let top = full.texels().iter().copied().fold(0.0f32, f32::max);
            assert_eq!(
                q.unorm_scale(),
                top,
                "{what} {precision:?}: the scale is the largest texel"
            );
            let half_step = 0.5 * scale / steps + 1e-7 * scale;
            let worst = q
                .texels()
                .iter()
                .zip(full.texels())
                .map(|(a, b)| f64::from((a - b).abs()))
                .fold(0.0, f64::max);
            assert!(
                worst <= half_step,
                "{what} {precision:?}: texel off by {worst:e} > {half_step:e}"
            );
            assert_eq!(q.bytes(), bytes * full.texels().len(), "{what} {precision:?}");
            for d in &dirs {
                let (a, b) = (q.intensity_dir_cd(*d), full.intensity_dir_cd(*d));
                assert!(a.is_finite() && a >= 0.0, "{what} {precision:?} {d}: {a}");
                assert!(
                    (a - b).abs() <= half_step * r.i_max_cd,
                    "{what} {precision:?} {d}: {a} vs {b}"
                );
            }
            assert!(q.name().ends_with(precision.suffix()), "{}", q.name());
        }
    }
    for s in [
        "catmull-rom@x5/bilinear+u16",
        "catmull-rom@x5/bilinear+u8",
        "bilinear@x2/nearest+u8+reduced",
    ] {
        let spec: TextureSpec = s.parse().unwrap();
        assert_eq!(spec.to_string(), s);
        assert_eq!(s.parse::<Recon>().unwrap().to_string(), s);
    }
    let names: Vec<String> = representations(Symmetry::None, &[1, 2, 5, 10])
        .iter()
        .map(|r| r.to_string())
        .collect();
    for want in ["catmull-rom@x5/bilinear+u16", "catmull-rom@x5/bilinear+u8"] {
        assert!(names.iter().any(|n| n == want), "{want} not in {names:?}");
    }
}

/// Every comparison names its smallest reconstruction within 1 % of I_max
/// (issue 30 item 5: `compare --json` and the Python `compare` carry
/// `tradeoff`'s key): the rule recomputed from its own rows, and null when
/// no row is within.
#[test]
fn comparisons_name_the_smallest_within_1pct() {
    let lum = Synth::CosinePower { p: 5.0 }
        .build(&GridSpec::uniform(5.0, 2.5).unwrap(), 1000.0)
        .unwrap();
    let opts = |recons: &[&str]| CompareOptions {
        recons: recons.iter().map(|s| s.parse().unwrap()).collect(),
        truth: Truth::of_luminaire(&lum),
        directions: Directions::Dense(2000),
        factor: 1,
        solid_tolerance: None,
        timing_samples: 50,
        timing_repeats: 1,
        ..Default::default()
    };
    let c = photosolid::compare::compare(lum.distribution(), None, &opts(&["bilinear", "sh:2", "lobes:1"])).unwrap();
    let want = c
        .results
        .iter()
        .filter(|r| r.radial_max_pct <= 1.0)
        .min_by(|a, b| {
            a.bytes
                .cmp(&b.bytes)
                .then(a.radial_max_pct.total_cmp(&b.radial_max_pct))
        })
        .map(|r| r.name.clone());
    assert_eq!(c.smallest_within_1pct, want);
    assert_eq!(c.smallest_within_1pct.as_deref(), Some("lobes:1"), "{:?}", c.results);
    let json = serde_json::to_value(&c).unwrap();
    assert_eq!(json["smallest_within_1pct"], "lobes:1");
    let none = photosolid::compare::compare(lum.distribution(), None, &opts(&["sh:2"])).unwrap();
    assert!(none.results[0].radial_max_pct > 1.0);
    assert_eq!(none.smallest_within_1pct, None);
    assert!(serde_json::to_value(&none).unwrap()["smallest_within_1pct"].is_null());
}

/// BC6H textures (issue 30 item 5, feature `bc6h`): encoded by Intel's ISPC
/// compressor and read back by bcdec, an independent decoder. 1 byte per
/// texel in whole 4 x 4 blocks; every texel finite and non-negative; on
/// smooth textures each texel within 1 % of the texture's largest texel of
/// its f32 value (measured: 0.19-0.55 %, BC6H's 3-4-bit indices between
/// half-float endpoints), bilinear lookups within the same bound (convex
/// weights). The spelling round-trips; the trade table has the row.
#[test]
fn bc6h_textures_read_back_within_their_blocks() {
    use photosolid::compare::trade::representations;
    use photosolid::reconstruct::{bc6h, render, Lookup, StoredTexture};
    if !bc6h::available() {
        eprintln!("SKIP bc6h_textures_read_back_within_their_blocks: built without the bc6h feature");
        assert!("catmull-rom@x5/bilinear+bc6h".parse::<Recon>().is_err());
        return;
    }
    for (what, synth) in [
        ("roadway", Synth::Roadway),
        ("batwing", Synth::Batwing),
        (
            "spot p 128",
            Synth::Spot {
                p: 128.0,
                cutoff_deg: 60.0,
            },
        ),
    ] {
        let lum = synth.build(&GridSpec::uniform(5.0, 2.5).unwrap(), 1000.0).unwrap();
        let r = render(&LightTexture::new(lum.distribution()).unwrap(), Filter::CatmullRom, 5).unwrap();
        let full = StoredTexture::new(&r, None, Precision::F32, Lookup::Bilinear);
        let b = StoredTexture::new(&r, None, Precision::Bc6h, Lookup::Bilinear);
        assert_eq!(b.precision(), Precision::Bc6h);
        let (h, (_, w)) = (b.height(), b.stored_columns());
        assert_eq!(b.bytes(), w.div_ceil(4) * h.div_ceil(4) * 16, "{what}");
        let top = f64::from(full.texels().iter().copied().fold(0.0f32, f32::max));
        let errs: Vec<f64> = b
            .texels()
            .iter()
            .zip(full.texels())
            .map(|(a, f)| {
                assert!(a.is_finite() && *a >= 0.0, "{what}: {a}");
                f64::from((a - f).abs()) / top
            })
            .collect();
        let worst = errs.iter().copied().fold(0.0, f64::max);
        let rms = (errs.iter().map(|e| e * e).sum::<f64>() / errs.len() as f64).sqrt();
        eprintln!(
            "{what}: BC6H texel error max {:.3} %, RMS {:.4} % of the largest texel",
            100.0 * worst,
            100.0 * rms
        );
        assert!(worst <= 0.01, "{what}: {worst}");
        for d in photosolid::metrics::random_directions(3000, 5) {
            let (a, f) = (b.intensity_dir_cd(d), full.intensity_dir_cd(d));
            assert!(
                (a - f).abs() <= worst * top * r.i_max_cd + 1e-9,
                "{what} {d}: {a} vs {f}"
            );
        }
    }
    let s = "catmull-rom@x5/bilinear+bc6h";
    assert_eq!(s.parse::<Recon>().unwrap().to_string(), s);
    let names: Vec<String> = representations(Symmetry::None, &[1, 2, 5, 10])
        .iter()
        .map(|r| r.to_string())
        .collect();
    assert!(names.iter().any(|n| n == s), "{names:?}");
}

/// `texture -o OUT.dds` (issue 30 item 5): a DDS file of BC6H_UF16 blocks
/// whose texels, decoded, are within the printed error of the float texture
/// written by the same render, and the printed max and RMS are what the
/// decoded file gives (python/tests/test_dds.py reads the same file with
/// OpenImageIO and texture2ddecoder).
#[test]
fn texture_writes_bc6h_dds_with_its_error() {
    use photosolid::reconstruct::{bc6h, exr_io};
    let t = tempfile::tempdir().unwrap();
    let run = |args: &[&str]| common::cli::ok(&common::cli::run(args, t.path()));
    run(&["synth", "batwing", "-o", "b.ldt"]);
    if !bc6h::available() {
        let o = common::cli::run(&["texture", "b.ldt", "-o", "t.dds"], t.path());
        let err = common::cli::fails(&o, 1);
        assert!(err.contains("no BC6H encoder"), "{err}");
        return;
    }
    run(&["texture", "b.ldt", "--backend", "cpu", "-o", "t.exr"]);
    let out = run(&["texture", "b.ldt", "--backend", "cpu", "-o", "t.dds"]);
    let (exr, _) = exr_io::read_exr(t.path().join("t.exr")).unwrap();
    let (blocks, w, h) = bc6h::read_dds(&std::fs::read(t.path().join("t.dds")).unwrap()).unwrap();
    assert_eq!((w, h), (exr.mapping.width, exr.mapping.height));
    let decoded = bc6h::decode(&blocks, w, h);
    let errs: Vec<f64> = decoded
        .iter()
        .zip(&exr.data)
        .map(|(d, f)| (f64::from(*d) - f64::from(*f)).abs())
        .collect();
    let max = 100.0 * errs.iter().copied().fold(0.0, f64::max);
    let rms = 100.0 * (errs.iter().map(|e| e * e).sum::<f64>() / errs.len() as f64).sqrt();
    assert!(max > 0.0 && max < 2.0, "{max}");
    let expect = format!(
        "max {} %, RMS {} % of I_max",
        photosolid::numfmt::significant(max, 3),
        photosolid::numfmt::significant(rms, 3)
    );
    assert!(out.contains(&expect), "{out}\nexpected: {expect}");
}
