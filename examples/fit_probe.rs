use photosolid::fit::*;
use std::time::Instant;
fn main() {
    let c5: Vec<f64> = (0..72).map(|k| k as f64 * 5.0).collect();
    let g25: Vec<f64> = (0..=72).map(|k| k as f64 * 2.5).collect();
    let m = FittedLights::new(vec![
        Light::Spot(Spot {
            hemisphere: Hemisphere::Down,
            weight_cd: 1000.0,
            exponent: 30.0,
            cutoff_deg: 20.0,
            tilt_deg: 40.0,
            azimuth_deg: 300.0,
        }),
        Light::Point { weight_cd: 80.0 },
    ]);
    let d = m.sample(&c5, &g25).unwrap();
    let t = Instant::now();
    let f = fit(
        &d,
        &FitOptions {
            parallel: false,
            ..Default::default()
        },
    )
    .unwrap();
    let el = t.elapsed();
    print!(
        "{}",
        FitReport::of(&f)
            .to_text()
            .lines()
            .filter(|l| !l.starts_with("      "))
            .collect::<Vec<_>>()
            .join("\n")
    );
    let ev: usize = f.trials.iter().map(|t| t.evaluations).sum();
    println!(
        "\n{:?} total evals {} -> {:.1} us/eval",
        el,
        ev,
        el.as_secs_f64() * 1e6 / ev as f64
    );
}
