//! The `index.html` of `scene --report` and `plan --report`: the text
//! summary, the isolux maps (inline PNGs, also written next to it) and one
//! interactive 3D view ([`crate::report::viewer`]) per luminaire: its
//! reference solid (the scene's reference, Catmull–Rom on the native grid)
//! and the representation the scene uses (`scene`) or the plan chose (`plan`).

use std::fmt::Write as _;

use crate::report::compare_report::esc;
use crate::report::plot::png_data_uri;
use crate::report::viewer::{self, SolidSet, ViewerData};
use crate::scene::plan::{Models, Representation};
use crate::scene::{Scene, SceneError};

/// One luminaire's packed solids: the reference and `shown` (when it is not the reference).
pub fn luminaire_viewer(scene: &Scene, index: usize, shown: Option<&Representation>) -> Result<ViewerData, SceneError> {
    let lum = &scene.luminaires[index];
    let model = |e| SceneError::Model {
        luminaire: lum.name.clone(),
        source: e,
    };
    let texture = lum.texture()?;
    let models = Models::new(lum, texture.as_ref());
    let reference_rep = Representation::default();
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
    Ok(ViewerData::new(&SolidSet {
        reference_label: &label,
        reference: &*reference,
        recons: &recons,
        i_max: lum.luminaire.distribution().max_cd(),
        note: None,
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
    shown: &[Option<Representation>],
) -> Result<String, SceneError> {
    let mut s = format!(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>{t}</title>\n<style>\n\
body{{font-family:sans-serif;margin:2em;max-width:1200px;color:#222}}\n\
figure{{display:inline-block;margin:1em;vertical-align:top}}\n\
img{{max-width:100%;border:1px solid #ddd}}\n\
</style>\n</head>\n<body>\n<h1>{t}</h1>\n<pre>{}</pre>\n",
        esc(summary),
        t = esc(title)
    );
    for k in 0..scene.luminaires.len() {
        let rep = shown
            .get(k)
            .cloned()
            .flatten()
            .or_else(|| scene.luminaires[k].representation.clone());
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
