//! `photosolid export FILE --engine pbrt|ue5|ue4|unity-point|unity-spot|threejs|babylon|blender|gltf|godot -o OUT
//! [--resolution N] [--filter F]`: write one engine's light-profile layout (see `docs/engines.md`).

use std::path::PathBuf;

use clap::Args;
use photosolid::engines::{export, Engine, EngineOptions};
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
    #[command(flatten)]
    read: ReadArgs,
}

pub fn run(a: ExportArgs) -> anyhow::Result<i32> {
    let want = a.engine.extension();
    let ext = a
        .output
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    if ext != want {
        anyhow::bail!("{}: the {} layout is written as .{want}", a.output.display(), a.engine);
    }
    super::check_output("-o", &a.output)?;
    let lum = super::load(&a.file, &a.read)?;
    let opts = EngineOptions {
        resolution: a.resolution,
        filter: a.filter,
    };
    let e = export(a.engine, &lum, &a.output, &opts)?;
    print!("{}: {} ", a.output.display(), e.layout);
    if let Some((w, h)) = e.size {
        print!("({w} x {h})");
    }
    if let Some(phi) = e.pbrt_flux_lm {
        print!("; 4 pi x mean = {phi:.6} lm");
    }
    println!();
    // What the written layout costs in accuracy: the engines measurement of this
    // engine alone, and `layout-limit` when it is above 5 % radial max.
    let measured = photosolid::engines::measure(
        &lum,
        &photosolid::engines::EnginesOptions {
            engines: vec![a.engine],
            truth: photosolid::synth::Truth::of_luminaire(&lum),
            layout: opts,
            ..Default::default()
        },
    )?;
    for w in &measured.warnings {
        eprintln!("warning: {w}");
    }
    Ok(0)
}
