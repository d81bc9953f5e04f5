//! Every reconstruction of FILE against a field reference: the closed-form
//! truth, or a reconstruction of OTHER (`dense`) or of FILE itself.

use super::*;

/// Every reconstruction of `a` (FILE scaled by `k`) against the closed-form
/// truth the options record, scaled by `k` too.
///
/// Errors: no truth recorded ([`ModelError::Parameter`]); those of the
/// reference solid and of [`compare_fields`].
pub(super) fn compare_with_truth(
    a: &Distribution,
    k: f64,
    opts: &CompareOptions,
    progress: &Progress<'_>,
) -> Result<Comparison, ModelError> {
    let truth = opts.truth.ok_or_else(|| ModelError::Parameter {
        name: "against",
        value: "truth".into(),
        reason: "this file records no closed-form truth (only files written by `photosolid synth` do); \
                 use withheld, or --vs a denser measurement"
            .into(),
    })?;
    let truth = Truth {
        peak_cd: truth.peak_cd * k,
        ..truth
    };
    let refinement = opts.refinement(a.max_cd());
    let (solid, found) = refinement.solid_with_progress(&truth, a, Units::Candela, &|_, _, what| {
        progress(0, opts.recons.len(), &format!("reference: {what}"))
    })?;
    let reference = FieldReference {
        label: format!("truth ({})", truth),
        kind: ReferenceKind::Truth,
        field: &truth,
        dist: a,
        solid,
        deviation: found.map(|f| f.tested_deviation_cd),
        file_dist: None,
    };
    compare_fields(a, &reference, opts, progress)
}

/// Every reconstruction of `a` (FILE, scaled) against the reconstruction `r`
/// of `other` (OTHER, scaled: `dense`), or without OTHER of `a` itself (the
/// row of `r` then left out).
pub(super) fn compare_with_recon(
    a: &Distribution,
    r: Recon,
    other: Option<&Distribution>,
    opts: &CompareOptions,
    progress: &Progress<'_>,
) -> Result<Comparison, ModelError> {
    let ref_dist = other.unwrap_or(a);
    let refs = Reconstructions::new(ref_dist.clone(), &[r])?;
    let field = refs.field(r)?;
    let (label, kind) = match other {
        Some(_) => (format!("dense: {r} of OTHER"), ReferenceKind::Dense),
        None => (
            format!("{r} of FILE (a reconstruction, not the truth)"),
            ReferenceKind::Reconstruction,
        ),
    };
    let recons: Vec<Recon> = if other.is_some() {
        opts.recons.clone()
    } else {
        opts.recons.iter().copied().filter(|x| *x != r).collect()
    };
    let refinement = opts.refinement(ref_dist.max_cd());
    let (solid, deviation) = own_or_grid_solid(&refs, r, &*field, ref_dist, &refinement, &|_, _, what| {
        progress(0, opts.recons.len(), &format!("reference: {what}"))
    })?;
    let reference = FieldReference {
        label,
        kind,
        field: &*field,
        dist: ref_dist,
        solid,
        deviation,
        file_dist: other.map(|_| a),
    };
    compare_fields(a, &reference, &CompareOptions { recons, ..opts.clone() }, progress)
}

/// A field reference and what its metrics need.
struct FieldReference<'a> {
    label: String,
    kind: ReferenceKind,
    field: &'a dyn IntensityField,
    /// The reference's own data (I_max, measured direction set, plots).
    dist: &'a Distribution,
    solid: Mesh,
    /// The adaptive reference solid's tested deviation from its field (cd).
    deviation: Option<f64>,
    /// FILE's data when the reference is another file (plots).
    file_dist: Option<&'a Distribution>,
}

/// Every reconstruction of `a` against a field reference.
fn compare_fields(
    a: &Distribution,
    reference: &FieldReference<'_>,
    opts: &CompareOptions,
    progress: &Progress<'_>,
) -> Result<Comparison, ModelError> {
    let c = FieldComparison::new(a, reference, opts)?;
    let mut results = Vec::with_capacity(opts.recons.len());
    let mut fields = Vec::with_capacity(opts.recons.len());
    for (i, &r) in opts.recons.iter().enumerate() {
        progress(i, opts.recons.len(), &r.to_string());
        let row_progress = |_: usize, _: usize, what: &str| progress(i, opts.recons.len(), &format!("{r}: {what}"));
        let field = c.recs.field(r)?;
        results.push(c.row(r, &*field, &row_progress)?);
        fields.push((r.to_string(), field));
    }
    progress(opts.recons.len(), opts.recons.len(), "done");
    mark_pareto(&mut results);
    let plots = opts.plots.then(|| {
        let named: Vec<(String, &dyn IntensityField)> = fields.iter().map(|(n, f)| (n.clone(), &**f)).collect();
        plot_data::plot_data(
            &named,
            Some((reference.label.as_str(), reference.field)),
            reference.dist,
            reference.file_dist,
            c.i_max,
        )
    });
    Ok(c.comparison(results, plots))
}

/// One comparison against a field reference: what every row is measured
/// against and with.
struct FieldComparison<'a> {
    a: &'a Distribution,
    reference: &'a FieldReference<'a>,
    opts: &'a CompareOptions,
    /// The reconstructions of `a`.
    recs: Reconstructions,
    /// The reference solid's radial function.
    ref_rm: RadialMesh,
    /// The reference solid's BVH, once a row is measured on solids.
    ref_bvh: std::sync::OnceLock<crate::metrics::Bvh>,
    /// The reference's I_max, cd.
    i_max: f64,
    /// The Hausdorff tolerance, cd.
    tol_cd: f64,
    /// The directions of the radial metrics, and the reference's values at them (cd).
    set: DirectionSet,
    values: Vec<f64>,
    /// The directions each reconstruction is timed at.
    timing: Vec<glam::DVec3>,
    refinement: Refinement,
    /// The reference's tested deviation from its field (cd): its profile's
    /// when it is measured on its profile, else its solid's.
    deviation: Option<f64>,
    /// The reference's meridian profile, when both files are rotational and it is C-independent.
    ref_profile: Option<Profile>,
    /// The knots of `a`'s grid: the γ angles a field is tested C-independent on.
    start: SolidGrid,
    /// The solid tolerance, cd (`None`: fixed grids).
    solid_tol_cd: Option<f64>,
}

impl<'a> FieldComparison<'a> {
    /// The reconstructions of `a`, the direction set with the reference's values,
    /// and the reference's profile where rows are measured on profiles.
    fn new(
        a: &'a Distribution,
        reference: &'a FieldReference<'a>,
        opts: &'a CompareOptions,
    ) -> Result<Self, ModelError> {
        let recs = Reconstructions::new(a.clone(), &opts.recons)?;
        let ref_rm = RadialMesh::new(&reference.solid);
        let i_max = reference.dist.max_cd();
        let tol_cd = opts.tolerance.max(0.0) * i_max;
        let set = match opts.directions {
            Directions::Measured => DirectionSet::measured(reference.dist),
            Directions::Dense(n) => DirectionSet::fibonacci(n),
        };
        let values = eval_all(reference.field, &set.directions);
        let timing = opts.timing_directions();
        let refinement = opts.refinement(i_max);
        let mut deviation = reference.deviation;
        // Solids of revolution: the reference's profile, when both files are rotational and it is C-independent.
        let rotational = a.symmetry() == Symmetry::Rotational && reference.dist.symmetry() == Symmetry::Rotational;
        let start = SolidGrid::knots(a)?;
        let ref_profile = match rotational && profile::is_c_independent(reference.field, start.gamma_angles_deg()) {
            true => {
                let (g, dev) = refinement.profile_gammas(reference.field, reference.dist)?;
                deviation = dev;
                Some(Profile::of_field(reference.field, &g))
            }
            false => None,
        };
        Ok(Self {
            a,
            reference,
            opts,
            recs,
            ref_rm,
            ref_bvh: std::sync::OnceLock::new(),
            i_max,
            tol_cd,
            set,
            values,
            timing,
            refinement,
            deviation,
            ref_profile,
            start,
            solid_tol_cd: opts.solid_tolerance.map(|f| f.max(0.0) * i_max),
        })
    }

    /// What a row is measured against: the reference's solid, radial function and values.
    fn target(&self) -> FieldTarget<'_> {
        FieldTarget {
            field: self.reference.field,
            solid: &self.reference.solid,
            radial: &self.ref_rm,
            bvh: &self.ref_bvh,
            set: &self.set,
            values: &self.values,
            i_max: self.i_max,
            tol_cd: self.tol_cd,
            zotti_c: self.opts.zotti_c,
            timing: &self.timing,
            repeats: self.opts.timing_repeats,
            hausdorff_only: self.opts.hausdorff_only,
        }
    }

    /// The row of `r`, whose field is `field`: on the meridian profiles when the
    /// reference has one and `field` is C-independent (or measured), else on its
    /// solid; with the deviation of its solid or profile (cd).
    fn row(&self, r: Recon, field: &dyn IntensityField, progress: &Progress<'_>) -> Result<ReconResult, ModelError> {
        let (a, target) = (self.a, self.target());
        // The measured solid of rotational data is the solid of revolution of its measured
        // profile (the measured field is exact at the measured directions, so the profile at
        // the file's γ angles passes through every measured point); a C-independent
        // reconstruction's profile is refined to the solid tolerance.
        let on_profile = self
            .ref_profile
            .as_ref()
            .filter(|_| r == Recon::Measured || profile::is_c_independent(field, self.start.gamma_angles_deg()));
        let (mut row, dev) = match on_profile {
            Some(rp) if r == Recon::Measured => {
                let own = Profile::of_field(field, a.gamma_angles_deg());
                let revolved = |_c: f64, g: f64| own.radius_at(g);
                let row = measure_profile(&r.to_string(), field, &revolved, &own, rp, &target);
                (row, None)
            }
            Some(rp) => {
                let (g, dev) = self.refinement.profile_gammas(field, a)?;
                let row = measure_profile(&r.to_string(), field, field, &Profile::of_field(field, &g), rp, &target);
                (row, dev)
            }
            None => {
                let (solid, dev) = own_or_grid_solid(&self.recs, r, field, a, &self.refinement, progress)?;
                (measure_field(&r.to_string(), field, &solid, &target), dev)
            }
        };
        row.solid_deviation_cd = dev;
        row.solid_tolerance_reached = dev.zip(self.solid_tol_cd).map(|(d, t)| d <= t);
        Ok(row)
    }

    /// The comparison of the rows `results` (Pareto front marked) with `plots`.
    fn comparison(&self, results: Vec<ReconResult>, plots: Option<PlotData>) -> Comparison {
        let reference = super::ReferenceFacts {
            reference: self.reference.label.clone(),
            kind: self.reference.kind,
            directions: self.set.label.clone(),
            n_directions: self.set.len(),
            radial_max_method: MAX_REFINEMENT.describe(&self.set),
            tolerance_cd: self.tol_cd,
            solid_tolerance_cd: self.solid_tol_cd,
            solid_deviation_cd: self.deviation,
            i_max_cd: self.i_max,
            reference_triangles: self.reference.solid.n_triangles(),
        };
        Comparison::assemble(self.opts, reference, results, plots)
    }
}
