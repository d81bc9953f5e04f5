//! The `index.html` of `scene --report` and `plan --report`: the text
//! summary, the isolux maps (inline PNGs, also written next to it) and one
//! interactive 3D view ([`crate::viewer`]) per luminaire: its
//! reference solid (the scene's reference, Catmull–Rom on the native grid)
//! and the representation the scene uses (`scene`) or the plan chose (`plan`).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use crate::compare_report::esc;
use crate::plot::{isolux_plot, png_data_uri, IsoluxSpec, MapAxis, MapQuantity, Plot};
use crate::scene::illuminance::SceneResult;
use crate::scene::plan::{Models, PlanResult, Recon, REFERENCE};
use crate::scene::ReceiverShape;
use crate::scene::{Scene, SceneError};
use crate::viewer::{self, SolidSet, ViewerData};
use glam::DVec3;

/// The (s, t) plane coordinates of world point `p` on the plane
/// `origin + s·u + t·v` (least squares for points off the plane).
fn plane_coords(origin: DVec3, u: DVec3, v: DVec3, p: DVec3) -> (f64, f64) {
    let d = p - origin;
    let (uu, uv, vv) = (u.dot(u), u.dot(v), v.dot(v));
    let (du, dv) = (d.dot(u), d.dot(v));
    let det = uu * vv - uv * uv;
    if det == 0.0 {
        return (f64::NAN, f64::NAN);
    }
    ((du * vv - dv * uv) / det, (dv * uu - du * uv) / det)
}

/// The map axis along `edge` from `origin`: the world coordinate when the
/// edge runs along x, y or z ("x (m)"), else metres along the edge.
fn map_axis(origin: DVec3, edge: DVec3, name: &str) -> MapAxis {
    let len = edge.length();
    for (a, axis) in ["x", "y", "z"].iter().enumerate() {
        if len > 0.0 && (edge[a].abs() - len).abs() <= 1e-9 * len {
            return MapAxis {
                start: origin[a],
                end: origin[a] + edge[a],
                title: format!("{axis} (m)"),
            };
        }
    }
    MapAxis {
        start: 0.0,
        end: len,
        title: format!("m along {name} from its origin"),
    }
}

/// The isolux map of plane receiver `index` ([`isolux_plot`]); `None` for a point receiver.
///
/// # Errors
/// The plot's error ([`crate::Error::Encode`]) when the map cannot be drawn.
pub fn isolux_map(scene: &Scene, result: &SceneResult, index: usize) -> crate::Result<Option<Plot>> {
    let (Some(rec), Some(res)) = (scene.receivers.get(index), result.receivers.get(index)) else {
        return Ok(None);
    };
    let ReceiverShape::Plane { origin, u, v, nu, nv } = rec.shape else {
        return Ok(None);
    };
    let values: Vec<f64> = res.points.iter().map(|p| p.e_lux).collect();
    let marks: Vec<(f64, f64)> = scene
        .luminaires
        .iter()
        .map(|l| plane_coords(origin, u, v, l.pose.position))
        .collect();
    isolux_plot(&IsoluxSpec {
        quantity: MapQuantity::ILLUMINANCE,
        name: &rec.name,
        values: &values,
        grid: (nu, nv),
        size_m: (u.length(), v.length()),
        e_avg_lux: res.e_avg_lux,
        u_axis: map_axis(origin, u, "u"),
        v_axis: map_axis(origin, v, "v"),
        marks: &marks,
        limits: &[],
    })
    .map(Some)
}

/// Write `isolux_<k>_<name>.png` for every plane receiver into `dir`; returns the paths.
///
/// # Errors
/// [`crate::Error::Io`] (the path, the I/O error) when a map cannot be
/// written; the plot's error when one cannot be drawn.
pub fn write_maps(scene: &Scene, result: &SceneResult, dir: &Path) -> crate::Result<Vec<PathBuf>> {
    let io = |p: &Path, e: std::io::Error| crate::Error::io(p, e);
    std::fs::create_dir_all(dir).map_err(|e| io(dir, e))?;
    let mut out = Vec::new();
    for (k, r) in result.receivers.iter().enumerate() {
        if let Some(plot) = isolux_map(scene, result, k)? {
            let safe: String = r
                .name
                .chars()
                .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
                .collect();
            let path = dir.join(format!("isolux_{}_{safe}.png", k + 1));
            crate::formats::write_atomic(&path, &plot.png)?;
            out.push(path);
        }
    }
    Ok(out)
}

/// One luminaire's packed solids: the reference and `shown` (when it is not the reference).
///
/// # Errors
/// [`SceneError::Model`] when a representation cannot be built.
pub fn luminaire_viewer(scene: &Scene, index: usize, shown: Option<&Recon>) -> Result<ViewerData, SceneError> {
    let lum = &scene.luminaires[index];
    let model = |e| lum.model_error(e);
    let reference_rep = REFERENCE;
    let wanted: Vec<Recon> = std::iter::once(reference_rep).chain(shown.copied()).collect();
    let models = Models::new(lum, &wanted).map_err(model)?;
    let reference = models.field(&reference_rep).map_err(model)?;
    let mut fields = Vec::new();
    if let Some(r) = shown.filter(|r| **r != reference_rep) {
        // Named as the field names itself: what plan.json calls it.
        let field = models.field(r).map_err(model)?;
        fields.push((field.name(), field));
    }
    let recons: Vec<(String, &dyn crate::model::IntensityField)> =
        fields.iter().map(|(n, f)| (n.clone(), &**f)).collect();
    let label = format!(
        "{reference_rep} on the native grid of {} (the scene's reference)",
        lum.name
    );
    // A cropped representation holds only the directions the scene sees: its
    // error is measured over those, and the legend says so.
    let error_domain = match shown {
        Some(Recon::Cropped {
            gamma_from,
            gamma_to,
            c,
            ..
        }) => Some(crate::compare::view::ErrorDomain {
            gamma_deg: (*gamma_from, *gamma_to),
            c_deg: *c,
        }),
        _ => None,
    };
    Ok(ViewerData::new(&SolidSet {
        reference_label: &label,
        reference: &*reference,
        recons: &recons,
        i_max: lum.luminaire.distribution().max_cd(),
        note: None,
        error_domain,
    }))
}

/// The page: `title`, the `summary` text, the `maps` (`(caption, png)`) and
/// a 3D view per luminaire, showing `shown[k]` for luminaire k (`None`: the
/// luminaire's own representation, else only the reference).
pub fn to_html(
    title: &str,
    scene: &Scene,
    summary: &str,
    maps: &[(String, Vec<u8>)],
    shown: &[Option<Recon>],
) -> Result<String, SceneError> {
    let mut s = format!(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>{t}</title>\n<style>\n\
body{{font-family:sans-serif;margin:2em;max-width:1200px;color:#222}}\n\
figure{{display:inline-block;margin:1em;vertical-align:top}}\n\
img{{max-width:100%;border:1px solid #ddd}}\n\
pre{{white-space:pre-wrap;overflow-wrap:anywhere}}\n\
</style>\n</head>\n<body>\n<h1>{t}</h1>\n<pre>{}</pre>\n",
        esc(summary),
        t = esc(title)
    );
    for k in 0..scene.luminaires.len() {
        let rep = shown
            .get(k)
            .cloned()
            .flatten()
            .or_else(|| scene.luminaires[k].representation);
        let _ = writeln!(s, "<h2>Luminaire {}</h2>", esc(&scene.luminaires[k].name));
        s.push_str(&viewer::html(
            &luminaire_viewer(scene, k, rep.as_ref())?,
            "the isolux maps below",
        ));
    }
    if !maps.is_empty() {
        s.push_str("<h2>Isolux maps</h2>\n");
        for (caption, png) in maps {
            let _ = writeln!(
                s,
                "<figure><img src=\"{}\" alt=\"{c}\"><figcaption>{c}</figcaption></figure>",
                png_data_uri(png),
                c = esc(caption)
            );
        }
    }
    s.push_str("</body>\n</html>\n");
    Ok(s)
}

/// HTML sections for the end of another report (`photosolid demo`): the
/// scene (`title`, its text `scene_text`, links to its isolux `maps`, PNG
/// files beside the page: inlined they would push the demo page past 1 MB)
/// and the plan (`plan_text`).
pub fn scene_and_plan_html(title: &str, scene_text: &str, maps: &[String], plan_text: &str) -> String {
    let mut s = format!(
        "<h2>Built-in scene</h2>\n<p>{}</p>\n<pre>{}</pre>\n",
        esc(title),
        esc(scene_text)
    );
    if !maps.is_empty() {
        s.push_str("<p>Isolux maps:");
        for m in maps {
            let _ = write!(s, " <a href=\"{0}\">{0}</a>", esc(m));
        }
        s.push_str("</p>\n");
    }
    let _ = writeln!(
        s,
        "<h2>Plan</h2>\n<p>The cheapest representation of each luminaire within the plan's tolerance on that \
         scene.</p>\n<pre>{}</pre>",
        esc(plan_text)
    );
    s
}

/// Write `value` as pretty JSON to `dir/name`, atomically.
fn write_json(dir: &Path, name: &str, value: &impl serde::Serialize) -> crate::Result<PathBuf> {
    let path = dir.join(name);
    let json = serde_json::to_string_pretty(value).map_err(|e| crate::Error::Encode {
        format: "JSON",
        message: format!("{}: {e}", path.display()),
    })?;
    crate::formats::write_atomic(&path, format!("{json}\n").as_bytes())?;
    Ok(path)
}

/// Write `index.html` into `dir`, atomically.
fn write_index(dir: &Path, html: &str) -> crate::Result<PathBuf> {
    let path = dir.join("index.html");
    crate::formats::write_atomic(&path, html.as_bytes())?;
    Ok(path)
}

/// The report of `scene --report DIR`: `scene.json`, one isolux map per
/// plane receiver ([`write_maps`]) and `index.html`
/// (the `summary` text, the maps, a 3D view per luminaire). Returns the files
/// written, in that order.
pub fn write_scene_report(
    dir: &Path,
    scene: &Scene,
    result: &SceneResult,
    summary: &str,
) -> crate::Result<Vec<PathBuf>> {
    let io = |p: &Path, e: std::io::Error| crate::Error::io(p, e);
    std::fs::create_dir_all(dir).map_err(|e| io(dir, e))?;
    let mut written = vec![write_json(dir, "scene.json", result)?];
    let mut maps = Vec::new();
    for path in write_maps(scene, result, dir)? {
        let name = path
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        maps.push((name, std::fs::read(&path).map_err(|e| io(&path, e))?));
        written.push(path);
    }
    let html = to_html("Scene: illuminance", scene, summary, &maps, &[])?;
    written.push(write_index(dir, &html)?);
    Ok(written)
}

/// The report of `plan --report DIR`: `plan.json` and `index.html` (the
/// `summary` text and a 3D view of each luminaire's chosen representation;
/// plan rows are named as the scene's luminaires). Returns the files written.
pub fn write_plan_report(dir: &Path, scene: &Scene, result: &PlanResult, summary: &str) -> crate::Result<Vec<PathBuf>> {
    std::fs::create_dir_all(dir).map_err(|e| crate::Error::io(dir, e))?;
    let mut written = vec![write_json(dir, "plan.json", result)?];
    let chosen: Vec<Option<Recon>> = scene
        .luminaires
        .iter()
        .map(|l| {
            result
                .luminaires
                .iter()
                .find(|p| p.name == l.name)
                .map(|p| p.chosen_spec)
        })
        .collect();
    let html = to_html("Scene: plan", scene, summary, &[], &chosen)?;
    written.push(write_index(dir, &html)?);
    Ok(written)
}

/// The scene result as text (what `photosolid scene` prints).
pub fn scene_text(r: &SceneResult) -> String {
    use std::fmt::Write;
    let mut s = format!("scene {}\n", r.scene);
    for l in &r.luminaires {
        let ff = &l.far_field;
        let _ = writeln!(
            s,
            "luminaire {:?}: {}, {} source{}, {} bytes; point-source error max {:.3} % (largest \
             dimension {:.3} m, under 1 % from {} x it, five-times rule {})",
            l.name,
            l.representation,
            l.source,
            // The patches are the area source's: a point source has none to count.
            match l.source {
                crate::scene::SourceKind::Area => format!(
                    " ({}{})",
                    crate::error::count(l.area.patches, "patch", "patches"),
                    if l.area.converged { "" } else { ", NOT converged" }
                ),
                crate::scene::SourceKind::Point => String::new(),
            },
            l.bytes,
            ff.max_error_pct,
            ff.largest_dimension_m,
            ff.ratio_under_1pct.map_or("-".into(), |x| format!("{x:.2}")),
            if ff.five_times_rule_holds { "holds" } else { "fails" }
        );
    }
    let _ = writeln!(
        s,
        "{:<16} {:>6} {:>7} {:>11} {:>11} {:>11} {:>7} {:>9}",
        "receiver", "kind", "points", "Eavg lx", "Emin lx", "Emax lx", "U0", "Emin/Emax"
    );
    let opt = |x: Option<f64>| x.map_or("-".into(), |v| format!("{v:.3}"));
    for rc in &r.receivers {
        let _ = writeln!(
            s,
            "{:<16} {:>6} {:>7} {:>11.3} {:>11.3} {:>11.3} {:>7} {:>9}",
            rc.name,
            rc.kind,
            rc.points.len(),
            rc.e_avg_lux,
            rc.e_min_lux,
            rc.e_max_lux,
            opt(rc.u0),
            opt(rc.emin_emax)
        );
    }
    s
}

/// The plan as text (what `photosolid plan` prints).
pub fn plan_text(p: &PlanResult) -> String {
    use std::fmt::Write;
    let mut s = format!("plan for {} (tolerance {} %)\n", p.scene, p.tolerance_pct);
    for l in &p.luminaires {
        let _ = writeln!(
            s,
            "luminaire {:?}: chosen {} — {} bytes, {:.1} ns/eval, error max {:.4} % mean {:.4} % (measured on the \
             scene against {}); far field ok: {}; {} candidates, {} rejected",
            l.name,
            l.chosen,
            l.bytes,
            l.ns_per_eval,
            l.max_error_pct,
            l.mean_error_pct,
            l.reference,
            l.far_field_ok,
            l.candidates,
            l.rejected.len()
        );
        for c in &l.rejected {
            let _ = writeln!(
                s,
                "  rejected {:<42} {:<5} {:>9} B {:>10.1} ns  max {:>9.4} %  mean {:>9.4} %",
                c.representation,
                c.source.to_string(),
                c.bytes,
                c.ns_per_eval,
                c.max_error_pct,
                c.mean_error_pct
            );
        }
        for u in &l.unavailable {
            let _ = writeln!(s, "  unavailable {}: {}", u.representation, u.reason);
        }
    }
    let _ = writeln!(
        s,
        "every chosen representation at once: error max {:.4} % mean {:.4} %",
        p.combined_max_error_pct, p.combined_mean_error_pct
    );
    s
}
