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
use photosolid::report::road_report::{road_answer_text, write_road_report};
use photosolid::scene::road::classes::{class_names, lighting_class, LightingClass};
use photosolid::scene::road::design::{judge, maximize, maximize_grid, MaximizeAnswer, RoadAnswer, SearchRange};
use photosolid::scene::road::layout::{Road, RoadKey};
use photosolid::scene::road::quantities::{evaluate, RoadOptions};

use super::UsageError;

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

pub(crate) fn parse_class(s: &str) -> Result<LightingClass, String> {
    lighting_class(s).ok_or_else(|| {
        format!(
            "`{s}` is not a lighting class of EN 13201-2:2015: expected one of {}",
            class_names().join(", ")
        )
    })
}

fn parse_key(s: &str) -> Result<RoadKey, String> {
    RoadKey::parse(s).ok_or_else(|| {
        let keys: Vec<_> = RoadKey::ALL.iter().map(|k| k.as_str()).collect();
        format!("`{s}` is not a numeric [road] key: expected one of {}", keys.join(", "))
    })
}

fn number(s: &str, what: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(x),
        _ => Err(format!("{what} `{s}` is not a finite number")),
    }
}

/// `A:B` or `A:B:STEP`.
fn parse_range(s: &str) -> Result<(f64, f64, Option<f64>), String> {
    let parts: Vec<&str> = s.split(':').collect();
    if !(2..=3).contains(&parts.len()) {
        return Err(format!("`{s}`: expected START:END or START:END:STEP"));
    }
    let (a, b) = (number(parts[0], "START")?, number(parts[1], "END")?);
    if b <= a {
        return Err(format!("`{s}` is empty: expected START < END"));
    }
    let step = match parts.get(2) {
        Some(p) => {
            let st = number(p, "STEP")?;
            if st <= 0.0 {
                return Err(format!("STEP {st} must be > 0"));
            }
            Some(st)
        }
        None => None,
    };
    Ok((a, b, step))
}

/// `KEY=A:B:STEP`: the key and its values A, A + STEP, ... up to B.
fn parse_grid(s: &str) -> Result<(RoadKey, Vec<f64>), String> {
    let (key, range) = s
        .split_once('=')
        .ok_or_else(|| format!("`{s}`: expected KEY=START:END:STEP"))?;
    let key = parse_key(key)?;
    let (a, b, step) = parse_range(range)?;
    let step = step.ok_or_else(|| format!("`{s}`: expected KEY=START:END:STEP (the STEP is required)"))?;
    let n = ((b - a) / step + 1e-9).floor() as usize;
    if n > 1000 {
        return Err(format!("`{s}` has {} values: at most 1001", n + 1));
    }
    let values: Vec<f64> = (0..=n).map(|i| ((a + i as f64 * step) * 1e9).round() / 1e9).collect();
    for v in &values {
        key.check(*v).map_err(|e| e.to_string())?;
    }
    Ok((key, values))
}

/// The search range of `key` for `road` from `--range` (or the key's default).
fn search_range(a: &RoadArgs, key: RoadKey, road: &Road) -> anyhow::Result<SearchRange> {
    // A grid over the mounting height: the default spacing range spans every height's.
    let held_default = |(held, values): &(RoadKey, Vec<f64>)| {
        let at = |v: f64| held.set(road, v).ok().and_then(|r| SearchRange::default_for(key, &r));
        let ends: Vec<(f64, f64)> = values.iter().filter_map(|&v| at(v)).collect();
        (!ends.is_empty()).then(|| {
            let lo = ends.iter().map(|e| e.0).fold(f64::INFINITY, f64::min);
            let hi = ends.iter().map(|e| e.1).fold(f64::NEG_INFINITY, f64::max);
            (lo, hi)
        })
    };
    let default = a
        .grid
        .as_ref()
        .and_then(held_default)
        .or_else(|| SearchRange::default_for(key, road));
    let (start, end, step) = match (a.range, default) {
        (Some(r), _) => r,
        (None, Some((s, e))) => (s, e, None),
        (None, None) => {
            return Err(UsageError(format!(
                "--maximize {}: give the range to search with --range START:END[:STEP] (only spacing_m has a default)",
                key.as_str()
            ))
            .into())
        }
    };
    SearchRange::new(key, start, end, step)
        .map_err(|e| UsageError(format!("--range for --maximize {}: {e}", key.as_str())).into())
}

pub fn run_road(a: RoadArgs) -> anyhow::Result<i32> {
    if let Some(dir) = &a.report {
        super::check_report_dir("--report", dir)?;
    }
    if let (Some(m), Some((g, _))) = (a.maximize, &a.grid) {
        if m == *g {
            return Err(UsageError(format!("--grid varies {}, the key --maximize searches", g.as_str())).into());
        }
    }
    let road = Road::load(&a.scene)?;
    let options = RoadOptions::default();
    let range = match a.maximize {
        Some(key) => Some(search_range(&a, key, &road)?),
        None => None,
    };
    let answer = match &a.class {
        None => RoadAnswer {
            result: evaluate(&road, &options)?,
            verdict: None,
            maximize: None,
        },
        Some(class) => {
            let judged = judge(&road, class, &options)?;
            let maximize = match &range {
                None => None,
                Some(range) => Some(super::with_progress("road calculations", |progress| match &a.grid {
                    None => maximize(&road, class, range, &options, Some(progress))
                        .map(|m| MaximizeAnswer::One(Box::new(m))),
                    Some((held, values)) => maximize_grid(&road, class, range, *held, values, &options, Some(progress))
                        .map(MaximizeAnswer::Grid),
                })?),
            };
            RoadAnswer {
                result: judged.result,
                verdict: Some(judged.verdict),
                maximize,
            }
        }
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
