//! Compare photometric solids: how wrong is each reconstruction, where, and what does it cost.
//!
//! Between any two of: the measured solid, each filter's reconstruction, the
//! fitted OpenGL lights, another file's distribution (Ashdown 1999, docs/domain.md §6):
//! - the **Hausdorff distance** of the photometric solids (symmetric and both
//!   one-sided, with mean and RMS surface distance), certified to within a
//!   tolerance ([`crate::metrics::hausdorff()`]): "H = 12.31 cd (+0.05)";
//! - the **radial errors** over a stated direction set
//!   ([`crate::metrics::radial_errors`]); their maximum is the cheap radial
//!   bound of H (max over directions of |I1 − I2| ≥ H), estimated on the set
//!   and, against a field reference, refined between its directions by a
//!   local search around the largest samples
//!   ([`crate::metrics::radial::refine_max`], [`crate::metrics::MAX_REFINEMENT`];
//!   `radial_max_method` says what the max is, `radial_max_sampled_cd` keeps the set's own);
//! - the **time per sample** of evaluating the reconstruction.
//!
//! # What is compared with what
//! - One file: each reconstruction of FILE against the reference `against`
//!   of FILE (default: its measured solid).
//! - `vs` OTHER: each reconstruction of FILE (default list starts with FILE's
//!   measured solid) against the reference `against` of OTHER (default:
//!   OTHER's measured solid), FILE optionally aligned first ([`align`]).
//!
//! Solids: the measured solid is [`crate::solid::measured_solid`] (Delaunay
//! of the measured directions); the others are grid solids, by default
//! adaptive ([`crate::solid::adaptive`]): each within
//! [`CompareOptions::solid_tolerance`] of its field's solid at every tested
//! point (a distance bound, checked independently in `tests/it/adaptive_solid.rs`),
//! so the Hausdorff distance of the *fields'* solids lies within about twice
//! that tolerance of the meshes' figure
//! (`|H(S_a, S_b) − H(M_a, M_b)| ≤ H(M_a, S_a) + H(M_b, S_b)`, the triangle
//! inequality); `solid_deviation_cd` reports the largest deviation
//! tested. With a fixed `factor` ([`CompareOptions::solid_tolerance`] =
//! `None`) they are on [`SolidGrid::refined`]`(d, factor)` and no such
//! statement is made.
//!
//! # Rotationally symmetric files
//! When FILE (and OTHER) are rotational and a reconstruction and the
//! reference are both independent of C (tested on samples,
//! [`crate::metrics::profile::is_c_independent`]), their solids are solids
//! of revolution: the row's Hausdorff distance and radial bound are
//! measured on the meridian profiles ([`crate::metrics::profile`]: exactly
//! the distance of the solids of revolution, no C facets), the profile's γ
//! angles refined to the same tolerance; `profile_segments` says so and
//! `triangles` is 0. The measured row of rotational data is measured the
//! same way: its solid is the solid of revolution of the measured profile
//! (the polyline through the measured points, one segment per γ interval),
//! and its radial errors are those of that solid's radial function (the
//! expanded Delaunay solid of [`crate::solid::measured_solid`] adds facets
//! in C that the data does not have). Other rows (a fit with a tilted axis)
//! use meshes as before. As a field elsewhere (plots, `withheld`),
//! "measured" is the radial function of the measured solid (exact at the
//! measured directions, linear on its triangles).
//!
//! Each adaptive solid is refined within [`SOLID_MAX_POINTS`] and stops
//! where halving no longer reduces a deviation (a jump,
//! [`crate::solid::adaptive`]); `solid_tolerance_reached` says per row
//! whether its `solid_deviation_cd` is within `solid_tolerance_cd`. The radial bound
//! `radial_bound_cd` is max |r_A(ω) − r_B(ω)| over the direction set of the
//! two *meshes'* radial functions (ray cast), so it bounds the meshes'
//! Hausdorff distance up to the set's density.
//!
//! # Normalisation
//! Each distribution is scaled before anything is built: `cd` (none),
//! `peak` (its own I_max = 1) or `klm` (cd/klm, 1000 I / Φ with its own
//! flux). Every length (`*_cd` keys) is in that unit; `units` says which.

pub mod align;
mod fields;
mod measure;
mod options;
mod plot_data;
pub mod trade;
pub mod view;
mod withheld;
mod withheld_source;

use serde::Serialize;

pub use align::{best_alignment, Alignment};
use measure::measure_profile;
pub use measure::SOLID_MAX_POINTS;
pub(crate) use measure::{measure_field, own_or_grid_solid, FieldTarget};
pub use options::{Against, CompareOptions, Directions, Normalize, SourceMeasurements};
pub(crate) use plot_data::plot_data;
pub use plot_data::{ErrorMap, PlotData, PolarPlane};
pub use view::{SampledSolid, SampledSolids, SolidSet};
pub use withheld::SURFACE_SEARCH_MAX_POINTS;

use crate::error::ModelError;
use crate::metrics::profile::{self, Profile};
use crate::metrics::{
    corresponding_bounds, field_radial_errors, hausdorff_bvh, hausdorff_bvh_below_bounds, hausdorff_bvh_bounded,
    hausdorff_bvh_bounded_within, pareto_front, time_per_sample_ns, Bvh, DirectionSet, Hausdorff, OneSided,
    MAX_REFINEMENT, ZOTTI_C,
};
pub use crate::model::Progress;
use crate::model::{Distribution, IntensityField, Symmetry};
use crate::reconstruct::eval_all;
use crate::registry::{Recon, Reconstructions};
use crate::solid::{AdaptiveOptions, Mesh, RadialMesh, Refinement, SolidGrid, Tolerance, Units};
use crate::synth::Truth;

/// The metrics of one reconstruction against the reference.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ReconResult {
    /// The reconstruction (`measured`, a filter name, `fitted-gl`).
    pub name: String,
    /// Bytes the reconstruction holds to answer lookups.
    pub bytes: usize,
    /// Hausdorff distance (attained), in `units`: symmetric between the
    /// solids for a field reference; for `withheld`, the largest distance
    /// from a withheld measured point to the solid rebuilt without it
    /// (how: `withheld_distance`).
    pub hausdorff_cd: f64,
    /// Certified gap: H ≤ hausdorff_cd + hausdorff_bound_cd (0 for `withheld`: exact point distances).
    pub hausdorff_bound_cd: f64,
    /// H as % of the reference I_max.
    pub hausdorff_pct: f64,
    /// One-sided h(reconstruction → reference) (null for `withheld`).
    pub recon_to_ref: Option<OneSided>,
    /// One-sided h(reference → reconstruction); for `withheld`, the withheld
    /// points to the rebuilt solids (null when only H was measured:
    /// [`CompareOptions::hausdorff_only`]).
    pub ref_to_recon: Option<OneSided>,
    /// Mean surface distance (mean of the one-sided area-weighted means;
    /// withheld: mean point distance; null when only H was measured).
    pub mean_surface_distance_cd: Option<f64>,
    /// RMS surface distance (both directions pooled; withheld: RMS point
    /// distance; null when only H was measured).
    pub rms_surface_distance_cd: Option<f64>,
    /// The radial bound: max |r_recon(ω) − r_ref(ω)| of the two solids
    /// (meshes, ray cast) over the direction set (≥ H up to the set's
    /// density); for `withheld`, equal to `radial_max_cd`.
    pub radial_bound_cd: f64,
    /// Largest radial difference of the fields, in `units`: over the
    /// direction set, refined locally between its directions against a
    /// field reference (the comparison's `radial_max_method` says how;
    /// [`crate::metrics::radial::refine_max`]).
    pub radial_max_cd: f64,
    /// Largest radial difference of the fields, % of the reference I_max.
    pub radial_max_pct: f64,
    /// Where it is, (C, γ) degrees.
    pub radial_max_at_deg: (f64, f64),
    /// Largest radial difference over the direction set's directions alone
    /// (before the refinement), in `units`: a lower bound of `radial_max_cd`.
    pub radial_max_sampled_cd: f64,
    /// The same, % of the reference I_max.
    pub radial_max_sampled_pct: f64,
    /// Solid-angle-weighted RMS radial difference, in `units`.
    pub radial_rms_cd: f64,
    /// The same, % of the reference I_max.
    pub radial_rms_pct: f64,
    /// Zotti's relative error (unweighted, constant `zotti_c`).
    pub zotti_err: f64,
    /// Zotti's relative error, solid-angle weighted.
    pub zotti_err_solid_angle: f64,
    /// Flux difference over the direction set, % of the reference flux.
    pub flux_error_pct: f64,
    /// Misplaced-flux fraction, in [0, 2].
    pub misplaced_flux: f64,
    /// Median time (ns) per lookup from a unit direction (one thread).
    pub time_per_sample_ns: Option<f64>,
    /// Triangles of the reconstruction's solid (0 when measured on profiles).
    pub triangles: usize,
    /// Segments of the meridian profile when the row was measured on the
    /// profiles of two solids of revolution (see the module docs); absent otherwise.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub profile_segments: Option<usize>,
    /// `withheld` reference only: how the distance from a withheld point to
    /// the rebuilt solid was measured: `surface` (searched on the solid of a
    /// continuous field, [`crate::metrics::nearest`]), `mesh` (exact to the
    /// adaptive mesh of a field that may jump, whose solid has walls, of a
    /// fold with more than [`SURFACE_SEARCH_MAX_POINTS`] searched points, where one mesh is cheaper,
    /// or to the measured solid), `cells` (exact, in closed form, to the
    /// patches and walls of a field made of constant cells: a nearest
    /// lookup of a texture or of the data, [`crate::metrics::cells`]), `profile` (a solid of
    /// revolution's meridian), or `origin` (kept data all zero); several
    /// joined by `+` when folds differ.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub withheld_distance: Option<String>,
    /// The largest deviation of this row's adaptive solid (or profile) from
    /// its field at the tested points, in `units`; absent for a fixed grid
    /// or the measured solid. Above `solid_tolerance_cd` where the field
    /// jumps (a cut-off, the nearest filter): refined to the minimum step.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub solid_deviation_cd: Option<f64>,
    /// Whether `solid_deviation_cd` is within `solid_tolerance_cd` (false
    /// where a jump, the minimum step or the point budget stopped the
    /// refinement: [`crate::solid::adaptive::Stop`]); absent with it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub solid_tolerance_reached: Option<bool>,
    /// How the representation was built when the data chose it
    /// ([`IntensityField::form`]: `rings`, `zonal`); absent otherwise.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub form: Option<String>,
    /// On the Pareto front of (time per sample, bytes, H).
    pub pareto: bool,
}

/// The distance figures of one row, however they were measured.
pub(crate) struct Distances {
    pub value: f64,
    pub bound: f64,
    pub recon_to_ref: Option<OneSided>,
    pub ref_to_recon: Option<OneSided>,
    pub mean: Option<f64>,
    pub rms: Option<f64>,
    pub radial_bound: f64,
}

impl ReconResult {
    /// One row from its distances, radial errors (against a reference of peak `i_max`) and costs.
    pub(crate) fn new(
        name: String,
        bytes: usize,
        d: Distances,
        rad: &crate::metrics::RadialErrors,
        i_max: f64,
        time_ns: Option<f64>,
        triangles: usize,
    ) -> Self {
        Self {
            name,
            bytes,
            hausdorff_cd: d.value,
            hausdorff_bound_cd: d.bound,
            hausdorff_pct: if i_max > 0.0 { 100.0 * d.value / i_max } else { 0.0 },
            recon_to_ref: d.recon_to_ref,
            ref_to_recon: d.ref_to_recon,
            mean_surface_distance_cd: d.mean,
            rms_surface_distance_cd: d.rms,
            radial_bound_cd: d.radial_bound,
            radial_max_cd: rad.max_abs_cd,
            radial_max_pct: rad.max_pct,
            radial_max_at_deg: rad.max_at_deg,
            radial_max_sampled_cd: rad.sampled_max_abs_cd,
            radial_max_sampled_pct: rad.sampled_max_pct,
            radial_rms_cd: rad.rms_cd,
            radial_rms_pct: rad.rms_pct,
            zotti_err: rad.zotti_err,
            zotti_err_solid_angle: rad.zotti_err_solid_angle,
            flux_error_pct: rad.flux_error_pct,
            misplaced_flux: rad.misplaced_flux,
            time_per_sample_ns: time_ns,
            triangles,
            profile_segments: None,
            withheld_distance: None,
            solid_deviation_cd: None,
            solid_tolerance_reached: None,
            form: None,
            pareto: false,
        }
    }
}

/// What a comparison's errors are measured against: its JSON value
/// (`reference_kind`) is the lowercase name, `truth`, `withheld`, `dense`
/// or `reconstruction` (a contract of `compare --json`, `tradeoff --json`
/// and `engines --json`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum ReferenceKind {
    /// The closed-form truth of a synthetic file.
    Truth,
    /// Measured planes and rows withheld from the reconstructions.
    Withheld,
    /// A reconstruction of a denser measurement (`--vs OTHER`).
    Dense,
    /// A reconstruction of FILE itself (not the truth).
    Reconstruction,
}

impl ReferenceKind {
    /// The name, as the JSON writes it.
    pub fn as_str(self) -> &'static str {
        match self {
            ReferenceKind::Truth => "truth",
            ReferenceKind::Withheld => "withheld",
            ReferenceKind::Dense => "dense",
            ReferenceKind::Reconstruction => "reconstruction",
        }
    }
}

impl std::fmt::Display for ReferenceKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

impl PartialEq<&str> for ReferenceKind {
    fn eq(&self, other: &&str) -> bool {
        self.as_str() == *other
    }
}

/// The `warnings` of a comparison (and of the trade and engines tables): the
/// reader warnings of FILE, then those of OTHER (`--vs`), each message
/// prefixed with OTHER's path so the two files' warnings stay apart.
pub fn file_warnings(
    file: &crate::model::Luminaire,
    other: Option<(&str, &crate::model::Luminaire)>,
) -> Vec<crate::error::Warning> {
    let mut out = file.warnings().to_vec();
    if let Some((path, lum)) = other {
        out.extend(lum.warnings().iter().map(|w| {
            let mut w = w.clone();
            w.message = format!("{path}: {}", w.message);
            w
        }));
    }
    out
}

/// The result of [`compare`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Comparison {
    /// FILE (set by the caller; empty by default).
    pub file: String,
    /// OTHER, with `vs`.
    pub vs: Option<String>,
    /// What the errors are measured against, in words: e.g. `truth
    /// (cosine-power p=5 peak=1000cd)`, `withheld (2-fold hold-out of the
    /// measured planes and rows)`, `dense: catmull-rom of OTHER`, or
    /// `catmull-rom of FILE (a reconstruction, not the truth)`.
    pub reference: String,
    /// `truth`, `withheld`, `dense` or `reconstruction`.
    pub reference_kind: ReferenceKind,
    /// Normalisation.
    pub normalize: Normalize,
    /// Unit of every `*_cd` value.
    pub units: String,
    /// Direction set of the radial metrics, e.g. `fibonacci 20000`.
    pub directions: String,
    /// Its size.
    pub n_directions: usize,
    /// What each row's `radial_max_cd` is, in words: e.g. `max over 20000
    /// directions (fibonacci 20000), refined locally around the 32 largest
    /// (pattern search to 0.001 deg)` against a field reference, `max over
    /// the 1234 withheld measured directions` against withheld measurements.
    pub radial_max_method: String,
    /// Hausdorff tolerance, fraction of I_max.
    pub tolerance: f64,
    /// The same in percent of I_max (`--tolerance 0.1%` is 0.1).
    pub tolerance_pct: f64,
    /// The same in `units`.
    pub tolerance_cd: f64,
    /// Grid solid refinement factor (used when `solid_tolerance_cd` is null).
    pub factor: usize,
    /// The adaptive solids' tolerance, in `units` (null: fixed `factor`).
    pub solid_tolerance_cd: Option<f64>,
    /// The same in percent of I_max (`--solid-tolerance 0.05%` is 0.05; null: fixed `factor`).
    pub solid_tolerance_pct: Option<f64>,
    /// The largest deviation of the reference's adaptive solid (or profile)
    /// from its field at the tested points, in `units` (null: fixed
    /// `factor`, or no reference solid); each row has its own.
    pub solid_deviation_cd: Option<f64>,
    /// Whether the reference's `solid_deviation_cd` is within `solid_tolerance_cd` (null with it).
    pub solid_tolerance_reached: Option<bool>,
    /// Reference I_max, in `units`.
    pub i_max_cd: f64,
    /// Triangles of the reference solid (0 for `withheld`).
    pub reference_triangles: usize,
    /// Zotti's constant C, fraction of I_max.
    pub zotti_c: f64,
    /// The alignment applied to FILE (with `vs` and `align`).
    pub alignment: Option<Alignment>,
    /// One per reconstruction.
    pub results: Vec<ReconResult>,
    /// The reconstruction with the fewest bytes whose radial max error is
    /// within 1 % of I_max against this comparison's reference (ties: the
    /// smaller error), or null when none is: `tradeoff`'s key of the same
    /// name, for any set of reconstructions ([`smallest_within_1pct`]).
    pub smallest_within_1pct: Option<String>,
    /// Plot data (with `plots`), not in the JSON.
    #[serde(skip)]
    pub plots: Option<PlotData>,
    /// With `vs`: flux, flux code, zonal lumens, UGR, BUG and luminance of
    /// FILE and OTHER side by side (set by the caller; see
    /// `photometry::derived::side_by_side`). Absent from the JSON when unset.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub photometry_side_by_side: Option<Vec<crate::photometry::derived::SideRow>>,
    /// The files' reader warnings, coded (`{line, code, message}`; codes in
    /// docs/warnings.md), OTHER's prefixed with its path (set by the caller).
    pub warnings: Vec<crate::error::Warning>,
}

/// The name with the fewest bytes among `rows` (name, bytes, radial max
/// error in % of I_max) whose error is at most `pct` (ties: the smaller
/// error); None when none is. The one rule of `smallest_within_1pct`. A
/// `…+gpu` row (the GPU's evaluation of a representation another row names)
/// is not a representation of its own and is never the answer.
pub fn smallest_named<'a>(rows: impl IntoIterator<Item = (&'a str, usize, f64)>, pct: f64) -> Option<String> {
    rows.into_iter()
        .filter(|r| r.2 <= pct && !r.0.ends_with(crate::registry::GPU_SUFFIX))
        .min_by(|a, b| a.1.cmp(&b.1).then(a.2.total_cmp(&b.2)))
        .map(|r| r.0.to_string())
}

/// [`Comparison::smallest_within_1pct`] of `results`: within
/// [`trade::WITHIN_PCT`] (1 %) of I_max.
pub fn smallest_within_1pct(results: &[ReconResult]) -> Option<String> {
    smallest_named(
        results.iter().map(|r| (r.name.as_str(), r.bytes, r.radial_max_pct)),
        trade::WITHIN_PCT,
    )
}

/// What a comparison's reference contributes to its [`Comparison`]: the
/// fields that differ between a field reference and withheld measurements.
pub(crate) struct ReferenceFacts {
    /// [`Comparison::reference`].
    pub reference: String,
    /// [`Comparison::reference_kind`].
    pub kind: ReferenceKind,
    /// [`Comparison::directions`].
    pub directions: String,
    /// [`Comparison::n_directions`].
    pub n_directions: usize,
    /// [`Comparison::radial_max_method`].
    pub radial_max_method: String,
    /// [`Comparison::tolerance_cd`].
    pub tolerance_cd: f64,
    /// [`Comparison::solid_tolerance_cd`].
    pub solid_tolerance_cd: Option<f64>,
    /// [`Comparison::solid_deviation_cd`].
    pub solid_deviation_cd: Option<f64>,
    /// [`Comparison::i_max_cd`].
    pub i_max_cd: f64,
    /// [`Comparison::reference_triangles`].
    pub reference_triangles: usize,
}

impl Comparison {
    /// The comparison of the rows `results` against `reference` under
    /// `opts` (the one place its fields are filled); `file`, `vs`, the
    /// alignment, the side-by-side photometry and the warnings are the
    /// caller's to set.
    pub(crate) fn assemble(
        opts: &CompareOptions,
        reference: ReferenceFacts,
        results: Vec<ReconResult>,
        plots: Option<PlotData>,
    ) -> Self {
        Comparison {
            file: String::new(),
            vs: None,
            reference: reference.reference,
            reference_kind: reference.kind,
            normalize: opts.normalize,
            units: opts.normalize.unit().into(),
            directions: reference.directions,
            n_directions: reference.n_directions,
            radial_max_method: reference.radial_max_method,
            tolerance: opts.tolerance,
            tolerance_pct: crate::error::percent_of(opts.tolerance),
            tolerance_cd: reference.tolerance_cd,
            factor: opts.factor,
            solid_tolerance_cd: reference.solid_tolerance_cd,
            solid_tolerance_pct: opts.solid_tolerance.map(crate::error::percent_of),
            solid_deviation_cd: reference.solid_deviation_cd,
            solid_tolerance_reached: reference
                .solid_deviation_cd
                .zip(reference.solid_tolerance_cd)
                .map(|(d, t)| d <= t),
            i_max_cd: reference.i_max_cd,
            reference_triangles: reference.reference_triangles,
            zotti_c: opts.zotti_c,
            alignment: None,
            smallest_within_1pct: smallest_within_1pct(&results),
            results,
            plots,
            photometry_side_by_side: None,
            warnings: Vec::new(),
        }
    }

    /// Whether H is a certified Hausdorff distance between two solids
    /// (within `tolerance_cd`, with a bound per row): false against withheld
    /// measurements, where H is the exact one-sided distance from the
    /// withheld points and no solid of the reference exists.
    pub fn hausdorff_certified(&self) -> bool {
        self.reference_kind != ReferenceKind::Withheld
    }
}

/// Symmetric Hausdorff distance between two solids (f32 positions widened to f64,
/// held once, by the BVHs).
pub fn solid_hausdorff(a: &Mesh, b: &Mesh, tolerance: f64) -> Hausdorff {
    let (ba, bb) = rayon::join(
        || Bvh::build_owned(a.positions_f64(), a.triangles()),
        || Bvh::build_owned(b.positions_f64(), b.triangles()),
    );
    hausdorff_bvh((&ba, a.triangles()), (&bb, b.triangles()), tolerance)
}

/// How much of the Hausdorff distance between two solids to measure.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SurfaceSearch {
    /// H with the mean and RMS surface distances: every vertex searched
    /// ([`hausdorff_bvh_below_bounds`]), each search started below its bound.
    Full,
    /// H alone: only the triangles that can set it are searched
    /// ([`hausdorff_bvh_bounded`]); no mean or RMS.
    SupremumOnly,
}

/// [`solid_hausdorff`] of two solids with their radial functions, which
/// bound every vertex's distance to the other solid ([`RadialMesh::distance_bound`]):
/// with [`SurfaceSearch::Full`] the same numbers as [`solid_hausdorff`], found
/// faster (each vertex's search starts below its bound, not below the last
/// vertex's distance plus the step between them, which on a fine solid is
/// many times the distance).
pub fn solid_hausdorff_radial(
    a: (&Mesh, &RadialMesh),
    b: (&Mesh, &RadialMesh),
    tolerance: f64,
    search: SurfaceSearch,
) -> Hausdorff {
    let bb = Bvh::build_owned(b.0.positions_f64(), b.0.triangles());
    solid_hausdorff_indexed(a, (b.0, b.1, &bb), tolerance, search)
}

/// [`solid_hausdorff_radial`] against a solid whose BVH is already built
/// (`b.2`, over `b.0`'s positions and triangles): the reference of a
/// comparison is the same for every row, so its BVH is built once, not once
/// a row (on a synthetic file's truth, 434 k triangles, about 0.1 s a row).
pub fn solid_hausdorff_indexed(
    a: (&Mesh, &RadialMesh),
    b: (&Mesh, &RadialMesh, &Bvh),
    tolerance: f64,
    search: SurfaceSearch,
) -> Hausdorff {
    if a.0.positions() == b.0.positions() && a.0.triangles() == b.0.triangles() {
        return same_surface(search);
    }
    let pa = a.0.positions_f64();
    let pb = b.2.positions();
    let scale = a.0.max_radius().max(b.0.max_radius());
    let ((ua, ub), ba) = rayon::join(
        || {
            rayon::join(
                || vertex_bounds(&pa, (b.1, pb), scale),
                || vertex_bounds(pb, (a.1, &pa), scale),
            )
        },
        || Bvh::build_owned(pa.clone(), a.0.triangles()),
    );
    let sides = (
        (&ba, a.0.triangles(), ua.as_slice()),
        (b.2, b.0.triangles(), ub.as_slice()),
    );
    match search {
        SurfaceSearch::Full => hausdorff_bvh_below_bounds(sides.0, sides.1, tolerance),
        // Solids on one grid with the same triangles: each triangle is within its
        // vertices' largest displacement of the other solid (`corresponding_bounds`).
        SurfaceSearch::SupremumOnly if a.0.triangles() == b.0.triangles() => {
            let within = corresponding_bounds(&pa, pb, a.0.triangles(), scale);
            hausdorff_bvh_bounded_within(sides.0, sides.1, tolerance, (&within, &within))
        }
        SurfaceSearch::SupremumOnly => hausdorff_bvh_bounded(sides.0, sides.1, tolerance),
    }
}

/// The distances between two solids with the same vertices and triangles: one
/// surface, so every distance is 0 exactly, found without a query (an engine
/// row whose defect does not change the file, such as a single C-plane of
/// rotational data, is its reference's own solid).
fn same_surface(search: SurfaceSearch) -> Hausdorff {
    let zero = match search {
        SurfaceSearch::Full => Some(0.0),
        SurfaceSearch::SupremumOnly => None,
    };
    let side = OneSided {
        value: 0.0,
        bound: 0.0,
        mean: zero,
        rms: zero,
        queries: 0,
        converged: true,
    };
    Hausdorff {
        value: 0.0,
        bound: 0.0,
        a_to_b: side,
        b_to_a: side,
    }
}

/// [`solid_hausdorff_radial`] with [`SurfaceSearch::SupremumOnly`]: H alone.
pub fn solid_hausdorff_bounded(a: (&Mesh, &RadialMesh), b: (&Mesh, &RadialMesh), tolerance: f64) -> Hausdorff {
    solid_hausdorff_radial(a, b, tolerance, SurfaceSearch::SupremumOnly)
}

/// An upper bound of each point's distance to the solid `other` (its
/// radial function and vertex positions), `scale` the larger solid's radius (cd).
///
/// A point p ≠ 0 is bounded by its distance to the triangles `other`
/// indexes around p's direction ([`RadialMesh::distance_bound`]: they hold
/// the one the ray along p leaves through, so the bound is at most the
/// radial difference, and less where the solid is oblique to the ray).
/// Where there are none (a zero-intensity region) or p is the origin, the
/// triangle inequality through the origin gives |p| + the nearest vertex's
/// radius. The margin (1e-9 relative plus 1e-7 of the scale) covers
/// rounding: a bound, never an estimate.
fn vertex_bounds(points: &[glam::DVec3], other: (&RadialMesh, &[glam::DVec3]), scale: f64) -> Vec<f64> {
    use rayon::prelude::*;
    let (radial, other_points) = other;
    let nearest_vertex = other_points.iter().map(|q| q.length()).fold(f64::INFINITY, f64::min);
    let margin = 1e-7 * scale;
    points
        .par_iter()
        .map(|&p| {
            let u = radial.distance_bound(p).unwrap_or(p.length() + nearest_vertex);
            u * (1.0 + 1e-9) + margin
        })
        .collect()
}

/// The polygon sag of a mesh whose vertices lie on the sphere of `radius` about the origin:
/// the largest distance between a triangle's plane region and the sphere,
/// `max_t (radius − sqrt(radius² − ρ_t²))` with ρ_t the triangle's circumradius
/// (half the longest edge for degenerate triangles). Each point of the mesh is
/// within it of the sphere and each point of the sphere within it of the
/// mesh (for a closed mesh around the centre), so H(mesh, sphere) ≤ sag.
pub fn sphere_sag(mesh: &Mesh, radius: f64) -> f64 {
    let p = mesh.positions();
    mesh.triangles()
        .iter()
        .map(|t| {
            let v = t.map(|i| glam::Vec3::from_array(p[i as usize]).as_dvec3());
            let (a, b, c) = ((v[1] - v[2]).length(), (v[2] - v[0]).length(), (v[0] - v[1]).length());
            let area2 = (v[1] - v[0]).cross(v[2] - v[0]).length();
            let longest = a.max(b).max(c);
            let rho = if area2 > 1e-12 * longest * longest {
                a * b * c / (2.0 * area2)
            } else {
                0.5 * longest
            };
            let rho = rho.min(radius);
            radius - (radius * radius - rho * rho).sqrt()
        })
        .fold(0.0, f64::max)
}

/// Compare the reconstructions of `file` with the reference (see the module docs).
///
/// # Errors
/// All-zero data, unknown grids, a failed fit, `truth` without a known
/// truth, `withheld` on a grid with nothing to withhold.
pub fn compare(
    file: &Distribution,
    vs: Option<&Distribution>,
    opts: &CompareOptions,
) -> Result<Comparison, ModelError> {
    compare_with_progress(file, vs, opts, &|_, _, _| {})
}

/// [`compare`], calling `progress` before each reconstruction is measured.
pub fn compare_with_progress(
    file: &Distribution,
    vs: Option<&Distribution>,
    opts: &CompareOptions,
    progress: &Progress<'_>,
) -> Result<Comparison, ModelError> {
    let k = opts.normalize.factor(file, opts.lamp_flux_lm[0])?;
    let mut a = file.scaled(k)?;
    let b_dist = match vs {
        Some(o) => Some(o.scaled(opts.normalize.factor(o, opts.lamp_flux_lm[1])?)?),
        None => None,
    };
    let mut alignment = None;
    if let (true, Some(b)) = (opts.align, &b_dist) {
        let al = best_alignment(&a, b, 4000)?;
        if al.rotate_deg != 0.0 || al.mirror {
            a = a.reoriented(al.rotate_deg, al.mirror)?;
        }
        alignment = Some(al);
    }
    let against = opts.reference(b_dist.is_some());
    let mut comparison = match (against, &b_dist) {
        // `k`: a Type A/B file's readings are scaled as the distribution was.
        (Against::Withheld, None) => withheld::compare_withheld(&a, k, opts, progress)?,
        (Against::Withheld, Some(_)) => {
            return Err(ModelError::Parameter {
                name: "against",
                value: "withheld".into(),
                reason: "withheld measurements are FILE's own; without --vs OTHER".into(),
            })
        }
        (Against::Truth, Some(_)) => {
            return Err(ModelError::Parameter {
                name: "against",
                value: "truth".into(),
                reason: "the truth is FILE's closed form; without --vs OTHER".into(),
            })
        }
        (Against::Truth, None) => fields::compare_with_truth(&a, k, opts, progress)?,
        (Against::Recon(r), other) => fields::compare_with_recon(&a, r, other.as_ref(), opts, progress)?,
    };
    comparison.alignment = alignment;
    Ok(comparison)
}

/// Mark the rows on the Pareto front of (time per sample, bytes, H).
pub(crate) fn mark_pareto(rows: &mut [ReconResult]) {
    let costs: Vec<Vec<f64>> = rows
        .iter()
        .map(|r| vec![r.time_per_sample_ns.unwrap_or(f64::NAN), r.bytes as f64, r.hausdorff_cd])
        .collect();
    for (r, p) in rows.iter_mut().zip(pareto_front(&costs)) {
        r.pareto = p;
    }
}
