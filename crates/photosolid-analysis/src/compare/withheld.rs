//! The `withheld` reference: k-fold hold-out of the measured grid.
//!
//! For each fold ([`kfold`]) every reconstruction is rebuilt from the kept
//! planes (rows) only and evaluated at the withheld measured directions
//! (every symmetry image of a withheld stored sample). The radial metrics
//! pool all folds (with k = 2 every inner sample is withheld once per axis,
//! so twice in all, each time with its measured solid angle). The
//! Hausdorff figure is one-sided and exact: the largest distance from a
//! withheld measured point `I·d` to the solid rebuilt without it. (A field
//! symmetric with the data, checked at every withheld point and at probe
//! directions over the sphere, is searched once per withheld stored sample:
//! its images are equally far from its solid.)

use glam::DVec3;
use rayon::prelude::*;

use super::{mark_pareto, own_or_grid_solid, CompareOptions, Comparison, Distances, Progress, ReconResult};
use crate::error::ModelError;
use crate::metrics::cells::{distances_to_cells, largest_distance_to_cells};
use crate::metrics::hausdorff::distances;
use crate::metrics::profile::{self, Profile};
use crate::metrics::{
    distances_to_solid, largest_distance_to_solid, radial_errors, time_per_sample_ns, Bvh, DirectionSet, NearestSearch,
    OneSided,
};
use crate::model::frame::direction;
use crate::model::{Distribution, IntensityField, Symmetry, ANGLE_EPS};
use crate::reconstruct::{eval_all, kfold, Fold};
use crate::registry::{Recon, Reconstructions};
use crate::solid::Refinement;

/// Searched points of one fold up to which the distances are searched on the
/// solid itself (`metrics::nearest`, 33-49 µs a point on 2 cores below; a field
/// symmetric with the data searches each stored sample once, not each of its
/// images, where the field is checked symmetric with the data); above, one
/// adaptive mesh of the rebuilt solid is cheaper. A mesh costs what the solid
/// needs, 0.6-7 s a row whatever the count, so the switch is where the search
/// costs about as much (release build, 2 cores, one row of the default
/// `compare`). With a small cap's seeds only at local minima of its samples
/// the search is about 1.5 times cheaper than when the switch sat at 6,000:
/// ITALO (6,400 points a fold) catmull-rom 1.91 s meshed, 0.85 s searched,
/// bilinear 0.85 / 0.75 s; OutdoorRoadway (12,800) catmull-rom 4.28 / 2.49 s,
/// bilinear 3.48 / 2.47 s. Searched, H moved by -0.013 to +0.006 % of I_max
/// on those two files (the meshes' 0.05 % tolerance).
pub const SURFACE_SEARCH_MAX_POINTS: usize = 13_000;

/// What one row gathers over the folds: each withheld point's
/// reconstructed value and distance (cd), and how the distances were measured.
#[derive(Default)]
struct RowDistances {
    /// The rebuilt field at each withheld direction, cd.
    recon: Vec<f64>,
    /// Each withheld point's distance to the rebuilt solid, cd.
    dist: Vec<f64>,
    /// The most triangles of a rebuilt solid (0 when none was meshed).
    triangles: usize,
    /// The largest deviation of a meshed solid or profile from its field, cd.
    deviation: Option<f64>,
    /// The most segments of a meridian profile.
    segments: Option<usize>,
    /// How the distances were measured (`ReconResult::withheld_distance`), in order of first use.
    methods: Vec<&'static str>,
    /// Points searched on the solid (symmetric images share a search).
    searched: usize,
    /// Only H is measured ([`CompareOptions::hausdorff_only`]): the folds
    /// searched on the solid or in cells then add only to `largest`, and
    /// `dist` holds the distances of the others (meshes, profiles).
    hausdorff_only: bool,
    /// The largest distance of the folds measured for H alone, cd.
    largest: f64,
}

impl RowDistances {
    fn method(&mut self, m: &'static str) {
        if !self.methods.contains(&m) {
            self.methods.push(m);
        }
    }

    /// The largest distance measured so far, cd.
    fn h(&self) -> f64 {
        self.dist.iter().copied().fold(self.largest, f64::max)
    }

    /// `self` followed by `next` (the fold after it): values in order, the
    /// largest of the maxima, methods in order of first use.
    fn merge(mut self, next: RowDistances) -> RowDistances {
        self.recon.extend(next.recon);
        self.dist.extend(next.dist);
        self.triangles = self.triangles.max(next.triangles);
        self.deviate(next.deviation);
        self.segments = self.segments.max(next.segments);
        for m in next.methods {
            self.method(m);
        }
        self.searched += next.searched;
        self.largest = self.largest.max(next.largest);
        self
    }

    fn deviate(&mut self, dev: Option<f64>) {
        if let Some(d) = dev {
            self.deviation = Some(self.deviation.map_or(d, |x| x.max(d)));
        }
    }

    /// Search the distances of the withheld points `polar` (one per stored
    /// sample with `images`) on the solid of `field`: only those that can set
    /// H when only H is measured (cheaper than a mesh at any count), else
    /// every one up to [`SURFACE_SEARCH_MAX_POINTS`]. False when a mesh is cheaper.
    fn add_searched(
        &mut self,
        field: &dyn IntensityField,
        polar: Vec<(DVec3, f64)>,
        images: Option<SharedImages>,
    ) -> bool {
        let searched = images.as_ref().map_or(polar.len(), |i| i.first.len());
        if self.hausdorff_only {
            let points = match images {
                Some(i) => i.first.iter().map(|&k| polar[k]).collect(),
                None => polar,
            };
            let l = largest_distance_to_solid(field, &points, &NearestSearch::default(), self.h());
            self.searched += l.searched;
            self.largest = self.largest.max(l.value_cd);
        } else if searched <= SURFACE_SEARCH_MAX_POINTS {
            self.searched += searched;
            self.dist.extend(surface_distances(field, &polar, images.as_ref()));
        } else {
            return false;
        }
        self.method("surface");
        true
    }

    /// Rebuild `r` from `fold`'s kept data and measure the `withheld`
    /// points (directions and measured values, cd) against it.
    fn add_fold(
        &mut self,
        r: Recon,
        fold: &Fold,
        withheld: &FoldPoints,
        rotational: bool,
        refinement: &Refinement,
        progress: &Progress<'_>,
    ) -> Result<(), ModelError> {
        let (set, m) = (&withheld.set, &withheld.measured_cd[..]);
        // Each withheld point as its direction and measured value, and as a position (cd).
        let polar = withheld.polar();
        let points: Vec<DVec3> = polar.iter().map(|&(d, v)| v * d).collect();
        // Kept data that is zero everywhere reconstructs to nothing: the
        // solid is the origin, every withheld point is |p| away from it.
        if fold.kept.max_cd() <= 0.0 {
            self.method("origin");
            self.recon.extend(std::iter::repeat_n(0.0, set.len()));
            self.dist.extend(m.iter().map(|v| v.abs()));
            return Ok(());
        }
        let recs = Reconstructions::new(fold.kept.clone(), &[r])?;
        let field = recs.field(r)?;
        self.recon.extend(eval_all(&*field, &set.directions));
        // Rotational data and a C-independent reconstruction: a solid of
        // revolution, the distances from its profile (metrics::profile).
        let start = crate::solid::SolidGrid::knots(&fold.kept)?;
        if rotational && r != Recon::Measured && profile::is_c_independent(&*field, start.gamma_angles_deg()) {
            let (g, dev) = refinement.profile_gammas(&*field, &fold.kept)?;
            self.deviate(dev);
            self.method("profile");
            let own = Profile::of_field(&*field, &g);
            self.segments = self.segments.max(Some(own.n_segments()));
            self.dist.extend(profile::distances_3d(&points, &own));
            return Ok(());
        }
        // Constant cells (a nearest lookup of a texture or of the data): exact distances to its
        // patches and walls in closed form (metrics::cells), no mesh.
        if let Some(cells) = field.constant_cells() {
            self.method("cells");
            if self.hausdorff_only {
                let l = largest_distance_to_cells(&cells, &polar, self.h());
                self.largest = self.largest.max(l.value_cd);
            } else {
                self.dist.extend(distances_to_cells(&cells, &polar));
            }
            return Ok(());
        }
        // Any other continuous field: the distance to its solid, searched on
        // the solid itself (metrics::nearest), with the walls along its rims
        // (a lobe mixture's hemisphere steps) searched beside it (metrics::walls).
        // The measured solid is a mesh, and a field that may jump elsewhere
        // has walls only a mesh holds.
        // A field that answers only in batches (the GPU's) is meshed: the search asks one direction at a time.
        if r != Recon::Measured && field.rims().is_some() && !field.prefers_batches() {
            let values = &self.recon[self.recon.len() - polar.len()..];
            let tol_cd = SYMMETRY_TOLERANCE * fold.kept.max_cd();
            let images = shared_images(&*field, fold.kept.symmetry(), values, &withheld.stored, tol_cd);
            if self.add_searched(&*field, polar, images) {
                return Ok(());
            }
        }
        self.method("mesh");
        match own_or_grid_solid(&recs, r, &*field, &fold.kept, refinement, progress) {
            Ok((solid, dev)) => {
                self.deviate(dev);
                self.triangles = self.triangles.max(solid.n_triangles());
                let pos = solid.positions_f64();
                self.dist
                    .extend(distances(&points, &Bvh::build(&pos, solid.triangles())));
            }
            // A reconstruction that is zero everywhere (a fit to dark data) has no solid either.
            Err(ModelError::AllZero(_)) => self.dist.extend(m.iter().map(|v| v.abs())),
            Err(e) => return Err(e),
        }
        Ok(())
    }
}

/// Every reconstruction of `a` against its own withheld measurements.
///
/// `scale`: what the file's values were multiplied by to give `a` (the
/// normalisation), applied to a Type A/B file's readings as well.
pub(super) fn compare_withheld(
    a: &Distribution,
    scale: f64,
    opts: &CompareOptions,
    progress: &Progress<'_>,
) -> Result<Comparison, ModelError> {
    let h = HoldOut::new(a, scale, opts)?;
    let i_max = h.i_max;
    let mut results = Vec::with_capacity(opts.recons.len());
    for (i, &r) in opts.recons.iter().enumerate() {
        progress(i, opts.recons.len(), &r.to_string());
        let row_progress = |_: usize, _: usize, what: &str| progress(i, opts.recons.len(), &format!("{r}: {what}"));
        results.push(h.row(r, &row_progress)?);
    }
    progress(opts.recons.len(), opts.recons.len(), "done");
    mark_pareto(&mut results);
    let plots = opts.plots.then(|| h.plot_data(a));
    let reference = super::ReferenceFacts {
        reference: h.reference.clone(),
        kind: super::ReferenceKind::Withheld,
        directions: h.pooled.label.clone(),
        n_directions: h.pooled.len(),
        radial_max_method: format!("max over the {} withheld measured directions", h.pooled.len()),
        // Printed in the file's unit; the withheld H is exact and uses no tolerance.
        tolerance_cd: opts.tolerance * i_max,
        solid_tolerance_cd: h.solid_tol_cd,
        solid_deviation_cd: None,
        i_max_cd: i_max,
        reference_triangles: 0,
    };
    Ok(Comparison::assemble(opts, reference, results, plots))
}

/// Two field values count as equal for [`shared_images`] within this
/// fraction of the kept data's I_max (a filter's images differ by rounding,
/// about 1e-16; a distance differs by at most the value's difference).
const SYMMETRY_TOLERANCE: f64 = 1e-9;

/// Withheld points searched once per stored sample: `first` holds the first
/// point of each sample (indices into the points), `of_point` each point's
/// position in `first`.
struct SharedImages {
    first: Vec<usize>,
    of_point: Vec<usize>,
}

/// Probe directions of the symmetry check in [`shared_images`] (a Fibonacci lattice).
const SYMMETRY_PROBES: usize = 1024;

/// The images of each withheld stored sample (`stored`: the sample of each
/// point) share one search when the rebuilt field is symmetric with the data
/// (`symmetry`, the kept data's): a point and its images are then equally far
/// from its solid. A filter's texture holds the stored planes' images and is
/// symmetric; a render whose column centres are not symmetric, a block-
/// compressed texture or a fit need not be. So the symmetry is checked, not
/// assumed, where the searches look: `Some` only when the field's `values` at
/// the points equal their sample's first point's value, and the field at
/// [`SYMMETRY_PROBES`] directions spread over the sphere equals it at each of
/// their images, all within `tol_cd`, and some sample has two points. (Equal
/// values at the points alone would miss a field that agrees there but not
/// between them, where a search may find the nearest point.)
fn shared_images(
    field: &dyn IntensityField,
    symmetry: Symmetry,
    values: &[f64],
    stored: &[(usize, usize)],
    tol_cd: f64,
) -> Option<SharedImages> {
    let (first, of_point) = first_images(stored);
    if first.len() == stored.len() || values.len() != stored.len() {
        return None;
    }
    let at_points = values
        .iter()
        .zip(&of_point)
        .all(|(v, &k)| (v - values[first[k]]).abs() <= tol_cd);
    let at_probes = || {
        DirectionSet::fibonacci(SYMMETRY_PROBES)
            .directions
            .iter()
            .all(|&(c, g)| {
                let v = field.intensity_cd(c, g);
                symmetry
                    .images(c)
                    .into_iter()
                    .all(|ci| (field.intensity_cd(ci, g) - v).abs() <= tol_cd)
            })
    };
    (at_points && at_probes()).then_some(SharedImages { first, of_point })
}

/// The distance of each withheld point `polar` (direction, measured cd) to
/// the solid of `field`, searched on the solid itself: once per stored sample
/// when `images` says the field is symmetric with the data.
fn surface_distances(field: &dyn IntensityField, polar: &[(DVec3, f64)], images: Option<&SharedImages>) -> Vec<f64> {
    let search = NearestSearch::default();
    let Some(images) = images else {
        return distances_to_solid(field, polar, &search);
    };
    let points: Vec<(DVec3, f64)> = images.first.iter().map(|&i| polar[i]).collect();
    let d = distances_to_solid(field, &points, &search);
    images.of_point.iter().map(|&k| d[k]).collect()
}

/// The first point of each stored sample in `stored` (indices into it), and
/// for every point the position of its sample's first point in that list.
fn first_images(stored: &[(usize, usize)]) -> (Vec<usize>, Vec<usize>) {
    let mut seen = std::collections::HashMap::with_capacity(stored.len());
    let mut first = Vec::new();
    let of_point = stored
        .iter()
        .enumerate()
        .map(|(i, key)| {
            *seen.entry(*key).or_insert_with(|| {
                first.push(i);
                first.len() - 1
            })
        })
        .collect();
    (first, of_point)
}

/// The withheld points of one fold.
pub(super) struct FoldPoints {
    /// The withheld directions, each with its measured solid angle.
    pub(super) set: DirectionSet,
    /// The measured value at each of them, cd.
    pub(super) measured_cd: Vec<f64>,
    /// The stored sample each of them is an image of: `(ic, ig)` of the
    /// Type C grid, or `(ih, iv)` of a Type A/B file's readings.
    pub(super) stored: Vec<(usize, usize)>,
}

impl FoldPoints {
    /// Each point as its unit direction and measured value (cd).
    fn polar(&self) -> Vec<(DVec3, f64)> {
        self.set
            .directions
            .iter()
            .zip(&self.measured_cd)
            .map(|(&(c, g), &v)| (direction(c, g), v))
            .collect()
    }

    /// Every symmetry image of the stored samples `fold` withholds from `a`.
    fn of(a: &Distribution, fold: &Fold, planes: &[(f64, usize)]) -> Self {
        let mut mask = vec![false; a.n_c() * a.n_gamma()];
        for &(ic, ig) in &fold.withheld {
            mask[ic * a.n_gamma() + ig] = true;
        }
        let at = |ic: usize, ig: usize| mask[ic * a.n_gamma() + ig];
        let set = DirectionSet::measured_where(a, "withheld", at);
        // The same order as `measured_where`: rows, then full planes; a pole
        // row is one direction, kept when any plane's sample there is (`kfold`
        // withholds no pole today: this keeps the lists aligned if it did).
        let mut measured_cd = Vec::with_capacity(set.len());
        let mut stored = Vec::with_capacity(set.len());
        for (ig, &g) in a.gamma_angles_deg().iter().enumerate() {
            let pole = g <= ANGLE_EPS || g >= 180.0 - ANGLE_EPS;
            let withheld = planes.iter().filter(|&&(_, ic)| at(ic, ig));
            for &(_, ic) in withheld.take(if pole { 1 } else { usize::MAX }) {
                measured_cd.push(a.value_cd(ic, ig));
                stored.push((ic, ig));
            }
        }
        debug_assert_eq!(stored.len(), set.len(), "one value per withheld direction");
        Self {
            set,
            measured_cd,
            stored,
        }
    }
}

/// One withheld comparison's folds and withheld points, and what every row
/// is measured with.
struct HoldOut<'a> {
    opts: &'a CompareOptions,
    /// What was withheld (the comparison's `reference`).
    reference: String,
    folds: Vec<Fold>,
    /// The withheld points of each fold.
    sets: Vec<FoldPoints>,
    /// Every fold's withheld directions (the radial metrics pool the folds).
    pooled: DirectionSet,
    /// The measured value at each direction of `pooled`, cd.
    m_all: Vec<f64>,
    /// The reconstructions from all the data (bytes, timing, plots).
    full: Reconstructions,
    /// The directions each reconstruction is timed at.
    timing: Vec<DVec3>,
    refinement: Refinement,
    /// I_max of the data, cd.
    i_max: f64,
    rotational: bool,
    /// The solid tolerance, cd (`None`: fixed grids).
    solid_tol_cd: Option<f64>,
}

impl<'a> HoldOut<'a> {
    /// The folds of `a` and their withheld points, and `a`'s reconstructions
    /// (`scale`: the normalisation of `a`, for a Type A/B file's readings).
    ///
    /// Errors: those of [`kfold`] and of the reconstructions; data without
    /// light ([`ModelError::AllZero`]).
    fn new(a: &Distribution, scale: f64, opts: &'a CompareOptions) -> Result<Self, ModelError> {
        let i_max = a.max_cd();
        if i_max.is_nan() || i_max <= 0.0 {
            return Err(ModelError::AllZero("errors are relative to I_max"));
        }
        let readings = match &opts.source {
            Some(src) => super::withheld_source::source_folds(a, scale, src, opts.folds)?,
            None => None,
        };
        let (folds, sets, of_readings) = match readings {
            Some((folds, sets)) => (folds, sets, true),
            None => {
                let folds = kfold(a, opts.folds)?;
                let planes = a.full_planes();
                let sets: Vec<FoldPoints> = folds.iter().map(|f| FoldPoints::of(a, f, &planes)).collect();
                (folds, sets, false)
            }
        };
        let withheld_what = if of_readings { "readings" } else { "samples" };
        let pooled = DirectionSet {
            label: format!(
                "withheld {withheld_what} of a {}-fold hold-out ({} folds)",
                opts.folds,
                folds.len()
            ),
            directions: sets.iter().flat_map(|s| s.set.directions.iter().copied()).collect(),
            weights: sets.iter().flat_map(|s| s.set.weights.iter().copied()).collect(),
        };
        let m_all: Vec<f64> = sets.iter().flat_map(|s| s.measured_cd.iter().copied()).collect();
        let full = Reconstructions::new(a.clone(), &opts.recons)?;
        let reference = match (&opts.source, of_readings) {
            (Some(src), true) => format!(
                "withheld ({}-fold hold-out of the Type {:?} file's own readings: its horizontal and vertical angles; each reconstruction rebuilt from the rest through the same conversion to Type C)",
                opts.folds, src.grid.kind
            ),
            (Some(src), false) => format!(
                "withheld ({}-fold hold-out of the converted Type C grid's C-planes and gamma rows: the Type {:?} readings do not rebuild this distribution; each reconstruction rebuilt without them)",
                opts.folds, src.grid.kind
            ),
            (None, _) => format!(
                "withheld ({}-fold hold-out of the measured C-planes and gamma rows; each reconstruction rebuilt without them)",
                opts.folds
            ),
        };
        Ok(Self {
            opts,
            reference,
            folds,
            sets,
            pooled,
            m_all,
            full,
            timing: opts.timing_directions(),
            refinement: opts.refinement(i_max),
            i_max,
            rotational: a.symmetry() == crate::model::Symmetry::Rotational,
            solid_tol_cd: opts.solid_tolerance.map(|f| f.max(0.0) * i_max),
        })
    }

    /// Every fold of the row of `r`, merged in fold order.
    ///
    /// The folds run side by side: each one's serial steps (rebuilding the
    /// reconstruction, meshing, a BVH) then overlap another's parallel search
    /// instead of leaving cores idle (`compare` on 8.IES used 1.4 of 2 cores
    /// with the folds one after the other; BENCHMARKS.md). Every fold's values
    /// are its own, so the merged row equals the sequential one. With H alone
    /// a fold no longer prunes its points with the largest distance of the
    /// folds before it, only with its own: more points are searched, H is the
    /// same, and `tradeoff` was still faster (projector 4.3 → 3.8 s).
    fn row_distances(&self, r: Recon, progress: &Progress<'_>) -> Result<RowDistances, ModelError> {
        let fresh = || RowDistances {
            hausdorff_only: self.opts.hausdorff_only,
            ..RowDistances::default()
        };
        let folds = self
            .folds
            .par_iter()
            .zip(self.sets.par_iter())
            .map(|(fold, points)| {
                let mut acc = fresh();
                acc.add_fold(r, fold, points, self.rotational, &self.refinement, progress)?;
                Ok(acc)
            })
            .collect::<Result<Vec<_>, ModelError>>()?;
        Ok(folds.into_iter().fold(fresh(), RowDistances::merge))
    }

    /// The row of `r`: rebuilt without each fold's withheld points and measured
    /// at them (the folds pooled), its bytes and lookup time from all the data.
    fn row(&self, r: Recon, progress: &Progress<'_>) -> Result<ReconResult, ModelError> {
        let i_max = self.i_max;
        let row_acc = self.row_distances(r, progress)?;
        let h = row_acc.h();
        let RowDistances {
            recon: recon_all,
            dist: dist_all,
            triangles,
            deviation,
            segments,
            methods,
            searched: _,
            hausdorff_only,
            largest: _,
        } = row_acc;
        let rad = radial_errors(&self.pooled, &self.m_all, &recon_all, i_max, self.opts.zotti_c);
        let n = dist_all.len().max(1) as f64;
        // With H alone, the searched folds' points have no distances: no mean.
        let mean = (!hausdorff_only).then(|| dist_all.iter().sum::<f64>() / n);
        let rms = (!hausdorff_only).then(|| (dist_all.iter().map(|d| d * d).sum::<f64>() / n).sqrt());
        let field = self.full.field(r)?;
        let mut row = ReconResult::new(
            r.to_string(),
            field.bytes(),
            Distances {
                value: h,
                bound: 0.0,
                recon_to_ref: None,
                ref_to_recon: mean.zip(rms).map(|(mean, rms)| OneSided {
                    value: h,
                    bound: 0.0,
                    mean: Some(mean),
                    rms: Some(rms),
                    queries: dist_all.len(),
                    // Exact point-to-triangle distances: nothing left to refine.
                    converged: true,
                }),
                mean,
                rms,
                radial_bound: rad.max_abs_cd,
            },
            &rad,
            i_max,
            Some(time_per_sample_ns(&*field, &self.timing, self.opts.timing_repeats)),
            triangles,
        );
        row.solid_deviation_cd = deviation;
        row.solid_tolerance_reached = deviation.zip(self.solid_tol_cd).map(|(d, t)| d <= t);
        row.profile_segments = segments;
        row.withheld_distance = Some(methods.join("+"));
        row.form = field.form();
        Ok(row)
    }

    /// The report's plot data: every reconstruction of `a` from all its data, and
    /// the 3D view against the measured solid ([`measured_viewer`]).
    fn plot_data(&self, a: &Distribution) -> super::PlotData {
        let fields: Vec<(String, Box<dyn IntensityField + '_>)> = self
            .opts
            .recons
            .iter()
            .filter_map(|&r| self.full.field(r).ok().map(|f| (r.to_string(), f)))
            .collect();
        let named: Vec<(String, &dyn IntensityField)> = fields.iter().map(|(n, f)| (n.clone(), &**f)).collect();
        let mut p = super::plot_data::plot_data(&named, None, a, None, self.i_max);
        p.viewer = measured_viewer(a, &named, self.i_max);
        p
    }
}

/// The 3D view of a withheld comparison: withheld points are no surface, so
/// the colours show each reconstruction's difference from the measured solid
/// (through every measured point), and the caption says so. `None` when the
/// measured solid cannot be built (the table is still written).
fn measured_viewer(
    a: &Distribution,
    named: &[(String, &dyn IntensityField)],
    i_max: f64,
) -> Option<super::SampledSolids> {
    let measured = Reconstructions::new(a.clone(), &[Recon::Measured]).ok()?;
    let field = measured.field(Recon::Measured).ok()?;
    let others: Vec<(String, &dyn IntensityField)> = named
        .iter()
        .filter(|(n, _)| *n != Recon::Measured.to_string())
        .map(|(n, f)| (n.clone(), *f))
        .collect();
    Some(super::SampledSolids::new(&super::SolidSet {
        reference_label: "the measured solid (through every measured point)",
        reference: &*field,
        recons: &others,
        i_max,
        note: Some(
            "The table measures against the withheld measurements; a surface cannot be withheld, \
             so the colours show the difference from the measured solid."
                .into(),
        ),
        error_domain: None,
    }))
}

#[cfg(test)]
mod tests;
