//! Command-line arguments and dispatch. Each subcommand lives in its own file.

mod compare;
mod convert;
mod demo;
mod engines;
mod export;
mod fit;
mod gpu_check;
mod grid;
mod hausdorff;
mod holdout;
mod info;
mod mesh;
mod synth;
mod texture;
mod tradeoff;
mod validate;

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand};
use photosolid::formats::{Handedness, ReadOptions};

/// Analyse and compare the photometric solids of real luminaires (IES LM-63, EULUMDAT).
#[derive(Parser, Debug)]
#[command(name = "photosolid", version, about, propagate_version = true)]
pub struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Print the photometric summary of one file (flux, LOR, beam angles, ...).
    Info(info::InfoArgs),
    /// Check files and directories (recursive); exit 1 if any file fails to load.
    Validate(validate::ValidateArgs),
    /// Convert between IES and EULUMDAT (format from OUT's extension).
    Convert(convert::ConvertArgs),
    /// Write an analytic distribution (isotropic, lambertian, cosine-power, spot, batwing, roadway).
    Synth(synth::SynthArgs),
    /// Render a light distribution texture (5x supersampled float texture) to EXR and PNG.
    Texture(texture::TextureArgs),
    /// Drop measured planes/rows, reconstruct them with each filter, report the errors.
    Holdout(holdout::HoldoutArgs),
    /// Time per sample vs hold-out error of every filter (Pareto rows marked).
    Tradeoff(tradeoff::TradeoffArgs),
    /// Build the photometric solid as a mesh (OBJ, PLY, STL, GLB).
    Mesh(mesh::MeshArgs),
    /// Print the measured grid as JSON or CSV (for independent cross-checks).
    Grid(grid::GridArgs),
    /// Certified Hausdorff distance between two mesh files (PLY/OBJ).
    Hausdorff(hausdorff::HausdorffArgs),
    /// Run the main job on a built-in example luminaire (no file needed).
    Demo(demo::DemoArgs),
    /// Approximate the luminaire by at most 2 OpenGL lights (spot / point; Zotti et al. 2005).
    Fit(fit::FitArgs),
    /// Render every file with every filter on the GPU and the CPU; exit 1 if any texel differs by more than 1e-5.
    GpuCheck(gpu_check::GpuCheckArgs),
    /// Compare reconstructions (and other files): Hausdorff distance, radial errors, speed; HTML report.
    Compare(compare::CompareArgs),
    /// Write one renderer's light-profile layout (pbrt, ue5, ue4, unity-point, unity-spot, threejs, babylon, blender, gltf).
    Export(export::ExportArgs),
    /// How far each renderer's lookup is from the file: trade-table metrics per engine, defect rows.
    Engines(engines::EnginesArgs),
}

/// Reader options shared by every command that loads files.
#[derive(Args, Debug, Clone)]
pub struct ReadArgs {
    /// Repair duplicate or unsorted angle lists (sort, drop duplicates) with a warning, instead of failing.
    #[arg(long)]
    repair: bool,
    /// Rotation sense of Type A/B horizontal angles: ccw (C90 = +y, default) or cw.
    #[arg(long, default_value = "ccw", value_parser = ["ccw", "cw"])]
    handedness: String,
    /// EULUMDAT with several lamp sets: cd/klm refer to the first set's flux (default) or the sum.
    #[arg(long, default_value = "first", value_parser = ["first", "sum"])]
    lamp_sets: String,
}

impl ReadArgs {
    fn options(&self) -> ReadOptions {
        ReadOptions {
            repair: self.repair,
            handedness: if self.handedness == "cw" {
                Handedness::Clockwise
            } else {
                Handedness::CounterClockwise
            },
            lamp_set_flux: if self.lamp_sets == "sum" {
                photosolid::formats::LampSetFlux::Sum
            } else {
                photosolid::formats::LampSetFlux::First
            },
        }
    }
}

/// Load one file with the reader options, as an anyhow error naming it.
fn load(path: &PathBuf, read: &ReadArgs) -> anyhow::Result<photosolid::Luminaire> {
    Ok(photosolid::load_with(path, &read.options())?)
}

/// Run a parsed command line; returns the exit code.
pub fn run(cli: Cli) -> anyhow::Result<i32> {
    match cli.command {
        Command::Info(a) => info::run(a),
        Command::Validate(a) => validate::run(a),
        Command::Convert(a) => convert::run(a),
        Command::Synth(a) => synth::run(a),
        Command::Texture(a) => texture::run(a),
        Command::Holdout(a) => holdout::run(a),
        Command::Tradeoff(a) => tradeoff::run(a),
        Command::Mesh(a) => mesh::run(a),
        Command::Grid(a) => grid::run(a),
        Command::Hausdorff(a) => hausdorff::run(a),
        Command::Demo(a) => demo::run(a),
        Command::Fit(a) => fit::run(a),
        Command::GpuCheck(a) => gpu_check::run(a),
        Command::Compare(a) => compare::run(a),
        Command::Export(a) => export::run(a),
        Command::Engines(a) => engines::run(a),
    }
}

/// Render `tex` on the backend the user asked for (`auto`, `gpu`, `cpu`);
/// returns the texture and where it was rendered (for the user).
///
/// `auto` uses a GPU adapter when one exists (honouring `WGPU_BACKEND`) and
/// otherwise falls back to the CPU with a one-line notice on stderr; `gpu`
/// without an adapter is an error naming the drivers tried. Built without
/// the `gpu` feature, `auto` is the CPU and `gpu` an error.
fn render_on(
    backend: &str,
    tex: &photosolid::reconstruct::LightTexture,
    filter: photosolid::reconstruct::Filter,
    factor: u32,
    clamp: bool,
) -> anyhow::Result<(photosolid::reconstruct::Rendered, String)> {
    let options = photosolid::reconstruct::RenderOptions {
        filter,
        factor,
        clamp,
        ..Default::default()
    };
    #[cfg(feature = "gpu")]
    {
        use photosolid::gpu::{self, Backend, Resolved};
        let b: Backend = backend.parse().map_err(anyhow::Error::msg)?;
        match gpu::resolve(b)? {
            Resolved::Gpu(ctx) => return Ok((gpu::render_gpu(ctx, tex, &options)?, format!("gpu: {}", ctx.adapter()))),
            Resolved::Cpu { notice: Some(n) } => eprintln!("{n}"),
            Resolved::Cpu { notice: None } => {}
        }
    }
    #[cfg(not(feature = "gpu"))]
    if backend == "gpu" {
        anyhow::bail!(
            "--backend gpu: this photosolid binary was built without GPU support (cargo feature `gpu`); use \
             --backend cpu or auto"
        );
    }
    Ok((photosolid::reconstruct::render_with(tex, &options)?, "cpu".to_string()))
}

/// The hold-out reports as a text table.
fn holdout_table(reports: &[photosolid::reconstruct::HoldoutReport]) -> String {
    use std::fmt::Write;
    let mut s = format!(
        "{:<16} {:>9} {:>9} {:>9} {:>22} {:>10} {:>8}\n",
        "filter", "rms %", "rms-all %", "max %", "max at (C, gamma)", "flux %", "clamped"
    );
    for r in reports {
        let _ = writeln!(
            s,
            "{:<16} {:>9.3} {:>9.3} {:>9.3} {:>22} {:>+10.3} {:>8}",
            r.filter.to_string(),
            r.rms_percent,
            r.rms_all_percent,
            r.max_percent,
            format!("({:.1}, {:.1})", r.max_at.0, r.max_at.1),
            r.flux_error_percent,
            r.clamped
        );
    }
    s
}
