//! `photosolid gpu-check [PATHS...] [--factor 5] [--filter F]... [--tolerance 0.001%]`:
//! render every loadable file with every filter on the GPU and on the CPU,
//! from the same plans, and compare texel by texel.
//!
//! Prints the largest |gpu − cpu| (texels are I / I_max) per file and an
//! overall line; exit status 1 when any exceeds the tolerance. Files that do
//! not load (or have no positive intensity) are counted and skipped; a path
//! that does not exist, or a run where no file loads, is an error (a check
//! that checked nothing fails).
//! `WGPU_BACKEND=vulkan|gl` selects the driver. The check itself is
//! `photosolid::gpu::check`; this file parses the arguments and prints.

use std::path::PathBuf;

use clap::Args;
use photosolid::reconstruct::Filter;

use super::ReadArgs;

#[derive(Args, Debug)]
pub struct GpuCheckArgs {
    /// Files and directories (searched recursively for .ies/.ldt, TM-33 .xml and .gldf, any case; a .gldf gives every photometry).
    #[arg(default_value = "../shared/corpus")]
    paths: Vec<PathBuf>,
    /// Supersampling factor in both axes (1-32).
    #[arg(long, default_value_t = 5, value_parser = super::parse::texture_factor, allow_negative_numbers = true)]
    factor: u32,
    /// Filters to check (repeatable). Default: every filter (nearest, bilinear,
    /// catmull-rom, mitchell, bspline, pchip) and mitchell:0:0.75.
    #[arg(long)]
    filter: Vec<Filter>,
    /// Largest allowed |gpu - cpu| per texel, a percent of I_max with its sign (a bare number is refused).
    #[arg(long, default_value = "0.001%", value_parser = super::parse::pct_of_peak_or_zero, allow_hyphen_values = true)]
    tolerance: super::parse::PctOfPeak,
    #[command(flatten)]
    read: ReadArgs,
}

#[cfg(not(feature = "gpu"))]
pub fn run(_a: GpuCheckArgs) -> anyhow::Result<i32> {
    Err(anyhow::Error::from(photosolid::Error::from(photosolid::error::GpuError::NotBuilt)).context("gpu-check"))
}

#[cfg(feature = "gpu")]
pub fn run(a: GpuCheckArgs) -> anyhow::Result<i32> {
    use photosolid::gpu::check::{check_file, CheckInputs, CheckOptions, CheckSummary};
    use photosolid::gpu::GpuContext;

    let opts = CheckOptions {
        factor: a.factor,
        filters: if a.filter.is_empty() {
            CheckOptions::default_filters()
        } else {
            a.filter.clone()
        },
        tolerance: a.tolerance.fraction(),
    };
    // Load every file before touching the GPU: a run that would check nothing fails early.
    let inputs = CheckInputs::collect(&a.paths, &a.read.options())?;
    for s in &inputs.skipped {
        outln!("{}: skipped ({})", s.path.display(), s.reason);
    }
    inputs
        .require_some(&a.paths)
        .map_err(|e| anyhow::anyhow!("gpu-check {e}"))?;
    let ctx = GpuContext::global()?;
    outln!(
        "gpu-check: {} files, {} filters, factor {}, adapter {}",
        inputs.files.len(),
        opts.filters.len(),
        opts.factor,
        ctx.adapter()
    );
    let mut summary = CheckSummary::start();
    for (path, tex) in &inputs.textures {
        let f = check_file(ctx, path, tex, &opts)?;
        print_file(path, &f, &a.tolerance, opts.tolerance)?;
        summary.add(&f);
    }
    let (worst, at) = summary.worst.clone().unwrap_or((0.0, "-".into()));
    outln!(
        "overall: {} files x {} filters = {} renders at factor {} on {}: max |gpu - cpu| = {:.3e} \
         (at {}; fractions of I_max), tolerance {} of I_max; {} over tolerance; {} clamped-count mismatches ({} more within rounding of 0); {} \
         files skipped; {:.1?}",
        inputs.textures.len(),
        opts.filters.len(),
        summary.checked,
        opts.factor,
        ctx.adapter(),
        worst,
        at,
        a.tolerance,
        summary.failed,
        summary.clamp_mismatches,
        summary.clamp_rounding,
        inputs.skipped.len(),
        summary.elapsed
    );
    let passed = summary.passed().map_err(|e| anyhow::anyhow!("gpu-check {e}"))?;
    Ok(if passed { 0 } else { 1 })
}

/// One file's lines: each clamped-count difference and the file's largest difference.
#[cfg(feature = "gpu")]
fn print_file(
    path: &std::path::Path,
    f: &photosolid::gpu::check::FileCheck,
    tolerance: &super::parse::PctOfPeak,
    tolerance_fraction: f64,
) -> std::io::Result<()> {
    for m in &f.clamp_mismatches {
        outln!(
            "{}: [{}] clamped texels differ: gpu {} cpu {} ({}: {}..={} texels are below 0 or within {} of it)",
            path.display(),
            m.filter,
            m.gpu,
            m.cpu,
            if m.within_rounding() {
                "within rounding of 0"
            } else {
                "FAIL"
            },
            m.within_tolerance.0,
            m.within_tolerance.1,
            tolerance
        );
    }
    outln!(
        "{}: {} x {} texels, max |gpu - cpu| = {:.3e} ({}){}",
        path.display(),
        f.height,
        f.width,
        f.max_diff,
        f.max_filter,
        if f.max_diff > tolerance_fraction { "  FAIL" } else { "" }
    );
    Ok(())
}
