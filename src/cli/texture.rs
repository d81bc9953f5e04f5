//! `photosolid texture FILE --filter F [--factor 5] [-o out.exr|out.dds|out.png] [--png out.png] [--backend auto|gpu|cpu]`:
//! at least one output; the encoder follows the extension.

use std::path::PathBuf;

use anyhow::Context;
use clap::Args;
use photosolid::reconstruct::bc6h::write_dds;
use photosolid::reconstruct::{exr_io, Backend, Filter, LightTexture, RenderOptions};
use photosolid::registry::render_on;
use photosolid::report::plot::{write_texture_preview, TexturePreview, DEFAULT_EXPOSURE};

use super::ReadArgs;

#[derive(Args, Debug)]
pub struct TextureArgs {
    /// A photometric file: .ies, .ldt, TM-33 .xml, or a GLDF photometry (FILE.gldf#ID; FILE.gldf when it holds one).
    file: PathBuf,
    /// Reconstruction filter: nearest, bilinear, catmull-rom, mitchell, mitchell:B,C, bspline, pchip.
    #[arg(long, default_value = "catmull-rom")]
    filter: Filter,
    /// Supersampling factor in both axes (1-32).
    #[arg(long, default_value_t = 5, value_parser = super::parse::texture_factor, allow_negative_numbers = true)]
    factor: u32,
    /// Output, format from the extension: .exr (single float channel, I / I_max;
    /// metadata in the header), .dds (BC6H_UF16 block-compressed, what a
    /// renderer uploads: texels I / I_max in red, green and blue; I_max is
    /// printed, the format has no place for it) or .png (the preview, as --png).
    #[arg(short, long)]
    output: Option<PathBuf>,
    /// PNG preview (Wallner's exposure tone map, viridis, colour bar in cd, axes in degrees); the name must end in .png.
    #[arg(long)]
    png: Option<PathBuf>,
    /// Exposure k of the preview's tone map y = 1 - exp(-k x).
    #[arg(long, default_value_t = DEFAULT_EXPOSURE, value_parser = super::parse::positive)]
    exposure: f64,
    /// Keep cubic overshoot below zero (default: clamped to 0, and the clamped texels counted).
    #[arg(long)]
    unclamped: bool,
    /// Where to render: auto (GPU when an adapter exists, else CPU, with a notice), gpu, or cpu.
    /// WGPU_BACKEND=vulkan|gl restricts the GPU drivers tried. Same result on every backend.
    #[arg(long, value_enum, default_value = "auto")]
    backend: Backend,
    #[command(flatten)]
    read: ReadArgs,
}

/// What a texture output path gets, from its extension.
#[derive(Clone, Copy, PartialEq)]
enum Encoding {
    Exr,
    Png,
    /// BC6H_UF16 in a DDS file (feature `bc6h`).
    Dds,
}

/// The encoder of `path` from its extension (any case), one of `accepted`
/// (with their dot), or an error naming the flag, the path and the extensions it accepts.
fn encoding(flag: &'static str, path: &std::path::Path, accepted: &'static [&'static str]) -> anyhow::Result<Encoding> {
    let ext = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("exr") if accepted.contains(&".exr") => Ok(Encoding::Exr),
        Some("png") if accepted.contains(&".png") => Ok(Encoding::Png),
        Some("dds") if accepted.contains(&".dds") => {
            if photosolid::reconstruct::bc6h::available() {
                Ok(Encoding::Dds)
            } else {
                Err(anyhow::anyhow!(
                    "{flag} {}: this build has no BC6H encoder (feature `bc6h`); write .exr instead",
                    path.display()
                ))
            }
        }
        _ => Err(anyhow::Error::from(photosolid::Error::UnknownExtension {
            path: path.to_path_buf(),
            what: "texture format",
            accepted,
        })
        .context(flag)),
    }
}

pub fn run(a: TextureArgs) -> anyhow::Result<i32> {
    // Check the outputs before loading and rendering anything.
    let mut outputs = Vec::new();
    if let Some(out) = &a.output {
        outputs.push((out, encoding("-o", out, &[".exr", ".dds", ".png"])?));
    }
    if let Some(png) = &a.png {
        outputs.push((png, encoding("--png", png, &[".png"])?));
    }
    if outputs.is_empty() {
        anyhow::bail!("nothing to write: give -o OUT.exr (float texture) and/or --png OUT.png (preview)");
    }
    for (path, _) in &outputs {
        super::check_output(if Some(*path) == a.png.as_ref() { "--png" } else { "-o" }, path)?;
    }
    let lum = super::load(&a.file, &a.read)?;
    let tex = LightTexture::new(lum.distribution()).context("building the light distribution texture")?;
    let options = RenderOptions {
        filter: a.filter,
        factor: a.factor,
        clamp: !a.unclamped,
        ..RenderOptions::default()
    };
    let out = render_on(a.backend, &tex, &options)?;
    if let Some(notice) = out.notice {
        eprintln!("{notice}");
    }
    let (rendered, on) = (out.rendered, out.on);
    let (h, w) = (rendered.mapping.height, rendered.mapping.width);
    outln!(
        "{}: {} x {} texels (gamma x C), filter {}, factor {}, I_max {:.3} cd, {} texels clamped ({on})",
        a.file.display(),
        h,
        w,
        rendered.filter,
        rendered.factor,
        rendered.i_max_cd,
        rendered.clamped
    );
    for (path, e) in outputs {
        match e {
            Encoding::Exr => exr_io::write_exr(
                path,
                &rendered,
                &exr_io::ExrMeta {
                    source: Some(a.file.display().to_string()),
                },
            )?,
            Encoding::Dds => {
                // The encoder's slowest, best settings take about 1 s per million texels.
                let e = super::with_progress("BC6H blocks", |progress| {
                    progress(0, 1, "encoding");
                    write_dds(path, &rendered)
                })?;
                outln!(
                    "{}: BC6H_UF16, texels I / I_max (I_max {:.3} cd); decoded against the float texels: max {} %, RMS {} % of I_max",
                    path.display(),
                    rendered.i_max_cd,
                    photosolid::numfmt::significant(100.0 * e.max, 3),
                    photosolid::numfmt::significant(100.0 * e.rms, 3)
                );
            }
            Encoding::Png => write_texture_preview(
                path,
                &TexturePreview {
                    exposure: a.exposure,
                    ..TexturePreview::new(&rendered)
                },
            )?,
        }
        outln!("wrote {}", path.display());
    }
    Ok(0)
}
