//! The speed/accuracy trade: every representation a renderer could hold, its
//! cost (bytes, time per lookup from a unit direction) and its error against
//! the truth, the withheld measurements, or a denser file.
//!
//! Representations ([`representations`]): the measured solid; every filter
//! evaluated on the native grid (the texture of measured values, f64);
//! Catmull–Rom textures rendered at factors k read back with nearest,
//! bilinear and Catmull–Rom lookups; the k = 5 bilinear texture stored in
//! f16, 16-bit and 8-bit normalised integers (`+u16`, `+u8`: steps of the
//! largest texel), BC6H blocks (`+bc6h`, feature `bc6h`) and/or only in the symmetry's C sector; the fitted OpenGL lights with
//! precomputed axes and cut-off cosines; spherical harmonics `sh:L` of the
//! Catmull–Rom reconstruction for L in [`SH_DEGREES`] and L =
//! [`FRONT_SH_DEGREE`], and on data the same in every C-plane L in
//! [`ZONAL_FRONT_SH_DEGREES`] ([`crate::reconstruct::sh`], Lanczos-windowed, named
//! in `window`); mixtures of K cosine-power lobes `lobes:K` for K in
//! [`LOBE_COUNTS`] and K in [`FRONT_LOBE_COUNTS`] ([`crate::fit::lobes`]);
//! then the representations on the open trait ([`crate::registry::Representation`]:
//! the mean profile over C, `c-mean`, where the file stores more than one
//! plane, then those a caller added to the registry). Errors come from [`compare`](super::compare())
//! (same metrics, same reference rules); a row is on the Pareto front
//! (`pareto`) when no other row is at most as costly in time, bytes and
//! Hausdorff error and cheaper in one, and on the bytes front
//! (`pareto_bytes`) when no other row is at most as large and as far off in
//! radial max error and better in one. `smallest_within_1pct` names the
//! smallest row whose radial max error is within 1 % of I_max.
//!
//! With [`TradeOptions::gpu`] (feature `gpu`), the k = 5 Catmull–Rom texture
//! is also read by the GPU's texture hardware, bilinear and Catmull–Rom from
//! linear fetches ([`Recon::Gpu`], rows named `…+gpu`): their errors are
//! measured exactly as the other rows' (the hardware lookup evaluated in
//! batches), their `ns_per_sample` is the batch's end-to-end time per
//! direction as the caller sees it (upload, dispatch, read-back),
//! `ns_per_sample_gpu` the dispatch alone, and they name the adapter, the
//! texture format, the observed sub-texel weight precision and the largest
//! difference from the exact lookup on the same texels. `sh:16+gpu` and
//! `lobes:4+gpu` are the largest series and mixture of the table evaluated
//! by the GPU's compute shader in f32 (`gpu::compact`), measured the same
//! way; their largest difference is from the CPU's f64 evaluation of the
//! same stored parameters.

use serde::Serialize;

use super::{compare_with_progress, Against, CompareOptions, Comparison, Progress};
use crate::error::ModelError;
use crate::model::{Distribution, IntensityField, Symmetry};
use crate::reconstruct::{ShWindow, TextureSpec};
use crate::registry::{Job, Recon, Registry};

pub use crate::registry::builtin::{
    FRONT_LOBE_COUNTS, FRONT_SH_DEGREE, LOBE_COUNTS, SH_DEGREES, ZONAL_FRONT_SH_DEGREES,
};

/// The trade table's CPU rows for data with `symmetry` whose C-planes
/// differ, textures at each of `factors` (see the module docs): the built-in
/// registry's candidates for [`Job::TradeRows`].
pub fn representations(symmetry: Symmetry, factors: &[u32]) -> Vec<Recon> {
    Registry::builtin().candidates(&Job::TradeRows { symmetry, factors })
}

/// The trade table's CPU rows for `file` (its declared symmetry; the extra
/// zonal `sh:L` rows, [`ZONAL_FRONT_SH_DEGREES`], where every C-plane holds
/// the same values), then those of the representations on the open trait
/// (the built-in `c-mean` where the file stores more than one plane, then
/// those added to `registry`, [`Registry::register`]): its candidates for
/// [`Job::Tradeoff`].
pub fn representations_of(file: &Distribution, factors: &[u32], registry: &Registry) -> Vec<Recon> {
    registry.candidates(&Job::Tradeoff {
        file,
        factors,
        gpu: false,
    })
}

/// Largest radial error (% of I_max) of [`TradeTable::smallest_within_1pct`].
pub const WITHIN_PCT: f64 = 1.0;

/// One representation's costs and errors.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TradeRow {
    /// The representation (`catmull-rom`, `catmull-rom@x5/bilinear+f16`, `fitted-gl`, `measured`).
    pub representation: String,
    /// The same as a value of the registry (`None` for a row built by hand),
    /// so that nothing finds a row's reconstruction by its name; not in the JSON.
    #[serde(skip)]
    pub recon: Option<Recon>,
    /// Bytes it holds to answer lookups.
    pub bytes: usize,
    /// Median ns per lookup from a unit direction vector, one thread, f64.
    pub ns_per_sample: f64,
    /// Stored-texture rows: median ns per lookup with every step in f32 from
    /// an f32 unit vector (angles, texel coordinates, weights, sums), as a
    /// shader computes it; null for other rows.
    pub ns_per_sample_f32: Option<f64>,
    /// Stored-texture rows: largest |f32 lookup − f64 lookup| over the timing
    /// directions, % of I_max: what computing in f32 alone costs (about 1e-4 %
    /// for bilinear and Catmull-Rom; for nearest a whole texel step, where an
    /// f32 angle falls on the other side of a texel edge).
    pub f32_vs_f64_max_pct: Option<f64>,
    /// `+gpu` rows: median ns per direction of the GPU dispatch alone
    /// (the timing directions resident on the device); null for CPU rows and
    /// for a representation on the open trait, whose GPU path is timed whole
    /// (`ns_per_sample`).
    pub ns_per_sample_gpu: Option<f64>,
    /// `+gpu` rows: the adapter, e.g. `llvmpipe (LLVM 15.0.6, 256 bits) [Vulkan, Cpu, …]`.
    pub adapter: Option<String>,
    /// `+gpu` texture rows: the texture format used (`R32Float`, or `R16Float` where
    /// the adapter cannot filter 32-bit floats); null for `sh:L+gpu` and `lobes:K+gpu`.
    pub texture_format: Option<String>,
    /// `+gpu` texture rows: the adapter's observed sub-texel weight precision, bits
    /// (`gpu::precision::subtexel_precision`, 65,537 probes: 16 means at least 16).
    pub subtexel_bits: Option<f64>,
    /// `+gpu` rows: largest |hardware − exact lookup on the same texels| over
    /// the timing directions, % of I_max: the cost of hardware filtering alone;
    /// for `sh:L+gpu` and `lobes:K+gpu`, |f32 shader − f64 CPU evaluation of
    /// the same stored parameters|, % of the file's I_max; for a
    /// representation on the open trait (`c-mean+gpu`), |its GPU − its CPU
    /// instance| over the same directions, % of the file's I_max.
    pub hardware_vs_exact_max_pct: Option<f64>,
    /// Hausdorff distance, % of the reference I_max (certified for a field
    /// reference: the true value is at most this plus `hausdorff_bound_pct`).
    pub hausdorff_pct: f64,
    /// Certified gap of `hausdorff_pct`, % of I_max.
    pub hausdorff_bound_pct: f64,
    /// Largest radial error, % of I_max.
    pub radial_max_pct: f64,
    /// Solid-angle weighted RMS radial error, % of I_max.
    pub radial_rms_pct: f64,
    /// Flux error over the direction set, % of the reference flux.
    pub flux_error_pct: f64,
    /// `sh:L` rows: the window applied to the bands (`lanczos`); null for other rows.
    pub window: Option<String>,
    /// How the representation was built when the data chose it: `rings` (lobes
    /// swept about the vertical axis), `zonal` (SH, m = 0 only); null otherwise.
    pub form: Option<String>,
    /// On the Pareto front of (ns_per_sample, bytes, hausdorff_pct).
    pub pareto: bool,
    /// On the Pareto front of (bytes, radial_max_pct): no other row at most
    /// as large and as far off, and smaller or nearer in one.
    pub pareto_bytes: bool,
}

/// The trade table of one file.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TradeTable {
    /// FILE (set by the caller).
    pub file: String,
    /// What the errors are measured against, in words.
    pub reference: String,
    /// `truth`, `withheld`, `dense` or `reconstruction`.
    pub reference_kind: super::ReferenceKind,
    /// Direction set of the radial metrics.
    pub directions: String,
    /// What each row's `radial_max_pct` is, in words (the comparison's `radial_max_method`).
    pub radial_max_method: String,
    /// One per representation.
    pub rows: Vec<TradeRow>,
    /// The representation with the fewest bytes whose radial max error is
    /// within 1 % of the reference I_max ([`WITHIN_PCT`]; ties: the smaller
    /// error), or null when none is.
    pub smallest_within_1pct: Option<String>,
    /// The comparison the rows come from (plots, full metrics), not in the JSON.
    #[serde(skip)]
    pub comparison: Comparison,
    /// The file's reader warnings, coded (set by the caller; docs/warnings.md).
    pub warnings: Vec<crate::error::Warning>,
}

/// Options of [`trade_table`].
#[derive(Debug, Clone, PartialEq)]
pub struct TradeOptions {
    /// Texture factors. Default: 1, 2, 5, 10.
    pub factors: Vec<u32>,
    /// The comparison's options; its `recons` are replaced by [`representations`].
    pub compare: CompareOptions,
    /// Add the GPU texture-hardware rows (module docs). Default: false.
    pub gpu: bool,
    /// The representations beyond the built-in ones whose default instances
    /// are rows. Default: none.
    pub registry: Registry,
}

impl Default for TradeOptions {
    fn default() -> Self {
        Self {
            factors: vec![1, 2, 5, 10],
            compare: CompareOptions {
                factor: 2,
                ..CompareOptions::default()
            },
            gpu: false,
            registry: Registry::default(),
        }
    }
}

/// Measure every representation of `file` against the reference (the
/// rules of [`compare`](super::compare): `truth` when known, else
/// `withheld`; with `vs`, the denser file).
pub fn trade_table(
    file: &Distribution,
    vs: Option<&Distribution>,
    opts: &TradeOptions,
    progress: &Progress<'_>,
) -> Result<TradeTable, ModelError> {
    // With `gpu`, the GPU's twins: the k = 5 Catmull–Rom texture read with the hardware's
    // bilinear filter and with Catmull–Rom from linear fetches, `sh:16+gpu` and `lobes:4+gpu`.
    let mut recons = opts.registry.candidates(&Job::Tradeoff {
        file,
        factors: &opts.factors,
        gpu: opts.gpu,
    });
    if matches!(opts.compare.against, Some(Against::Recon(_))) && vs.is_none() {
        // A reconstruction of FILE as its own reference is not a row.
        recons.retain(|r| Some(Against::Recon(*r)) != opts.compare.against);
    }
    let c = compare_with_progress(
        file,
        vs,
        &CompareOptions {
            recons: recons.clone(),
            // The table shows H alone: no point is searched that cannot set it.
            hausdorff_only: true,
            ..opts.compare.clone()
        },
        progress,
    )?;
    let pct = |v: f64| if c.i_max_cd > 0.0 { 100.0 * v / c.i_max_cd } else { 0.0 };
    let mut rows: Vec<TradeRow> = c
        .results
        .iter()
        .zip(&recons) // one result per reconstruction, in order
        .map(|(r, &recon)| TradeRow {
            representation: r.name.clone(),
            recon: Some(recon),
            bytes: r.bytes,
            ns_per_sample: r.time_per_sample_ns.unwrap_or_default(),
            ns_per_sample_f32: None,
            f32_vs_f64_max_pct: None,
            ns_per_sample_gpu: None,
            adapter: None,
            texture_format: None,
            subtexel_bits: None,
            hardware_vs_exact_max_pct: None,
            hausdorff_pct: r.hausdorff_pct,
            hausdorff_bound_pct: pct(r.hausdorff_bound_cd),
            radial_max_pct: r.radial_max_pct,
            radial_rms_pct: r.radial_rms_pct,
            flux_error_pct: r.flux_error_pct,
            window: None,
            form: r.form.clone(),
            pareto: r.pareto,
            pareto_bytes: false,
        })
        .collect();
    for row in &mut rows {
        add_columns(row, file, &opts.compare)?;
    }
    mark_pareto_bytes(&mut rows);
    Ok(TradeTable {
        file: String::new(),
        reference: c.reference.clone(),
        reference_kind: c.reference_kind,
        directions: c.directions.clone(),
        radial_max_method: c.radial_max_method.clone(),
        smallest_within_1pct: smallest_within(&rows, WITHIN_PCT),
        rows,
        comparison: c,
        warnings: Vec::new(),
    })
}

/// The columns of `row` that only some representations have: a texture's
/// f32 evaluation, the GPU's, a series' window.
fn add_columns(row: &mut TradeRow, file: &Distribution, opts: &CompareOptions) -> Result<(), ModelError> {
    match row.recon {
        Some(Recon::Gpu(spec)) => gpu_columns(row, file, spec, opts)?,
        Some(r @ (Recon::Sh { gpu: true, .. } | Recon::Lobes { gpu: true, .. })) => {
            compact_gpu_columns(row, file, r, opts)?;
            if matches!(r, Recon::Sh { .. }) {
                row.window = Some(ShWindow::Lanczos.name().into());
            }
        }
        Some(Recon::Texture(spec)) => f32_columns(row, file, spec, opts)?,
        Some(Recon::Sh { .. }) => row.window = Some(ShWindow::Lanczos.name().into()),
        Some(r @ Recon::Extension { gpu: true, .. }) => open_gpu_columns(row, file, r, opts)?,
        _ => {}
    }
    Ok(())
}

/// Fill the GPU columns of a representation on the open trait evaluated by
/// the GPU (`NAME+gpu`, `Representation::build_gpu`): the adapter, and the
/// largest difference from its CPU instance over the CPU rows' timing
/// directions. Its dispatch alone is not separable from the caller's time
/// (`ns_per_sample`, upload to read-back), so `ns_per_sample_gpu` stays empty.
fn open_gpu_columns(
    row: &mut TradeRow,
    file: &Distribution,
    r: Recon,
    opts: &CompareOptions,
) -> Result<(), ModelError> {
    let Recon::Extension { id, param, .. } = r else {
        return Ok(());
    };
    let device = gpu_device(row)?;
    if let crate::device::Selected::Gpu { adapter } = device
        .select(crate::reconstruct::Backend::Gpu)
        .map_err(|e| gpu_error(row, e))?
    {
        row.adapter = Some(adapter);
    }
    let cpu = Recon::Extension { id, param, gpu: false };
    let built = crate::registry::Reconstructions::new(file.clone(), &[r, cpu])?;
    let dirs: Vec<(f64, f64)> = opts
        .timing_directions()
        .into_iter()
        .map(crate::model::frame::unit_angles)
        .collect();
    let on_gpu = built.field(r)?.intensity_batch_cd(&dirs);
    let on_cpu = built.field(cpu)?.intensity_batch_cd(&dirs);
    let largest = on_gpu
        .iter()
        .zip(&on_cpu)
        .map(|(g, c)| (g - c).abs())
        .fold(0.0, f64::max);
    let i_max = file.max_cd();
    row.hardware_vs_exact_max_pct = Some(if i_max > 0.0 { 100.0 * largest / i_max } else { 0.0 });
    Ok(())
}

/// Mark the rows on the Pareto front of (bytes, radial max error). A `+gpu`
/// row is the GPU's evaluation of a representation another row holds (the
/// same bytes): it is not on this front and does not displace its CPU twin.
pub fn mark_pareto_bytes(rows: &mut [TradeRow]) {
    let gpu = |r: &TradeRow| r.recon.is_some_and(|x| x.on_gpu());
    let costs: Vec<Vec<f64>> = rows
        .iter()
        .filter(|r| !gpu(r))
        .map(|r| vec![r.bytes as f64, r.radial_max_pct])
        .collect();
    let mut front = crate::metrics::pareto_front(&costs).into_iter();
    for r in rows.iter_mut() {
        r.pareto_bytes = !gpu(r) && front.next().unwrap_or(false);
    }
}

/// The row with the fewest bytes whose radial max error is at most `pct`
/// (% of I_max); ties go to the smaller error. `None` when no row is.
pub fn smallest_within(rows: &[TradeRow], pct: f64) -> Option<String> {
    super::smallest_named(
        rows.iter()
            .map(|r| (r.representation.as_str(), r.bytes, r.radial_max_pct)),
        pct,
    )
}

/// Fill the f32 columns of a stored-texture row: the same texels read with
/// every step in f32, timed on the same directions, and their largest
/// difference from the f64 lookup.
fn f32_columns(
    row: &mut TradeRow,
    file: &Distribution,
    spec: TextureSpec,
    opts: &CompareOptions,
) -> Result<(), ModelError> {
    use crate::reconstruct::{render, LightTexture, StoredTexture};
    let rendered = render(&LightTexture::new(file)?, spec.filter, spec.factor)?;
    let reduced = spec.reduced.then(|| file.symmetry());
    let tex = StoredTexture::new(&rendered, reduced, spec.precision, spec.lookup);
    let dirs = opts.timing_directions();
    let dirs32: Vec<glam::Vec3> = dirs.iter().map(|d| d.as_vec3()).collect();
    row.ns_per_sample_f32 = Some(crate::metrics::cost::time_per_sample_ns_f32(
        |d| tex.cd_dir_f32(d),
        &dirs32,
        opts.timing_repeats,
    ));
    let i_max = tex.i_max_cd();
    let worst = dirs
        .iter()
        .zip(&dirs32)
        .map(|(d, d32)| (tex.cd_dir_f32(*d32) as f64 - tex.intensity_dir_cd(*d)).abs())
        .fold(0.0, f64::max);
    row.f32_vs_f64_max_pct = Some(if i_max > 0.0 { 100.0 * worst / i_max } else { 0.0 });
    Ok(())
}

/// The installed GPU device, or the error naming the `+gpu` row that needs it.
fn gpu_device(row: &TradeRow) -> Result<&'static dyn crate::device::GpuDevice, ModelError> {
    crate::device::device().map_err(|source| gpu_error(row, source))
}

/// A GPU failure as the error of the row that met it.
fn gpu_error(row: &TradeRow, source: crate::error::GpuError) -> ModelError {
    ModelError::gpu(row.representation.clone(), source)
}

/// Fill the GPU columns of a `+gpu` row, timed on the CPU rows' directions
/// (same count, same seed).
fn gpu_columns(
    row: &mut TradeRow,
    file: &Distribution,
    spec: TextureSpec,
    opts: &CompareOptions,
) -> Result<(), ModelError> {
    let device = gpu_device(row)?;
    let h = device
        .texture_row(file, spec, &opts.timing_directions(), opts.timing_repeats)
        .map_err(|e| gpu_error(row, e))?;
    row.ns_per_sample_gpu = Some(h.ns_per_sample_dispatch);
    row.adapter = Some(h.adapter);
    row.texture_format = Some(h.texture_format);
    row.subtexel_bits = Some(h.subtexel_bits);
    row.hardware_vs_exact_max_pct = Some(100.0 * h.vs_exact_max);
    Ok(())
}

/// Fill the GPU columns of a `sh:L+gpu` or `lobes:K+gpu` row: the adapter,
/// the dispatch time, and the largest difference from the CPU evaluation of
/// the same stored parameters (`hardware_vs_exact_max_pct`).
fn compact_gpu_columns(
    row: &mut TradeRow,
    file: &Distribution,
    r: Recon,
    opts: &CompareOptions,
) -> Result<(), ModelError> {
    let device = gpu_device(row)?;
    let compact = crate::registry::Reconstructions::new(file.clone(), &[r])?.compact(r)?;
    let h = device
        .compact_row(compact, &opts.timing_directions(), opts.timing_repeats)
        .map_err(|e| gpu_error(row, e))?;
    row.ns_per_sample_gpu = Some(h.ns_per_sample_dispatch);
    row.adapter = Some(h.adapter);
    let i_max = file.max_cd();
    row.hardware_vs_exact_max_pct = Some(if i_max > 0.0 {
        100.0 * h.vs_exact_max_cd / i_max
    } else {
        0.0
    });
    Ok(())
}
