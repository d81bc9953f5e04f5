//! Several emitters in one TM-33 document: their ids, `FILE.xml#ID`
//! addressing (as `FILE.gldf#ID` names one photometry of a container), and
//! the choice of one.
//!
//! TM-33-23 gives each `Emitter` an `ID` child element (e.g. the
//! `crates/atla/tests/samples/tm33-23/*.xml` documents of eulumdat-rs:
//! `<Emitter><ID>hort-led-panel-1</ID>…`), and the luminaire's `NumEmitters`
//! counts them. An emitter's id here is that text; an emitter without one (or
//! whose id another emitter shares) is named by its 1-based position among
//! the emitters with intensity data, so every emitter has exactly one name.

use std::path::{Path, PathBuf};

use roxmltree::Node;

use crate::error::{ErrorKind, ParseError};
use crate::formats::xml::{child_text, children, error_at};

/// The emitters of `root` that hold intensity data, in document order.
pub(super) fn with_data<'a, 'i>(root: Node<'a, 'i>) -> Vec<Node<'a, 'i>> {
    children(root, "Emitter")
        .filter(|e| super::read::block_of(*e).is_some())
        .collect()
}

/// The name of each of `emitters` (see the module docs).
pub(super) fn ids(emitters: &[Node<'_, '_>]) -> Vec<String> {
    let own: Vec<Option<&str>> = emitters
        .iter()
        .map(|e| child_text(*e, &["ID"]).map(str::trim).filter(|s| !s.is_empty()))
        .collect();
    own.iter()
        .enumerate()
        .map(|(k, id)| match id {
            Some(id) if own.iter().filter(|o| **o == Some(*id)).count() == 1 => (*id).to_string(),
            _ => (k + 1).to_string(),
        })
        .collect()
}

/// The emitter named `id`, or the only one when `id` is `None`.
///
/// # Errors
/// No emitter with intensity data; several and no `id` (the message lists
/// the ids and says to name one as `FILE.xml#ID`); an `id` the document does
/// not hold (the message lists those it holds).
pub(super) fn choose<'a, 'i>(path: &Path, root: Node<'a, 'i>, id: Option<&str>) -> Result<Node<'a, 'i>, ParseError> {
    let emitters = with_data(root);
    let names = ids(&emitters);
    match (id, emitters.as_slice()) {
        (_, []) => Err(error_at(
            path,
            root,
            ErrorKind::Invalid,
            "an <Emitter> with a <LuminousData> (or <LuminousIntensity>, <IntensityDistribution>) block of \
             <IntensityData>",
            "none",
        )),
        (None, [one]) => Ok(*one),
        (None, _) => Err(error_at(
            path,
            root,
            ErrorKind::Invalid,
            format!(
                "one emitter: this document holds {} with intensity data; name one as {}#ID",
                emitters.len(),
                path.display()
            ),
            format!("the ids {}", names.join(", ")),
        )),
        (Some(id), _) => names.iter().position(|n| n == id).map(|k| emitters[k]).ok_or_else(|| {
            error_at(
                path,
                root,
                ErrorKind::Invalid,
                format!("an emitter id of the document: {}", names.join(", ")),
                format!("`{id}`"),
            )
        }),
    }
}

/// `FILE.xml#ID` split into the document and the emitter id (everything
/// after the first `.xml#`, case-insensitive: an id may hold `#`); `None` for anything else,
/// including an existing file whose name holds `#`.
pub fn split_reference(path: &Path) -> Option<(PathBuf, String)> {
    if path.exists() {
        return None;
    }
    let s = path.to_str()?;
    let at = s.to_ascii_lowercase().find(".xml#")?;
    Some((PathBuf::from(&s[..at + 4]), s[at + 5..].to_string()))
}

/// `FILE.xml#ID` as a path (the name the emitter's luminaire and messages carry).
pub fn reference(file: &Path, id: &str) -> PathBuf {
    PathBuf::from(format!("{}#{id}", file.display()))
}

/// The ids of the emitters with intensity data of a TM-33 document, in
/// document order; empty when `bytes` are not a well-formed TM-33 document.
pub fn emitter_ids(bytes: &[u8]) -> Vec<String> {
    let Ok(text) = std::str::from_utf8(bytes) else {
        return Vec::new();
    };
    let Ok(doc) = roxmltree::Document::parse(text) else {
        return Vec::new();
    };
    if !super::looks_like(bytes) {
        return Vec::new();
    }
    ids(&with_data(doc.root_element()))
}

/// The TM-33 document at `path` as one `FILE.xml#ID` path per emitter when
/// it holds several; otherwise (one emitter, unreadable, not TM-33) `path`
/// itself, so that loading it reports why.
pub fn expand(path: &Path) -> Vec<PathBuf> {
    let Ok(bytes) = crate::formats::files::read_capped(path, crate::formats::MAX_FILE_BYTES) else {
        return vec![path.to_path_buf()];
    };
    match emitter_ids(&bytes).as_slice() {
        ids @ [_, _, ..] => ids.iter().map(|id| reference(path, id)).collect(),
        _ => vec![path.to_path_buf()],
    }
}
