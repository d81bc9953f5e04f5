//! `photosolid demo`: the main job on a built-in luminaire, no file needed.
//!
//! Builds the synthetic asymmetric road luminaire, writes it as EULUMDAT and
//! IES into the output directory, reads both back and prints their `info`
//! side by side, so the whole read/compute/write path runs.

use std::path::PathBuf;

use clap::Args;
use photosolid::report::InfoReport;
use photosolid::synth::{GridSpec, Synth};

#[derive(Args, Debug)]
pub struct DemoArgs {
    /// Directory for the demo's files.
    #[arg(short, long, default_value = "out/demo")]
    output: PathBuf,
}

pub fn run(a: DemoArgs) -> anyhow::Result<i32> {
    std::fs::create_dir_all(&a.output)?;
    let grid = GridSpec::uniform(5.0, 2.5)?;
    let lum = Synth::Roadway.build(&grid, 12_000.0)?;
    println!("built-in luminaire: synthetic road luminaire, peak 12000 cd, 5° x 2.5° grid");
    let mut text = String::new();
    for ext in ["ldt", "ies"] {
        let path = a.output.join(format!("demo_roadway.{ext}"));
        photosolid::save(&lum, &path, &Default::default())?;
        let back = photosolid::load(&path)?;
        text.push_str(&format!("\n== {} ==\n", path.display()));
        text.push_str(&InfoReport::of(&back).to_text());
    }
    println!("{text}");
    Ok(0)
}
