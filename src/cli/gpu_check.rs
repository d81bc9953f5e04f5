//! `photosolid gpu-check [PATHS...] [--factor 5] [--filter F]... [--tolerance 1e-5]`:
//! render every loadable file with every filter on the GPU and on the CPU,
//! from the same plans, and compare texel by texel.
//!
//! Prints the largest |gpu − cpu| (texels are I / I_max) per file and an
//! overall line; exit status 1 when any exceeds the tolerance. Files that do
//! not load (or have no positive intensity) are counted and skipped; a path
//! that does not exist, or a run where no file loads, is an error (a check
//! that checked nothing fails).
//! `WGPU_BACKEND=vulkan|gl` selects the driver.

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
    #[arg(long, default_value_t = 5, value_parser = super::parse::texture_factor)]
    factor: u32,
    /// Filters to check (repeatable). Default: every filter (nearest, bilinear,
    /// catmull-rom, mitchell, bspline, pchip) and mitchell:0,0.75.
    #[arg(long)]
    filter: Vec<Filter>,
    /// Largest allowed |gpu - cpu| per texel (fraction of I_max).
    #[arg(long, default_value_t = 1e-5, value_parser = super::parse::non_negative)]
    tolerance: f64,
    #[command(flatten)]
    read: ReadArgs,
}

#[cfg(not(feature = "gpu"))]
pub fn run(_a: GpuCheckArgs) -> anyhow::Result<i32> {
    anyhow::bail!("gpu-check: this photosolid binary was built without GPU support (cargo feature `gpu`)")
}

#[cfg(feature = "gpu")]
pub fn run(a: GpuCheckArgs) -> anyhow::Result<i32> {
    use photosolid::gpu::{self, GpuContext};
    use photosolid::reconstruct::{LightTexture, RenderOptions};

    let filters = if a.filter.is_empty() {
        let mut f = Filter::ALL.to_vec();
        f.push(Filter::Mitchell { b: 0.0, c: 0.75 });
        f
    } else {
        a.filter.clone()
    };
    let mut files = Vec::new();
    for p in &a.paths {
        if !p.exists() {
            anyhow::bail!("{}: no such file or directory: nothing to check", p.display());
        }
        photosolid::formats::collect_files(p, &mut files)?;
    }
    // Load every file before touching the GPU: a run that would check nothing fails early.
    let opts = a.read.options();
    let mut textures = Vec::new();
    let mut skipped = 0usize;
    for f in &files {
        match photosolid::load_with(f, &opts)
            .map_err(anyhow::Error::from)
            .and_then(|l| Ok(LightTexture::new(l.distribution())?))
        {
            Ok(t) => textures.push((f, t)),
            Err(e) => {
                skipped += 1;
                outln!(
                    "{}: skipped ({})",
                    f.display(),
                    e.to_string().lines().next().unwrap_or("")
                );
            }
        }
    }
    if textures.is_empty() {
        anyhow::bail!(
            "gpu-check checked nothing: none of the {} file(s) found under {} loaded",
            files.len(),
            a.paths
                .iter()
                .map(|p| p.display().to_string())
                .collect::<Vec<_>>()
                .join(", ")
        );
    }
    let ctx = GpuContext::global()?;
    outln!(
        "gpu-check: {} files, {} filters, factor {}, adapter {}",
        files.len(),
        filters.len(),
        a.factor,
        ctx.adapter()
    );
    let t0 = std::time::Instant::now();
    let (mut checked, mut failed, mut clamp_mismatch) = (0usize, 0usize, 0usize);
    let mut worst = (0.0f64, String::new());
    for (f, tex) in &textures {
        let items: Vec<(&LightTexture, RenderOptions)> = filters
            .iter()
            .map(|&filter| {
                (
                    tex,
                    RenderOptions {
                        filter,
                        factor: a.factor,
                        ..RenderOptions::default()
                    },
                )
            })
            .collect();
        // One plan per filter, shared by both renders; one GPU submission per
        // group of at most 2^25 texels.
        let plans = gpu::plans(&items)?;
        let jobs = gpu::jobs(&items, &plans);
        let mut file_max = (0.0f64, Filter::Nearest);
        let mut start = 0;
        while start < jobs.len() {
            let mut end = start + 1;
            let mut n = jobs[start].height() * jobs[start].width();
            while end < jobs.len() && n + jobs[end].height() * jobs[end].width() <= 1 << 25 {
                n += jobs[end].height() * jobs[end].width();
                end += 1;
            }
            let out = ctx.render_jobs(&jobs[start..end])?;
            for (job, g) in jobs[start..end].iter().zip(&out) {
                let cpu = gpu::render_cpu(job);
                let d = g
                    .data
                    .iter()
                    .zip(&cpu.data)
                    .map(|(x, y)| {
                        let d = (x - y).abs() as f64;
                        if d.is_nan() {
                            f64::INFINITY
                        } else {
                            d
                        }
                    })
                    .fold(0.0, f64::max);
                if g.data.len() != cpu.data.len() || d > a.tolerance {
                    failed += 1;
                }
                if g.clamped != cpu.clamped {
                    clamp_mismatch += 1;
                    outln!(
                        "{}: [{}] clamped texels differ: gpu {} cpu {}",
                        f.display(),
                        job.plan.filter,
                        g.clamped,
                        cpu.clamped
                    );
                }
                if d > file_max.0 || file_max.0 == 0.0 && job.plan.filter == filters[0] {
                    file_max = (d, job.plan.filter);
                }
                checked += 1;
            }
            start = end;
        }
        let (h, w) = (plans[0].mapping.height, plans[0].mapping.width);
        outln!(
            "{}: {h} x {w} texels, max |gpu - cpu| = {:.3e} ({}){}",
            f.display(),
            file_max.0,
            file_max.1,
            if file_max.0 > a.tolerance { "  FAIL" } else { "" }
        );
        if file_max.0 > worst.0 || worst.1.is_empty() {
            worst = (file_max.0, format!("{} [{}]", f.display(), file_max.1));
        }
    }
    let loaded = files.len() - skipped;
    outln!(
        "overall: {loaded} files x {} filters = {checked} renders at factor {} on {}: max |gpu - cpu| = {:.3e} \
         (at {}), tolerance {:e}; {failed} over tolerance; {clamp_mismatch} clamped-count mismatches; {skipped} \
         files skipped; {:.1?}",
        filters.len(),
        a.factor,
        ctx.adapter(),
        worst.0,
        if worst.1.is_empty() { "-" } else { &worst.1 },
        a.tolerance,
        t0.elapsed()
    );
    if checked == 0 {
        anyhow::bail!("gpu-check checked nothing: no render was compared");
    }
    Ok(if failed > 0 { 1 } else { 0 })
}
