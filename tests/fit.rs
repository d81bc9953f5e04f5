//! Fitted OpenGL lights (Zotti et al. 2005): recovery of known lights from
//! synthetic data, extremes, honest failures, and the corpus table.

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
        .intensities()
        .iter()
        .map(|v| v * (1.0 + sigma * n.gauss()).max(0.0))
        .collect();
    Distribution::new(d.c_angles().to_vec(), d.gamma_angles().to_vec(), cd, d.symmetry()).unwrap()
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
        assert!(
            dw <= tol.weight_rel,
            "{what}: weight {} vs {}\n{table}",
            b.weight_cd(),
            a.weight_cd()
        );
        if let (Light::Spot(a), Light::Spot(b)) = (a, b) {
            let dp = (a.exponent - b.exponent).abs() / a.exponent.max(1.0);
            let dc = (a.cutoff_deg - b.cutoff_deg).abs();
            let dx = angle_between(a.axis(), b.axis());
            worst[0] = worst[0].max(dp);
            worst[1] = worst[1].max(dc);
            worst[2] = worst[2].max(dx);
            assert!(
                dp <= tol.exponent_rel,
                "{what}: exponent {} vs {}\n{table}",
                b.exponent,
                a.exponent
            );
            assert!(
                dc <= tol.cutoff_deg,
                "{what}: cut-off {} vs {}\n{table}",
                b.cutoff_deg,
                a.cutoff_deg
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
