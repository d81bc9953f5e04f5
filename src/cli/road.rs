//! `photosolid road SCENE [--json] [--report DIR]`: a thin layer over
//! `photosolid::scene::road` (JSON keys: `scene::road::quantities::RoadResult`;
//! `lanes: [{lane, l_av_cd_m2, u_o, u_l, ti_pct}]`, `overall: {l_av_cd_m2,
//! u_o, u_l, ti_pct, r_ei, e_av_lux, e_min_lux, u_o_e, e_hs_av_lux}`).

use std::path::PathBuf;

use clap::Args;
use photosolid::report::road_report::{road_text, write_road_report};
use photosolid::scene::road::layout::Road;
use photosolid::scene::road::quantities::{evaluate, RoadOptions};

#[derive(Args, Debug)]
pub struct RoadArgs {
    /// A scene file with a [road] table (TOML; see docs/road.md).
    scene: PathBuf,
    /// Print JSON.
    #[arg(long)]
    json: bool,
    /// Write road.json, the illuminance map of the field (PNG) and index.html into DIR.
    #[arg(long)]
    report: Option<PathBuf>,
}

pub fn run_road(a: RoadArgs) -> anyhow::Result<i32> {
    if let Some(dir) = &a.report {
        super::check_report_dir("--report", dir)?;
    }
    let road = Road::load(&a.scene)?;
    let result = evaluate(&road, &RoadOptions::default())?;
    if let Some(dir) = &a.report {
        for path in write_road_report(dir, &result)? {
            eprintln!("wrote {}", path.display());
        }
    }
    super::emit(a.json, &result, &road_text(&result))?;
    if a.json {
        // the text summary already lists them
        for w in &result.warnings {
            eprintln!("warning: {w}");
        }
    }
    Ok(0)
}
