//! The comparison report: a text table, `report.md`, `report.json`,
//! a self-contained `index.html` (inline PNG data URIs and the interactive
//! 3D view [`crate::viewer`]; no network, no external CSS or JS) and the PNGs (polar diagrams, error maps, the
//! speed/accuracy scatter), all written atomically.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use crate::compare::{Comparison, ErrorMap, PolarPlane, ReconResult};
use crate::error::Error;
use crate::formats::write_atomic;
use crate::photometry::derived::{side_by_side_markdown, side_by_side_text};
use crate::plot::{self, ColorScale, HeatmapSpec, LineSpec, PolarSpec, ScatterPoint, ScatterSpec, Series, SeriesStyle};
use crate::registry::Recon;

/// Significant digits of every number in the tables and texts of a comparison.
const DIGITS: usize = 4;

/// A number of the comparison tables: [`DIGITS`] significant digits at every magnitude.
fn num(x: f64) -> String {
    super::significant(x, DIGITS)
}

/// "H = 12.31 cd (+0.05)".
pub fn hausdorff_text(r: &ReconResult, unit: &str) -> String {
    format!("H = {} {unit} (+{})", num(r.hausdorff_cd), num(r.hausdorff_bound_cd))
}

/// What H and the radial max mean for this comparison: certified to a bound
/// against a reference solid, or exact (one-sided) against withheld points.
fn hausdorff_meaning(c: &Comparison) -> String {
    if c.hausdorff_certified() {
        "H certified: the true Hausdorff distance lies in [H, H + bound]; radial max is the radial bound (>= H)".into()
    } else if c.results.iter().any(|r| r.mean_surface_distance_cd.is_none()) {
        // CompareOptions::hausdorff_only (tradeoff): no point was searched that could not set H.
        format!(
            "H: the exact one-sided distance from the {} withheld measured points to each solid rebuilt without them \
             (searched on the solid itself for continuous reconstructions, only from the points whose distance \
             along their own direction exceeds the largest found, so at any count; in closed form for nearest \
             lookups, where a point on the wall between two cells is on the solid; to the mesh for the measured \
             solid, other fields that jump and the GPU's); only H was measured: h(ref->recon) and mean dist are \
             not (-); radial max over the same points",
            c.n_directions
        )
    } else {
        format!(
            "H: the exact one-sided distance from the {} withheld measured points to each solid rebuilt without them \
             (no bound to certify; searched on the solid itself for continuous reconstructions, in closed form for \
             nearest lookups, where a point on the wall between two cells is on the solid; to the mesh for the \
             measured solid, other fields that jump, the GPU's and folds of over {} searched points; each row's \
             withheld_distance says which); radial max over the same points",
            c.n_directions,
            crate::compare::SURFACE_SEARCH_MAX_POINTS
        )
    }
}

/// The lines above the table: the files, the reference, the solids and
/// tolerances, the direction set and the alignment.
fn header(c: &Comparison) -> Vec<String> {
    let mut l = vec![format!("file: {}", c.file)];
    if let Some(v) = &c.vs {
        l.push(format!("vs: {v}"));
    }
    l.push(reference_line(c));
    l.push(format!(
        "units: {} (--units {}); {}; Hausdorff tolerance {}% of I_max = {} {}{}",
        c.units,
        serde_json::to_value(c.normalize)
            .ok()
            .and_then(|v| v.as_str().map(str::to_string))
            .unwrap_or_default(),
        solids_text(c),
        c.tolerance_pct,
        num(c.tolerance_cd),
        c.units,
        if c.hausdorff_certified() {
            ""
        } else {
            " (not needed: H against withheld points is computed exactly)"
        }
    ));
    l.push(format!(
        "radial metrics over {} directions ({}), Zotti C = {} of I_max; radial max: {}",
        c.n_directions, c.directions, c.zotti_c, c.radial_max_method
    ));
    l.push(format!(
        "smallest within 1 % radial max: {}",
        c.smallest_within_1pct.as_deref().unwrap_or("none")
    ));
    if let Some(a) = &c.alignment {
        l.push(format!(
            "alignment: FILE rotated {} deg{} (step {} deg, {} candidates): RMS {:.3} % -> {:.3} % of I_max",
            a.rotate_deg,
            if a.mirror { " after mirroring C" } else { "" },
            a.step_deg,
            a.candidates,
            a.rms_pct_unaligned,
            a.rms_pct
        ));
    }
    l
}

/// The header's reference line: its I_max, and its triangles or withheld directions.
fn reference_line(c: &Comparison) -> String {
    if c.hausdorff_certified() {
        format!(
            "reference: {} (I_max {} {}, {} triangles)",
            c.reference,
            num(c.i_max_cd),
            c.units,
            c.reference_triangles
        )
    } else {
        format!(
            "reference: {} (I_max {} {}, {} withheld measured directions)",
            c.reference,
            num(c.i_max_cd),
            c.units,
            c.n_directions
        )
    }
}

/// How the solids were built (adaptive within a tolerance, or a fixed
/// factor), and which of them did not reach the tolerance.
fn solids_text(c: &Comparison) -> String {
    let solids = match (c.solid_tolerance_cd, c.solid_deviation_cd) {
        (Some(t), Some(d)) => format!(
            "adaptive grid solids within {}{} {} of their fields at the tested points (the reference's: {} {})",
            pct_note(c.solid_tolerance_pct),
            num(t),
            c.units,
            num(d),
            c.units
        ),
        (Some(t), None) => format!(
            "adaptive grid solids within {}{} {} of their fields at the tested points",
            pct_note(c.solid_tolerance_pct),
            num(t),
            c.units
        ),
        _ => format!("grid solids refined x{}", c.factor),
    };
    let short = solids_short(c);
    match short.is_empty() {
        true => solids,
        false => format!(
            "{solids}, NOT reached by {} (a jump in the field, the minimum step or the point budget stopped the refinement)",
            short.join(", ")
        ),
    }
}

/// The solids that did not get within their tolerance (a jump in the
/// field, the point budget), each with its deviation: the reference first.
fn solids_short(c: &Comparison) -> Vec<String> {
    c.solid_tolerance_reached
        .filter(|r| !r)
        .map(|_| {
            format!(
                "the reference ({} {})",
                num(c.solid_deviation_cd.unwrap_or(f64::NAN)),
                c.units
            )
        })
        .into_iter()
        .chain(
            c.results
                .iter()
                .filter(|r| r.solid_tolerance_reached == Some(false))
                .map(|r| {
                    format!(
                        "{} ({} {})",
                        r.name,
                        num(r.solid_deviation_cd.unwrap_or(f64::NAN)),
                        c.units
                    )
                }),
        )
        .collect()
}

const COLS: [&str; 15] = [
    "reconstruction",
    "bytes",
    "H",
    "+bound",
    "H %",
    "h(recon->ref)",
    "h(ref->recon)",
    "mean dist",
    "radial bound",
    "radial max %",
    "radial rms %",
    "Zotti err",
    "flux %",
    "misplaced",
    "ns/sample",
];

fn row(r: &ReconResult) -> Vec<String> {
    vec![
        format!(
            "{}{}{}",
            r.name,
            r.form.as_deref().map(|f| format!(" ({f})")).unwrap_or_default(),
            if r.pareto { " *" } else { "" }
        ),
        r.bytes.to_string(),
        num(r.hausdorff_cd),
        num(r.hausdorff_bound_cd),
        // The percent the terminal tables of tradeoff and engines print.
        num(r.hausdorff_pct),
        r.recon_to_ref.map_or("-".into(), |h| num(h.value)),
        r.ref_to_recon.map_or("-".into(), |h| num(h.value)),
        r.mean_surface_distance_cd.map_or("-".into(), num),
        num(r.radial_bound_cd),
        num(r.radial_max_pct),
        num(r.radial_rms_pct),
        num(r.zotti_err),
        format!(
            "{}{}",
            if r.flux_error_pct > 0.0 { "+" } else { "" },
            num(r.flux_error_pct)
        ),
        num(r.misplaced_flux),
        r.time_per_sample_ns.map_or("-".into(), num),
    ]
}

/// The plain-text summary printed by `photosolid compare`.
pub fn to_text(c: &Comparison) -> String {
    let mut s = header(c).join("\n");
    s.push('\n');
    if let Some(rows) = &c.photometry_side_by_side {
        s.push_str(&side_by_side_text(rows, "FILE", "OTHER"));
        s.push('\n');
    }
    let rows: Vec<Vec<String>> = c.results.iter().map(row).collect();
    let w: Vec<usize> = (0..COLS.len())
        .map(|k| {
            rows.iter()
                .map(|r| r[k].len())
                .chain([COLS[k].len()])
                .max()
                .unwrap_or(0)
        })
        .collect();
    let line = |cells: &[String]| -> String {
        let mut l = String::new();
        for (k, cell) in cells.iter().enumerate() {
            if k == 0 {
                let _ = write!(l, "{:<w$}", cell, w = w[k]);
            } else {
                let _ = write!(l, "  {:>w$}", cell, w = w[k]);
            }
        }
        l.push('\n');
        l
    };
    s += &line(&COLS.map(String::from));
    for r in &rows {
        s += &line(r);
    }
    let _ = writeln!(
        s,
        "lengths in {}; {}; * = Pareto (time, bytes, H)",
        c.units,
        hausdorff_meaning(c)
    );
    for r in &c.results {
        let partial = r.recon_to_ref.is_some_and(|h| !h.converged) || r.ref_to_recon.is_some_and(|h| !h.converged);
        if partial {
            let _ = writeln!(
                s,
                "{}: partial: bound not reached (refinement cap); H lies in [{}, {}]",
                r.name,
                r.hausdorff_cd,
                r.hausdorff_cd + r.hausdorff_bound_cd
            );
        }
    }
    s
}

fn md_table(c: &Comparison) -> String {
    let mut s = format!("| {} |\n|{}\n", COLS.join(" | "), "---|".repeat(COLS.len()));
    for r in &c.results {
        let _ = writeln!(s, "| {} |", row(r).join(" | "));
    }
    s
}

/// `s` with `&`, `<`, `>` and quotes escaped for HTML text and attribute values.
pub fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

fn slug(s: &str) -> String {
    s.chars()
        .map(|ch| if ch.is_ascii_alphanumeric() { ch } else { '-' })
        .collect()
}

/// One figure: file name, caption, PNG bytes.
pub struct Figure {
    /// File name inside the report directory.
    pub file: String,
    /// Caption.
    pub caption: String,
    /// The PNG.
    pub png: Vec<u8>,
}

/// Draw the report's figures (needs the comparison's plot data; none without it).
pub fn figures(c: &Comparison) -> Result<Vec<Figure>, Error> {
    let Some(p) = &c.plots else { return Ok(Vec::new()) };
    let mut out = Vec::new();
    for (k, plane) in p.planes.iter().enumerate() {
        out.push(polar_figure(c, k, plane)?);
    }
    for m in &p.error_maps {
        out.push(error_figure(c, m)?);
    }
    out.extend(scatter_figures(c)?);
    out.extend(degree_figure(c)?);
    Ok(out)
}

/// The polar diagram of plane pair `k` (the third: the plane of maximum
/// intensity): every reconstruction's curve over the measured points.
fn polar_figure(c: &Comparison, k: usize, plane: &PolarPlane) -> Result<Figure, Error> {
    let names = ["polar_c0_c180.png", "polar_c90_c270.png", "polar_cmax.png"];
    let mut series: Vec<Series> = plane
        .curves
        .iter()
        .enumerate()
        .map(|(i, (name, pts))| Series {
            label: name.clone(),
            points: pts.clone(),
            color: plot::palette(i),
            style: if name.ends_with("(reference)") {
                SeriesStyle::Dashed
            } else {
                plot::style_of(i)
            },
        })
        .collect();
    for (j, (label, pts)) in plane.measured.iter().enumerate() {
        series.push(Series {
            label: label.clone(),
            points: pts.clone(),
            color: if j == 0 { [0, 0, 0] } else { [110, 110, 110] },
            style: SeriesStyle::Markers,
        });
    }
    let title = if k == 2 {
        format!(
            "Plane of maximum intensity: C{:.1} - C{:.1}",
            plane.right_c, plane.left_c
        )
    } else {
        format!("C{:.0} - C{:.0}", plane.right_c, plane.left_c)
    };
    let c_name = |c: f64| {
        if c.fract() == 0.0 {
            format!("C{c:.0}")
        } else {
            format!("C{c:.1}")
        }
    };
    let (l, r) = (c_name(plane.left_c), c_name(plane.right_c));
    let png = plot::polar_diagram(&PolarSpec {
        title: &title,
        left: &l,
        right: &r,
        unit: &c.units,
        series: &series,
        ..PolarSpec::default()
    })?;
    Ok(Figure {
        file: names[k.min(2)].into(),
        caption: format!("{title}: every reconstruction over the measured points ({})", c.units),
        png,
    })
}

/// The heat map of one reconstruction's signed error over C × γ.
fn error_figure(c: &Comparison, m: &ErrorMap) -> Result<Figure, Error> {
    let title = format!("{} - {}: signed error, % of I_max", m.name, c.reference);
    let png = plot::heatmap(&HeatmapSpec {
        title: &title,
        xs: &m.xs,
        ys: &m.ys,
        values: &m.values,
        unit: "% of I_max",
        scale: ColorScale::Diverging,
        ..HeatmapSpec::default()
    })?;
    Ok(Figure {
        file: format!("error_{}.png", slug(&m.name)),
        caption: format!(
            "Signed error of {} against {} over C x gamma (degrees), % of I_max",
            m.name, c.reference
        ),
        png,
    })
}

/// The speed and the memory scatters against the Hausdorff distance, each
/// when some row has its cost.
fn scatter_figures(c: &Comparison) -> Result<Vec<Figure>, Error> {
    let mut out = Vec::new();
    let pts: Vec<ScatterPoint> = c
        .results
        .iter()
        .filter_map(|r| {
            r.time_per_sample_ns.map(|t| ScatterPoint {
                label: r.name.clone(),
                x: t,
                y: r.hausdorff_pct,
            })
        })
        .collect();
    if !pts.is_empty() {
        let png = plot::scatter(&ScatterSpec {
            title: "Speed vs accuracy",
            x_label: "time per sample (ns)",
            y_label: "Hausdorff distance (% of I_max)",
            points: &pts,
            log_x: true,
            ..ScatterSpec::default()
        })?;
        out.push(Figure {
            file: "scatter.png".into(),
            caption: "Time per sample vs Hausdorff distance; the Pareto front is marked".into(),
            png,
        });
    }
    let by_bytes: Vec<ScatterPoint> = c
        .results
        .iter()
        .filter(|r| r.bytes > 0)
        .map(|r| ScatterPoint {
            label: r.name.clone(),
            x: r.bytes as f64,
            y: r.hausdorff_pct,
        })
        .collect();
    if !by_bytes.is_empty() {
        let png = plot::scatter(&ScatterSpec {
            title: "Memory vs accuracy",
            x_label: "bytes held",
            y_label: "Hausdorff distance (% of I_max)",
            points: &by_bytes,
            log_x: true,
            ..ScatterSpec::default()
        })?;
        out.push(Figure {
            file: "scatter_bytes.png".into(),
            caption: "Bytes held vs Hausdorff distance; the Pareto front of these two axes is marked".into(),
            png,
        });
    }
    Ok(out)
}

/// One error column of a row, % of I_max.
type Metric = fn(&ReconResult) -> f64;

/// The error of the spherical-harmonic rows against their degree L (when
/// two degrees or more were compared): radial max, radial RMS and the
/// Hausdorff distance, % of I_max, against the comparison's reference;
/// half-float coefficients (`sh:L+f16`) dashed beside the f32 ones.
fn degree_figure(c: &Comparison) -> Result<Option<Figure>, Error> {
    let sh: Vec<(usize, bool, &ReconResult)> = c
        .results
        .iter()
        .filter_map(|r| match r.name.parse::<Recon>() {
            // The GPU rows evaluate the same coefficients: the CPU rows stand for them.
            Ok(Recon::Sh {
                degree,
                f16,
                gpu: false,
            }) => Some((degree, f16, r)),
            _ => None,
        })
        .collect();
    let mut degrees: Vec<usize> = sh.iter().map(|s| s.0).collect();
    degrees.sort_unstable();
    degrees.dedup();
    if degrees.len() < 2 {
        return Ok(None);
    }
    let metrics: [(&str, Metric); 3] = [
        ("radial max", |r| r.radial_max_pct),
        ("radial RMS", |r| r.radial_rms_pct),
        ("Hausdorff H", |r| r.hausdorff_pct),
    ];
    let mut series = Vec::new();
    for half in [false, true] {
        for (k, (what, value)) in metrics.iter().enumerate() {
            let points: Vec<(f64, f64)> = sh
                .iter()
                .filter(|s| s.1 == half)
                .map(|s| (s.0 as f64, value(s.2)))
                .collect();
            if !points.is_empty() {
                series.push(Series {
                    label: format!("{what}{}", if half { " (+f16)" } else { "" }),
                    points,
                    color: plot::palette(k),
                    style: if half { SeriesStyle::Dashed } else { SeriesStyle::Line },
                });
            }
        }
    }
    let title = format!(
        "Spherical harmonics: error against degree L ({})",
        c.reference_kind.as_str()
    );
    let png = plot::line_chart(&LineSpec {
        title: &title,
        x_label: "degree L (sh:L holds (L+1)^2 coefficients, L+1 when zonal)",
        y_label: "error (% of I_max)",
        series: &series,
        ..LineSpec::default()
    })?;
    Ok(Some(Figure {
        file: "error_vs_degree.png".into(),
        caption: format!(
            "Radial max, radial RMS and Hausdorff error of sh:L against {}, by degree L, % of I_max",
            c.reference
        ),
        png,
    }))
}

/// The title of `compare`'s report.
pub const COMPARE_TITLE: &str = "Photometric solid comparison";
/// The title of `tradeoff`'s report.
pub const TRADE_TITLE: &str = "Representations: bytes, time and error";

/// `report.md` titled `title`: the header, the table and the figures by file name.
pub fn to_markdown(c: &Comparison, figs: &[Figure], title: &str) -> String {
    let mut s = format!("# {title}\n\n");
    for l in header(c) {
        let _ = writeln!(s, "- {l}");
    }
    if let Some(rows) = &c.photometry_side_by_side {
        let _ = writeln!(
            s,
            "\n## Photometry side by side\n\nFILE = {}, OTHER = {}; difference = OTHER - FILE.\n\n{}",
            c.file,
            c.vs.as_deref().unwrap_or("-"),
            side_by_side_markdown(rows, "FILE", "OTHER")
        );
    }
    let _ = writeln!(s, "\n## Metrics\n\n{}", md_table(c));
    let _ = writeln!(
        s,
        "Lengths in {}. {}. * marks the Pareto front (time vs H).\n",
        c.units,
        hausdorff_meaning(c)
    );
    for r in &c.results {
        let _ = writeln!(s, "- {}: {}", r.name, hausdorff_text(r, &c.units));
    }
    if !figs.is_empty() {
        s.push_str("\n## Figures\n\n");
        for f in figs {
            let _ = writeln!(s, "![{}]({})\n", f.caption, f.file);
        }
    }
    s
}

/// `index.html`: self-contained, images inline.
pub fn to_html(c: &Comparison, figs: &[Figure], title: &str) -> String {
    let mut s = String::from(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>TITLE</title>\n<style>\n\
body{font-family:sans-serif;margin:2em;max-width:1200px;color:#222}\n\
table{border-collapse:collapse;font-size:0.9em}\n\
th,td{border:1px solid #bbb;padding:3px 6px;text-align:right}\n\
th:first-child,td:first-child{text-align:left}\n\
tr.pareto td:first-child{font-weight:bold}\n\
figure{display:inline-block;margin:1em;vertical-align:top}\n\
img{max-width:100%;border:1px solid #ddd}\n\
</style>\n</head>\n<body>\n<h1>TITLE</h1>\n<ul>\n",
    )
    .replace("TITLE", &esc(title));
    for l in header(c) {
        let _ = writeln!(s, "<li>{}</li>", esc(&l));
    }
    s.push_str("</ul>\n");
    // The report opens with the 3D view (README: "Every HTML report ... opens with an interactive 3D view").
    if let Some(v) = c.plots.as_ref().and_then(|p| p.viewer.as_ref()) {
        s.push_str(&crate::viewer::html(
            &crate::viewer::ViewerData::from_samples(v),
            "the static figures below",
        ));
    }
    if let Some(rows) = &c.photometry_side_by_side {
        s.push_str("<h2>Photometry side by side</h2>\n<p>Difference = OTHER &minus; FILE.</p>\n<table>\n<tr><th>quantity</th><th>unit</th><th>FILE</th><th>OTHER</th><th>difference</th></tr>\n");
        let f = |v: Option<f64>| v.map_or("-".to_string(), |x| format!("{x:.4}"));
        for r in rows {
            let _ = writeln!(
                s,
                "<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>",
                esc(&r.quantity),
                esc(r.unit),
                f(r.file),
                f(r.other),
                f(r.difference)
            );
        }
        s.push_str("</table>\n");
    }
    s.push_str("<h2>Metrics</h2>\n<table>\n<tr>");
    for h in COLS {
        let _ = write!(s, "<th>{}</th>", esc(h));
    }
    s.push_str("</tr>\n");
    for r in &c.results {
        let _ = write!(s, "<tr{}>", if r.pareto { " class=\"pareto\"" } else { "" });
        for cell in row(r) {
            let _ = write!(s, "<td>{}</td>", esc(&cell));
        }
        s.push_str("</tr>\n");
    }
    let _ = writeln!(
        s,
        "</table>\n<p>Lengths in {}. {}. * marks the Pareto front (time vs H).</p>",
        esc(&c.units),
        esc(&hausdorff_meaning(c))
    );
    if !figs.is_empty() {
        s.push_str("<h2>Figures</h2>\n");
        for f in figs {
            let _ = writeln!(
                s,
                "<figure><img src=\"{}\" alt=\"{}\"><figcaption>{}</figcaption></figure>",
                plot::png_data_uri(&f.png),
                esc(&f.caption),
                esc(&f.caption)
            );
        }
    }
    s.push_str("</body>\n</html>\n");
    s
}

/// Write `index.html`, `report.md`, `report.json` and the PNGs into `dir` (created); returns the paths written.
pub fn write_report(c: &Comparison, dir: &Path) -> Result<Vec<PathBuf>, Error> {
    write_titled(c, c, COMPARE_TITLE, dir)
}

/// The report of `c` under `title`, with `value` as `report.json`.
fn write_titled(c: &Comparison, value: &impl serde::Serialize, title: &str, dir: &Path) -> Result<Vec<PathBuf>, Error> {
    let figs = figures(c)?;
    write_files(
        dir,
        &figs,
        value,
        &to_markdown(c, &figs, title),
        &to_html(c, &figs, title),
    )
}

/// `tradeoff --report DIR`: the comparison's figures and pages under the
/// trade table's title, and `report.json` the trade table itself (what
/// `tradeoff --json` prints, `pareto` and `pareto_bytes` included).
pub fn write_trade_report(t: &crate::compare::trade::TradeTable, dir: &Path) -> Result<Vec<PathBuf>, Error> {
    write_titled(&t.comparison, t, TRADE_TITLE, dir)
}

/// Write a report's files into `dir` (created), each atomically: the
/// figures' PNGs, `report.json` (`value` as pretty JSON), `report.md` and
/// `index.html`. Returns the paths written.
pub fn write_files(
    dir: &Path,
    figs: &[Figure],
    value: &impl serde::Serialize,
    markdown: &str,
    html: &str,
) -> Result<Vec<PathBuf>, Error> {
    std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
    let mut written = Vec::new();
    let mut put = |name: &str, bytes: &[u8]| -> Result<(), Error> {
        let p = dir.join(name);
        write_atomic(&p, bytes)?;
        written.push(p);
        Ok(())
    };
    for f in figs {
        put(&f.file, &f.png)?;
    }
    let json = serde_json::to_string_pretty(value).map_err(|e| Error::Encode {
        format: "JSON",
        message: e.to_string(),
    })?;
    put("report.json", format!("{json}\n").as_bytes())?;
    put("report.md", markdown.as_bytes())?;
    put("index.html", html.as_bytes())?;
    Ok(written)
}

/// `0.05% of I_max = ` before a tolerance in cd, when the percent is known.
fn pct_note(pct: Option<f64>) -> String {
    pct.map(|p| format!("{p}% of I_max = ")).unwrap_or_default()
}
