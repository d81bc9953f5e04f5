//! The text summary and the `--report DIR` of `photosolid road`: `road.json`,
//! the luminance map seen from each observer lane and the illuminance map of
//! the field (axes in metres, colour bar in cd/m² or lux) and `index.html`
//! with the per-lane table; the road plan's `plan.json` and `index.html`.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use crate::report::compare_report::esc;
use crate::report::plot::{isolux_plot, png_data_uri, IsoluxSpec, MapAxis, MapQuantity};
use crate::scene::road::plan::RoadPlan;
use crate::scene::road::quantities::{Grid, RoadResult};
use crate::scene::road::RoadError;

fn sig(x: f64) -> String {
    crate::report::significant(x, 3)
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
    for l in &r.lanes {
        let _ = writeln!(
            s,
            "{:>5} {:>12} {:>6} {:>6} {:>7}",
            l.lane,
            sig(l.l_av_cd_m2),
            sig(l.u_o),
            sig(l.u_l),
            sig(l.ti_pct)
        );
    }
    let o = &r.overall;
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

fn io(p: &Path, e: impl std::fmt::Display) -> RoadError {
    RoadError::File {
        path: p.to_path_buf(),
        message: e.to_string(),
    }
}

/// The map of a grid (values in `quantity`'s unit), axes in metres.
fn map(name: &str, quantity: MapQuantity, g: &Grid, avg: f64) -> Result<crate::report::plot::Plot, RoadError> {
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
    })
    .map_err(|e| io(Path::new(name), e))
}

/// Write `bytes` to `dir/name` atomically (a temporary file renamed into place).
fn write_atomic(dir: &Path, name: &str, bytes: &[u8]) -> Result<PathBuf, RoadError> {
    let path = dir.join(name);
    let tmp = dir.join(format!(".{name}.tmp"));
    std::fs::write(&tmp, bytes).map_err(|e| io(&tmp, e))?;
    std::fs::rename(&tmp, &path).map_err(|e| io(&path, e))?;
    Ok(path)
}

/// The per-lane table as HTML.
fn lane_table(r: &RoadResult) -> String {
    let mut t = String::from(
        "<table border=\"1\" cellpadding=\"4\"><tr><th>observer lane</th><th>L_av (cd/m²)</th>\
         <th>U_o</th><th>U_l</th><th>TI (%)</th></tr>\n",
    );
    for l in &r.lanes {
        let _ = writeln!(
            t,
            "<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>",
            l.lane,
            sig(l.l_av_cd_m2),
            sig(l.u_o),
            sig(l.u_l),
            sig(l.ti_pct)
        );
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

/// Write `road.json`, `illuminance.png`, `luminance_lane{k}.png` (one per
/// observer lane) and `index.html` into `dir`; returns the paths.
pub fn write_road_report(dir: &Path, r: &RoadResult) -> Result<Vec<PathBuf>, RoadError> {
    std::fs::create_dir_all(dir).map_err(|e| io(dir, e))?;
    let json = serde_json::to_string_pretty(r).map_err(|e| io(&dir.join("road.json"), e))?;
    let mut paths = vec![write_atomic(dir, "road.json", json.as_bytes())?];
    let mut html = format!("<!doctype html><meta charset=\"utf-8\"><title>road</title>\n{PAGE_STYLE}\n");
    let _ = writeln!(html, "<h1>Road lighting</h1><pre>{}</pre>", esc(&road_text(r)));
    let _ = writeln!(html, "<h2>Per observer lane</h2>{}", lane_table(r));
    for (k, (grid, lane)) in r.luminance.iter().zip(&r.lanes).enumerate() {
        let name = format!("road luminance seen from lane {}", lane.lane);
        let plot = map(&name, MapQuantity::LUMINANCE, grid, lane.l_av_cd_m2)?;
        paths.push(write_atomic(dir, &format!("luminance_lane{}.png", k + 1), &plot.png)?);
        let _ = writeln!(
            html,
            "<h2>Luminance, observer in lane {}</h2><img alt=\"{}\" src=\"{}\">",
            lane.lane,
            esc(&name),
            png_data_uri(&plot.png)
        );
    }
    let plot = map(
        "road field illuminance",
        MapQuantity::ILLUMINANCE,
        &r.illuminance,
        r.overall.e_av_lux,
    )?;
    paths.push(write_atomic(dir, "illuminance.png", &plot.png)?);
    let _ = writeln!(
        html,
        "<h2>Illuminance of the field</h2><img alt=\"illuminance map\" src=\"{}\">",
        png_data_uri(&plot.png)
    );
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
