//! The text summary and the `--report DIR` of `photosolid road`: `road.json`,
//! the luminance map seen from each observer lane and the illuminance map of
//! the field (axes in metres, colour bar in cd/m² or lux) and `index.html`
//! with the per-lane table; the road plan's `plan.json` and `index.html`.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use crate::compare_report::esc;
use crate::plot::{
    isolux_plot, line_chart_plot, palette, png_data_uri, IsoluxSpec, LineSpec, MapAxis, MapLimit, MapQuantity, Series,
    SeriesStyle,
};
use crate::scene::road::classes::{ClassVerdict, Comparison};
use crate::scene::road::design::{Maximized, RoadAnswer};
use crate::scene::road::plan::RoadPlan;
use crate::scene::road::quantities::{Grid, RoadResult};
use crate::scene::road::RoadError;

fn sig(x: f64) -> String {
    crate::significant(x, 3)
}

/// The plain-text summary: the installation, a per-lane table, the overall values.
pub fn road_text(r: &RoadResult) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "road: {}", r.scene);
    let _ = writeln!(
        s,
        "luminaire {} ({}), {} arrangement, field {} m x {} m, surface {} (Q0 {})",
        r.luminaire,
        r.representation,
        r.arrangement,
        sig(r.field_m[0]),
        sig(r.field_m[1]),
        r.surface,
        sig(r.q0)
    );
    let _ = writeln!(
        s,
        "{:>5} {:>12} {:>6} {:>6} {:>7}",
        "lane", "L_av cd/m2", "U_o", "U_l", "TI %"
    );
    for [lane, l_av, u_o, u_l, ti] in lane_rows(r) {
        let _ = writeln!(s, "{lane:>5} {l_av:>12} {u_o:>6} {u_l:>6} {ti:>7}");
    }
    let o = &r.overall;
    let _ = writeln!(
        s,
        "choices: r-table interpolation {}, TI screening from the {}",
        r.r_interpolation.as_str(),
        match r.ti_screening {
            crate::scene::road::layout::TiScreening::Horizontal => "horizontal",
            crate::scene::road::layout::TiScreening::LineOfSight => "1-degree-down line of sight",
        }
    );
    let _ = writeln!(
        s,
        "overall: L_av {} cd/m2, U_o {}, U_l {}, TI {} %, R_EI {}",
        sig(o.l_av_cd_m2),
        sig(o.u_o),
        sig(o.u_l),
        sig(o.ti_pct),
        sig(o.r_ei)
    );
    let _ = writeln!(
        s,
        "illuminance: E_av {} lx, E_min {} lx, U_o(E) {}, E_hs,av {} lx",
        sig(o.e_av_lux),
        sig(o.e_min_lux),
        sig(o.u_o_e),
        sig(o.e_hs_av_lux)
    );
    for w in &r.warnings {
        let _ = writeln!(s, "warning: {w}");
    }
    s
}

/// A criterion's symbol as the text and the plots write it.
fn criterion_label(name: &str) -> &str {
    match name {
        "l_av_cd_m2" => "L_av",
        "u_o" => "U_o",
        "u_l" => "U_l",
        "ti_pct" => "TI",
        "r_ei" => "R_EI",
        "e_av_lux" => "E_av",
        "e_min_lux" => "E_min",
        "u_o_e" => "U_o(E)",
        other => other,
    }
}

/// The verdict as a table: each criterion, its limit, the value achieved, the margin.
pub fn verdict_text(v: &ClassVerdict) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "class {} ({}): {}",
        v.class,
        v.class_source,
        if v.pass { "PASSES" } else { "FAILS" }
    );
    let _ = writeln!(
        s,
        "  {:<18} {:>16} {:>10} {:>10}  verdict",
        "criterion", "required", "achieved", "margin"
    );
    for c in &v.criteria {
        let _ = writeln!(
            s,
            "  {:<18} {:>16} {:>10} {:>10}  {}{}",
            format!("{} ({})", criterion_label(c.name), c.name),
            format!("{} {} {}", c.comparison.symbol(), c.required, c.unit),
            sig(c.achieved),
            sig(c.margin),
            if c.pass { "pass" } else { "FAIL" },
            if c.condition.is_some() { " *" } else { "" }
        );
    }
    for c in v.criteria.iter().filter(|c| c.condition.is_some()) {
        let _ = writeln!(
            s,
            "  * {}: {}",
            criterion_label(c.name),
            c.condition.unwrap_or_default()
        );
    }
    for n in &v.class_notes {
        let _ = writeln!(s, "  not assessed: {n}");
    }
    s
}

/// One maximisation as text: the answer, its margins, the next value's failure.
pub fn maximized_text(m: &Maximized) -> String {
    let mut s = String::new();
    let unit = m.key.unit();
    let held = m
        .grid
        .map(|g| format!(" with {} = {}", g.key.as_str(), g.value))
        .unwrap_or_default();
    match m.value {
        Some(v) => {
            let _ = writeln!(
                s,
                "largest {} meeting {}{held}: {v} {unit} (searched {}:{} {unit}, scan step {}, bisection to {}; {} road calculations)",
                m.key.as_str(),
                m.class,
                m.range[0],
                m.range[1],
                m.step,
                m.resolution,
                m.evaluations
            );
            let margins: Vec<String> = m
                .margins
                .iter()
                .map(|g| format!("{} {}", criterion_label(g.name), sig(g.margin)))
                .collect();
            let _ = writeln!(s, "  margins there: {}", margins.join(", "));
            if let Some(next) = m.next_value {
                let _ = writeln!(s, "  at {next} {unit} the class fails");
            }
        }
        None => {
            let _ = writeln!(
                s,
                "largest {} meeting {}{held}: none; {}",
                m.key.as_str(),
                m.class,
                m.reason.as_deref().unwrap_or("")
            );
        }
    }
    s
}

/// The text of `photosolid road`: the road, with `--class` the verdict, with
/// `--maximize` the answers.
pub fn road_answer_text(a: &RoadAnswer) -> String {
    let mut s = road_text(&a.result);
    if let Some(v) = &a.verdict {
        s.push_str(&verdict_text(v));
    }
    if let Some(m) = &a.maximize {
        for one in m.answers() {
            s.push_str(&maximized_text(one));
        }
    }
    s
}

fn io(p: &Path, e: impl std::fmt::Display) -> RoadError {
    RoadError::File {
        path: p.to_path_buf(),
        message: e.to_string(),
    }
}

/// The map of a grid (values in `quantity`'s unit), axes in metres.
fn map(
    name: &str,
    quantity: MapQuantity,
    g: &Grid,
    avg: f64,
    limits: &[MapLimit],
) -> Result<crate::plot::Plot, RoadError> {
    let values: Vec<f64> = g.values.iter().flatten().copied().collect();
    let (nu, nv) = (g.x_m.len(), g.y_m.len());
    // cell centres: the first and last are half a cell inside the edges
    let lu = if nu > 0 { g.x_m[0] + g.x_m[nu - 1] } else { 0.0 };
    let (v0, v1) = if nv > 0 {
        let half = if nv > 1 { (g.y_m[1] - g.y_m[0]) / 2.0 } else { g.y_m[0] };
        (g.y_m[0] - half, g.y_m[nv - 1] + half)
    } else {
        (0.0, 0.0)
    };
    isolux_plot(&IsoluxSpec {
        quantity,
        name,
        values: &values,
        grid: (nu, nv),
        size_m: (lu, v1 - v0),
        e_avg_lux: avg,
        u_axis: MapAxis {
            start: 0.0,
            end: lu,
            title: "x (m), along the road".into(),
        },
        v_axis: MapAxis {
            start: v0,
            end: v1,
            title: "y (m), across the carriageway".into(),
        },
        marks: &[],
        limits,
    })
    .map_err(|e| io(Path::new(name), e))
}

/// Write `bytes` to `dir/name` atomically (the library's one atomic writer).
fn write_atomic(dir: &Path, name: &str, bytes: &[u8]) -> Result<PathBuf, RoadError> {
    let path = dir.join(name);
    crate::formats::write_atomic(&path, bytes).map_err(|e| match e {
        crate::Error::Io { source, .. } => io(&path, source),
        other => io(&path, other),
    })?;
    Ok(path)
}

/// One row per observer lane: the lane, L_av (cd/m²), U_o, U_l and TI (%)
/// to three significant digits; the one table the text summary and the
/// HTML page print.
fn lane_rows(r: &RoadResult) -> Vec<[String; 5]> {
    r.lanes
        .iter()
        .map(|l| {
            [
                l.lane.to_string(),
                sig(l.l_av_cd_m2),
                sig(l.u_o),
                sig(l.u_l),
                sig(l.ti_pct),
            ]
        })
        .collect()
}

/// The per-lane table as HTML.
fn lane_table(r: &RoadResult) -> String {
    let mut t = String::from(
        "<table border=\"1\" cellpadding=\"4\"><tr><th>observer lane</th><th>L_av (cd/m²)</th>\
         <th>U_o</th><th>U_l</th><th>TI (%)</th></tr>\n",
    );
    for cells in lane_rows(r) {
        let _ = writeln!(t, "<tr><td>{}</td></tr>", cells.join("</td><td>"));
    }
    let o = &r.overall;
    let _ = writeln!(
        t,
        "<tr><th>overall</th><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr></table>",
        sig(o.l_av_cd_m2),
        sig(o.u_o),
        sig(o.u_l),
        sig(o.ti_pct)
    );
    t
}

/// The road pages' style: long text lines wrap inside the page, images fit it.
const PAGE_STYLE: &str = "<style>body{font-family:sans-serif;margin:2em;max-width:1200px;color:#222}\
pre{white-space:pre-wrap;overflow-wrap:anywhere}img{max-width:100%}</style>";

/// The limits of `verdict`'s class to mark on a luminance map whose average
/// is `l_av` (cd/m²), or on the illuminance map (`luminance` false) whose
/// average is `e_av` (lx).
fn map_limits(verdict: Option<&ClassVerdict>, luminance: bool, avg: f64) -> Vec<MapLimit> {
    let Some(v) = verdict else { return Vec::new() };
    let mut out = Vec::new();
    for c in &v.criteria {
        let (value, label) = match (luminance, c.name) {
            (true, "l_av_cd_m2") => (
                c.required,
                format!("L = {} cd/m2 ({} L_av >= {})", c.required, v.class, c.required),
            ),
            (true, "u_o") => (
                c.required * avg,
                format!(
                    "L = {} cd/m2 = {} L_av ({} U_o)",
                    sig(c.required * avg),
                    c.required,
                    v.class
                ),
            ),
            (false, "e_av_lux") => (
                c.required,
                format!("E = {} lx ({} E_av >= {})", c.required, v.class, c.required),
            ),
            (false, "u_o_e") => (
                c.required * avg,
                format!(
                    "E = {} lx = {} E_av ({} U_o)",
                    sig(c.required * avg),
                    c.required,
                    v.class
                ),
            ),
            (false, "e_min_lux") => (c.required, format!("E = {} lx ({} E_min)", c.required, v.class)),
            _ => continue,
        };
        out.push(MapLimit { value, label });
    }
    out
}

/// The colour of the answers' markers.
const INK_BLACK: [u8; 3] = [0, 0, 0];

/// One chart per criterion of a maximisation: the value achieved against
/// the key (one curve per `--grid` value), the limit dashed, each answer marked.
fn maximize_charts(answers: &[Maximized]) -> Result<Vec<(String, crate::plot::Plot)>, RoadError> {
    let Some(first) = answers.first() else {
        return Ok(Vec::new());
    };
    let mut out = Vec::new();
    for (ci, (&name, &required)) in first.criteria.iter().zip(&first.required).enumerate() {
        let mut series = Vec::new();
        let mut answers_marked = Vec::new();
        for (k, m) in answers.iter().enumerate() {
            let label = match m.grid {
                Some(g) => format!("{} = {}", g.key.as_str(), g.value),
                None => criterion_label(name).to_string(),
            };
            let points: Vec<(f64, f64)> = m
                .samples
                .iter()
                .filter_map(|smp| smp.achieved.get(ci).copied().flatten().map(|a| (smp.value, a)))
                .collect();
            if let Some(p) = m.value.and_then(|v| points.iter().find(|p| p.0 == v)) {
                answers_marked.push(*p);
            }
            series.push(Series {
                label,
                points,
                color: palette(k),
                style: SeriesStyle::Line,
            });
        }
        series.push(Series {
            label: format!("largest passing {}", first.key.as_str()),
            points: answers_marked,
            color: INK_BLACK,
            style: SeriesStyle::Markers,
        });
        let (lo, hi) = (first.range[0], first.range[1]);
        let cmp = if first
            .margins
            .iter()
            .any(|g| g.name == name && g.comparison == Comparison::AtMost)
            || name == "ti_pct"
        {
            "<="
        } else {
            ">="
        };
        series.push(Series {
            label: format!("{} limit {cmp} {required}", first.class),
            points: vec![(lo, required), (hi, required)],
            color: [230, 40, 30],
            style: SeriesStyle::Dashed,
        });
        let unit = first.key.unit();
        let title = format!(
            "{} against {} ({})",
            criterion_label(name),
            first.key.as_str(),
            first.class
        );
        let x_label = format!("{} ({unit})", first.key.as_str());
        let y_unit = first.margins.iter().find(|g| g.name == name).map_or("", |g| g.unit);
        let y_label = if y_unit.is_empty() {
            criterion_label(name).to_string()
        } else {
            format!("{} ({})", criterion_label(name), y_unit.replace('²', "2"))
        };
        let plot = line_chart_plot(&LineSpec {
            title: &title,
            x_label: &x_label,
            y_label: &y_label,
            series: &series,
            ..LineSpec::default()
        })
        .map_err(|e| io(Path::new(name), e))?;
        out.push((format!("maximize_{name}.png"), plot));
    }
    Ok(out)
}

/// Write `road.json`, `illuminance.png`, `luminance_lane{k}.png` (one per
/// observer lane; with a class its limits marked), with `--maximize` one
/// `maximize_{criterion}.png` per criterion, and `index.html` into `dir`;
/// returns the paths.
pub fn write_road_report(dir: &Path, answer: &RoadAnswer) -> Result<Vec<PathBuf>, RoadError> {
    let r = &answer.result;
    let verdict = answer.verdict.as_ref();
    std::fs::create_dir_all(dir).map_err(|e| io(dir, e))?;
    let json = serde_json::to_string_pretty(answer).map_err(|e| io(&dir.join("road.json"), e))?;
    let mut paths = vec![write_atomic(dir, "road.json", json.as_bytes())?];
    let mut html = format!("<!doctype html><meta charset=\"utf-8\"><title>road</title>\n{PAGE_STYLE}\n");
    let _ = writeln!(
        html,
        "<h1>Road lighting</h1><pre>{}</pre>",
        esc(&road_answer_text(answer))
    );
    let _ = writeln!(html, "<h2>Per observer lane</h2>{}", lane_table(r));
    for (k, (grid, lane)) in r.luminance.iter().zip(&r.lanes).enumerate() {
        let name = format!("road luminance seen from lane {}", lane.lane);
        let limits = map_limits(verdict, true, lane.l_av_cd_m2);
        let plot = map(&name, MapQuantity::LUMINANCE, grid, lane.l_av_cd_m2, &limits)?;
        paths.push(write_atomic(dir, &format!("luminance_lane{}.png", k + 1), &plot.png)?);
        let _ = writeln!(
            html,
            "<h2>Luminance, observer in lane {}</h2><img alt=\"{}\" src=\"{}\">",
            lane.lane,
            esc(&name),
            png_data_uri(&plot.png)
        );
    }
    let limits = map_limits(verdict, false, r.overall.e_av_lux);
    let plot = map(
        "road field illuminance",
        MapQuantity::ILLUMINANCE,
        &r.illuminance,
        r.overall.e_av_lux,
        &limits,
    )?;
    paths.push(write_atomic(dir, "illuminance.png", &plot.png)?);
    let _ = writeln!(
        html,
        "<h2>Illuminance of the field</h2><img alt=\"illuminance map\" src=\"{}\">",
        png_data_uri(&plot.png)
    );
    if let Some(m) = &answer.maximize {
        let _ = writeln!(html, "<h2>Each criterion against {}</h2>", m.answers()[0].key.as_str());
        for (file, plot) in maximize_charts(m.answers())? {
            paths.push(write_atomic(dir, &file, &plot.png)?);
            let _ = writeln!(html, "<img alt=\"{}\" src=\"{}\">", esc(&file), png_data_uri(&plot.png));
        }
    }
    paths.push(write_atomic(dir, "index.html", html.as_bytes())?);
    Ok(paths)
}

/// Write the road plan's `plan.json` and `index.html` (its text table) into
/// `dir`; returns the paths.
pub fn write_road_plan_report(dir: &Path, p: &RoadPlan, text: &str) -> Result<Vec<PathBuf>, RoadError> {
    std::fs::create_dir_all(dir).map_err(|e| io(dir, e))?;
    let json = serde_json::to_string_pretty(p).map_err(|e| io(&dir.join("plan.json"), e))?;
    let html = format!(
        "<!doctype html><meta charset=\"utf-8\"><title>road plan</title>\n{PAGE_STYLE}\n<h1>Road plan</h1><pre>{}</pre>\n",
        esc(text)
    );
    Ok(vec![
        write_atomic(dir, "plan.json", json.as_bytes())?,
        write_atomic(dir, "index.html", html.as_bytes())?,
    ])
}
