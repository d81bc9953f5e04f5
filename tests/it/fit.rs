//! Fitted OpenGL lights (Zotti et al. 2005): recovery of known lights from
//! synthetic data, extremes, honest failures, and the corpus table.

use crate::common;

use photosolid::fit::{error_of, fit, ErrorMetric, Fit, FitOptions, FittedLights, Hemisphere, Light, Spot};
use photosolid::model::{Distribution, Symmetry};

/// Full-circle C angles (degrees) with step `c`, and γ 0..=180 with step `g`.
fn grid(c: f64, g: f64) -> (Vec<f64>, Vec<f64>) {
    let cs: Vec<f64> = (0..).map(|k| k as f64 * c).take_while(|&x| x < 360.0 - 1e-9).collect();
    let gs: Vec<f64> = (0..).map(|k| k as f64 * g).take_while(|&x| x <= 180.0 + 1e-9).collect();
    (cs, gs)
}

fn spot(h: Hemisphere, w: f64, p: f64, cut: f64, tilt: f64, az: f64) -> Light {
    Light::Spot(Spot {
        hemisphere: h,
        weight_cd: w,
        exponent: p,
        cutoff_deg: cut,
        tilt_deg: tilt,
        azimuth_deg: az,
    })
}

fn sample(lights: Vec<Light>, c: f64, g: f64) -> (FittedLights, Distribution) {
    let m = FittedLights::new(lights);
    let (cs, gs) = grid(c, g);
    let d = m.sample(&cs, &gs).unwrap();
    (m, d)
}

/// Small deterministic PRNG for the noise (SplitMix64 + Box–Muller).
struct Noise(u64);
impl Noise {
    fn u(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }
    fn gauss(&mut self) -> f64 {
        let (a, b) = (self.u().max(1e-300), self.u());
        (-2.0 * a.ln()).sqrt() * (std::f64::consts::TAU * b).cos()
    }
}

/// Multiplicative Gaussian noise of relative standard deviation `sigma`, every plane independent.
fn noisy(d: &Distribution, sigma: f64, seed: u64) -> Distribution {
    let mut n = Noise(seed);
    let cd: Vec<f64> = d
        .intensities_cd()
        .iter()
        .map(|v| v * (1.0 + sigma * n.gauss()).max(0.0))
        .collect();
    Distribution::new(
        d.c_angles_deg().to_vec(),
        d.gamma_angles_deg().to_vec(),
        cd,
        d.symmetry(),
    )
    .unwrap()
}

fn angle_between(a: [f64; 3], b: [f64; 3]) -> f64 {
    (a[0] * b[0] + a[1] * b[1] + a[2] * b[2])
        .clamp(-1.0, 1.0)
        .acos()
        .to_degrees()
}

/// Tolerances of one recovery check.
#[derive(Clone, Copy)]
struct Tol {
    exponent_rel: f64,
    cutoff_deg: f64,
    axis_deg: f64,
    weight_rel: f64,
}

const EXACT: Tol = Tol {
    exponent_rel: 0.02,
    cutoff_deg: 0.5,
    axis_deg: 0.5,
    weight_rel: 0.01,
};

/// Noise of 1 % (multiplicative Gaussian, fixed seed): the same tolerances,
/// except the cut-off: where the spot has faded below the noise at its
/// cut-off (spot + point: 899 cd · cos^12 61° ≈ 0.15 cd against 1 % of a
/// 60 cd floor), the data no longer place it; 1.5° then.
const NOISY: Tol = Tol {
    exponent_rel: 0.02,
    cutoff_deg: 1.5,
    axis_deg: 0.5,
    weight_rel: 0.01,
};

fn key(l: &Light) -> u8 {
    match l {
        Light::Point { .. } => 0,
        Light::Spot(s) if s.hemisphere == Hemisphere::Down => 1,
        Light::Spot(_) => 2,
    }
}

/// Check that `got` holds the lights of `want` within `tol`; returns the worst errors.
fn check(want: &FittedLights, f: &Fit, tol: Tol, what: &str) -> [f64; 4] {
    let got = f.model();
    let mut w = want.lights.clone();
    let mut g = got.lights.clone();
    w.sort_by_key(key);
    g.sort_by_key(key);
    let table = photosolid::fit::FitReport::of(f).to_text();
    assert_eq!(w.len(), g.len(), "{what}: wrong combination\n{table}");
    let mut worst = [0.0f64; 4];
    for (a, b) in w.iter().zip(&g) {
        assert_eq!(key(a), key(b), "{what}: wrong lights\n{table}");
        let dw = (a.weight_cd() - b.weight_cd()).abs() / a.weight_cd();
        worst[3] = worst[3].max(dw);
        assert_close!(
            b.weight_cd(),
            a.weight_cd(),
            rel = tol.weight_rel,
            "{what}: weight\n{table}"
        );
        if let (Light::Spot(a), Light::Spot(b)) = (a, b) {
            let dp = (a.exponent - b.exponent).abs() / a.exponent.max(1.0);
            let dc = (a.cutoff_deg - b.cutoff_deg).abs();
            let dx = angle_between(a.axis().to_array(), b.axis().to_array());
            worst[0] = worst[0].max(dp);
            worst[1] = worst[1].max(dc);
            worst[2] = worst[2].max(dx);
            assert!(
                dp <= tol.exponent_rel,
                "{what}: exponent {} vs {}\n{table}",
                b.exponent,
                a.exponent
            );
            assert_close!(
                b.cutoff_deg,
                a.cutoff_deg,
                abs = tol.cutoff_deg,
                "{what}: cut-off\n{table}"
            );
            assert!(dx <= tol.axis_deg, "{what}: axis off by {dx} deg\n{table}");
        }
    }
    assert!(f.error().is_finite());
    eprintln!(
        "{what}: {} error {:.2e}; worst exponent {:.2e} rel, cut-off {:.3} deg, axis {:.3} deg, weight {:.2e} rel",
        f.chosen().combination.name(),
        f.error(),
        worst[0],
        worst[1],
        worst[2],
        worst[3]
    );
    worst
}

fn cases() -> Vec<(&'static str, Vec<Light>, f64, f64)> {
    use Hemisphere::*;
    vec![
        (
            "single spot, 1 deg",
            vec![spot(Down, 1000.0, 6.5, 37.3, 0.0, 0.0)],
            5.0,
            1.0,
        ),
        // On a 2.5° grid only the cell of the cut-off is known; 41.25 is a cell's middle.
        (
            "single spot, 2.5 deg",
            vec![spot(Down, 1000.0, 20.0, 41.25, 0.0, 0.0)],
            5.0,
            2.5,
        ),
        ("spot up", vec![spot(Up, 500.0, 2.0, 63.7, 0.0, 0.0)], 5.0, 1.0),
        (
            "spot + point",
            vec![
                spot(Down, 900.0, 12.0, 60.2, 0.0, 0.0),
                Light::Point { weight_cd: 60.0 },
            ],
            5.0,
            1.0,
        ),
        (
            "two opposite spots",
            vec![
                spot(Down, 1000.0, 4.0, 75.4, 0.0, 0.0),
                spot(Up, 300.0, 20.0, 30.6, 0.0, 0.0),
            ],
            5.0,
            1.0,
        ),
        (
            "off-axis spot",
            vec![spot(Down, 1000.0, 10.0, 35.0, 25.0, 60.0)],
            5.0,
            2.5,
        ),
        (
            "off-axis spot + point",
            vec![
                spot(Down, 1000.0, 30.0, 20.0, 40.0, 300.0),
                Light::Point { weight_cd: 80.0 },
            ],
            5.0,
            2.5,
        ),
        (
            "two off-axis spots",
            vec![
                spot(Down, 1000.0, 8.0, 50.0, 15.0, 200.0),
                spot(Up, 400.0, 3.0, 40.0, 30.0, 45.0),
            ],
            5.0,
            2.5,
        ),
    ]
}

#[test]
fn recovers_known_lights_from_noiseless_data() {
    for (what, lights, c, g) in cases() {
        let (m, d) = sample(lights, c, g);
        let f = fit(&d, &FitOptions::default()).unwrap();
        check(&m, &f, EXACT, what);
    }
}

#[test]
fn recovers_known_lights_under_one_percent_noise() {
    for (i, (what, lights, c, g)) in cases().into_iter().enumerate() {
        let (m, d) = sample(lights, c, g);
        let d = noisy(&d, 0.01, 1000 + i as u64);
        let f = fit(&d, &FitOptions::default()).unwrap();
        check(&m, &f, NOISY, what);
        // The error is about the noise level.
        assert!(f.error() < 0.02, "{what}: {}", f.error());
    }
}

fn rot(lights: Vec<Light>, g: f64) -> (FittedLights, Distribution) {
    let m = FittedLights::new(lights);
    let (_, gs) = grid(360.0, g);
    let d = m.sample(&[0.0], &gs).unwrap();
    (m, d)
}

fn trial<'a>(f: &'a Fit, name: &str) -> &'a photosolid::fit::Trial {
    f.trials.iter().find(|t| t.combination.name() == name).unwrap()
}

fn all_finite(f: &Fit) {
    for t in &f.trials {
        if let Some(e) = t.error {
            assert!(e.is_finite() && e >= 0.0, "{:?}", t);
        }
        for l in t.model.iter().flat_map(|m| &m.lights) {
            assert!(l.weight_cd().is_finite() && l.weight_cd() >= 0.0);
            if let Light::Spot(s) = l {
                s.validate().unwrap();
            }
        }
    }
}

#[test]
fn exponent_zero_and_128_are_recovered() {
    let (m, d) = rot(vec![spot(Hemisphere::Down, 700.0, 0.0, 50.3, 0.0, 0.0)], 1.0);
    let f = fit(&d, &FitOptions::default()).unwrap();
    all_finite(&f);
    check(&m, &f, EXACT, "exponent 0");
    let (m, d) = rot(vec![spot(Hemisphere::Down, 700.0, 128.0, 20.4, 0.0, 0.0)], 1.0);
    let f = fit(&d, &FitOptions::default()).unwrap();
    check(&m, &f, EXACT, "exponent 128");
}

#[test]
fn cutoffs_near_zero_and_at_ninety() {
    // Only the nadir sample is lit: the exponent is undetermined, the cut-off is under one step.
    let (_, d) = rot(vec![spot(Hemisphere::Down, 500.0, 10.0, 0.4, 0.0, 0.0)], 1.0);
    let f = fit(&d, &FitOptions::default()).unwrap();
    all_finite(&f);
    assert!(f.error() < 1e-6, "{}", f.error());
    let Light::Spot(s) = f.model().lights[0] else {
        panic!("{:?}", f.model())
    };
    assert!(s.cutoff_deg < 1.0, "{s:?}");
    assert_close!(s.weight_cd, 500.0, abs = 1e-6, "{s:?}");
    // Cut-off 0 exactly (OpenGL: only the axis itself).
    let (_, d) = rot(vec![spot(Hemisphere::Down, 500.0, 3.0, 0.0, 0.0, 0.0)], 1.0);
    let f = fit(&d, &FitOptions::default()).unwrap();
    assert!(f.error() < 1e-6);
    // Cut-off 90 with p = 0: the horizon is lit, and the fit says 90.
    let (m, d) = rot(vec![spot(Hemisphere::Down, 500.0, 0.0, 90.0, 0.0, 0.0)], 1.0);
    let f = fit(&d, &FitOptions::default()).unwrap();
    check(&m, &f, EXACT, "cut-off 90, p = 0");
    let Light::Spot(s) = f.model().lights[0] else { panic!() };
    assert_eq!(s.cutoff_deg, 90.0);
    // Cut-off 90 with p = 3 (zero at the horizon: 89.5 and 90 are the same light).
    let (m, d) = rot(vec![spot(Hemisphere::Down, 500.0, 3.0, 90.0, 0.0, 0.0)], 1.0);
    check(
        &m,
        &fit(&d, &FitOptions::default()).unwrap(),
        EXACT,
        "cut-off 90, p = 3",
    );
}

#[test]
fn spot_along_the_pole_in_asymmetric_data() {
    let (m, d) = sample(
        vec![
            spot(Hemisphere::Down, 1000.0, 15.0, 46.25, 0.0, 0.0),
            spot(Hemisphere::Up, 300.0, 5.0, 35.0, 35.0, 120.0),
        ],
        5.0,
        2.5,
    );
    assert_eq!(d.symmetry(), Symmetry::None);
    let f = fit(&d, &FitOptions::default()).unwrap();
    assert!(!f.axis_vertical);
    check(&m, &f, EXACT, "spot along the pole");
    let down = f
        .model()
        .lights
        .iter()
        .find_map(|l| match l {
            Light::Spot(s) if s.hemisphere == Hemisphere::Down => Some(*s),
            _ => None,
        })
        .unwrap();
    assert!(down.tilt_deg < 0.5, "{down:?}");
}

#[test]
fn one_dark_hemisphere_skips_its_spots() {
    let (_, d) = rot(vec![spot(Hemisphere::Down, 1000.0, 5.0, 60.0, 0.0, 0.0)], 2.5);
    let f = fit(&d, &FitOptions::default()).unwrap();
    assert_eq!(f.chosen().combination.name(), "spot-down");
    for name in ["spot-up", "point+spot-up", "spot-down+spot-up"] {
        let t = trial(&f, name);
        assert!(
            t.error.is_none() && t.skipped.as_deref() == Some("the upper hemisphere is dark"),
            "{t:?}"
        );
    }
    // Only the lower hemisphere measured (γ 0..90).
    let gs: Vec<f64> = (0..=90).map(f64::from).collect();
    let d = FittedLights::new(vec![spot(Hemisphere::Down, 1000.0, 5.0, 60.0, 0.0, 0.0)])
        .sample(&[0.0], &gs)
        .unwrap();
    let f = fit(&d, &FitOptions::default()).unwrap();
    assert_eq!(f.chosen().combination.name(), "spot-down");
    assert!(trial(&f, "spot-up")
        .skipped
        .as_deref()
        .unwrap()
        .contains("no measured direction"));
}

#[test]
fn all_equal_data_is_a_point_light() {
    let (_, gs) = grid(15.0, 5.0);
    let (cs, _) = grid(15.0, 5.0);
    let d = Distribution::new(cs.clone(), gs.clone(), vec![250.0; cs.len() * gs.len()], Symmetry::None).unwrap();
    let f = fit(&d, &FitOptions::default()).unwrap();
    all_finite(&f);
    assert!(f.axis_vertical, "identical planes are rotational");
    assert_eq!(f.chosen().combination.name(), "point");
    assert_close!(f.model().lights[0].weight_cd(), 250.0, abs = 1e-9);
    assert!(f.error() < 1e-12);
    // A flat lower hemisphere measured alone: a point light and a p = 0 spot both fit; the point wins.
    let g90: Vec<f64> = (0..=18).map(|k| k as f64 * 5.0).collect();
    let d = Distribution::new(vec![0.0], g90.clone(), vec![40.0; g90.len()], Symmetry::Rotational).unwrap();
    let f = fit(&d, &FitOptions::default()).unwrap();
    assert_eq!(f.chosen().combination.name(), "point");
}

#[test]
fn all_zero_data_is_a_clear_error() {
    let d = Distribution::new(vec![0.0], vec![0.0, 90.0, 180.0], vec![0.0; 3], Symmetry::Rotational).unwrap();
    let e = fit(&d, &FitOptions::default()).unwrap_err();
    assert!(matches!(e, photosolid::ModelError::AllZero(_)), "{e}");
    assert!(e.to_string().contains("zero everywhere"));
    let d = Distribution::new(vec![0.0], vec![0.0, 90.0], vec![-1.0, -2.0], Symmetry::Rotational).unwrap();
    assert!(fit(&d, &FitOptions::default()).is_err());
    let d = Distribution::new(vec![0.0], vec![0.0, 90.0], vec![1.0, 2.0], Symmetry::Rotational).unwrap();
    for bad in [
        FitOptions {
            max_lights: 3,
            ..Default::default()
        },
        FitOptions {
            tolerance: f64::NAN,
            ..Default::default()
        },
        FitOptions {
            guard: 0.0,
            ..Default::default()
        },
    ] {
        assert!(fit(&d, &bad).is_err());
    }
}

/// Distributions without spot character (Zotti et al. 2005, §5: central obstruction, ring
/// maxima) are fitted and reported with their error, not hidden.
#[test]
fn batwing_and_ring_are_reported_honestly() {
    let bat = photosolid::synth::Synth::Batwing
        .build(&photosolid::synth::GridSpec::uniform(15.0, 2.5).unwrap(), 1000.0)
        .unwrap()
        .into_distribution();
    let (_, gs) = grid(360.0, 2.5);
    // A ring: peak at γ = 60°, nothing at the nadir.
    let ring: Vec<f64> = gs
        .iter()
        .map(|&g| {
            if g <= 90.0 {
                1000.0 * (-((g - 60.0) / 10.0).powi(2)).exp()
            } else {
                0.0
            }
        })
        .collect();
    let ring = Distribution::new(vec![0.0], gs.clone(), ring, Symmetry::Rotational).unwrap();
    for (what, d) in [("batwing", bat), ("ring", ring)] {
        let f = fit(&d, &FitOptions::default()).unwrap();
        all_finite(&f);
        eprintln!("{what}:\n{}", photosolid::fit::FitReport::of(&f).to_text());
        assert!(f.error() > 0.05, "{what}: a spot cannot be this good: {}", f.error());
        assert!(f.error().is_finite());
    }
}

#[test]
fn roadway_fits_with_a_tilted_spot() {
    let d = photosolid::synth::Synth::Roadway
        .build(&photosolid::synth::GridSpec::uniform(5.0, 2.5).unwrap(), 1000.0)
        .unwrap()
        .into_distribution();
    let f = fit(&d, &FitOptions::default()).unwrap();
    all_finite(&f);
    eprintln!("{}", photosolid::fit::FitReport::of(&f).to_text());
    // The roadway's two lobes peak at gamma 65 towards C60 and C120 (mirror
    // images about the C90-C270 plane: the street side); the house side
    // (C270) gets only 0.15 cos(gamma).
    let dir = photosolid::model::frame::direction;
    let peaks = [dir(60.0, 65.0), dir(120.0, 65.0)];
    let off_peak = |v: glam::DVec3| {
        peaks
            .iter()
            .map(|p| p.angle_between(v).to_degrees())
            .fold(f64::INFINITY, f64::min)
    };
    // Measured (deterministic fit): spot-down+spot-up, error 0.28849. A bound
    // of 0.35 leaves about 20 % for optimiser or floating-point changes, and
    // the models that miss the tilt fail it: a point light 0.618, the up spot
    // alone 0.610, a vertical cosine spot 0.575, even one lobe fitted exactly
    // (down spot, tilt 65, azimuth 60, exponent 8) 0.531. The broad down spot
    // alone, tilted 24.8 degrees towards C90, meets it (0.310): it is a
    // tilted spot, and the peak check below tells it apart.
    assert!(f.error() < 0.35, "error {}", f.error());
    let spots: Vec<&Spot> = f
        .model()
        .lights
        .iter()
        .filter_map(|l| match l {
            Light::Spot(s) => Some(s),
            Light::Point { .. } => None,
        })
        .collect();
    // The tilt the name promises: a vertical spot cannot throw light to one
    // side. Measured: down spot tilt 18.2 at azimuth 91.7 (between the lobes),
    // up spot tilt 90.0 (on the horizon) at azimuth 57.6.
    assert!(spots.iter().any(|s| s.tilt_deg >= 10.0), "{spots:?}");
    // Every spot leans to the street side (C in (0, 180): +y), none to the
    // house. Measured axis y: 0.31 and 0.84.
    for s in &spots {
        assert!(s.tilt_deg == 0.0 || s.axis().y > 0.2, "{s:?}");
    }
    // The fitted model's strongest direction (1 degree grid) is near a lobe.
    // Measured: C 58, gamma 88, 23.1 degrees from (C60, gamma 65). An up spot
    // cannot go below the horizon, 25 degrees above the peak, so 30 degrees
    // is the honest bound; a vertical model peaks 65 degrees off, one
    // pointing at the house side more than 90. The azimuth is free: within 10
    // degrees of C60 or C120.
    let (mut best, mut at) = (f64::NEG_INFINITY, (0.0, 0.0));
    for c in 0..360 {
        for g in 0..=180 {
            let i = f.model().intensity(c as f64, g as f64);
            if i > best {
                (best, at) = (i, (c as f64, g as f64));
            }
        }
    }
    let off = off_peak(dir(at.0, at.1));
    eprintln!(
        "model peak {best:.1} cd at C {} gamma {}, {off:.2} degrees off the nearer lobe",
        at.0, at.1
    );
    assert!(off < 30.0, "peak at {at:?}, {off} degrees off");
    assert!(
        (at.0 - 60.0).abs() <= 10.0 || (at.0 - 120.0).abs() <= 10.0,
        "peak at {at:?}"
    );
}

#[test]
fn deterministic_and_independent_of_threads() {
    let (_, d) = sample(
        vec![
            spot(Hemisphere::Down, 1000.0, 8.0, 50.0, 15.0, 200.0),
            spot(Hemisphere::Up, 400.0, 3.0, 40.0, 30.0, 45.0),
        ],
        5.0,
        2.5,
    );
    let d = noisy(&d, 0.01, 7);
    let a = fit(&d, &FitOptions::default()).unwrap();
    let b = fit(&d, &FitOptions::default()).unwrap();
    let c = fit(
        &d,
        &FitOptions {
            parallel: false,
            ..Default::default()
        },
    )
    .unwrap();
    assert_eq!(a, b);
    assert_eq!(a.trials, c.trials);
}

#[test]
fn error_of_agrees_and_solid_angle_metric_recovers() {
    let (m, d) = sample(
        vec![
            spot(Hemisphere::Down, 900.0, 12.0, 60.2, 10.0, 30.0),
            Light::Point { weight_cd: 60.0 },
        ],
        5.0,
        2.5,
    );
    let opts = FitOptions {
        metric: ErrorMetric::SolidAngle,
        ..Default::default()
    };
    let f = fit(&d, &opts).unwrap();
    check(&m, &f, EXACT, "solid-angle metric");
    for t in f.trials.iter().filter(|t| t.model.is_some()) {
        let e = error_of(&d, t.model.as_ref().unwrap(), ErrorMetric::SolidAngle, opts.guard).unwrap();
        assert_close!(e, t.error.unwrap(), abs = 1e-12, "{e} vs {:?}", t.error);
    }
    // The true model has zero error under both metrics.
    assert!(error_of(&d, &m, ErrorMetric::Relative, 0.02).unwrap() < 1e-12);
}

#[test]
fn selection_prefers_fewer_lights_within_tolerance() {
    // A spot over a faint point floor (0.3 % of I_max).
    let (_, d) = rot(
        vec![
            spot(Hemisphere::Down, 1000.0, 6.0, 70.0, 0.0, 0.0),
            Light::Point { weight_cd: 3.0 },
        ],
        2.5,
    );
    let strict = fit(
        &d,
        &FitOptions {
            tolerance: 0.0,
            ..Default::default()
        },
    )
    .unwrap();
    assert_eq!(strict.chosen().lights, 2);
    let lax = fit(
        &d,
        &FitOptions {
            tolerance: 1.0,
            ..Default::default()
        },
    )
    .unwrap();
    assert_eq!(lax.chosen().lights, 1);
    let one = fit(
        &d,
        &FitOptions {
            max_lights: 1,
            ..Default::default()
        },
    )
    .unwrap();
    assert_eq!(one.trials.len(), 3);
    assert!(one.trials.iter().all(|t| t.lights == 1));
}

#[test]
fn report_has_gl_units_and_snippets() {
    let (_, d) = sample(vec![spot(Hemisphere::Down, 1000.0, 10.0, 35.0, 25.0, 60.0)], 5.0, 2.5);
    let f = fit(&d, &FitOptions::default()).unwrap();
    let r = photosolid::fit::FitReport::of(&f);
    let v = serde_json::to_value(&r).unwrap();
    for k in [
        "reconstruction",
        "metric",
        "guard",
        "tolerance",
        "i_max_cd",
        "chosen",
        "error",
        "lights",
        "trials",
        "frames",
        "glsl",
        "gl_fixed_function",
    ] {
        assert!(v.get(k).is_some(), "missing {k}");
    }
    assert_eq!(v["reconstruction"], "fitted-gl");
    assert_eq!(v["trials"].as_array().unwrap().len(), 6);
    let l = &v["lights"][0];
    let dz = l["direction_luminaire"].as_array().unwrap();
    let dy = l["direction_gl"].as_array().unwrap();
    // y-up = (x, z, −y) of z-up.
    assert_close!(dy[1].as_f64().unwrap(), dz[2].as_f64().unwrap(), abs = 1e-12);
    assert_close!(dy[2].as_f64().unwrap(), -dz[1].as_f64().unwrap(), abs = 1e-12);
    assert!(r.glsl.contains("float luminaireIntensity(vec3 L)"));
    assert_eq!(r.gl_fixed_function[0].GL_QUADRATIC_ATTENUATION, 1.0);
    assert!(r.to_text().contains("* spot-down"));
}

/// Every loadable corpus file (all that the manifest does not mark
/// malformed) fits with a finite error; the table of every combination is a
/// golden snapshot, printed with timings under `--nocapture`.
#[test]
fn corpus_files_fit() {
    let Some(root) = common::corpus() else { return };
    let root = root.as_path();
    let mut entries: Vec<_> = common::manifest(root)
        .into_iter()
        .filter(|e| e.photometric() && !e.malformed())
        .collect();
    entries.sort_by(|a, b| a.path.cmp(&b.path));
    let files: Vec<std::path::PathBuf> = entries.into_iter().map(|e| e.path).collect();
    let (mut loaded, mut skipped) = (0, 0);
    let mut table =
        String::from("file | chosen | error | spot-down | spot-up | point | point+down | point+up | down+up | ms\n");
    // The same table without timings is a golden snapshot (fits are deterministic).
    let mut snap =
        String::from("file | chosen | error | spot-down | spot-up | point | point+down | point+up | down+up\n");
    for p in &files {
        let lum = photosolid::load(p).unwrap_or_else(|e| panic!("{e}"));
        if lum.distribution().max_cd() <= 0.0 {
            skipped += 1;
            continue;
        }
        loaded += 1;
        let t = std::time::Instant::now();
        let f = fit(lum.distribution(), &FitOptions::default()).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
        let ms = t.elapsed().as_secs_f64() * 1e3;
        all_finite(&f);
        assert!(f.error().is_finite(), "{}", p.display());
        let cell = |t: &photosolid::fit::Trial| t.error.map_or("-".to_string(), |e| format!("{e:.4}"));
        let row = format!(
            "{} | {} | {:.4} | {}",
            p.strip_prefix(root).unwrap_or(p).display(),
            f.chosen().combination.name(),
            f.error(),
            f.trials.iter().map(cell).collect::<Vec<_>>().join(" | ")
        );
        table += &format!("{row} | {ms:.1}\n");
        snap += &format!("{row}\n");
    }
    eprintln!("corpus: {loaded} fitted, {skipped} not loadable\n{table}");
    assert!(loaded >= 100, "only {loaded} corpus files fitted");
    within_two_percent_of_the_recorded_errors(&snap);
    common::snapshot("fit_corpus.txt", &snap);
}

/// Issue 26 item 3: the faster search may move a fit, but no combination's error on any
/// corpus file may grow by more than 2 % (relative) over the errors recorded before it
/// (`tests/snapshots/fit_errors_2026-12-03.txt`, the table of the fit as it was on that
/// day, frozen: never regenerated). The same files, the same skipped combinations.
fn within_two_percent_of_the_recorded_errors(table: &str) {
    let rows = |t: &str| -> Vec<Vec<String>> {
        t.lines()
            .skip(1)
            .map(|l| l.split(" | ").map(str::to_string).collect())
            .collect()
    };
    let recorded = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/snapshots/fit_errors_2026-12-03.txt"),
    )
    .unwrap();
    let (before, now) = (rows(&recorded), rows(table));
    assert_eq!(before.len(), now.len(), "the corpus changed: record a new table");
    let (mut worse, mut better, mut worst) = (Vec::new(), 0, (1.0f64, String::new()));
    for (b, n) in before.iter().zip(&now) {
        assert_eq!(b[0], n[0], "the corpus changed: record a new table");
        // Columns 3.. are the combinations' errors (4 decimals, "-" when skipped).
        for (col, (x, y)) in b.iter().zip(n).enumerate().skip(3) {
            if x == "-" || y == "-" {
                assert_eq!(x, y, "{} column {col}: skipped before or now, not both", n[0]);
                continue;
            }
            let (x, y): (f64, f64) = (x.parse().unwrap(), y.parse().unwrap());
            // Half a unit of the 4th decimal: both numbers are rounded.
            if y > x * 1.02 + 1e-4 {
                worse.push(format!("{} column {col}: {x} -> {y}", n[0]));
            }
            if y < x - 1e-4 {
                better += 1;
            }
            if x > 0.0 && y / x > worst.0 {
                worst = (y / x, format!("{} column {col}: {x} -> {y}", n[0]));
            }
        }
    }
    eprintln!(
        "fit errors against the recorded table: {better} cells better, largest ratio {:.4} ({})",
        worst.0, worst.1
    );
    assert!(
        worse.is_empty(),
        "fit errors more than 2 % above the recorded table:\n{}",
        worse.join("\n")
    );
}

#[test]
fn cli_fit_reports_a_missing_file() {
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_photosolid"))
        .args([
            "fit",
            "does-not-exist.ies",
            "--max-lights",
            "1",
            "--error",
            "solid-angle",
        ])
        .output()
        .unwrap();
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("does-not-exist.ies"));
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_photosolid"))
        .args(["fit", "x.ies", "--max-lights", "3"])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2), "clap rejects --max-lights 3");
}
