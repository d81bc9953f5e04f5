//! `plan` on a road: the cheapest representation of the road's luminaire
//! that keeps every road quantity within its limit of the reference.
//!
//! A road has one luminaire file, so the plan has one choice. Every candidate
//! of [`crate::plan`] (filters on the native grid, the trade table's
//! textures, the fitted lights, a re-stored symmetry) is put into the road
//! and the whole road is computed again ([`evaluate`]); a candidate is within
//! when, against the reference (Catmull-Rom on the native grid):
//! - L_av of every observer lane and E_av of the field change by at most the
//!   relative tolerance,
//! - U_o and U_l of every lane by at most [`UNIFORMITY_LIMIT`] (absolute),
//! - TI of every lane by at most [`TI_LIMIT_PP`] percentage points;
//! - with a lighting class (`plan --class`), every criterion's verdict
//!   (pass or fail) equals the reference's.
//!
//! The cheapest is the fewest bytes, then the fewest ns per evaluation.

use serde::Serialize;

use super::classes::{ClassVerdict, LightingClass};
use super::layout::Road;
use super::quantities::{evaluate, Overall, RoadOptions, RoadResult};
use super::RoadError;
use crate::metrics::{random_directions, time_per_sample_ns};
use crate::model::{IntensityField, Progress};
use crate::plan::{candidate_representations, Models, Recon, REFERENCE};
use crate::registry::Registry;

/// Largest change of U_o or U_l a candidate may make (absolute).
pub const UNIFORMITY_LIMIT: f64 = 0.01;
/// Largest change of TI a candidate may make, percentage points.
pub const TI_LIMIT_PP: f64 = 0.5;

/// How far one candidate moves each road quantity from the reference: the
/// largest change over the observer lanes (signed: the candidate's value
/// minus the reference's, at the lane where the magnitude is largest).
#[derive(Debug, Clone, Serialize)]
pub struct RoadCandidate {
    /// The representation (as `scene` and `road` accept it).
    pub representation: String,
    /// Bytes held by its field.
    pub bytes: usize,
    /// Time per intensity evaluation on one thread, ns.
    pub ns_per_eval: f64,
    /// L_av change, % of the reference's L_av of that lane.
    pub l_av_change_pct: f64,
    /// E_av change, % of the reference's E_av.
    pub e_av_change_pct: f64,
    /// U_o change (absolute).
    pub u_o_change: f64,
    /// U_l change (absolute).
    pub u_l_change: f64,
    /// TI change, percentage points.
    pub ti_change_pp: f64,
    /// With a class: whether each criterion's verdict (pass or fail) is the reference's.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub verdicts_match: Option<bool>,
    /// With a class: whether the class passes with this candidate.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub class_pass: Option<bool>,
    /// Whether every change is within its limit (and, with a class, the verdicts match).
    pub within: bool,
    /// The candidate's installation values.
    pub overall: Overall,
}

/// The plan of a road (JSON of `photosolid plan` on a `[road]` file).
#[derive(Debug, Clone, Serialize)]
pub struct RoadPlan {
    /// The scene file.
    pub scene: String,
    /// The photometric file.
    pub luminaire: String,
    /// The reference every candidate is measured against.
    pub reference: String,
    /// Relative tolerance on L_av and E_av, %.
    pub tolerance_pct: f64,
    /// Absolute tolerance on U_o and U_l.
    pub uniformity_limit: f64,
    /// Tolerance on TI, percentage points.
    pub ti_limit_pp: f64,
    /// The lighting class whose verdicts a candidate must keep (`plan --class`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub class: Option<&'static str>,
    /// The reference's verdict against that class.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reference_verdict: Option<super::classes::ClassVerdict>,
    /// The chosen (cheapest within) representation.
    pub chosen: String,
    /// Its bytes.
    pub bytes: usize,
    /// The reference's installation values.
    pub reference_overall: Overall,
    /// Every candidate, cheapest first.
    pub candidates: Vec<RoadCandidate>,
    /// Candidates that could not be built, and why.
    pub unavailable: Vec<crate::plan::Unavailable>,
    /// The reference calculation's warnings, coded (docs/warnings.md).
    pub warnings: Vec<crate::error::Warning>,
}

/// Signed change of largest magnitude over the lanes.
fn largest(changes: impl Iterator<Item = f64>) -> f64 {
    changes.fold(0.0, |a: f64, b| if b.abs() > a.abs() { b } else { a })
}

fn relative_pct(value: f64, reference: f64) -> f64 {
    if reference > 0.0 {
        100.0 * (value - reference) / reference
    } else if value > 0.0 {
        100.0
    } else {
        0.0
    }
}

fn compare(candidate: &RoadResult, reference: &RoadResult) -> [f64; 5] {
    let pairs = || candidate.lanes.iter().zip(&reference.lanes);
    [
        largest(pairs().map(|(c, r)| relative_pct(c.l_av_cd_m2, r.l_av_cd_m2))),
        relative_pct(candidate.overall.e_av_lux, reference.overall.e_av_lux),
        largest(pairs().map(|(c, r)| c.u_o - r.u_o)),
        largest(pairs().map(|(c, r)| c.u_l - r.u_l)),
        largest(pairs().map(|(c, r)| c.ti_pct - r.ti_pct)),
    ]
}

/// The road computed again with `rep` (whose field is `field`), compared with `reference`.
fn measure(
    road: &Road,
    rep: Recon,
    field: &dyn IntensityField,
    dirs: &[glam::DVec3],
    reference: &RoadResult,
    tolerance: f64,
    class: Option<(&LightingClass, &ClassVerdict)>,
) -> Result<RoadCandidate, RoadError> {
    let mut with = road.clone();
    with.representation = Some(rep);
    let result = evaluate(&with, &RoadOptions::default())?;
    let [l, e, uo, ul, ti] = compare(&result, reference);
    let verdict = class.map(|(c, _)| c.verdict(&result.overall));
    let verdicts_match = class
        .zip(verdict.as_ref())
        .map(|((_, r), v)| r.criteria.iter().zip(&v.criteria).all(|(a, b)| a.pass == b.pass));
    let within = l.abs() <= 100.0 * tolerance
        && e.abs() <= 100.0 * tolerance
        && uo.abs() <= UNIFORMITY_LIMIT
        && ul.abs() <= UNIFORMITY_LIMIT
        && ti.abs() <= TI_LIMIT_PP
        && verdicts_match != Some(false);
    Ok(RoadCandidate {
        representation: rep.to_string(),
        bytes: field.bytes(),
        ns_per_eval: time_per_sample_ns(field, dirs, 3),
        l_av_change_pct: l,
        e_av_change_pct: e,
        u_o_change: uo,
        u_l_change: ul,
        ti_change_pp: ti,
        verdicts_match,
        class_pass: verdict.map(|v| v.pass),
        within,
        overall: result.overall,
    })
}

/// The road computed with the reference representation and, with a class, its verdict.
fn reference_of(road: &Road, class: Option<&LightingClass>) -> Result<(RoadResult, Option<ClassVerdict>), RoadError> {
    let mut base = road.clone();
    base.representation = None;
    Ok(match class {
        Some(c) => {
            let judged = super::design::judge(&base, c, &RoadOptions::default())?;
            (judged.result, Some(judged.verdict))
        }
        None => (evaluate(&base, &RoadOptions::default())?, None),
    })
}

/// Plan `road` with the relative `tolerance` (a fraction: 0.01 = 1 %) on
/// L_av and E_av; with a `class`, a candidate must also keep every
/// criterion's verdict of the reference. `progress(done, candidates, "road:
/// CANDIDATE")` is called before each candidate.
///
/// # Errors
/// [`RoadError::Invalid`] for a tolerance that is not a finite fraction
/// ≥ 0; any error of [`evaluate`] on the reference, or of
/// [`super::design::judge`] when the class cannot be judged.
pub fn plan_road(
    road: &Road,
    tolerance: f64,
    class: Option<&LightingClass>,
    registry: &Registry,
    progress: Option<&Progress<'_>>,
) -> Result<RoadPlan, RoadError> {
    if !(tolerance.is_finite() && tolerance >= 0.0) {
        return Err(RoadError::Invalid {
            key: "tolerance",
            reason: format!("expected a finite fraction >= 0, found {tolerance}"),
        });
    }
    let (reference, reference_verdict) = reference_of(road, class)?;
    let judged_by = class.zip(reference_verdict.as_ref());
    let template = road.scene_luminaire("road luminaire", road.luminaires(0.0, 0.0)[0].pose);
    let texture = template.texture().map_err(|e| RoadError::Luminaire {
        file: road.file.clone(),
        message: e.to_string(),
    })?;
    let reps = if texture.is_some() {
        candidate_representations(&template, None, registry)
    } else {
        vec![REFERENCE]
    };
    let models = Models::new(&template, &reps).map_err(|e| RoadError::Luminaire {
        file: road.file.clone(),
        message: e.to_string(),
    })?;
    let dirs = random_directions(4096, 0x20AD);
    let mut candidates = Vec::new();
    let mut unavailable = Vec::new();
    let n = reps.len();
    for (k, rep) in reps.into_iter().enumerate() {
        if let Some(say) = progress {
            say(k, n, &format!("road: {rep}"));
        }
        match models.field(&rep) {
            Ok(field) => candidates.push(measure(road, rep, &*field, &dirs, &reference, tolerance, judged_by)?),
            Err(e) => unavailable.push(crate::plan::Unavailable {
                representation: rep.to_string(),
                reason: e.to_string(),
            }),
        }
    }
    candidates.sort_by(|a, b| a.bytes.cmp(&b.bytes).then(a.ns_per_eval.total_cmp(&b.ns_per_eval)));
    // The reference is always a candidate and always within (all changes 0);
    // no candidate within would mean it failed to build: say so, invent nothing.
    let chosen = candidates
        .iter()
        .find(|c| c.within)
        .map(|c| (c.representation.clone(), c.bytes))
        .ok_or_else(|| RoadError::Luminaire {
            file: road.file.clone(),
            message: format!(
                "no representation is within the limits, not even the reference ({})",
                unavailable
                    .iter()
                    .map(|u| format!("{}: {}", u.representation, u.reason))
                    .collect::<Vec<_>>()
                    .join("; ")
            ),
        })?;
    Ok(RoadPlan {
        scene: reference.scene.clone(),
        luminaire: reference.luminaire.clone(),
        reference: REFERENCE.to_string(),
        tolerance_pct: 100.0 * tolerance,
        uniformity_limit: UNIFORMITY_LIMIT,
        ti_limit_pp: TI_LIMIT_PP,
        class: class.map(|c| c.name),
        reference_verdict,
        chosen: chosen.0,
        bytes: chosen.1,
        reference_overall: reference.overall,
        candidates,
        unavailable,
        warnings: reference.warnings.clone(),
    })
}

/// The text summary of a road plan.
pub fn road_plan_text(p: &RoadPlan) -> String {
    use std::fmt::Write;
    let mut s = String::new();
    let _ = writeln!(
        s,
        "road plan: {} ({}), reference {}; limits: L_av and E_av {} %, U_o and U_l {}, TI {} pp",
        p.scene, p.luminaire, p.reference, p.tolerance_pct, p.uniformity_limit, p.ti_limit_pp
    );
    if let (Some(class), Some(v)) = (p.class, &p.reference_verdict) {
        let _ = writeln!(
            s,
            "class {class}: the reference {}; a candidate is within only when every criterion's verdict is the reference's",
            if v.pass { "passes" } else { "fails" }
        );
    }
    let _ = writeln!(s, "chosen: {} ({} bytes)", p.chosen, p.bytes);
    let _ = writeln!(
        s,
        "{:<44} {:>9} {:>8} {:>9} {:>9} {:>8} {:>8} {:>8}  within",
        "representation", "bytes", "ns", "L_av %", "E_av %", "U_o", "U_l", "TI pp"
    );
    for c in &p.candidates {
        let _ = writeln!(
            s,
            "{:<44} {:>9} {:>8.1} {:>+9.3} {:>+9.3} {:>+8.4} {:>+8.4} {:>+8.3}  {}",
            c.representation,
            c.bytes,
            c.ns_per_eval,
            c.l_av_change_pct,
            c.e_av_change_pct,
            c.u_o_change,
            c.u_l_change,
            c.ti_change_pp,
            match (c.within, c.verdicts_match) {
                (true, _) => "yes",
                (false, Some(false)) => "no (class verdict changes)",
                (false, _) => "no",
            }
        );
    }
    for u in &p.unavailable {
        let _ = writeln!(s, "unavailable: {}: {}", u.representation, u.reason);
    }
    s
}
