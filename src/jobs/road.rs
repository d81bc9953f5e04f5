//! The job of `road`: a road's quantities, its verdict against a lighting
//! class, and the largest value of a key that meets the class.

use std::path::Path;

use crate::model::Progress;
use crate::scene::road::classes::{class_names, lighting_class, LightingClass};
use crate::scene::road::design::{judge, maximize, maximize_grid, MaximizeAnswer, RoadAnswer, SearchRange};
use crate::scene::road::layout::{Road, RoadKey};
use crate::scene::road::quantities::{evaluate, RoadOptions};
use crate::scene::road::RoadError;

/// A search range as `--range A:B[:STEP]` writes it: start, end, step (None: (B - A)/100).
pub type Range = (f64, f64, Option<f64>);

/// The options of `road` (the CLI's flags).
#[derive(Clone, Debug, Default)]
pub struct RoadSettings {
    /// `--class`: judge the road against this lighting class.
    pub class: Option<LightingClass>,
    /// `--maximize`: the key whose largest value meeting the class is searched (needs `class`).
    pub maximize: Option<RoadKey>,
    /// `--range`: the range searched (None: the key's default; only spacing_m has one).
    pub range: Option<Range>,
    /// `--grid`: search once for each of these values of another key.
    pub grid: Option<(RoadKey, Vec<f64>)>,
}

fn option(option: &str, message: String) -> RoadError {
    RoadError::Option {
        option: option.to_string(),
        message,
    }
}

/// The lighting class `s` names (`M3`), or an error listing the classes.
pub fn parse_class(s: &str) -> Result<LightingClass, RoadError> {
    lighting_class(s).ok_or_else(|| {
        option(
            "--class",
            format!(
                "`{s}` is not a lighting class of EN 13201-2:2015: expected one of {}",
                class_names().join(", ")
            ),
        )
    })
}

/// The numeric `[road]` key `s` names, or an error listing the keys.
pub fn parse_key(s: &str) -> Result<RoadKey, RoadError> {
    RoadKey::parse(s).ok_or_else(|| {
        let keys: Vec<_> = RoadKey::ALL.iter().map(|k| k.as_str()).collect();
        option(
            "--maximize",
            format!("`{s}` is not a numeric [road] key: expected one of {}", keys.join(", ")),
        )
    })
}

fn number(s: &str, what: &str) -> Result<f64, RoadError> {
    match s.trim().parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(x),
        _ => Err(option("--range", format!("{what} `{s}` is not a finite number"))),
    }
}

/// `A:B` or `A:B:STEP`.
pub fn parse_range(s: &str) -> Result<Range, RoadError> {
    let parts: Vec<&str> = s.split(':').collect();
    if !(2..=3).contains(&parts.len()) {
        return Err(option(
            "--range",
            format!("`{s}`: expected START:END or START:END:STEP"),
        ));
    }
    let (a, b) = (number(parts[0], "START")?, number(parts[1], "END")?);
    if b <= a {
        return Err(option("--range", format!("`{s}` is empty: expected START < END")));
    }
    let step = match parts.get(2) {
        Some(p) => {
            let st = number(p, "STEP")?;
            if st <= 0.0 {
                return Err(option("--range", format!("STEP {st} must be > 0")));
            }
            Some(st)
        }
        None => None,
    };
    Ok((a, b, step))
}

/// `KEY=A:B:STEP`: the key and its values A, A + STEP, ... up to B.
pub fn parse_grid(s: &str) -> Result<(RoadKey, Vec<f64>), RoadError> {
    let (key, range) = s
        .split_once('=')
        .ok_or_else(|| option("--grid", format!("`{s}`: expected KEY=START:END:STEP")))?;
    let key = parse_key(key)?;
    let (a, b, step) = parse_range(range)?;
    let step = step.ok_or_else(|| {
        option(
            "--grid",
            format!("`{s}`: expected KEY=START:END:STEP (the STEP is required)"),
        )
    })?;
    let n = ((b - a) / step + 1e-9).floor() as usize;
    if n > 1000 {
        return Err(option("--grid", format!("`{s}` has {} values: at most 1001", n + 1)));
    }
    let values: Vec<f64> = (0..=n).map(|i| ((a + i as f64 * step) * 1e9).round() / 1e9).collect();
    for v in &values {
        key.check(*v)?;
    }
    Ok((key, values))
}

impl RoadSettings {
    /// The search range of `key` on `road` (`range`, or the key's default).
    fn search_range(&self, key: RoadKey, road: &Road) -> Result<SearchRange, RoadError> {
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
        let default = self
            .grid
            .as_ref()
            .and_then(held_default)
            .or_else(|| SearchRange::default_for(key, road));
        let (start, end, step) = match (self.range, default) {
            (Some(r), _) => r,
            (None, Some((s, e))) => (s, e, None),
            (None, None) => {
                return Err(option(
                    &format!("--maximize {}", key.as_str()),
                    "give the range to search with --range START:END[:STEP] (only spacing_m has a default)".into(),
                ))
            }
        };
        SearchRange::new(key, start, end, step)
            .map_err(|e| option(&format!("--range for --maximize {}", key.as_str()), e.to_string()))
    }

    /// The options' own consistency, before any work.
    fn check(&self) -> Result<(), RoadError> {
        if self.maximize.is_some() && self.class.is_none() {
            return Err(option("--maximize", "needs --class".into()));
        }
        if (self.range.is_some() || self.grid.is_some()) && self.maximize.is_none() {
            return Err(option(
                if self.range.is_some() { "--range" } else { "--grid" },
                "needs --maximize".into(),
            ));
        }
        if let (Some(m), Some((g, _))) = (self.maximize, &self.grid) {
            if m == *g {
                return Err(option(
                    "--grid",
                    format!("varies {}, the key --maximize searches", g.as_str()),
                ));
            }
        }
        Ok(())
    }
}

/// `photosolid road SCENE`: the answer `road --json` prints.
pub fn road(scene: &Path, settings: &RoadSettings, progress: Option<&Progress<'_>>) -> Result<RoadAnswer, RoadError> {
    settings.check()?;
    let road = Road::load(scene)?;
    let options = RoadOptions::default();
    let range = settings
        .maximize
        .map(|key| settings.search_range(key, &road))
        .transpose()?;
    let Some(class) = &settings.class else {
        return Ok(RoadAnswer {
            result: evaluate(&road, &options)?,
            verdict: None,
            maximize: None,
        });
    };
    let judged = judge(&road, class, &options)?;
    let maximize = match &range {
        None => None,
        Some(range) => Some(match &settings.grid {
            None => maximize(&road, class, range, &options, progress).map(|m| MaximizeAnswer::One(Box::new(m)))?,
            Some((held, values)) => {
                maximize_grid(&road, class, range, *held, values, &options, progress).map(MaximizeAnswer::Grid)?
            }
        }),
    };
    Ok(RoadAnswer {
        result: judged.result,
        verdict: Some(judged.verdict),
        maximize,
    })
}
