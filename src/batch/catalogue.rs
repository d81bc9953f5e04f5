//! The catalogue page of a batch (`photosolid batch --report DIR`).
//!
//! `DIR/index.html`: one table row per file, sortable by any column (click
//! a header; a few lines of inline JavaScript, no network), with a polar
//! thumbnail of the C0-C180 and C90-C270 planes (cd) per loaded file
//! (`DIR/thumb-NNNNN.png`, 360 × 360 px, shown at [`THUMB_SHOWN_PX`] px). Outliers come first: files that
//! did not load, then hold-out/fit failures, flux mismatches (computed flux
//! more than [`crate::photometry::FLUX_MISMATCH`] off the declared one) and
//! files with warnings, each with the reason in the `outlier` column.
//! `DIR/report.json` holds the rows, `DIR/report.md` the outliers.
//!
//! The page fits a 1280 px wide window ([`PAGE_WIDTH_PX`]): a fixed table
//! layout ([`COLUMNS`]: the thumbnail, path and outlier columns have fixed
//! widths, the numeric columns share the rest), the path shown as file name
//! over its directory, each truncated with an ellipsis and the full path in
//! the cell's `title`, the outlier reason wrapped.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

use rayon::prelude::*;

use super::BatchRecord;
use crate::error::Error;
use crate::formats::ReadOptions;
use crate::model::Progress;
use crate::photometry::plane_profile;
use crate::report::compare_report::{esc, write_files, Figure};
use crate::report::plot::{self, PolarSpec, Series, SeriesStyle};

/// Thumbnail size, px.
pub const THUMB_SIZE: (u32, u32) = (360, 360);

/// Size a thumbnail is shown at on the page, px (click it for the full image).
pub const THUMB_SHOWN_PX: u32 = 56;

/// The window width the page is laid out for, px.
pub const PAGE_WIDTH_PX: u32 = 1280;

/// The page's columns: header (HTML) and width in px (`None`: an equal share of
/// what the fixed columns leave, at least [`MIN_NUMERIC_PX`]).
pub const COLUMNS: [(&str, Option<u32>); 17] = [
    ("polar (cd)", Some(THUMB_SHOWN_PX + 8)),
    ("path", Some(170)),
    ("outlier", Some(140)),
    ("format", Some(52)),
    ("symmetry", Some(70)),
    ("grid C x &gamma;", None),
    ("max cd", None),
    ("flux lm", None),
    ("declared lm", None),
    ("flux ratio", None),
    ("LOR", None),
    ("beam &deg;", None),
    ("field &deg;", None),
    ("best filter", Some(78)),
    ("hold-out RMS % I_max", None),
    ("fitted GL", Some(86)),
    ("GL error", None),
];

/// The narrowest a numeric column may get, px: "1234567.8" at 12 px plus padding.
pub const MIN_NUMERIC_PX: u32 = 60;

/// Why `r` is an outlier (empty when it is not), and its rank: 0 not loaded,
/// 1 a step failed, 2 a physically impossible declaration or a flux mismatch, 3 other warnings, 4 none.
pub fn outlier(r: &BatchRecord) -> (u8, String) {
    if !r.ok {
        return (0, "failed to load".into());
    }
    if !r.errors.is_empty() {
        return (1, r.errors.join("; "));
    }
    let impossible: Vec<&str> = r
        .warnings
        .iter()
        .map(String::as_str)
        .filter(|w| crate::photometry::IMPOSSIBLE_DECLARATIONS.contains(w))
        .collect();
    if !impossible.is_empty() {
        return (
            2,
            format!("physically impossible declaration: {}", impossible.join(", ")),
        );
    }
    if r.flux_mismatch() {
        let ratio = r.flux_ratio.unwrap_or(f64::NAN);
        return (2, format!("flux mismatch: computed / declared = {ratio:.3}"));
    }
    if !r.warnings.is_empty() {
        return (3, format!("warnings: {}", r.warnings.join(", ")));
    }
    (4, String::new())
}

/// The rows in page order: outliers first (by rank), then by path.
pub fn page_order(rows: &[BatchRecord]) -> Vec<usize> {
    let mut idx: Vec<usize> = (0..rows.len()).collect();
    idx.sort_by(|&a, &b| {
        outlier(&rows[a])
            .0
            .cmp(&outlier(&rows[b]).0)
            .then_with(|| rows[a].path.cmp(&rows[b].path))
    });
    idx
}

/// The polar thumbnail (C0-C180 and C90-C270, cd) of the file at `path`.
///
/// # Errors
/// The load error, or the plot's.
pub fn thumbnail(path: &Path, read: &ReadOptions) -> Result<Vec<u8>, Error> {
    let lum = crate::load_with(path, read)?;
    let d = lum.distribution();
    let g = d.gamma_angles_deg();
    let pair = |right: f64, left: f64| -> Vec<(f64, f64)> {
        let (r, l) = (plane_profile(d, right), plane_profile(d, left));
        let mut pts: Vec<(f64, f64)> = g.iter().zip(&l).rev().map(|(&g, &v)| (-g, v)).collect();
        pts.extend(g.iter().zip(&r).filter(|(&g, _)| g > 0.0).map(|(&g, &v)| (g, v)));
        pts
    };
    let series = [
        Series {
            label: "C0-C180".into(),
            points: pair(0.0, 180.0),
            color: plot::palette(0),
            style: SeriesStyle::Line,
        },
        Series {
            label: "C90-C270".into(),
            points: pair(90.0, 270.0),
            color: plot::palette(1),
            style: SeriesStyle::Dashed,
        },
    ];
    plot::polar_diagram(&PolarSpec {
        title: "",
        left: "",
        right: "",
        unit: "cd",
        series: &series,
        size: THUMB_SIZE,
    })
}

fn num(x: Option<f64>, digits: usize) -> (String, String) {
    match x {
        Some(v) => (format!("{v}"), format!("{v:.digits$}")),
        None => (String::new(), "-".into()),
    }
}

const SORT_JS: &str = "document.querySelectorAll('th').forEach((th,i)=>th.addEventListener('click',()=>{\
const tb=th.closest('table').tBodies[0];const rows=[...tb.rows];const asc=th.dataset.asc!=='1';\
th.dataset.asc=asc?'1':'0';const key=r=>{const c=r.cells[i];return c.dataset.v!==undefined?c.dataset.v:c.textContent};\
rows.sort((a,b)=>{const x=key(a),y=key(b);const nx=parseFloat(x),ny=parseFloat(y);\
let c=(!isNaN(nx)&&!isNaN(ny))?nx-ny:(x===''?1:y===''?-1:x.localeCompare(y));return asc?c:-c});\
rows.forEach(r=>tb.appendChild(r))}));";

/// The page (see the module docs); `thumbs[i]` is the thumbnail file of `rows[i]`, if any.
pub fn to_html(rows: &[BatchRecord], thumbs: &[Option<String>]) -> String {
    let order = page_order(rows);
    let n_out = rows.iter().filter(|r| r.is_outlier()).count();
    let n_ok = rows.iter().filter(|r| r.ok).count();
    let mut h = String::from(
        "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><meta name=\"viewport\" content=\"width=device-width\">\
<title>photosolid batch catalogue</title><style>\
body{font-family:sans-serif;margin:8px}table{border-collapse:collapse;font-size:12px;table-layout:fixed;width:100%}\
th,td{border:1px solid #ccc;padding:2px 4px;text-align:right;overflow:hidden;overflow-wrap:anywhere}\
td.t{text-align:left}td.p{text-align:left;white-space:nowrap}\
td.p div{overflow:hidden;text-overflow:ellipsis}td.p .dir{color:#777;font-size:11px}\
td img{display:block}\
th{cursor:pointer;background:#eee;position:sticky;top:0;font-weight:600;overflow-wrap:normal}tr.out td{background:#fff3e0}</style></head><body>\n",
    );
    let _ = writeln!(
        h,
        "<h1>Catalogue</h1><p>{} files, {} loaded, {} outliers (listed first: not loaded, hold-out or fit failed, \
         flux mismatch over {:.0} %, warnings). Click a column header to sort. Hold-out: each filter rebuilds the \
         withheld measurements (every 2nd C-plane and gamma row dropped); errors in % of I_max. Fitted GL error: \
         the fit's relative RMS error against every measured direction (fraction).</p>",
        rows.len(),
        n_ok,
        n_out,
        100.0 * crate::photometry::FLUX_MISMATCH
    );
    write_table_head(&mut h);
    for &i in &order {
        write_row(&mut h, &rows[i], thumbs[i].as_deref());
    }
    let _ = write!(h, "</tbody></table>\n<script>{SORT_JS}</script>\n</body></html>\n");
    h
}

/// The table's column widths and sortable header, up to the body's opening tag.
fn write_table_head(h: &mut String) {
    h.push_str("<table><colgroup>");
    for (_, w) in COLUMNS {
        match w {
            Some(w) => {
                let _ = write!(h, "<col style=\"width:{w}px\">");
            }
            None => h.push_str("<col>"),
        }
    }
    h.push_str("</colgroup><thead><tr>");
    for (name, _) in COLUMNS {
        let _ = write!(h, "<th>{name}</th>");
    }
    h.push_str("</tr></thead><tbody>\n");
}

/// One file's row: its thumbnail (`thumb`), path, outlier reason, grid,
/// photometry, hold-out and fit; the sort key of each cell in `data-v`.
fn write_row(h: &mut String, r: &BatchRecord, thumb: Option<&str>) {
    let (rank, why) = outlier(r);
    let path = esc(&r.path);
    let img = thumb
        .map(|f| {
            format!(
                "<a href=\"{0}\"><img src=\"{0}\" width=\"{THUMB_SHOWN_PX}\" height=\"{THUMB_SHOWN_PX}\" \
                 loading=\"lazy\" alt=\"polar\"></a>",
                esc(f)
            )
        })
        .unwrap_or_default();
    let _ = write!(
        h,
        "<tr{}><td data-v=\"{rank}\">{img}</td><td class=\"p\" title=\"{path}\" data-v=\"{path}\">{}</td>\
<td class=\"t\" data-v=\"{rank} {}\">{}</td><td class=\"t\">{}</td><td class=\"t\">{}</td><td data-v=\"{}\">{}</td>",
        if rank < 4 { " class=\"out\"" } else { "" },
        path_cell(&r.path),
        esc(&why),
        esc(&why),
        esc(r.format.as_deref().unwrap_or("-")),
        esc(r.symmetry.as_deref().unwrap_or("-")),
        r.n_c_full.unwrap_or(0) as u64 * r.n_gamma.unwrap_or(0) as u64,
        match (r.n_c_full, r.n_gamma) {
            (Some(c), Some(g)) => format!("{c} x {g}"),
            _ => "-".into(),
        },
    );
    for (x, d) in [
        (r.max_cd, 1),
        (r.flux_lm, 1),
        (r.declared_flux_lm, 1),
        (r.flux_ratio, 3),
        (r.lor, 3),
        (r.beam_angle_deg, 1),
        (r.field_angle_deg, 1),
    ] {
        let (v, text) = num(x, d);
        let _ = write!(h, "<td data-v=\"{v}\">{text}</td>");
    }
    let (v, text) = num(r.best_filter_rms_pct, 3);
    let _ = write!(
        h,
        "<td class=\"t\">{}</td><td data-v=\"{v}\">{text}</td><td class=\"t\">{}</td>",
        esc(r.best_filter.as_deref().unwrap_or("-")),
        esc(r.fitted_gl.as_deref().unwrap_or("-"))
    );
    let (v, text) = num(r.fitted_gl_error, 4);
    let _ = writeln!(h, "<td data-v=\"{v}\">{text}</td></tr>");
}

/// The path cell's content: the file name over its directory, escaped.
fn path_cell(path: &str) -> String {
    let p = Path::new(path);
    let name = p
        .file_name()
        .map_or_else(|| path.to_string(), |n| n.to_string_lossy().into_owned());
    let dir = p.parent().map(|d| d.display().to_string()).unwrap_or_default();
    format!("<div>{}</div><div class=\"dir\">{}</div>", esc(&name), esc(&dir))
}

/// A short Markdown list of the outliers.
fn to_markdown(rows: &[BatchRecord]) -> String {
    let mut m = format!("# Catalogue\n\n{} files. Outliers:\n\n", rows.len());
    for i in page_order(rows) {
        let (rank, why) = outlier(&rows[i]);
        if rank < 4 {
            let _ = writeln!(m, "- `{}`: {why}", rows[i].path);
        }
    }
    m
}

/// Write the catalogue of `rows` into `dir` (created): thumbnails (files
/// reloaded with `read`, in parallel), `index.html`, `report.md`,
/// `report.json`, each atomically. A file that no longer loads gets no
/// thumbnail. `progress(done, total, path)` follows the thumbnails.
///
/// # Errors
/// [`Error::Io`] naming the file that could not be written.
pub fn write(dir: &Path, rows: &[BatchRecord], read: &ReadOptions, progress: &Progress) -> Result<Vec<PathBuf>, Error> {
    let done = AtomicUsize::new(0);
    let pngs: Vec<Option<Vec<u8>>> = rows
        .par_iter()
        .map(|r| {
            let png = if r.ok {
                thumbnail(Path::new(&r.path), read).ok()
            } else {
                None
            };
            progress(done.fetch_add(1, Ordering::Relaxed) + 1, rows.len(), &r.path);
            png
        })
        .collect();
    let mut figs = Vec::new();
    let mut thumbs = Vec::with_capacity(rows.len());
    for (i, png) in pngs.into_iter().enumerate() {
        thumbs.push(png.map(|png| {
            let file = format!("thumb-{i:05}.png");
            figs.push(Figure {
                file: file.clone(),
                caption: rows[i].path.clone(),
                png,
            });
            file
        }));
    }
    write_files(dir, &figs, &rows, &to_markdown(rows), &to_html(rows, &thumbs))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Outliers come first, in rank order; the page holds a row per file and the sort script.
    #[test]
    fn outliers_first() {
        let dir = tempfile::tempdir().unwrap();
        let grid = crate::synth::GridSpec::uniform(15.0, 5.0).unwrap();
        let good = dir.path().join("a.ldt");
        crate::save(
            &crate::synth::Synth::Isotropic.build(&grid, 10.0).unwrap().into(),
            &good,
            &Default::default(),
        )
        .unwrap();
        let missing = dir.path().join("z.ies");
        let rows = super::super::run(&[good, missing], &Default::default(), &|_, _, _| {});
        assert_eq!(page_order(&rows), vec![1, 0]);
        let out = dir.path().join("cat");
        write(&out, &rows, &ReadOptions::default(), &|_, _, _| {}).unwrap();
        let html = std::fs::read_to_string(out.join("index.html")).unwrap();
        assert!(html.find("z.ies").unwrap() < html.find("a.ldt").unwrap());
        assert!(html.contains("thumb-00000.png") && !html.contains("thumb-00001.png"));
        assert!(html.contains("<script>"));
        let png = std::fs::read(out.join("thumb-00000.png")).unwrap();
        assert_eq!(&png[..4], b"\x89PNG");
    }

    /// At 1280 px every column is on screen: a fixed layout whose fixed widths
    /// leave each numeric column at least [`MIN_NUMERIC_PX`], small thumbnails,
    /// the path truncated with its full text in `title`.
    #[test]
    fn page_fits_1280_px() {
        let fixed: u32 = COLUMNS.iter().filter_map(|c| c.1).sum();
        let flexible = COLUMNS.iter().filter(|c| c.1.is_none()).count() as u32;
        // body margin 8 px each side.
        let left = PAGE_WIDTH_PX - 16 - fixed;
        assert!(left / flexible >= MIN_NUMERIC_PX, "{left} px for {flexible} columns");
        let mut row = BatchRecord::empty(Path::new("/some/very/long/directory/name/of/a/catalogue/LUM-123.ies"));
        row.ok = true;
        row.max_cd = Some(1234567.8);
        let html = to_html(&[row], &[Some("thumb-00000.png".into())]);
        assert!(html.contains("table-layout:fixed") && html.contains("width:100%"));
        assert!(html.contains("text-overflow:ellipsis"));
        assert_eq!(
            html.matches("<col").count() - html.matches("<colgroup").count(),
            COLUMNS.len()
        );
        assert!(html.contains(&format!("width=\"{THUMB_SHOWN_PX}\"")) && THUMB_SHOWN_PX <= 64);
        assert!(html.contains("title=\"/some/very/long/directory/name/of/a/catalogue/LUM-123.ies\""));
        assert!(html.contains("<div>LUM-123.ies</div>"));
    }

    /// A file with a physically impossible declaration is an outlier of rank
    /// 2 that names it, ahead of files with other warnings (rank 3).
    #[test]
    fn impossible_declarations_are_outliers() {
        let mut row = BatchRecord::empty(std::path::Path::new("x.ldt"));
        row.ok = true;
        row.warnings = vec!["dff-mismatch".into()];
        assert_eq!(outlier(&row).0, 3);
        row.warnings.push("lor-above-100".into());
        let (rank, why) = outlier(&row);
        assert_eq!(rank, 2);
        assert!(
            why.contains("physically impossible") && why.contains("lor-above-100"),
            "{why}"
        );
    }
}
