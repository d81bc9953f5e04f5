//! The engines report ([`crate::engines::EnginesReport`]): the comparison
//! report's table, polar diagrams and error maps (one per engine row, signed,
//! % of I_max, C x γ) with the reference's own map first, then each defect's
//! source line and the resolution searches. `report.json` is the engines JSON.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use crate::compare::{Comparison, Normalize, ReconResult};
use crate::compare_report::{self, esc, Figure};
use crate::engines::EnginesReport;
use crate::error::Error;
use crate::plot::{self, ColorScale, HeatmapSpec};

/// The engines table as a [`Comparison`] (one result per row), so the
/// comparison report draws it.
pub fn to_comparison(r: &EnginesReport) -> Comparison {
    let results: Vec<ReconResult> = r.rows.iter().map(|row| row.metrics.clone()).collect();
    Comparison {
        file: r.file.clone(),
        vs: None,
        reference: r.reference.clone(),
        reference_kind: r.reference_kind,
        normalize: Normalize::Cd,
        units: r.units.clone(),
        directions: r.directions.clone(),
        n_directions: r.n_directions,
        radial_max_method: r.radial_max_method.clone(),
        tolerance: r.hausdorff_tolerance,
        tolerance_pct: crate::error::percent_of(r.hausdorff_tolerance),
        tolerance_cd: r.hausdorff_tolerance * r.i_max_cd,
        factor: r.factor,
        solid_tolerance_cd: None,
        solid_tolerance_pct: None,
        solid_deviation_cd: None,
        solid_tolerance_reached: None,
        i_max_cd: r.i_max_cd,
        reference_triangles: 0,
        zotti_c: crate::metrics::ZOTTI_C,
        alignment: None,
        smallest_within_1pct: crate::compare::smallest_within_1pct(&results),
        results,
        plots: r.plots.clone(),
        photometry_side_by_side: None,
        warnings: r.warnings.clone(),
    }
}

/// The figures: the reference's map, then the comparison report's.
pub fn figures(r: &EnginesReport) -> Result<Vec<Figure>, Error> {
    let mut out = Vec::new();
    if let Some(m) = &r.reference_map {
        let title = format!("Reference: {} (% of I_max)", m.name);
        out.push(Figure {
            file: "reference.png".into(),
            caption: format!("The reference over C x gamma (degrees), % of I_max: {}", m.name),
            png: plot::heatmap(&HeatmapSpec {
                title: &title,
                xs: &m.xs,
                ys: &m.ys,
                values: &m.values,
                unit: "% of I_max",
                scale: ColorScale::Sequential,
                ..HeatmapSpec::default()
            })?,
        });
    }
    out.extend(compare_report::figures(&to_comparison(r))?);
    Ok(out)
}

/// Defect sources, resolution searches, layouts and their stand-in steps, one line each.
fn notes(r: &EnginesReport) -> Vec<String> {
    let mut lines = Vec::new();
    for row in &r.rows {
        let _ = row.source.as_ref().map(|src| {
            lines.push(format!("{} (against {}): {}", row.name, row.against, src));
        });
    }
    for s in &r.resolutions {
        let tried: Vec<String> = s
            .tried
            .iter()
            .map(|t| {
                format!(
                    "{}: H {:.4} % (+{:.4})",
                    t.resolution, t.hausdorff_pct, t.hausdorff_bound_pct
                )
            })
            .collect();
        lines.push(format!(
            "{} within {} % of I_max: {} (tried {})",
            s.engine,
            100.0 * s.tolerance,
            s.resolution.map_or("none up to the largest".into(), |n| n.to_string()),
            tried.join("; ")
        ));
    }
    for sk in &r.skipped {
        lines.push(format!("{} skipped: {}", sk.engine, sk.reason));
    }
    for row in &r.rows {
        lines.push(format!("{} emulates: {}", row.name, row.engine_version));
    }
    for row in r.rows.iter().filter(|x| x.kind == "layout") {
        lines.push(format!("{}: {}", row.name, row.layout));
        for step in &row.stand_ins {
            lines.push(format!("{}: stand-in, not from the engine's source: {step}", row.name));
        }
    }
    lines
}

/// The title of `engines`' report.
pub const ENGINES_TITLE: &str = "Engines: lookup errors";

/// Write `index.html`, `report.md`, `report.json` and the PNGs into `dir`; returns the paths written.
pub fn write_report(r: &EnginesReport, dir: &Path) -> Result<Vec<PathBuf>, Error> {
    let figs = figures(r)?;
    let c = to_comparison(r);
    let notes = notes(r);
    let mut md = compare_report::to_markdown(&c, &figs, ENGINES_TITLE);
    md.push_str("\n## Layouts, defects and resolutions\n\n");
    for l in &notes {
        let _ = writeln!(md, "- {l}");
    }
    let mut section = String::from("<h2>Layouts, defects and resolutions</h2>\n<ul>\n");
    for l in &notes {
        let _ = writeln!(section, "<li>{}</li>", esc(l));
    }
    section.push_str("</ul>\n</body>");
    let html = compare_report::to_html(&c, &figs, ENGINES_TITLE).replacen("</body>", &section, 1);
    compare_report::write_files(dir, &figs, r, &md, &html)
}
