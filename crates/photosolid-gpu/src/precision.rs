//! What hardware filtering costs in accuracy, per adapter: the observed
//! sub-texel weight precision ([`subtexel_precision`]) and, for one texture
//! specification, the hardware lookup against the exact lookup on the same
//! texels with its dispatch time ([`hardware_row`], the GPU columns of
//! `compare::trade`).

use glam::DVec3;

use super::realtime::{HardwareLookup, RealtimeTexture, MODE_PROBE};
use super::{GpuContext, GpuError};
use crate::model::{Distribution, IntensityField};
use crate::reconstruct::{render, LightTexture, Precision, Rendered, TextureSpec};

/// The observed precision of an adapter's bilinear sub-texel weights.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct SubtexelPrecision {
    /// The adapter, as [`crate::AdapterSummary`] prints it.
    pub adapter: String,
    /// The texture format probed (`R32Float` or `R16Float`).
    pub format: String,
    /// Sub-texel offsets sampled between two texel centres (evenly spaced, ends included).
    pub probes: usize,
    /// Distinct interpolated values seen (weights of the second texel, 0 to 1).
    pub distinct_weights: usize,
    /// log2(distinct_weights − 1): bits of sub-texel weight precision
    /// (fractional for non-power-of-two counts). The probe resolves at most
    /// log2(probes − 1) bits: a value at that limit means "at least".
    pub bits: f64,
    /// Largest |weight − offset| over the probes: the weight quantisation error, texels.
    pub max_weight_error: f64,
}

/// Measure the adapter's sub-texel weight precision: a 2-texel ramp (0, 1)
/// sampled with the linear sampler at `probes` evenly spaced offsets between
/// the two texel centres; every returned value is the weight of the second
/// texel, so the number of distinct values is the number of weight levels.
///
/// # Errors
/// Device errors; [`GpuError::InvalidJob`] for fewer than 2 probes.
pub fn subtexel_precision(ctx: &GpuContext, probes: usize) -> Result<SubtexelPrecision, GpuError> {
    if probes < 2 {
        return Err(GpuError::InvalidJob {
            index: 0,
            reason: "at least 2 probes".into(),
        });
    }
    let ramp = Rendered {
        data: vec![0.0, 1.0],
        mapping: crate::reconstruct::TexelMapping { height: 1, width: 2 },
        i_max_cd: 1.0,
        filter: crate::reconstruct::Filter::Bilinear,
        factor: 1,
        measured_gamma: (0.0, 180.0),
        clamped: 0,
    };
    let tex = RealtimeTexture::new(ctx, &ramp, None, Precision::F32, HardwareLookup::Linear)?;
    // Texel centres at u = 1/4 and 3/4; offset f in [0, 1] between them.
    let offsets: Vec<f64> = (0..probes).map(|k| k as f64 / (probes - 1) as f64).collect();
    let data: Vec<[f32; 4]> = offsets
        .iter()
        .map(|f| [((0.5 + f) / 2.0) as f32, 0.5, 0.0, 0.0])
        .collect();
    let batch = tex.prepare_raw(&data, MODE_PROBE)?;
    tex.run(&batch)?;
    let w = tex.read(&batch)?;
    let max_weight_error = w
        .iter()
        .zip(&offsets)
        .map(|(&v, f)| (f64::from(v) - f).abs())
        .fold(0.0, f64::max);
    let mut levels: Vec<u32> = w.iter().map(|v| v.to_bits()).collect();
    levels.sort_unstable();
    levels.dedup();
    let distinct = levels.len();
    Ok(SubtexelPrecision {
        adapter: ctx.adapter().to_string(),
        format: format!("{:?}", tex.format()),
        probes,
        distinct_weights: distinct,
        bits: ((distinct.max(2) - 1) as f64).log2(),
        max_weight_error,
    })
}

/// The GPU figures of one trade-table row.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct HardwareRow {
    /// The adapter's sub-texel precision (with its name).
    pub precision: SubtexelPrecision,
    /// The texture format used (`R32Float` or `R16Float`).
    pub texture_format: String,
    /// Median ns per direction of the dispatch alone (directions resident on the device).
    pub ns_per_sample_dispatch: f64,
    /// Largest |hardware − exact lookup on the same texels| over the
    /// directions, fraction of I_max.
    pub vs_exact_max: f64,
}

/// Build `spec`'s texture of `dist` on `ctx`, and measure its hardware
/// lookup against the exact lookup on the same texels at `dirs` (and time
/// its dispatch over `repeats` runs).
///
/// # Errors
/// Model errors of the render (as text), device errors.
pub fn hardware_row(
    ctx: &GpuContext,
    dist: &Distribution,
    spec: TextureSpec,
    dirs: &[DVec3],
    repeats: usize,
) -> Result<HardwareRow, GpuError> {
    let invalid = |e: crate::error::ModelError| GpuError::InvalidJob {
        index: 0,
        reason: e.to_string(),
    };
    let tex = LightTexture::new(dist).map_err(invalid)?;
    let rendered = render(&tex, spec.filter, spec.factor).map_err(invalid)?;
    let reduced = spec.reduced.then(|| dist.symmetry());
    let rt = RealtimeTexture::new(
        ctx,
        &rendered,
        reduced,
        spec.precision,
        HardwareLookup::for_lookup(spec.lookup),
    )?;
    let hw = rt.sample_dirs_cd(dirs)?;
    let i_max = rt.exact().i_max_cd();
    let vs_exact_max = dirs
        .iter()
        .zip(&hw)
        .map(|(d, h)| (h - rt.exact().intensity_dir_cd(*d)).abs() / i_max)
        .fold(0.0, f64::max);
    Ok(HardwareRow {
        precision: subtexel_precision(ctx, PROBES)?,
        texture_format: format!("{:?}", rt.format()),
        ns_per_sample_dispatch: rt.dispatch_ns_per_sample(dirs, repeats)?,
        vs_exact_max,
    })
}

/// Probes of the precision measurement in [`hardware_row`]: resolves up to 16 bits.
pub const PROBES: usize = 65_537;
