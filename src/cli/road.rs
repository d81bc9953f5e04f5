//! `photosolid road SCENE [--class CLASS [--maximize KEY [--range A:B[:STEP]]
//! [--grid KEY=A:B:STEP]]] [--json] [--report DIR]`: a thin layer over
//! `photosolid::scene::road` (JSON keys: `scene::road::design::RoadAnswer`;
//! `lanes: [{lane, l_av_cd_m2, u_o, u_l, ti_pct}]`, `overall: {l_av_cd_m2,
//! u_o, u_l, ti_pct, r_ei, e_av_lux, e_min_lux, u_o_e, e_hs_av_lux}`; with
//! `--class`: `class`, `criteria: [{name, required, comparison, achieved,
//! unit, pass}]`, `pass`; with `--maximize`: `maximize: {key, value, range,
//! step, margins}` or an array of them with `--grid`).

use std::path::PathBuf;

use clap::Args;
use photosolid::jobs::{self, RoadSettings};
use photosolid::report::road_report::{road_answer_text, write_road_report};
use photosolid::scene::road::classes::LightingClass;
use photosolid::scene::road::layout::RoadKey;
use photosolid::scene::road::RoadError;

#[derive(Args, Debug)]
pub struct RoadArgs {
    /// A scene file with a [road] table (TOML; see docs/road.md).
    scene: PathBuf,
    /// Judge the road against a lighting class of EN 13201-2:2015: M1-M6, C0-C5 or P1-P6.
    #[arg(long, value_name = "CLASS", value_parser = parse_class)]
    class: Option<LightingClass>,
    /// The [road] key whose largest value meeting --class is searched (spacing_m,
    /// mounting_height_m, overhang_m, tilt_deg, setback_m, lane_width_m, maintenance_factor).
    #[arg(long, value_name = "KEY", requires = "class", value_parser = parse_key)]
    maximize: Option<RoadKey>,
    /// The range searched, in the key's unit; STEP defaults to (B - A)/100. Default for
    /// spacing_m: 1 to 6 mounting heights; the other keys need one.
    #[arg(long, value_name = "A:B[:STEP]", requires = "maximize", value_parser = parse_range)]
    range: Option<(f64, f64, Option<f64>)>,
    /// Search once for each value of another key: KEY=A:B:STEP (e.g. mounting_height_m=8:12:1).
    #[arg(long, value_name = "KEY=A:B:STEP", requires = "maximize", value_parser = parse_grid)]
    grid: Option<(RoadKey, Vec<f64>)>,
    /// Print JSON.
    #[arg(long)]
    json: bool,
    /// Write road.json, the maps of the field (PNG; with --class the limits marked), the
    /// criteria against the key with --maximize, and index.html into DIR.
    #[arg(long)]
    report: Option<PathBuf>,
}

/// The message of a road option's error, as clap prints it after the flag.
fn message(e: RoadError) -> String {
    match e {
        RoadError::Option { message, .. } => message,
        e => e.to_string(),
    }
}

pub(crate) fn parse_class(s: &str) -> Result<LightingClass, String> {
    jobs::parse_class(s).map_err(message)
}

fn parse_key(s: &str) -> Result<RoadKey, String> {
    jobs::parse_key(s).map_err(message)
}

fn parse_range(s: &str) -> Result<jobs::Range, String> {
    jobs::parse_range(s).map_err(message)
}

fn parse_grid(s: &str) -> Result<(RoadKey, Vec<f64>), String> {
    jobs::parse_grid(s).map_err(message)
}

pub fn run_road(a: RoadArgs) -> anyhow::Result<i32> {
    if let Some(dir) = &a.report {
        super::check_report_dir("--report", dir)?;
    }
    let settings = RoadSettings {
        class: a.class.clone(),
        maximize: a.maximize,
        range: a.range,
        grid: a.grid.clone(),
    };
    let answer = match a.maximize {
        Some(_) => super::with_progress("road calculations", |progress| {
            jobs::road(&a.scene, &settings, Some(progress))
        })?,
        None => jobs::road(&a.scene, &settings, None)?,
    };
    if let Some(dir) = &a.report {
        for path in write_road_report(dir, &answer)? {
            eprintln!("wrote {}", path.display());
        }
    }
    super::emit(a.json, &answer, &road_answer_text(&answer))?;
    if a.json {
        // the text summary already lists them
        for w in &answer.result.warnings {
            eprintln!("warning: {w}");
        }
    }
    Ok(0)
}
