//! `photosolid export FILE --engine pbrt|ue5|ue4|unity-point|unity-spot|threejs|babylon|blender|gltf|godot -o OUT
//! [--resolution N] [--filter F]`: write one engine's light-profile layout (see `docs/engines.md`).

use std::path::PathBuf;

use clap::Args;
use photosolid::engines::Engine;
use photosolid::jobs::{self, ExportSettings, Loaded};
use photosolid::reconstruct::Filter;

use super::ReadArgs;

#[derive(Args, Debug)]
pub struct ExportArgs {
    /// A photometric file: .ies, .ldt, TM-33 .xml, or a GLDF photometry (FILE.gldf#ID; FILE.gldf when it holds one).
    file: PathBuf,
    /// The engine: pbrt, ue5, ue4, unity-point, unity-spot, threejs, babylon, blender, gltf, godot.
    #[arg(long)]
    engine: Engine,
    /// Output: .exr for the image layouts, .ies for blender, .glb for gltf.
    #[arg(short = 'o', long = "output")]
    output: PathBuf,
    /// Resolution, for engines where it is a choice (pbrt: image side, default 256; unity-point and
    /// unity-spot: N, default 128; godot: panorama height, default 256, width twice it).
    #[arg(long)]
    resolution: Option<usize>,
    /// Filter photosolid samples the file with where it bakes the layout (pbrt, godot; the solid of gltf).
    #[arg(long, default_value = "catmull-rom")]
    filter: Filter,
    /// Print what was written as JSON instead of the line: `output`, `engine`, `layout`, `size`,
    /// `pbrt_flux_lm`, `warnings` (`layout-limit` when the layout is above 5 % radial max).
    #[arg(long)]
    json: bool,
    #[command(flatten)]
    read: ReadArgs,
}

pub fn run(a: ExportArgs) -> anyhow::Result<i32> {
    super::check_output("-o", &a.output)?;
    let file = Loaded::load(&a.file, &a.read.options())?;
    let settings = ExportSettings {
        engine: a.engine,
        resolution: a.resolution,
        filter: a.filter,
    };
    let written = jobs::export(file.named(), &a.output, &settings)?;
    if a.json {
        super::emit(true, &written, "")?;
    } else {
        print!("{}: {} ", a.output.display(), written.layout.as_deref().unwrap_or(""));
        if let Some((w, h)) = written.size {
            print!("({w} x {h})");
        }
        if let Some(phi) = written.pbrt_flux_lm {
            print!("; 4 pi x mean = {phi:.6} lm");
        }
        println!();
    }
    // What the written layout costs in accuracy: `layout-limit` above 5 % radial max.
    for w in &written.warnings {
        eprintln!("warning: {w}");
    }
    Ok(0)
}
