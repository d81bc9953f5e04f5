//! The cheapest representation of each luminaire that keeps the scene's
//! illuminance within a tolerance of the reference, measured on the scene.
//!
//! **Reference** per luminaire: Catmull-Rom on the native grid, as a
//! directional area source refined to convergence when the file (or the
//! scene) declares an opening with a size, as a point source otherwise or
//! where the scene sets `source = "point"`.
//!
//! **Candidates** ([`Recon`], the one registry's names): every filter on the native grid,
//! every filter rendered at factors 1, 2 and 5 read bilinearly (the trade
//! table's rows) and the Catmull-Rom renders also with the nearest and
//! Catmull-Rom lookups,
//! the fitted OpenGL lights (≤ 2), spherical harmonics `sh:{2,4,8,16}` and
//! lobe mixtures `lobes:{1,2,3,4}`, the native grid cropped to the γ rows and
//! the C sector the scene's receivers can see, and the grid re-stored with the symmetry the
//! data has; each as a point source and, where the opening has a size, as
//! the area source.
//!
//! **Error**: each candidate replaces its luminaire's reference while the
//! others stay; at every receiver point the total illuminance is compared
//! with the all-reference total ([`super::illuminance::relative_errors`]).
//! **Cost**: bytes held ([`IntensityField::bytes`], plus 32 bytes per patch
//! of an area source), then time per illuminance evaluation
//! ([`time_per_sample_ns`] on [`random_directions`], times the patch
//! count). The chosen candidate is the first within the tolerance in that
//! order; the reference always is (error 0), so a plan always exists.

use glam::DVec3;
use serde::Serialize;

use super::illuminance::{area_source, relative_difference, AreaRefinement, FarField, Source};
pub use super::representation::{Models, REFERENCE};
use super::{Scene, SceneError, SceneLuminaire, ScenePoint, SourceKind};
use crate::error::ModelError;
use crate::metrics::{random_directions, time_per_sample_ns};
use crate::model::{Distribution, IntensityField, Progress, Symmetry};
use crate::registry::{Job, Registry, Visible};
pub use crate::registry::{OwnedSampler, Recon};

/// Render factors of the texture candidates.
pub use crate::registry::builtin::PLAN_TEXTURE_FACTORS as TEXTURE_FACTORS;

/// What the scene can see of `lum` through `patches`: the γ rows (first,
/// last, degrees) and, when no kept row touches a pole (whose cubic taps
/// read the plane C + 180) and the data is not rotational, the C planes
/// (first, last counter-clockwise), each widened by two knots each side (the
/// cubic taps). `None` when that is the whole grid or nothing is seen.
fn visible_grid(lum: &SceneLuminaire, patches: &[(DVec3, f64)], points: &[ScenePoint]) -> Option<Visible> {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    let mut cs = Vec::new();
    for p in points {
        for &(local, _) in patches {
            let v = p.position - lum.pose.point_to_world(local);
            if p.normal.dot(v) >= 0.0 {
                continue; // arrives from behind the receiver: never looked up
            }
            if let Some((c, g)) = crate::model::frame::angles(lum.pose.to_local(v)) {
                lo = lo.min(g);
                hi = hi.max(g);
                cs.push(c);
            }
        }
    }
    let d = lum.luminaire.distribution();
    let g = d.gamma_angles_deg();
    if lo > hi || lo.is_nan() || hi.is_nan() {
        return None;
    }
    let first = g.partition_point(|&x| x <= lo).saturating_sub(1).saturating_sub(2);
    let last = (g.partition_point(|&x| x < hi) + 2).min(g.len() - 1);
    let pole = g[first] <= 0.0 || g[last] >= 180.0;
    let c = if pole || d.symmetry() == Symmetry::Rotational {
        None
    } else {
        visible_planes(d, &mut cs)
    };
    (first > 0 || last < g.len() - 1 || c.is_some()).then(|| (g[first], g[last], c))
}

/// The smallest arc of full-circle C planes holding every angle of `cs`
/// (degrees), widened by two planes each side; `None` when that is (almost) every plane.
fn visible_planes(d: &Distribution, cs: &mut [f64]) -> Option<(f64, f64)> {
    let planes: Vec<f64> = d.full_planes().iter().map(|p| p.0).collect();
    let n = planes.len();
    if cs.is_empty() || n < 8 {
        return None;
    }
    cs.sort_by(f64::total_cmp);
    // The arc is the circle minus the largest gap between consecutive seen angles.
    let mut gap = (cs[0] + 360.0 - cs[cs.len() - 1], cs.len() - 1);
    for k in 1..cs.len() {
        if cs[k] - cs[k - 1] > gap.0 {
            gap = (cs[k] - cs[k - 1], k - 1);
        }
    }
    let (start, end) = (cs[(gap.1 + 1) % cs.len()], cs[gap.1]);
    // Plane index at or below `start`, and at or above `end` (periodic), then two more each way.
    let below = (planes.partition_point(|&a| a <= start) + n - 1) % n;
    let above = planes.partition_point(|&a| a < end) % n;
    let (i0, i1) = ((below + n - 2) % n, (above + 2) % n);
    let count = (i1 + n - i0) % n + 1;
    (count + 2 < n).then(|| (planes[i0], planes[i1]))
}

/// One candidate's measured cost and error.
#[derive(Debug, Clone, Serialize)]
pub struct Candidate {
    /// The representation.
    pub representation: String,
    /// The same as a value (to rebuild its field, e.g. for the report's 3D view), not in the JSON.
    #[serde(skip)]
    pub spec: Recon,
    /// Point or area source.
    pub source: SourceKind,
    /// Bytes held (field + 32 per area patch).
    pub bytes: usize,
    /// Time per illuminance evaluation on one thread, ns (field time × patches).
    pub ns_per_eval: f64,
    /// Largest error over the scene's points, %.
    pub max_error_pct: f64,
    /// Mean error over the scene's points, %.
    pub mean_error_pct: f64,
    /// How the data shaped the representation ([`crate::model::IntensityField::form`]:
    /// `rings`, `zonal`); absent otherwise.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub form: Option<String>,
}

/// A candidate that could not be built, and why.
#[derive(Debug, Clone, Serialize)]
pub struct Unavailable {
    /// The representation.
    pub representation: String,
    /// Why.
    pub reason: String,
}

/// The plan for one luminaire.
#[derive(Debug, Clone, Serialize)]
pub struct LuminairePlan {
    /// Luminaire name.
    pub name: String,
    /// The chosen candidate, `representation, source`.
    pub chosen: String,
    /// Its representation.
    pub representation: String,
    /// The same as a value (to rebuild its field, e.g. for the report's 3D view), not in the JSON.
    #[serde(skip)]
    pub chosen_spec: Recon,
    /// Its source model.
    pub source: SourceKind,
    /// Its bytes.
    pub bytes: usize,
    /// Its time per evaluation, ns.
    pub ns_per_eval: f64,
    /// Its largest error on the scene, %.
    pub max_error_pct: f64,
    /// Its mean error on the scene, %.
    pub mean_error_pct: f64,
    /// Whether the point source (reference field) stays within the tolerance at every point.
    pub far_field_ok: bool,
    /// The five-times rule measured on this scene.
    pub far_field: FarField,
    /// The reference it was measured against.
    pub reference: String,
    /// The reference area source's refinement.
    pub area: AreaRefinement,
    /// Candidates measured: cheapest first (bytes, then time per evaluation),
    /// up to the chosen one, the first within the tolerance.
    pub candidates: usize,
    /// Dearer candidates not measured: a cheaper one is within the tolerance,
    /// so none of them could be chosen.
    pub candidates_not_measured: usize,
    /// Candidates over the tolerance, with their errors (cheapest first): every
    /// candidate measured before the chosen one.
    pub rejected: Vec<Candidate>,
    /// Candidates that could not be built.
    pub unavailable: Vec<Unavailable>,
}

/// Everything `photosolid plan` reports.
#[derive(Debug, Clone, Serialize)]
pub struct PlanResult {
    /// The scene file.
    pub scene: String,
    /// The tolerance, %.
    pub tolerance_pct: f64,
    /// How errors are measured.
    pub error_definition: &'static str,
    /// Per luminaire.
    pub luminaires: Vec<LuminairePlan>,
    /// Every chosen representation at once against the all-reference scene: largest error, %.
    pub combined_max_error_pct: f64,
    /// Mean of the same, %.
    pub combined_mean_error_pct: f64,
    /// The scene's warnings, coded (docs/warnings.md).
    pub warnings: Vec<crate::error::Warning>,
}

/// What [`plan`] writes in `error_definition`.
pub const ERROR_DEFINITION: &str = "per receiver point: |E(candidate in place of its luminaire's reference) - \
     E(all references)| / max(E(all references), 1e-3 x the receiver's largest reference E); reference: catmull-rom \
     on the native grid, area source refined to convergence when the opening has a size, else point source (a \
     point source also where the scene sets source = \"point\")";

/// Options of [`plan`].
#[derive(Debug, Clone, PartialEq)]
pub struct PlanOptions {
    /// Largest error allowed at any point, as a fraction (0.01 = 1 %).
    pub tolerance: f64,
    /// Directions timed per field.
    pub timing_directions: usize,
    /// Timing repeats (median).
    pub timing_repeats: usize,
    /// The representations beyond the built-in ones whose default instances
    /// are candidates. Default: none.
    pub registry: Registry,
}

impl Default for PlanOptions {
    fn default() -> Self {
        Self {
            tolerance: 0.01,
            timing_directions: 4096,
            timing_repeats: 5,
            registry: Registry::default(),
        }
    }
}

/// Every candidate representation of `lum` for this scene: `registry`'s
/// candidates for [`Job::Plan`] (the built-in ones, then those added to it).
pub(crate) fn candidate_representations(
    lum: &SceneLuminaire,
    visible: Option<Visible>,
    registry: &Registry,
) -> Vec<Recon> {
    registry.candidates(&Job::Plan {
        dist: lum.luminaire.distribution(),
        visible,
    })
}

/// The slot in `cache` of the models of luminaire `li`: luminaires of one
/// distribution share them (the fit, the lobes, the texture), so a plan of
/// four copies of one file prepares them once. `cache` holds (first
/// luminaire, its models).
fn shared_models(
    cache: &mut Vec<(usize, Models)>,
    luminaires: &[SceneLuminaire],
    li: usize,
    reps: &[Recon],
) -> Result<usize, ModelError> {
    let dist = luminaires[li].luminaire.distribution();
    if let Some(slot) = cache
        .iter()
        .position(|(first, _)| luminaires[*first].luminaire.distribution() == dist)
    {
        return Ok(slot);
    }
    cache.push((li, Models::new(&luminaires[li], reps)?));
    Ok(cache.len() - 1)
}

/// One luminaire's reference (module docs) measured on the scene.
struct Reference {
    /// Illuminance at every point (lx) from the reference area source (one
    /// patch for a point opening).
    lux: Vec<f64>,
    /// The same from the reference field as a point source, lx.
    point_lux: Vec<f64>,
    /// The area source's patches (luminaire frame m, share of the light);
    /// the area candidates use the same.
    patches: Vec<(DVec3, f64)>,
    /// The area source's refinement.
    refinement: AreaRefinement,
    /// The five-times rule measured on this scene.
    far_field: FarField,
    /// `FIELD, KIND source`.
    name: String,
}

impl Reference {
    /// The reference of `lum` at `points` of `scene`.
    fn measure(scene: &Scene, lum: &SceneLuminaire, points: &[ScenePoint]) -> Result<Self, SceneError> {
        let models = Models::new(lum, &[REFERENCE]).map_err(|e| lum.model_error(e))?;
        let field = models.field(&REFERENCE).map_err(|e| lum.model_error(e))?;
        let point = Source::point(&*field, lum);
        let point_lux = point.lux_all(points, &scene.occluders, None);
        let (area, area_lux, refinement) = area_source(&*field, lum, points, &scene.occluders);
        let far_field = FarField::measure(lum, points, &point_lux, &area_lux);
        // The scene's `source` decides, as `scene` does: a luminaire the scene
        // models as a point source is measured against its point source.
        let kind = lum.source_kind();
        let (lux, patches) = match kind {
            SourceKind::Point => (point_lux.clone(), vec![(DVec3::ZERO, 1.0)]),
            SourceKind::Area => (area_lux, area.patches),
        };
        Ok(Self {
            lux,
            point_lux,
            patches,
            refinement,
            far_field,
            name: format!("{}, {kind} source", field.name()),
        })
    }
}

/// Every luminaire's reference (`progress(luminaire, luminaires, what)`
/// before each) and their total illuminance at every point, lx.
fn references(
    scene: &Scene,
    points: &[ScenePoint],
    progress: &Progress<'_>,
) -> Result<(Vec<Reference>, Vec<f64>), SceneError> {
    let mut references = Vec::new();
    for (li, lum) in scene.luminaires.iter().enumerate() {
        progress(li, scene.luminaires.len(), &format!("{}: reference", lum.name));
        references.push(Reference::measure(scene, lum, points)?);
    }
    let mut total_ref = vec![0.0; points.len()];
    for r in &references {
        for (t, e) in total_ref.iter_mut().zip(&r.lux) {
            *t += e;
        }
    }
    Ok((references, total_ref))
}

/// What one luminaire's candidates are measured with.
struct Bench<'a> {
    scene: &'a Scene,
    lum: &'a SceneLuminaire,
    points: &'a [ScenePoint],
    reference: &'a Reference,
    /// Illuminance with every luminaire's reference at each point, lx.
    total_ref: &'a [f64],
    /// Directions each field's lookup is timed on.
    dirs: &'a [DVec3],
    options: &'a PlanOptions,
}

/// A candidate with its illuminance at every point (lx, this luminaire alone).
type Measured = (Candidate, Vec<f64>);

impl Bench<'_> {
    /// The representations of `reps` built from `models` (those that cannot
    /// be built, with the reason), each as a point source and, where the scene
    /// models the luminaire as an area source, as the area source; measured
    /// cheapest first (bytes, then time per evaluation), up to the first
    /// within the tolerance: a dearer candidate cannot be chosen, so it is not
    /// measured (the count of those is the third value). `progress` gets a
    /// line per candidate measured.
    fn measure_cheapest_first(
        &self,
        models: &Models,
        reps: Vec<Recon>,
        progress: &Progress<'_>,
    ) -> (Vec<Measured>, Vec<Unavailable>, usize) {
        let mut unavailable = Vec::new();
        let mut pending = Vec::new();
        for rep in reps {
            let field = match models.field(&rep) {
                Ok(f) => f,
                Err(e) => {
                    unavailable.push(Unavailable {
                        representation: rep.to_string(),
                        reason: e.to_string(),
                    });
                    continue;
                }
            };
            let ns = time_per_sample_ns(&*field, self.dirs, self.options.timing_repeats);
            let field = std::rc::Rc::new(field);
            pending.push((rep, field.clone(), ns, SourceKind::Point));
            if self.lum.source_kind() == SourceKind::Area {
                pending.push((rep, field, ns, SourceKind::Area));
            }
        }
        let n_patches = self.reference.patches.len();
        let cost = |(_, field, ns, kind): &(Recon, std::rc::Rc<Box<dyn IntensityField + '_>>, f64, SourceKind)| {
            let n = if *kind == SourceKind::Area { n_patches } else { 1 };
            (
                field.bytes() + if *kind == SourceKind::Area { n * 32 } else { 0 },
                ns * n as f64,
            )
        };
        pending.sort_by(|a, b| {
            let (ca, cb) = (cost(a), cost(b));
            ca.0.cmp(&cb.0).then(ca.1.total_cmp(&cb.1))
        });
        let tol_pct = 100.0 * self.options.tolerance;
        let total = pending.len();
        let mut measured = Vec::new();
        for (k, (rep, field, ns, kind)) in pending.iter().enumerate() {
            progress(k, total, &format!("{}: {rep} ({kind} source)", self.lum.name));
            let m = self.measure(*rep, &***field, *ns, *kind);
            let within = m.0.max_error_pct <= tol_pct;
            measured.push(m);
            if within {
                break;
            }
        }
        let not_measured = total - measured.len();
        (measured, unavailable, not_measured)
    }

    /// `field` (representation `rep`, `ns` per lookup) as a source of `kind`
    /// in place of the luminaire's reference.
    fn measure(&self, rep: Recon, field: &dyn IntensityField, ns: f64, kind: SourceKind) -> Measured {
        let src = match kind {
            SourceKind::Point => Source::point(field, self.lum),
            SourceKind::Area => Source::with_patches(field, self.lum, self.reference.patches.clone()),
        };
        let values = src.lux_all(self.points, &self.scene.occluders, None);
        let total: Vec<f64> = self
            .total_ref
            .iter()
            .zip(&self.reference.lux)
            .zip(&values)
            .map(|((t, r), v)| t - r + v)
            .collect();
        let (max, mean) = relative_difference(&total, self.total_ref, self.points);
        let n = src.patches.len();
        (
            Candidate {
                representation: field.name(),
                spec: rep,
                source: kind,
                bytes: field.bytes() + if kind == SourceKind::Area { n * 32 } else { 0 },
                ns_per_eval: ns * n as f64,
                max_error_pct: 100.0 * max,
                mean_error_pct: 100.0 * mean,
                form: field.form(),
            },
            values,
        )
    }

    /// The plan from the `measured` candidates (sorted here, cheapest first)
    /// and the chosen one's illuminance at every point, lx.
    ///
    /// # Errors
    /// [`SceneError::Model`] when not even the reference is within the tolerance.
    fn choose(
        &self,
        mut measured: Vec<Measured>,
        unavailable: Vec<Unavailable>,
    ) -> crate::Result<(LuminairePlan, Vec<f64>)> {
        measured.sort_by(|a, b| {
            a.0.bytes
                .cmp(&b.0.bytes)
                .then(a.0.ns_per_eval.total_cmp(&b.0.ns_per_eval))
        });
        let tol_pct = 100.0 * self.options.tolerance;
        let chosen_at = measured.iter().position(|(c, _)| c.max_error_pct <= tol_pct);
        let Some(chosen_at) = chosen_at else {
            return Err(SceneError::Model {
                luminaire: self.lum.name.clone(),
                source: ModelError::Internal("the reference itself is not within the tolerance".into()),
            }
            .into());
        };
        let (chosen, values) = measured[chosen_at].clone();
        let r = self.reference;
        let (ff_max, _) = relative_difference(
            &self
                .total_ref
                .iter()
                .zip(&r.lux)
                .zip(&r.point_lux)
                .map(|((t, r), p)| t - r + p)
                .collect::<Vec<_>>(),
            self.total_ref,
            self.points,
        );
        let plan = LuminairePlan {
            name: self.lum.name.clone(),
            chosen: format!("{}, {} source", chosen.representation, chosen.source),
            representation: chosen.representation.clone(),
            chosen_spec: chosen.spec,
            source: chosen.source,
            bytes: chosen.bytes,
            ns_per_eval: chosen.ns_per_eval,
            max_error_pct: chosen.max_error_pct,
            mean_error_pct: chosen.mean_error_pct,
            far_field_ok: 100.0 * ff_max <= tol_pct,
            far_field: r.far_field,
            reference: r.name.clone(),
            area: r.refinement,
            candidates: measured.len(),
            candidates_not_measured: 0,
            rejected: measured
                .iter()
                .filter(|(c, _)| c.max_error_pct > tol_pct)
                .map(|(c, _)| c.clone())
                .collect(),
            unavailable,
        };
        Ok((plan, values))
    }
}

/// Plan every luminaire of `scene` (see the module docs).
/// `progress(done, total, what)` is called before each luminaire's reference
/// (over the luminaires) and before each candidate (over its luminaire's
/// candidates), `what` naming the luminaire and the candidate.
///
/// # Errors
/// [`ModelError::Parameter`] for a tolerance that is not a finite fraction
/// ≥ 0; [`SceneError`] when a point lies in an opening or a luminaire's
/// model cannot be built.
pub fn plan(scene: &Scene, options: &PlanOptions, progress: Option<&Progress<'_>>) -> crate::Result<PlanResult> {
    if !(options.tolerance.is_finite() && options.tolerance >= 0.0) {
        return Err(ModelError::Parameter {
            name: "tolerance",
            value: options.tolerance.to_string(),
            reason: "expected a finite fraction >= 0".into(),
        }
        .into());
    }
    scene.check_points()?;
    let points = scene.points();
    let say = |done: usize, total: usize, what: &str| {
        if let Some(f) = progress {
            f(done, total, what)
        }
    };
    let (references, total_ref) = references(scene, &points, &say)?;
    let dirs = random_directions(options.timing_directions.max(1), 0x5CE7E);
    let mut plans = Vec::new();
    let mut total_chosen = vec![0.0; points.len()];
    let mut models_cache: Vec<(usize, Models)> = Vec::new();
    for (li, lum) in scene.luminaires.iter().enumerate() {
        let lit = lum.texture()?.is_some(); // an all-zero luminaire has one candidate
        let bench = Bench {
            scene,
            lum,
            points: &points,
            reference: &references[li],
            total_ref: &total_ref,
            dirs: &dirs,
            options,
        };
        let visible = visible_grid(lum, &bench.reference.patches, &points);
        let reps = if lit {
            candidate_representations(lum, visible, &options.registry)
        } else {
            vec![REFERENCE] // all-zero: every representation is the same dark field
        };
        let slot = shared_models(&mut models_cache, &scene.luminaires, li, &reps).map_err(|e| lum.model_error(e))?;
        let (measured, unavailable, not_measured) = bench.measure_cheapest_first(&models_cache[slot].1, reps, &say);
        let (mut plan, values) = bench.choose(measured, unavailable)?;
        plan.candidates_not_measured = not_measured;
        for (t, v) in total_chosen.iter_mut().zip(&values) {
            *t += v;
        }
        plans.push(plan);
    }
    let (cmax, cmean) = relative_difference(&total_chosen, &total_ref, &points);
    Ok(PlanResult {
        scene: scene
            .path
            .as_ref()
            .map_or("built-in scene".into(), |p| p.display().to_string()),
        tolerance_pct: 100.0 * options.tolerance,
        error_definition: ERROR_DEFINITION,
        luminaires: plans,
        combined_max_error_pct: 100.0 * cmax,
        combined_mean_error_pct: 100.0 * cmean,
        warnings: scene.warnings.clone(),
    })
}

#[cfg(test)]
mod spelling_tests {
    use super::super::representation::parse_representation;
    use super::*;

    /// A scene file's old texture spelling is read, with a deprecation
    /// warning naming the one spelling ([`Recon`]'s, the trade table's).
    #[test]
    fn texture_representations_parse_both_spellings() {
        let (old, warning) = parse_representation("texture catmull-rom x5 / bilinear +f16 +reduced").unwrap();
        let (new, none) = parse_representation("catmull-rom@x5/bilinear+f16+reduced").unwrap();
        assert_eq!(old, new);
        assert!(none.is_none());
        let warning = warning.unwrap();
        assert!(
            warning.contains("deprecated") && warning.contains("catmull-rom@x5/bilinear+f16+reduced"),
            "{warning}"
        );
        assert_eq!(new.to_string(), "catmull-rom@x5/bilinear+f16+reduced");
        assert!(parse_representation("texture catmull-rom x5 / bilinear +f32").is_err());
        assert_eq!(parse_representation("fitted").unwrap().0, Recon::FittedGl);
    }
}
