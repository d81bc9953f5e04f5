//! `photosolid scene SCENE [--json] [--report DIR]` and
//! `photosolid plan SCENE [--tolerance 1%] [--json] [--report DIR]`: thin
//! layers over `photosolid::scene` (JSON keys: `scene::illuminance::SceneResult`,
//! `scene::plan::PlanResult`).

use std::path::PathBuf;

use clap::Args;
use photosolid::report::road_report::write_road_plan_report;
use photosolid::report::scene_report::{plan_text, scene_text, write_plan_report, write_scene_report};
use photosolid::scene::illuminance::evaluate;
use photosolid::scene::plan::{plan, PlanOptions};
use photosolid::scene::road::layout::Road;
use photosolid::scene::road::plan::{plan_road, road_plan_text, RoadPlan};
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
    /// Largest illuminance error allowed at any receiver point, relative to the receiver's
    /// largest illuminance: a percent with its sign (`1%`; a bare number is refused).
    #[arg(long, value_name = "PCT%", default_value = "1%", value_parser = super::parse::pct_of_peak_or_zero, allow_hyphen_values = true)]
    tolerance: super::parse::PctOfPeak,
    /// On a road: a candidate is within only when each criterion of this EN 13201-2:2015
    /// lighting class (M1-M6, C0-C5, P1-P6) passes or fails as with the reference.
    #[arg(long, value_name = "CLASS", value_parser = super::road::parse_class)]
    class: Option<photosolid::scene::road::classes::LightingClass>,
    /// Print JSON.
    #[arg(long)]
    json: bool,
    /// Write plan.json and index.html (a 3D view of each luminaire's chosen representation) into DIR.
    #[arg(long)]
    report: Option<PathBuf>,
}

pub fn run_scene(a: SceneArgs) -> anyhow::Result<i32> {
    if let Some(dir) = &a.report {
        super::check_report_dir("--report", dir)?;
    }
    let scene = Scene::load(&a.scene)?;
    let result = super::with_progress("points", |progress| evaluate(&scene, Some(progress)))?;
    if let Some(dir) = &a.report {
        // The maps and the page, as before: scene.json is not announced.
        for path in write_scene_report(dir, &scene, &result, &scene_text(&result))?
            .iter()
            .skip(1)
        {
            eprintln!("wrote {}", path.display());
        }
    }
    super::emit(a.json, &result, &scene_text(&result))?;
    for w in &result.warnings {
        eprintln!("warning: {w}");
    }
    Ok(0)
}

pub fn run_plan(a: PlanArgs) -> anyhow::Result<i32> {
    if let Some(dir) = &a.report {
        super::check_report_dir("--report", dir)?;
    }
    if let Some(road) = Road::load_if_road(&a.scene)? {
        let result = super::with_progress("candidates", |progress| {
            plan_road(&road, a.tolerance.fraction(), a.class.as_ref(), Some(progress))
        });
        return write_road_plan(&a, &result?);
    }
    if let Some(class) = &a.class {
        return Err(super::UsageError(format!(
            "--class {}: {} has no [road] table, and lighting classes judge roads (docs/road.md)",
            class.name,
            a.scene.display()
        ))
        .into());
    }
    let scene = Scene::load(&a.scene)?;
    let options = PlanOptions {
        tolerance: a.tolerance.fraction(),
        ..PlanOptions::default()
    };
    let result = super::with_progress("steps", |progress| plan(&scene, &options, Some(progress)))?;
    if let Some(dir) = &a.report {
        for path in write_plan_report(dir, &scene, &result, &plan_text(&result))?
            .iter()
            .skip(1)
        {
            eprintln!("wrote {}", path.display());
        }
    }
    super::emit(a.json, &result, &plan_text(&result))?;
    Ok(0)
}

/// The output of `plan` on a `[road]` file (the road quantities decide; docs/road.md).
fn write_road_plan(a: &PlanArgs, result: &RoadPlan) -> anyhow::Result<i32> {
    let text = road_plan_text(result);
    if let Some(dir) = &a.report {
        for path in write_road_plan_report(dir, result, &text)? {
            eprintln!("wrote {}", path.display());
        }
    }
    super::emit(a.json, result, &text)?;
    Ok(0)
}
