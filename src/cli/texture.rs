//! `photosolid texture FILE --filter F [--factor 5] [-o out.exr] [--png out.png] [--backend auto|gpu|cpu]`.

use std::path::PathBuf;

use anyhow::Context;
use clap::Args;
use photosolid::reconstruct::{exr_io, preview, Filter, LightTexture};

use super::ReadArgs;

#[derive(Args, Debug)]
pub struct TextureArgs {
    /// An .ies or .ldt file.
    file: PathBuf,
    /// Reconstruction filter: nearest, bilinear, catmull-rom, mitchell, mitchell:B,C, bspline, pchip.
    #[arg(long, default_value = "catmull-rom")]
    filter: Filter,
    /// Supersampling factor in both axes (1-32).
    #[arg(long, default_value_t = 5)]
    factor: u32,
    /// EXR output (single float channel, I / I_max; metadata in the header).
    #[arg(short, long)]
    output: Option<PathBuf>,
    /// PNG preview (Wallner's exposure tone map, colour bar, axes in degrees).
    #[arg(long)]
    png: Option<PathBuf>,
    /// Exposure k of the preview's tone map y = 1 - exp(-k x).
    #[arg(long, default_value_t = preview::DEFAULT_EXPOSURE)]
    exposure: f64,
    /// Keep cubic overshoot below zero (default: clamped to 0, and the clamped texels counted).
    #[arg(long)]
    unclamped: bool,
    /// Where to render: auto (GPU when an adapter exists, else CPU, with a notice), gpu, or cpu.
    /// WGPU_BACKEND=vulkan|gl restricts the GPU drivers tried. Same result on every backend.
    #[arg(long, default_value = "auto", value_parser = ["auto", "gpu", "cpu"])]
    backend: String,
    #[command(flatten)]
    read: ReadArgs,
}

pub fn run(a: TextureArgs) -> anyhow::Result<i32> {
    let lum = super::load(&a.file, &a.read)?;
    let tex = LightTexture::new(&lum.distribution).context("building the light distribution texture")?;
    let (rendered, on) = super::render_on(&a.backend, &tex, a.filter, a.factor, !a.unclamped)?;
    let (h, w) = (rendered.mapping.height, rendered.mapping.width);
    println!(
        "{}: {} x {} texels (gamma x C), filter {}, factor {}, I_max {:.3} cd, {} texels clamped ({on})",
        a.file.display(),
        h,
        w,
        rendered.filter,
        rendered.factor,
        rendered.i_max_cd,
        rendered.clamped
    );
    if let Some(out) = &a.output {
        exr_io::write_exr(
            out,
            &rendered,
            &exr_io::ExrMeta {
                source: Some(a.file.display().to_string()),
            },
        )?;
        println!("wrote {}", out.display());
    }
    if let Some(png) = &a.png {
        preview::write_preview(png, &rendered, a.exposure)?;
        println!("wrote {}", png.display());
    }
    Ok(0)
}
