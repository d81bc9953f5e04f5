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
//!
//! What the README's demo paragraph promises, file by file (checked by
//! `tests/it/cli.rs` `demo_writes_what_the_readme_says`): `demo_roadway.ldt`; the
//! factor-5 texture of every filter as `texture-FILTER.exr` and
//! `texture-FILTER.png`; `index.html` opening with the 3D view, with its plots,
//! ending with the built-in scene (illuminance on the road and the sensor,
//! its isolux maps `isolux_*.png`) and the plan.

use std::path::{Path, PathBuf};

use clap::Args;
use photosolid::compare::Comparison;
use photosolid::fit::{fit, FitOptions, FitReport};
use photosolid::model::{Distribution, Luminaire};
use photosolid::reconstruct::{exr_io, holdout, render, Filter, HoldoutSpec, LightTexture};
use photosolid::report::plot::{write_texture_preview, TexturePreview};
use photosolid::report::{compare_report, InfoReport};
use photosolid::synth::{GridSpec, Synth, Truth};

#[derive(Args, Debug)]
pub struct DemoArgs {
    /// Directory for the demo's files.
    #[arg(short, long, default_value = "out/demo")]
    output: PathBuf,
}

pub fn run(a: DemoArgs) -> anyhow::Result<i32> {
    super::check_report_dir("-o", &a.output)?;
    std::fs::create_dir_all(&a.output).map_err(|e| photosolid::Error::io(&a.output, e))?;
    let grid = GridSpec::uniform(5.0, 2.5)?;
    let lum = Synth::Roadway.build(&grid, 12_000.0)?;
    outln!("built-in luminaire: synthetic road luminaire, peak 12000 cd, 5° x 2.5° grid");
    outln!("{}", write_and_read_back(&lum, &a.output)?);
    let d = lum.distribution();
    let tex = write_textures(d, &a.output)?;

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

    let c = compare_to_truth(&lum)?;
    print!("{}", compare_report::to_text(&c));
    let mut figs = compare_report::figures(&c)?;
    figs.extend(shading_figures(&tex, &a.output)?);
    let scene = scene_and_plan(&a.output)?;

    let (mut md, mut html) = (
        compare_report::to_markdown(&c, &figs, compare_report::COMPARE_TITLE),
        compare_report::to_html(&c, &figs, compare_report::COMPARE_TITLE),
    );
    // The report ends with the scene and the plan (README, `demo`).
    let tail =
        photosolid::report::scene_report::scene_and_plan_html(SCENE_TITLE, &scene.text, &scene.maps, &scene.plan);
    match html.rfind("</body>") {
        Some(i) => html.insert_str(i, &tail),
        None => html.push_str(&tail),
    }
    md.push_str(&format!(
        "\n## Built-in scene\n\n{SCENE_TITLE}\n\n```\n{}\n```\n\n## Plan\n\n```\n{}\n```\n",
        scene.text, scene.plan
    ));
    compare_report::write_files(&a.output, &figs, &c, &md, &html)?;
    outln!("report written to {}", a.output.join("index.html").display());
    Ok(0)
}

/// Writes `lum` as EULUMDAT and IES into `dir`, reads both back and returns
/// their `info` reports one after the other.
fn write_and_read_back(lum: &Luminaire, dir: &Path) -> anyhow::Result<String> {
    let mut text = String::new();
    for ext in ["ldt", "ies"] {
        let path = dir.join(format!("demo_roadway.{ext}"));
        photosolid::save(&lum.clone().into(), &path, &Default::default())?;
        let back = photosolid::load(&path)?;
        text.push_str(&format!("\n== {} ==\n", path.display()));
        text.push_str(&InfoReport::of(&back).to_text());
    }
    Ok(text)
}

/// Renders the factor-5 texture of every filter into `dir` (EXR and PNG
/// preview), printing each one's size; returns the light texture.
fn write_textures(d: &Distribution, dir: &Path) -> anyhow::Result<LightTexture> {
    outln!("== textures (factor 5; EXR and PNG in {}) ==", dir.display());
    let tex = LightTexture::new(d)?;
    for f in Filter::ALL {
        let r = render(&tex, f, 5)?;
        let (exr, png) = (
            dir.join(format!("texture-{f}.exr")),
            dir.join(format!("texture-{f}.png")),
        );
        exr_io::write_exr(
            &exr,
            &r,
            &exr_io::ExrMeta {
                source: Some("built-in synthetic road luminaire".into()),
            },
        )?;
        write_texture_preview(&png, &TexturePreview::new(&r))?;
        outln!(
            "{:<16} {} x {} texels ({} clamped): {}, {}",
            f.to_string(),
            r.mapping.width,
            r.mapping.height,
            r.clamped,
            exr.display(),
            png.display()
        );
    }
    Ok(tex)
}

/// Every reconstruction of `lum`, the measured solid included, against its
/// closed form (the built-in luminaire is analytic), with plots.
fn compare_to_truth(lum: &Luminaire) -> anyhow::Result<Comparison> {
    let truth = Truth::of_luminaire(lum);
    outln!(
        "\n== every reconstruction against the truth ({}) ==",
        truth.map_or("none".into(), |t| t.to_string())
    );
    let doc: photosolid::formats::Document = lum.clone().into();
    let file = photosolid::jobs::Named {
        name: "built-in synthetic road luminaire",
        document: &doc,
        handedness: Default::default(),
    };
    let settings = photosolid::jobs::CompareSettings {
        plots: true,
        ..Default::default()
    };
    Ok(photosolid::jobs::compare(
        file,
        None,
        &settings,
        &photosolid::jobs::no_progress,
    )?)
}

const SCENE_TITLE: &str = "built-in scene: the luminaire 8 m over a 40 m x 7 m road, a sensor 1 m under it";

/// The built-in scene's text, its isolux maps (file names in the report
/// directory) and the plan's text.
struct SceneSection {
    text: String,
    maps: Vec<String>,
    plan: String,
}

/// Evaluates and plans the built-in scene, printing both, and writes its
/// isolux maps into `dir`.
fn scene_and_plan(dir: &Path) -> anyhow::Result<SceneSection> {
    outln!("\n== {SCENE_TITLE} ==");
    let scene = photosolid::scene::demo_scene()?;
    let lit = photosolid::scene::illuminance::evaluate(&scene, None)?;
    let text = photosolid::report::scene_report::scene_text(&lit);
    outln!("{text}");
    let plan = photosolid::scene::plan::plan(&scene, &Default::default(), None)?;
    let plan = photosolid::report::scene_report::plan_text(&plan);
    outln!("{plan}");
    let maps = photosolid::report::scene_report::write_maps(&scene, &lit, dir)?
        .iter()
        .map(|path| {
            path.file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default()
        })
        .collect();
    Ok(SceneSection { text, maps, plan })
}

/// Wallner's (2008) Figure 5 setting: a plane lit through the bilinear and the
/// Catmull-Rom lookups of the factor-5 texture, on the installed GPU when an adapter
/// exists and always on the CPU (`photosolid::report::shading`); EXRs written
/// into `dir`, PNGs returned as report figures.
fn shading_figures(tex: &LightTexture, dir: &std::path::Path) -> anyhow::Result<Vec<compare_report::Figure>> {
    use photosolid::device::{installed, Selected};
    use photosolid::reconstruct::Backend;
    use photosolid::report::shading;
    let device = match installed() {
        Some(d) => match d.select(Backend::Auto)? {
            Selected::Gpu { .. } => Some(d),
            Selected::Cpu { notice } => {
                if let Some(n) = notice {
                    outln!("{n}: the shaded plane is rendered with the CPU lookups only");
                }
                None
            }
        },
        None => None,
    };
    let view = shading::PlaneView {
        height_m: 8.0,
        half_width_m: 24.0,
        pixels: 256,
    };
    let (figs, notes) = shading::report_figures(device, &render(tex, Filter::CatmullRom, 5)?, &view, dir)?;
    outln!("\n== shaded plane (EXR and PNG in {}) ==", dir.display());
    for n in notes {
        outln!("{n}");
    }
    Ok(figs)
}
