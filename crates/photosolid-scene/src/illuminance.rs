//! Illuminance at the receiver points: `E = Σ MF · I(d) · cos(incidence) / r²`.
//!
//! `d` is the direction from the light (the photometric centre, or a patch
//! of the opening) to the point, expressed in the luminaire frame after
//! undoing the aim ([`Pose::to_local`]); `I(d)` comes from any
//! [`IntensityField`]. Light arriving from behind a receiver (cos ≤ 0) or
//! blocked by an occluder counts 0. Points run in parallel (rayon).
//!
//! Relative differences between two illuminance sets (the far-field error,
//! a representation's error) divide by the reference value at the point,
//! floored at 1e-3 of the receiver's largest reference value: a point a
//! thousand times darker than the brightest point of its receiver is judged
//! in lux relative to that floor, so darkness cannot demand infinite
//! precision. Where a whole receiver is dark the floor is 0: equal values
//! differ by 0, and light where the reference has none counts as 100 %.

use std::sync::atomic::{AtomicUsize, Ordering};

use glam::DVec3;
use rayon::prelude::*;
use serde::Serialize;

use super::aim::Pose;
use super::representation::{Models, REFERENCE};
use super::{Occluder, Receiver, ReceiverShape, Scene, SceneError, SceneLuminaire, ScenePoint, SourceKind};
use crate::model::{IntensityField, Progress};

/// Most patches an area source is refined to.
pub const MAX_PATCHES: usize = 65_536;

/// The area source is refined (patch count × 4) until no point's
/// illuminance changes by more than this, relatively (see the module docs).
pub const AREA_CONVERGENCE: f64 = 1e-4;

/// Points lit less than this fraction of their receiver's brightest point
/// are compared against that floor (module docs).
pub const DARK_FLOOR: f64 = 1e-3;

/// A luminaire as a light source: a field, a pose, a maintenance factor and
/// where on the opening the light leaves (one patch at the centre for a point source).
pub struct Source<'a> {
    /// The intensity distribution (cd), luminaire frame.
    pub field: &'a dyn IntensityField,
    /// Where the luminaire hangs and how it is aimed.
    pub pose: Pose,
    /// Maintenance factor.
    pub maintenance_factor: f64,
    /// Patch centres (luminaire frame, m) and their shares of the intensity (sum 1).
    pub patches: Vec<(DVec3, f64)>,
}

impl<'a> Source<'a> {
    /// `lum`'s pose and maintenance factor with `field` emitted from `patches`.
    pub fn with_patches(field: &'a dyn IntensityField, lum: &SceneLuminaire, patches: Vec<(DVec3, f64)>) -> Self {
        Self {
            field,
            pose: lum.pose,
            maintenance_factor: lum.maintenance_factor,
            patches,
        }
    }

    /// `lum` as a point source of `field`: one patch at the photometric centre.
    pub fn point(field: &'a dyn IntensityField, lum: &SceneLuminaire) -> Self {
        Self::with_patches(field, lum, vec![(DVec3::ZERO, 1.0)])
    }

    /// Illuminance (lx) at one point.
    pub fn lux(&self, p: &ScenePoint, occluders: &[Occluder]) -> f64 {
        let mut e = 0.0;
        for &(local, share) in &self.patches {
            let from = self.pose.point_to_world(local);
            let v = p.position - from;
            let r2 = v.length_squared();
            if r2 == 0.0 || !r2.is_finite() {
                continue;
            }
            let cos_i = -p.normal.dot(v) / r2.sqrt();
            if cos_i <= 0.0 || occluders.iter().any(|o| o.blocks(from, p.position)) {
                continue;
            }
            let i = self.field.intensity_dir_cd(self.pose.to_local(v));
            e += share * i * cos_i / r2;
        }
        let e = e * self.maintenance_factor;
        if e.is_finite() {
            e.max(0.0)
        } else {
            0.0
        }
    }

    /// Illuminance (lx) at every point, in parallel; `progress(done, points,
    /// "illuminance")` is called after each point, from the worker threads.
    pub fn lux_all(&self, points: &[ScenePoint], occluders: &[Occluder], progress: Option<&Progress<'_>>) -> Vec<f64> {
        let done = AtomicUsize::new(0);
        points
            .par_iter()
            .map(|p| {
                let e = self.lux(p, occluders);
                if let Some(f) = progress {
                    f(done.fetch_add(1, Ordering::Relaxed) + 1, points.len(), "illuminance");
                }
                e
            })
            .collect()
    }
}

/// How far an area source was refined.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct AreaRefinement {
    /// Subdivision level n of [`super::opening::Opening::patches`].
    pub n: usize,
    /// Number of patches.
    pub patches: usize,
    /// Largest relative change (%) of a point's illuminance at the last refinement.
    pub last_change_pct: f64,
    /// Whether the change fell under [`AREA_CONVERGENCE`] before [`MAX_PATCHES`].
    pub converged: bool,
}

/// Relative difference (fraction) of `a` against the reference `b` at each
/// point, per the module docs (floors per receiver).
pub fn relative_errors(a: &[f64], b: &[f64], points: &[ScenePoint]) -> Vec<f64> {
    let floors = receiver_floors(points, b);
    points
        .iter()
        .zip(a.iter().zip(b))
        .map(|(p, (&x, &r))| {
            let d = (x - r).abs();
            let den = r.max(floors[p.receiver]);
            if d == 0.0 {
                0.0
            } else if den > 0.0 {
                d / den
            } else {
                1.0
            }
        })
        .collect()
}

/// Largest and mean of [`relative_errors`] (fractions; 0 for no points).
pub fn relative_difference(a: &[f64], b: &[f64], points: &[ScenePoint]) -> (f64, f64) {
    let e = relative_errors(a, b, points);
    let max = e.iter().copied().fold(0.0, f64::max);
    (
        max,
        if e.is_empty() {
            0.0
        } else {
            e.iter().sum::<f64>() / e.len() as f64
        },
    )
}

/// The directional area source of `lum` with `field`, refined until the
/// illuminance at `points` converges: the source, its values (lx) and the refinement.
pub fn area_source<'a>(
    field: &'a dyn IntensityField,
    lum: &SceneLuminaire,
    points: &[ScenePoint],
    occluders: &[Occluder],
) -> (Source<'a>, Vec<f64>, AreaRefinement) {
    let make = |n: usize| Source::with_patches(field, lum, lum.opening.patches(n));
    let mut n = 1;
    let mut src = make(n);
    let mut values = src.lux_all(points, occluders, None);
    let mut change = 0.0;
    if !lum.opening.is_point() {
        loop {
            let next = make(2 * n);
            if next.patches.len() > MAX_PATCHES {
                break;
            }
            let next_values = next.lux_all(points, occluders, None);
            change = relative_difference(&values, &next_values, points).0;
            n *= 2;
            src = next;
            values = next_values;
            if change <= AREA_CONVERGENCE {
                break;
            }
        }
    }
    let r = AreaRefinement {
        n,
        patches: src.patches.len(),
        last_change_pct: 100.0 * change,
        converged: change <= AREA_CONVERGENCE,
    };
    (src, values, r)
}

/// The point-source assumption checked on the scene (the five-times rule, measured).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct FarField {
    /// Largest luminous dimension, m (0: a point opening, the point form is exact).
    pub largest_dimension_m: f64,
    /// Largest error (%) of the point source against the area source over the scene's points.
    pub max_error_pct: f64,
    /// Mean error (%).
    pub mean_error_pct: f64,
    /// Smallest distance / largest dimension over the points (null for a point opening).
    pub min_distance_ratio: Option<f64>,
    /// The distance ratio from which on every point of the scene has an
    /// error under 1 % (null when even the farthest point fails, or for a point opening).
    pub ratio_under_1pct: Option<f64>,
    /// Whether every point at 5 or more luminaire sizes has an error under 1 %.
    pub five_times_rule_holds: bool,
}

impl FarField {
    /// Compare the point-source values with the area-source values (both lx, same points).
    pub fn measure(lum: &SceneLuminaire, points: &[ScenePoint], point_lux: &[f64], area_lux: &[f64]) -> FarField {
        let size = lum.opening.largest_dimension_m();
        let per_point = relative_errors(point_lux, area_lux, points);
        let max = per_point.iter().copied().fold(0.0, f64::max);
        let mean = if per_point.is_empty() {
            0.0
        } else {
            per_point.iter().sum::<f64>() / per_point.len() as f64
        };
        if size == 0.0 {
            return FarField {
                largest_dimension_m: 0.0,
                max_error_pct: 100.0 * max,
                mean_error_pct: 100.0 * mean,
                min_distance_ratio: None,
                ratio_under_1pct: None,
                five_times_rule_holds: true,
            };
        }
        let mut by_ratio: Vec<(f64, f64)> = points
            .iter()
            .zip(&per_point)
            .map(|(p, &e)| ((p.position - lum.pose.position).length() / size, e))
            .collect();
        by_ratio.sort_by(|a, b| b.0.total_cmp(&a.0));
        let mut ratio_under = None;
        for &(r, e) in &by_ratio {
            if e >= 0.01 {
                break;
            }
            ratio_under = Some(r);
        }
        FarField {
            largest_dimension_m: size,
            max_error_pct: 100.0 * max,
            mean_error_pct: 100.0 * mean,
            min_distance_ratio: by_ratio.last().map(|x| x.0),
            ratio_under_1pct: ratio_under,
            five_times_rule_holds: by_ratio.iter().filter(|x| x.0 >= 5.0).all(|x| x.1 < 0.01),
        }
    }
}

/// One receiver point's result.
#[derive(Debug, Clone, Serialize)]
pub struct PointResult {
    /// World position, m.
    pub position: [f64; 3],
    /// Illuminance, lx.
    pub e_lux: f64,
    /// Error (%) of treating every luminaire as a point source here.
    pub far_field_error_pct: f64,
    /// Smallest distance / largest luminous dimension over the luminaires
    /// with an opening of some size (null when every one is a point).
    pub distance_ratio: Option<f64>,
}

/// One receiver's result.
#[derive(Debug, Clone, Serialize)]
pub struct ReceiverResult {
    /// Receiver name.
    pub name: String,
    /// `plane` or `point`.
    pub kind: &'static str,
    /// Average illuminance, lx (mean over equal cells).
    pub e_avg_lux: f64,
    /// Minimum, lx.
    pub e_min_lux: f64,
    /// Maximum, lx.
    pub e_max_lux: f64,
    /// Uniformity Emin / Eavg (null when Eavg is 0).
    pub u0: Option<f64>,
    /// Emin / Emax (null when Emax is 0).
    pub emin_emax: Option<f64>,
    /// Grid size [nu, nv] of a plane (u fastest in `points`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub grid: Option<[usize; 2]>,
    /// Every point.
    pub points: Vec<PointResult>,
}

/// How one luminaire was evaluated.
#[derive(Debug, Clone, Serialize)]
pub struct LuminaireResult {
    /// Luminaire name.
    pub name: String,
    /// Representation used.
    pub representation: String,
    /// Source model used.
    pub source: SourceKind,
    /// Bytes of the representation.
    pub bytes: usize,
    /// The area source's refinement (also for a point source: what the far-field check used).
    pub area: AreaRefinement,
    /// The point-source assumption on this scene.
    pub far_field: FarField,
}

/// Everything `photosolid scene` reports.
#[derive(Debug, Clone, Serialize)]
pub struct SceneResult {
    /// The scene file.
    pub scene: String,
    /// Per luminaire.
    pub luminaires: Vec<LuminaireResult>,
    /// Per receiver.
    pub receivers: Vec<ReceiverResult>,
    /// What a reader must know: each receiver that no luminaire lights, by
    /// name, with why (it faces away, it lies behind the luminaires, outside
    /// every beam, or in the occluders' shadow). Empty when all is lit.
    pub warnings: Vec<crate::error::Warning>,
}

/// Per luminaire: the illuminance (lx) at every scene point with the
/// representation and source the scene asks for, with the point source, and
/// with the area source, plus its report line. Shared by [`evaluate`] and the plan.
pub(crate) fn luminaire_lux(
    scene: &Scene,
    lum: &SceneLuminaire,
    points: &[ScenePoint],
    progress: Option<&Progress<'_>>,
) -> Result<(Vec<f64>, Vec<f64>, LuminaireResult), SceneError> {
    let rep = lum.representation.unwrap_or(REFERENCE);
    let models = Models::new(lum, &[rep]).map_err(|e| lum.model_error(e))?;
    let field = models.field(&rep).map_err(|e| lum.model_error(e))?;
    let point = Source::point(&*field, lum);
    let point_lux = point.lux_all(points, &scene.occluders, progress);
    let (area, area_lux, refinement) = area_source(&*field, lum, points, &scene.occluders);
    let kind = lum.source_kind();
    let far_field = FarField::measure(lum, points, &point_lux, &area_lux);
    let bytes = field.bytes()
        + match kind {
            SourceKind::Point => 0,
            SourceKind::Area => area.patches.len() * std::mem::size_of::<(DVec3, f64)>(),
        };
    let used = if kind == SourceKind::Area {
        area_lux
    } else {
        point_lux.clone()
    };
    let report = LuminaireResult {
        name: lum.name.clone(),
        representation: field.name(),
        source: kind,
        bytes,
        area: refinement,
        far_field,
    };
    Ok((used, point_lux, report))
}

/// The result of receiver `r` of `scene`: its illuminance `values` (lx) and
/// point-source errors `far_field` (fractions), one per point.
fn receiver_result(scene: &Scene, r: &Receiver, values: &[f64], far_field: &[f64]) -> ReceiverResult {
    let n = r.points.len();
    let pts = r
        .points
        .iter()
        .zip(values)
        .zip(far_field)
        .map(|((p, &e), &ff)| PointResult {
            position: p.to_array(),
            e_lux: e,
            far_field_error_pct: 100.0 * ff,
            distance_ratio: scene
                .luminaires
                .iter()
                .filter(|l| !l.opening.is_point())
                .map(|l| (*p - l.pose.position).length() / l.opening.largest_dimension_m())
                .reduce(f64::min),
        })
        .collect();
    let (min, max) = values
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(lo, hi), &e| (lo.min(e), hi.max(e)));
    let min = if values.is_empty() { 0.0 } else { min };
    let avg = if values.is_empty() {
        0.0
    } else {
        values.iter().sum::<f64>() / n as f64
    };
    ReceiverResult {
        name: r.name.clone(),
        kind: match r.shape {
            ReceiverShape::Plane { .. } => "plane",
            ReceiverShape::Point => "point",
        },
        e_avg_lux: avg,
        e_min_lux: min,
        e_max_lux: max,
        u0: (avg > 0.0).then(|| min / avg),
        emin_emax: (max > 0.0).then(|| min / max),
        grid: match r.shape {
            ReceiverShape::Plane { nu, nv, .. } => Some([nu, nv]),
            ReceiverShape::Point => None,
        },
        points: pts,
    }
}

/// The illuminance at every receiver point of `scene` (see the module docs).
/// `progress(done, total, "illuminance")` counts points over all luminaire
/// passes (total = points × luminaires).
pub fn evaluate(scene: &Scene, progress: Option<&Progress<'_>>) -> Result<SceneResult, SceneError> {
    scene.check_points()?;
    let points = scene.points();
    let mut total = vec![0.0; points.len()];
    let mut total_point = vec![0.0; points.len()];
    let mut luminaires = Vec::new();
    let passes = scene.luminaires.len();
    for (li, lum) in scene.luminaires.iter().enumerate() {
        let pass = |done: usize, n: usize, what: &str| {
            if let Some(f) = progress {
                f(li * n + done, passes * n, what);
            }
        };
        let (used, point_lux, report) = luminaire_lux(scene, lum, &points, Some(&pass))?;
        for (t, e) in total.iter_mut().zip(used) {
            *t += e;
        }
        for (t, e) in total_point.iter_mut().zip(point_lux) {
            *t += e;
        }
        luminaires.push(report);
    }
    let per_point_ff = relative_errors(&total_point, &total, &points);
    let mut receivers = Vec::new();
    let mut offset = 0;
    for r in &scene.receivers {
        let n = r.points.len();
        receivers.push(receiver_result(
            scene,
            r,
            &total[offset..offset + n],
            &per_point_ff[offset..offset + n],
        ));
        offset += n;
    }
    let mut warnings = scene.warnings.clone();
    for (k, r) in receivers.iter().enumerate() {
        if r.e_max_lux <= 0.0 && !r.points.is_empty() {
            let these: Vec<&ScenePoint> = points.iter().filter(|p| p.receiver == k).collect();
            warnings.push(crate::error::Warning::new(
                crate::error::WarningCode::ReceiverUnlit,
                format!(
                    "receiver {:?} gets no light (0 lx at all {} points): {}",
                    r.name,
                    these.len(),
                    why_unlit(scene, &scene.receivers[k], &these)?
                ),
            ));
        }
    }
    Ok(SceneResult {
        scene: scene
            .path
            .as_ref()
            .map_or("built-in scene".into(), |p| p.display().to_string()),
        luminaires,
        receivers,
        warnings,
    })
}

/// Why a receiver that gets 0 lx is dark, in words: every point faces away
/// from every luminaire; or the luminaires it faces emit nothing towards it
/// (it lies behind them, above the horizontal of their frame, or outside
/// their beams); or it is lit without the occluders (their shadow).
fn why_unlit(scene: &Scene, receiver: &super::Receiver, points: &[&ScenePoint]) -> Result<String, SceneError> {
    let facing: Vec<(&ScenePoint, &SceneLuminaire)> = points
        .iter()
        .flat_map(|p| scene.luminaires.iter().map(move |l| (*p, l)))
        .filter(|(p, l)| p.normal.dot(l.pose.position - p.position) > 0.0)
        .collect();
    let n = receiver.normal;
    if facing.is_empty() {
        let fix = match receiver.shape {
            ReceiverShape::Plane { .. } => "its normal u × v",
            ReceiverShape::Point => "its normal",
        };
        let swap = match receiver.shape {
            ReceiverShape::Plane { .. } => "; swap u and v to turn it over",
            ReceiverShape::Point => "; reverse the normal",
        };
        return Ok(format!(
            "it faces away from every luminaire ({fix} = ({:.3}, {:.3}, {:.3}) points away from them{swap})",
            n.x + 0.0,
            n.y + 0.0,
            n.z + 0.0
        ));
    }
    // Lit when the occluders are taken away: their shadow.
    for lum in &scene.luminaires {
        let rep = lum.representation.unwrap_or(REFERENCE);
        let models = Models::new(lum, &[rep]).map_err(|e| lum.model_error(e))?;
        let field = models.field(&rep).map_err(|e| lum.model_error(e))?;
        let source = Source::point(&*field, lum);
        if points.iter().any(|p| source.lux(p, &[]) > 0.0) {
            return Ok("every point lies in the shadow of the occluders".into());
        }
    }
    // Behind: every direction it is seen in lies above the luminaire's horizontal (gamma > 90°).
    let behind = facing
        .iter()
        .all(|(p, l)| l.pose.to_local(p.position - l.pose.position).z > 0.0);
    let names: Vec<&str> = {
        let mut v: Vec<&str> = facing.iter().map(|(_, l)| l.name.as_str()).collect();
        v.dedup();
        v
    };
    Ok(if behind {
        format!(
            "it lies behind the luminaires it faces ({}): above their horizontal (gamma > 90°), where they emit nothing",
            names.join(", ")
        )
    } else {
        format!(
            "it lies outside every beam: the luminaires it faces ({}) emit 0 cd towards it",
            names.join(", ")
        )
    })
}

/// Per receiver: [`DARK_FLOOR`] × its largest value in `reference`.
pub(crate) fn receiver_floors(points: &[ScenePoint], reference: &[f64]) -> Vec<f64> {
    let mut floor = Vec::new();
    for (p, &e) in points.iter().zip(reference) {
        if floor.len() <= p.receiver {
            floor.resize(p.receiver + 1, 0.0);
        }
        floor[p.receiver] = f64::max(floor[p.receiver], e * DARK_FLOOR);
    }
    floor
}
