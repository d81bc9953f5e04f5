//! `photosolid scene SCENE [--json] [--report DIR]` and
//! `photosolid plan SCENE [--tolerance 1%] [--json] [--report DIR]`: thin
//! layers over `photosolid::scene` (JSON keys: `scene::illuminance::SceneResult`,
//! `scene::plan::PlanResult`).

use std::io::IsTerminal;
use std::path::{Path, PathBuf};

use clap::Args;
use photosolid::scene::illuminance::{evaluate, SceneResult};
use photosolid::scene::plan::{plan, PlanOptions, PlanResult};
use photosolid::scene::Scene;

#[derive(Args, Debug)]
pub struct SceneArgs {
    /// A scene file (TOML; see docs/scene.md).
    scene: PathBuf,
    /// Print JSON.
    #[arg(long)]
    json: bool,
    /// Write scene.json, an isolux map per plane receiver (PNG) and index.html (with a 3D view per luminaire) into DIR.
    #[arg(long)]
    report: Option<PathBuf>,
}

#[derive(Args, Debug)]
pub struct PlanArgs {
    /// A scene file (TOML; see docs/scene.md).
    scene: PathBuf,
    /// Largest illuminance error allowed at any receiver point: `1%` or a fraction (`0.01`).
    #[arg(long, default_value = "1%", value_parser = parse_tolerance)]
    tolerance: f64,
    /// Print JSON.
    #[arg(long)]
    json: bool,
    /// Write plan.json and index.html (a 3D view of each luminaire's chosen representation) into DIR.
    #[arg(long)]
    report: Option<PathBuf>,
}

/// `1%` → 0.01, `0.01` → 0.01.
fn parse_tolerance(s: &str) -> Result<f64, String> {
    let t = s.trim();
    let v = match t.strip_suffix('%') {
        Some(p) => p.trim().parse::<f64>().map(|x| x / 100.0),
        None => t.parse::<f64>(),
    }
    .map_err(|_| format!("expected a percentage such as 1% or a fraction such as 0.01, got {s:?}"))?;
    if v.is_finite() && v >= 0.0 {
        Ok(v)
    } else {
        Err(format!("expected a tolerance >= 0, got {s:?}"))
    }
}

/// Print the scene result as text.
pub fn scene_text(r: &SceneResult) -> String {
    use std::fmt::Write;
    let mut s = format!("scene {}\n", r.scene);
    for l in &r.luminaires {
        let ff = &l.far_field;
        let _ = writeln!(
            s,
            "luminaire {:?}: {}, {} source ({} patches{}), {} bytes; point-source error max {:.3} % (largest \
             dimension {:.3} m, under 1 % from {} x it, five-times rule {})",
            l.name,
            l.representation,
            l.source,
            l.area.patches,
            if l.area.converged { "" } else { ", NOT converged" },
            l.bytes,
            ff.max_error_pct,
            ff.largest_dimension_m,
            ff.ratio_under_1pct.map_or("-".into(), |x| format!("{x:.2}")),
            if ff.five_times_rule_holds { "holds" } else { "fails" }
        );
    }
    let _ = writeln!(
        s,
        "{:<16} {:>6} {:>7} {:>11} {:>11} {:>11} {:>7} {:>9}",
        "receiver", "kind", "points", "Eavg lx", "Emin lx", "Emax lx", "U0", "Emin/Emax"
    );
    let opt = |x: Option<f64>| x.map_or("-".into(), |v| format!("{v:.3}"));
    for rc in &r.receivers {
        let _ = writeln!(
            s,
            "{:<16} {:>6} {:>7} {:>11.3} {:>11.3} {:>11.3} {:>7} {:>9}",
            rc.name,
            rc.kind,
            rc.points.len(),
            rc.e_avg_lux,
            rc.e_min_lux,
            rc.e_max_lux,
            opt(rc.u0),
            opt(rc.emin_emax)
        );
    }
    s
}

/// Print the plan as text.
pub fn plan_text(p: &PlanResult) -> String {
    use std::fmt::Write;
    let mut s = format!("plan for {} (tolerance {} %)\n", p.scene, p.tolerance_pct);
    for l in &p.luminaires {
        let _ = writeln!(
            s,
            "luminaire {:?}: chosen {} — {} bytes, {:.1} ns/eval, error max {:.4} % mean {:.4} % (measured on the \
             scene against {}); far field ok: {}; {} candidates, {} rejected",
            l.name,
            l.chosen,
            l.bytes,
            l.ns_per_eval,
            l.max_error_pct,
            l.mean_error_pct,
            l.reference,
            l.far_field_ok,
            l.candidates,
            l.rejected.len()
        );
        for c in &l.rejected {
            let _ = writeln!(
                s,
                "  rejected {:<42} {:<5} {:>9} B {:>10.1} ns  max {:>9.4} %  mean {:>9.4} %",
                c.representation,
                c.source.to_string(),
                c.bytes,
                c.ns_per_eval,
                c.max_error_pct,
                c.mean_error_pct
            );
        }
        for u in &l.unavailable {
            let _ = writeln!(s, "  unavailable {}: {}", u.representation, u.reason);
        }
    }
    let _ = writeln!(
        s,
        "every chosen representation at once: error max {:.4} % mean {:.4} %",
        p.combined_max_error_pct, p.combined_mean_error_pct
    );
    s
}

fn write_json(dir: &Path, name: &str, value: &impl serde::Serialize) -> anyhow::Result<()> {
    std::fs::create_dir_all(dir).map_err(|e| anyhow::anyhow!("{}: {e}", dir.display()))?;
    let path = dir.join(name);
    std::fs::write(&path, serde_json::to_string_pretty(value)? + "\n")
        .map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
    Ok(())
}

pub fn run_scene(a: SceneArgs) -> anyhow::Result<i32> {
    let scene = Scene::load(&a.scene)?;
    let work = (scene.points().len() * scene.luminaires.len()) as u64;
    let bar = (std::io::stderr().is_terminal() && work > 20_000).then(|| indicatif::ProgressBar::new(work));
    let tick = |n: u64| {
        if let Some(b) = &bar {
            b.inc(n)
        }
    };
    let result = evaluate(&scene, Some(&tick))?;
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    if let Some(dir) = &a.report {
        write_json(dir, "scene.json", &result)?;
        let mut maps = Vec::new();
        for path in photosolid::scene::isolux::write_maps(&scene, &result, dir)? {
            eprintln!("wrote {}", path.display());
            let name = path
                .file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default();
            maps.push((name, std::fs::read(&path)?));
        }
        let html =
            photosolid::report::scene_report::to_html("Scene: illuminance", &scene, &scene_text(&result), &maps, &[])?;
        write_index(dir, &html)?;
    }
    super::emit(a.json, &result, &scene_text(&result))?;
    Ok(0)
}

pub fn run_plan(a: PlanArgs) -> anyhow::Result<i32> {
    let scene = Scene::load(&a.scene)?;
    let bar = std::io::stderr()
        .is_terminal()
        .then(indicatif::ProgressBar::new_spinner);
    let say = |m: &str| {
        if let Some(b) = &bar {
            b.set_message(m.to_string());
            b.tick();
        }
    };
    let options = PlanOptions {
        tolerance: a.tolerance,
        ..PlanOptions::default()
    };
    let result = plan(&scene, &options, Some(&say))?;
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    if let Some(dir) = &a.report {
        write_json(dir, "plan.json", &result)?;
        // The chosen representation of each luminaire (plan rows are named as the scene's luminaires).
        let chosen: Vec<Option<photosolid::scene::plan::Representation>> = scene
            .luminaires
            .iter()
            .map(|l| {
                result
                    .luminaires
                    .iter()
                    .find(|p| p.name == l.name)
                    .map(|p| p.chosen_spec.clone())
            })
            .collect();
        let html = photosolid::report::scene_report::to_html("Scene: plan", &scene, &plan_text(&result), &[], &chosen)?;
        write_index(dir, &html)?;
    }
    super::emit(a.json, &result, &plan_text(&result))?;
    Ok(0)
}

/// Write `index.html` into `dir` atomically and say so.
fn write_index(dir: &Path, html: &str) -> anyhow::Result<()> {
    let path = dir.join("index.html");
    photosolid::formats::write_atomic(&path, html.as_bytes())?;
    eprintln!("wrote {}", path.display());
    Ok(())
}
