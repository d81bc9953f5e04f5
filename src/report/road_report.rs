//! The text summary and the `--report DIR` of `photosolid road`: `road.json`,
//! the illuminance map of the field (isolux, axes in metres, colour bar in lux)
//! and `index.html` with the per-lane table.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use crate::report::compare_report::esc;
use crate::report::plot::{isolux_plot, png_data_uri, IsoluxSpec, MapAxis};
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

/// The isolux map of a grid (values in lx).
fn map(name: &str, g: &Grid, avg: f64) -> Result<crate::report::plot::Plot, RoadError> {
    let values: Vec<f64> = g.values.iter().flatten().copied().collect();
    let (nu, nv) = (g.x_m.len(), g.y_m.len());
    // cell centres: the first and last are half a cell inside the edges
    let lu = if nu > 0 { g.x_m[0] + g.x_m[nu - 1] } else { 0.0 };
    let lv = if nv > 0 { g.y_m[0] + g.y_m[nv - 1] } else { 0.0 };
    isolux_plot(&IsoluxSpec {
        name,
        values: &values,
        grid: (nu, nv),
        size_m: (lu, lv),
        e_avg_lux: avg,
        u_axis: MapAxis {
            start: 0.0,
            end: lu,
            title: "x (m), along the road".into(),
        },
        v_axis: MapAxis {
            start: 0.0,
            end: lv,
            title: "y (m), across the carriageway".into(),
        },
        marks: &[],
    })
    .map_err(|e| io(Path::new(name), e))
}

/// Write `road.json`, `illuminance.png` and `index.html` into `dir`; returns the paths.
pub fn write_road_report(dir: &Path, r: &RoadResult) -> Result<Vec<PathBuf>, RoadError> {
    std::fs::create_dir_all(dir).map_err(|e| io(dir, e))?;
    let json = dir.join("road.json");
    let text = serde_json::to_string_pretty(r).map_err(|e| io(&json, e))?;
    std::fs::write(&json, text).map_err(|e| io(&json, e))?;
    let plot = map("road field illuminance", &r.illuminance, r.overall.e_av_lux)?;
    let png = dir.join("illuminance.png");
    std::fs::write(&png, &plot.png).map_err(|e| io(&png, e))?;
    let mut html = String::from("<!doctype html><meta charset=\"utf-8\"><title>road</title>\n");
    let _ = writeln!(html, "<h1>Road lighting</h1><pre>{}</pre>", esc(&road_text(r)));
    let _ = writeln!(
        html,
        "<h2>Illuminance of the field</h2><img alt=\"illuminance map\" src=\"{}\">",
        png_data_uri(&plot.png)
    );
    let index = dir.join("index.html");
    std::fs::write(&index, html).map_err(|e| io(&index, e))?;
    Ok(vec![json, png, index])
}
