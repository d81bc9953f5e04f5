//! `photosolid scene SCENE [--json] [--report DIR]` and
//! `photosolid plan SCENE [--tolerance 1%] [--json] [--report DIR]`: thin
//! layers over `photosolid::scene` (JSON keys: `scene::illuminance::SceneResult`,
//! `scene::plan::PlanResult`).

use std::path::PathBuf;

use clap::Args;
use photosolid::jobs::{self, PlanAnswer, PlanSettings};
use photosolid::report::road_report::write_road_plan_report;
use photosolid::report::scene_report::{plan_text, scene_text, write_plan_report, write_scene_report};
use photosolid::scene::road::plan::road_plan_text;
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
    let result = super::with_progress("points", |progress| jobs::scene(&a.scene, Some(progress)))?;
    if let Some(dir) = &a.report {
        let scene = Scene::load(&a.scene)?;
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
    let settings = PlanSettings {
        tolerance: a.tolerance,
        class: a.class.clone(),
        // The command line offers the built-in representations.
        registry: photosolid::registry::Registry::builtin(),
    };
    let answer = super::with_progress("candidates", |progress| jobs::plan(&a.scene, &settings, Some(progress)))?;
    let text = match &answer {
        PlanAnswer::Road(result) => road_plan_text(result),
        PlanAnswer::Scene(result) => plan_text(result),
    };
    if let Some(dir) = &a.report {
        let written = match &answer {
            PlanAnswer::Road(result) => write_road_plan_report(dir, result, &text)?,
            // The page shows each luminaire's chosen representation: the scene is read again.
            PlanAnswer::Scene(result) => write_plan_report(dir, &Scene::load(&a.scene)?, result, &text)?
                .into_iter()
                .skip(1)
                .collect(),
        };
        for path in written {
            eprintln!("wrote {}", path.display());
        }
    }
    super::emit(a.json, &answer, &text)?;
    Ok(0)
}
