//! `photosolid demo`: the main job on a built-in luminaire, no file needed.
//!
//! Builds the synthetic asymmetric road luminaire, writes it as EULUMDAT and
//! IES into the output directory, reads both back and prints their `info`
//! side by side; then renders a texture with every filter (sizes printed),
//! runs the 2/2 hold-out, fits the OpenGL lights, measures every
//! reconstruction against the luminaire's closed form (the truth) and writes
//! the comparison report (`index.html`, `report.md`, `report.json`, PNGs)
//! into the output directory; finally evaluates and plans the built-in scene
//! (`photosolid::scene::demo_scene`). The report also shows a plane lit by
//! the luminaire through the bilinear and Catmull-Rom lookups (GPU texture
//! hardware when an adapter exists, and the CPU reference), with EXRs.

use std::path::PathBuf;

use clap::Args;
use photosolid::compare::{compare, CompareOptions};
use photosolid::fit::{fit, FitOptions, FitReport};
use photosolid::reconstruct::{holdout, render, Filter, HoldoutSpec, LightTexture};
use photosolid::report::{compare_report, InfoReport};
use photosolid::synth::{GridSpec, Synth, Truth};

#[derive(Args, Debug)]
pub struct DemoArgs {
    /// Directory for the demo's files.
    #[arg(short, long, default_value = "out/demo")]
    output: PathBuf,
}

pub fn run(a: DemoArgs) -> anyhow::Result<i32> {
    std::fs::create_dir_all(&a.output).map_err(|e| photosolid::Error::io(&a.output, e))?;
    let grid = GridSpec::uniform(5.0, 2.5)?;
    let lum = Synth::Roadway.build(&grid, 12_000.0)?;
    outln!("built-in luminaire: synthetic road luminaire, peak 12000 cd, 5° x 2.5° grid");
    let mut text = String::new();
    for ext in ["ldt", "ies"] {
        let path = a.output.join(format!("demo_roadway.{ext}"));
        photosolid::save(&lum.clone().into(), &path, &Default::default())?;
        let back = photosolid::load(&path)?;
        text.push_str(&format!("\n== {} ==\n", path.display()));
        text.push_str(&InfoReport::of(&back).to_text());
    }
    outln!("{text}");
    let d = lum.distribution();

    outln!("== textures (factor 5) ==");
    let tex = LightTexture::new(d)?;
    for f in Filter::ALL {
        let r = render(&tex, f, 5)?;
        outln!(
            "{:<16} {} x {} texels ({} clamped)",
            f.to_string(),
            r.mapping.width,
            r.mapping.height,
            r.clamped
        );
    }

    let spec = HoldoutSpec {
        c_step: 2,
        gamma_step: 2,
    };
    outln!("\n== hold-out: keep every 2 C-plane(s) and every 2 gamma row(s); errors in % of I_max ==");
    outln!(
        "{}",
        photosolid::reconstruct::HoldoutReport::table(&holdout(d, spec, &Filter::ALL)?)
    );

    outln!("== fitted OpenGL lights ==");
    print!("{}", FitReport::of(&fit(d, &FitOptions::default())?).to_text());

    // The built-in luminaire is analytic: every reconstruction, the measured
    // solid included, is measured against its closed form.
    let truth = Truth::of_luminaire(&lum);
    outln!(
        "\n== every reconstruction against the truth ({}) ==",
        truth.map_or("none".into(), |t| t.to_string())
    );
    let opts = CompareOptions {
        truth,
        plots: true,
        ..Default::default()
    };
    let mut c = compare(d, None, &opts)?;
    c.file = "built-in synthetic road luminaire".into();
    print!("{}", compare_report::to_text(&c));
    let mut figs = compare_report::figures(&c)?;
    figs.extend(shading_figures(&tex, &a.output)?);
    let (md, html) = (
        compare_report::to_markdown(&c, &figs),
        compare_report::to_html(&c, &figs),
    );
    compare_report::write_files(&a.output, &figs, &c, &md, &html)?;
    outln!("report written to {}", a.output.join("index.html").display());

    outln!("\n== built-in scene: the luminaire 8 m over a 40 m x 7 m road, a sensor 1 m under it ==");
    let scene = photosolid::scene::demo_scene()?;
    outln!(
        "{}",
        photosolid::report::scene_report::scene_text(&photosolid::scene::illuminance::evaluate(&scene, None)?)
    );
    let plan = photosolid::scene::plan::plan(&scene, &Default::default(), None)?;
    outln!("{}", photosolid::report::scene_report::plan_text(&plan));
    Ok(0)
}

/// Wallner's (2008) Figure 5 setting: a plane lit through the bilinear and the
/// Catmull-Rom lookups of the factor-5 texture, on the GPU when an adapter
/// exists and always on the CPU (`photosolid::gpu::shading`); EXRs written
/// into `dir`, PNGs returned as report figures.
#[cfg(feature = "gpu")]
fn shading_figures(tex: &LightTexture, dir: &std::path::Path) -> anyhow::Result<Vec<compare_report::Figure>> {
    use photosolid::gpu::{resolve, shading, Backend};
    let resolved = resolve(Backend::Auto)?;
    if let photosolid::gpu::Resolved::Cpu { notice: Some(n) } = resolved {
        outln!("{n}: the shaded plane is rendered with the CPU lookups only");
    }
    let view = shading::PlaneView {
        height_m: 8.0,
        half_width_m: 24.0,
        pixels: 256,
    };
    let (figs, notes) = shading::report_figures(resolved.gpu(), &render(tex, Filter::CatmullRom, 5)?, &view, dir)?;
    outln!("\n== shaded plane (EXR and PNG in {}) ==", dir.display());
    for n in notes {
        outln!("{n}");
    }
    Ok(figs)
}

#[cfg(not(feature = "gpu"))]
fn shading_figures(_: &LightTexture, _: &std::path::Path) -> anyhow::Result<Vec<compare_report::Figure>> {
    Ok(Vec::new())
}
