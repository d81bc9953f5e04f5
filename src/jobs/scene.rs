//! The jobs of `scene` and `plan`: a scene's illuminances, and the cheapest
//! representation of each luminaire within a tolerance of them.

use std::path::Path;

use serde::Serialize;

use crate::model::Progress;
use crate::numfmt::PctOfPeak;
use crate::registry::Registry;
use crate::scene::illuminance::{evaluate, SceneResult};
use crate::scene::plan::{plan as plan_scene, PlanOptions, PlanResult};
use crate::scene::road::classes::LightingClass;
use crate::scene::road::layout::Road;
use crate::scene::road::plan::{plan_road, RoadPlan};
use crate::scene::road::RoadError;
use crate::scene::Scene;

/// `photosolid scene SCENE`: the result `scene --json` prints.
pub fn scene(path: &Path, progress: Option<&Progress<'_>>) -> crate::Result<SceneResult> {
    let scene = Scene::load(path)?;
    Ok(evaluate(&scene, progress)?)
}

/// The options of `plan` (the CLI's flags).
#[derive(Clone, Debug)]
pub struct PlanSettings {
    /// `--tolerance`: the largest illuminance error at any receiver point, a
    /// percent of the receiver's largest illuminance. Default 1%.
    pub tolerance: PctOfPeak,
    /// `--class`: on a road, a candidate is within only when each criterion
    /// of the class passes or fails as with the reference.
    pub class: Option<LightingClass>,
    /// The representations offered beyond the built-in ones (the CLI's: none).
    pub registry: Registry,
}

impl Default for PlanSettings {
    fn default() -> Self {
        Self {
            tolerance: PctOfPeak(1.0),
            class: None,
            registry: Registry::default(),
        }
    }
}

/// What `plan` answers: a scene's plan, or a road's (decided by the road quantities).
#[derive(Debug, Serialize)]
#[serde(untagged)]
pub enum PlanAnswer {
    /// A scene file with luminaires and receivers.
    Scene(Box<PlanResult>),
    /// A scene file with a `[road]` table.
    Road(Box<RoadPlan>),
}

/// An error of a job over scenes and roads: the library's or the road's.
#[derive(Debug, thiserror::Error)]
pub enum JobError {
    /// The library's error.
    #[error(transparent)]
    Library(#[from] crate::Error),
    /// The road's error.
    #[error(transparent)]
    Road(#[from] RoadError),
}

impl JobError {
    /// The stable code ([`crate::error::ERROR_CODES`] or [`RoadError::code`]).
    pub fn code(&self) -> &'static str {
        match self {
            JobError::Library(e) => e.code(),
            JobError::Road(e) => e.code(),
        }
    }
}

/// `photosolid plan SCENE`: the plan `plan --json` prints; the scene and
/// its road both loaded here.
pub fn plan(path: &Path, settings: &PlanSettings, progress: Option<&Progress<'_>>) -> Result<PlanAnswer, JobError> {
    if let Some(road) = Road::load_if_road(path)? {
        let planned = plan_road(
            &road,
            settings.tolerance.fraction(),
            settings.class.as_ref(),
            &settings.registry,
            progress,
        )?;
        return Ok(PlanAnswer::Road(Box::new(planned)));
    }
    if let Some(class) = &settings.class {
        return Err(RoadError::Option {
            option: format!("--class {}", class.name),
            message: format!(
                "{} has no [road] table, and lighting classes judge roads (docs/road.md)",
                path.display()
            ),
        }
        .into());
    }
    let scene = Scene::load(path)?;
    let options = PlanOptions {
        tolerance: settings.tolerance.fraction(),
        registry: settings.registry.clone(),
        ..PlanOptions::default()
    };
    Ok(PlanAnswer::Scene(Box::new(plan_scene(&scene, &options, progress)?)))
}
