//! One row of a comparison: a field (its solid or its profile) measured
//! against the reference's solid, profile and values.

use super::*;
use std::sync::OnceLock;

/// What a field is measured against: the reference's solid, its radial
/// function, its values on the direction set, and the measurement settings.
pub(crate) struct FieldTarget<'a> {
    /// The reference field (its radial maximum is refined between the set's directions).
    pub field: &'a dyn IntensityField,
    pub solid: &'a Mesh,
    pub radial: &'a RadialMesh,
    /// The BVH of `solid`, built by the first row measured on solids and
    /// kept for the others (rows on profiles never build it).
    pub bvh: &'a OnceLock<Bvh>,
    pub set: &'a DirectionSet,
    /// The reference's intensity (cd) at every direction of `set`.
    pub values: &'a [f64],
    /// The reference's peak (cd), for percentages.
    pub i_max: f64,
    /// Hausdorff tolerance, cd.
    pub tol_cd: f64,
    pub zotti_c: f64,
    /// Unit directions to time lookups on (none: no timing).
    pub timing: &'a [glam::DVec3],
    pub repeats: usize,
    /// Only H is measured between the solids (the triangles that cannot set
    /// it are pruned, [`solid_hausdorff_bounded`]): no mean or RMS distance.
    pub hausdorff_only: bool,
}

/// One row: `field` (whose solid is `solid`) against `target`, every metric.
pub(crate) fn measure_field(
    name: &str,
    field: &dyn IntensityField,
    solid: &Mesh,
    target: &FieldTarget<'_>,
) -> ReconResult {
    let own = RadialMesh::new(solid);
    let search = if target.hausdorff_only {
        SurfaceSearch::SupremumOnly
    } else {
        SurfaceSearch::Full
    };
    let bvh = target
        .bvh
        .get_or_init(|| Bvh::build_owned(target.solid.positions_f64(), target.solid.triangles()));
    let h = solid_hausdorff_indexed((solid, &own), (target.solid, target.radial, bvh), target.tol_cd, search);
    let radial = radial_bound(&own, target.radial, &target.set.directions);
    measured_row(name, field, field, &h, radial, target, solid.n_triangles())
}

/// One row of a C-independent `field` whose profile is `own` against the
/// reference profile `reference`: the solids of revolution's Hausdorff
/// distance and radial bound from the profiles (see the module docs).
/// `surface` gives the radial errors' values (the field itself, or for the
/// measured solid of rotational data the revolution of its profile);
/// `field` the bytes and the lookup time.
pub(super) fn measure_profile(
    name: &str,
    field: &dyn IntensityField,
    surface: &dyn IntensityField,
    own: &Profile,
    reference: &Profile,
    target: &FieldTarget<'_>,
) -> ReconResult {
    use rayon::prelude::*;
    let h = profile::hausdorff(own, reference, target.tol_cd);
    let radial = target
        .set
        .directions
        .par_iter()
        .map(|&(_, g)| (own.radius_at(g) - reference.radius_at(g)).abs())
        .reduce(|| 0.0, f64::max);
    let mut row = measured_row(name, field, surface, &h, radial, target, 0);
    row.profile_segments = Some(own.n_segments());
    row
}

/// The row of `field` from its Hausdorff distance and radial bound to the
/// target, the radial errors from `surface`'s values (the maximum refined
/// between the set's directions, [`MAX_REFINEMENT`]).
fn measured_row(
    name: &str,
    field: &dyn IntensityField,
    surface: &dyn IntensityField,
    h: &Hausdorff,
    radial: f64,
    target: &FieldTarget<'_>,
    triangles: usize,
) -> ReconResult {
    let rad = field_radial_errors(
        target.set,
        target.values,
        target.field,
        surface,
        target.i_max,
        target.zotti_c,
        Some(&MAX_REFINEMENT),
    );
    let (ab, ba) = (h.a_to_b, h.b_to_a);
    let mut row = ReconResult::new(
        name.to_string(),
        field.bytes(),
        Distances {
            value: h.value,
            bound: h.bound,
            recon_to_ref: Some(ab),
            ref_to_recon: Some(ba),
            mean: ab.mean.zip(ba.mean).map(|(x, y)| 0.5 * (x + y)),
            rms: ab.rms.zip(ba.rms).map(|(x, y)| (0.5 * (x * x + y * y)).sqrt()),
            radial_bound: radial,
        },
        &rad,
        target.i_max,
        (!target.timing.is_empty()).then(|| time_per_sample_ns(field, target.timing, target.repeats)),
        triangles,
    );
    row.form = field.form();
    row
}

/// The solid of reconstruction `r` of `a`: the measured solid itself, else
/// the grid solid of `field` (already built, so a texture is not rendered
/// twice) under `refinement`, with an adaptive solid's tested deviation (cd);
/// each adaptive round is reported to `progress`.
pub(crate) fn own_or_grid_solid(
    recs: &Reconstructions,
    r: Recon,
    field: &dyn IntensityField,
    a: &Distribution,
    refinement: &Refinement,
    progress: &Progress<'_>,
) -> Result<(Mesh, Option<f64>), ModelError> {
    match r {
        Recon::Measured => Ok((recs.solid(r, 1)?, None)),
        _ => {
            let (mesh, found) = refinement.solid_with_progress(field, a, Units::Candela, progress)?;
            Ok((mesh, found.map(|f| f.tested_deviation_cd)))
        }
    }
}

/// The point budget (C x γ) of each adaptive grid solid of a comparison:
/// 2^19, about a million triangles. A comparison builds several solids (one
/// per reconstruction and fold) and measures each; where the budget stops a
/// refinement the row says so (`solid_tolerance_reached` false).
pub const SOLID_MAX_POINTS: usize = 1 << 19;

impl CompareOptions {
    /// How the grid solids are built for a reference of peak `i_max_cd` (cd):
    /// adaptive to `solid_tolerance` x `i_max_cd` (an absolute tolerance, the
    /// same for every solid) within [`SOLID_MAX_POINTS`], or refined `factor` times.
    pub fn refinement(&self, i_max_cd: f64) -> Refinement {
        match self.solid_tolerance {
            Some(f) => Refinement::Adaptive(AdaptiveOptions {
                max_points: SOLID_MAX_POINTS,
                ..AdaptiveOptions::new(Tolerance::Candela(f.max(0.0) * i_max_cd))
            }),
            None => Refinement::Factor(self.factor),
        }
    }
}

/// max over `dirs` of |r_a − r_b|.
pub(crate) fn radial_bound(a: &RadialMesh, b: &RadialMesh, dirs: &[(f64, f64)]) -> f64 {
    use rayon::prelude::*;
    dirs.par_iter()
        .map(|&(c, g)| {
            let w = crate::model::frame::direction(c, g);
            (a.radius(w) - b.radius(w)).abs()
        })
        .reduce(|| 0.0, f64::max)
}
