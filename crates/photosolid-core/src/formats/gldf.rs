//! GLDF containers (Global Lighting Data Format): a zip archive whose
//! `product.xml` lists the photometric files it holds.
//!
//! A photometry is named `FILE.gldf#ID`, where `ID` is the `id` attribute of
//! a `GeneralDefinitions/Photometries/Photometry` element. Its
//! `PhotometryFileReference/@fileId` names a `GeneralDefinitions/Files/File`
//! element whose text is the file name (`type="localFileName"`), stored in
//! the container's `ldc/` folder (a name that already carries a folder is
//! looked up as written). The file is read with the ordinary readers (format
//! from its extension, else from `contentType`, else from its content), so
//! a photometry behaves exactly like the same file on disk. A `File` of
//! another type (`url`) is listed but refused when loaded: photosolid does
//! not download. The element
//! names follow the GLDF documentation (globallightingdata/website,
//! `docs/structure/photometries.md` and `files.md`).
//!
//! The photometry's optional `DescriptivePhotometry` is kept as
//! [`GldfDeclared`] on the loaded luminaire, so `info` can show it next to
//! the computed values.
//!
//! Limits (a container is untrusted input): at most [`MAX_ENTRIES`]
//! entries, and at most [`MAX_MEMBER_BYTES`] uncompressed bytes read from
//! any one member, counted while inflating, so a zip bomb is refused after
//! reading that much, whatever its headers claim.

use std::io::Read;
use std::path::{Path, PathBuf};

use serde::Serialize;

use crate::error::{Error, ErrorKind, Location, ParseError, Result};
use crate::formats::xml::{self, child, child_number, child_text, children, error_at};
use crate::formats::{files, Document, ReadOptions, MAX_FILE_BYTES};
use crate::model::Format;

/// Most entries a container may hold (files and folders).
pub const MAX_ENTRIES: usize = 10_000;

/// Most uncompressed bytes read from one member (`product.xml` or a photometric file), bytes.
pub const MAX_MEMBER_BYTES: u64 = 64 * 1024 * 1024;

/// The declared UGR of the standard room (4H × 8H, reflectances 70/50/20, spacing-to-height 0.25 "LQ").
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct DeclaredUgr {
    /// Crosswise (GLDF `X`), UGR units.
    pub crosswise: f64,
    /// Endwise (GLDF `Y`), UGR units.
    pub endwise: f64,
}

/// What a GLDF container declares about one photometry
/// (`Photometry/DescriptivePhotometry`), as written: ratios as fractions
/// (GLDF writes 0..1), `None` when the element is absent.
///
/// This is the hook for the derived-photometry comparison: `info` shows
/// each declared value next to the one photosolid computes.
#[derive(Debug, Clone, PartialEq, Serialize, Default)]
pub struct GldfDeclared {
    /// The container file.
    pub container: PathBuf,
    /// The `Photometry` id.
    pub id: String,
    /// The photometric file inside the container (zip member name).
    pub file: String,
    /// `LightOutputRatio`, fraction.
    pub lor: Option<f64>,
    /// `DownwardFluxFraction`, fraction.
    pub dff: Option<f64>,
    /// `DownwardLightOutputRatio`, fraction.
    pub dlor: Option<f64>,
    /// `UpwardLightOutputRatio`, fraction.
    pub ulor: Option<f64>,
    /// `LuminousEfficacy`, lm/W.
    pub luminous_efficacy_lm_per_w: Option<f64>,
    /// `LuminaireLuminance`, cd/m².
    pub luminaire_luminance_cd_m2: Option<f64>,
    /// `CIE-FluxCode`, five numbers as written (e.g. `44 75 94 100 100`).
    pub cie_flux_code: Option<String>,
    /// `UGR-4H8H-70-50-20-LQ`.
    pub ugr_4h8h_70_50_20: Option<DeclaredUgr>,
    /// `LightDistributionBUG-Rating` as written (e.g. `B1 U0 G1`).
    pub bug_rating: Option<String>,
    /// `CutOffAngle`, degrees.
    pub cut_off_angle_deg: Option<f64>,
}

/// One photometry listed in a container.
#[derive(Debug, Clone, PartialEq)]
pub struct GldfPhotometry {
    /// The `Photometry` id.
    pub id: String,
    /// The zip member holding its file.
    pub member: String,
    /// The file's `type` and location when it is not stored in the container
    /// (`type="url"`): such a photometry is listed but cannot be loaded.
    pub remote: Option<String>,
    /// The `File/@contentType` (`ldc/eulumdat`, `ldc/iesna`, ...).
    pub content_type: String,
    /// Its `DescriptivePhotometry`.
    pub declared: GldfDeclared,
}

/// An opened container: the archive and its photometries in document order.
pub struct GldfContainer {
    path: PathBuf,
    archive: zip::ZipArchive<std::io::Cursor<Vec<u8>>>,
    /// The photometries of `product.xml`, in document order.
    pub photometries: Vec<GldfPhotometry>,
}

/// `FILE.gldf#ID` split into the container and the id (everything after the
/// first `.gldf#`); `FILE.gldf` gives
/// `(FILE.gldf, None)`; anything else (including an existing file whose
/// name holds `#`) is `None`.
pub fn split_reference(path: &Path) -> Option<(PathBuf, Option<String>)> {
    let is_gldf = |p: &Path| p.extension().is_some_and(|e| e.eq_ignore_ascii_case("gldf"));
    if is_gldf(path) {
        return Some((path.to_path_buf(), None));
    }
    if path.exists() {
        return None;
    }
    // The first `.gldf#` ends the container's name: an id may hold `#`.
    let s = path.to_str()?;
    let at = s.to_ascii_lowercase().find(".gldf#")?;
    Some((PathBuf::from(&s[..at + 5]), Some(s[at + 6..].to_string())))
}

/// `FILE.gldf#ID` as a path (the name a photometry's luminaire and messages carry).
pub fn reference(container: &Path, id: &str) -> PathBuf {
    PathBuf::from(format!("{}#{id}", container.display()))
}

fn bad(path: &Path, expected: impl Into<String>, found: impl Into<String>) -> Error {
    ParseError {
        path: path.to_path_buf(),
        location: Location::line(0),
        kind: ErrorKind::Invalid,
        expected: expected.into(),
        found: found.into(),
    }
    .into()
}

impl GldfContainer {
    /// Open the container at `path` and read its `product.xml`.
    ///
    /// # Errors
    /// The file cannot be read, is not a zip archive, holds more than
    /// [`MAX_ENTRIES`] entries, has no `product.xml`, or its `product.xml`
    /// is malformed XML or lacks a photometry's `File`; each naming the
    /// container and what was expected.
    pub fn open(path: &Path) -> Result<Self> {
        let bytes = files::read_capped(path, MAX_FILE_BYTES).map_err(|e| match e {
            files::ReadCappedError::Io(e) => Error::io(path, e),
            other => bad(
                path,
                format!("a GLDF container (zip) of at most {MAX_FILE_BYTES} bytes"),
                other.to_string(),
            ),
        })?;
        Self::from_bytes(path, bytes)
    }

    /// [`GldfContainer::open`] on the container's bytes, already read
    /// (`path` names it in messages; nothing is read from disk).
    ///
    /// # Errors
    /// As [`GldfContainer::open`], but for reading the file.
    pub fn from_bytes(path: &Path, bytes: Vec<u8>) -> Result<Self> {
        let archive = zip::ZipArchive::new(std::io::Cursor::new(bytes)).map_err(|e| {
            bad(
                path,
                "a GLDF container (a zip archive)",
                format!("not a zip archive: {e}"),
            )
        })?;
        if archive.len() > MAX_ENTRIES {
            return Err(bad(
                path,
                format!("a GLDF container of at most {MAX_ENTRIES} entries"),
                format!("{} entries", archive.len()),
            ));
        }
        let mut c = GldfContainer {
            path: path.to_path_buf(),
            archive,
            photometries: Vec::new(),
        };
        if c.archive.index_for_name("product.xml").is_none() {
            return Err(bad(
                path,
                "a GLDF container with product.xml at its top level",
                "no product.xml",
            ));
        }
        let product = c.member("product.xml")?;
        c.photometries = photometries(path, &product)?;
        Ok(c)
    }

    /// The container's path.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The ids of its photometries, in document order.
    pub fn ids(&self) -> Vec<&str> {
        self.photometries.iter().map(|p| p.id.as_str()).collect()
    }

    /// The bytes of member `name`, at most [`MAX_MEMBER_BYTES`] uncompressed.
    fn member(&mut self, name: &str) -> Result<Vec<u8>> {
        let path = self.path.clone();
        let entry = self
            .archive
            .by_name(name)
            .map_err(|e| bad(&path, format!("the member {name} in the GLDF container"), e.to_string()))?;
        let mut out = Vec::new();
        entry
            .take(MAX_MEMBER_BYTES + 1)
            .read_to_end(&mut out)
            .map_err(|e| bad(&path, format!("a readable member {name}"), e.to_string()))?;
        if out.len() as u64 > MAX_MEMBER_BYTES {
            return Err(bad(
                &path,
                format!("the member {name} of at most {MAX_MEMBER_BYTES} bytes uncompressed"),
                "more (a zip bomb?)",
            ));
        }
        Ok(out)
    }

    /// Load the photometry `id` with the ordinary readers; the luminaire's
    /// path is `FILE.gldf#ID` and the document carries the container's declared values.
    ///
    /// # Errors
    /// An unknown id (the message lists the ids), a referenced file missing
    /// from the container, or the reader's error on the file (named `FILE.gldf#ID`).
    pub fn load(&mut self, id: &str, opts: &ReadOptions) -> Result<Document> {
        let Some(p) = self.photometries.iter().find(|p| p.id == id).cloned() else {
            return Err(bad(
                &self.path,
                format!("a photometry id of the container: {}", self.ids().join(", ")),
                format!("`{id}`"),
            ));
        };
        if let Some(remote) = &p.remote {
            return Err(ParseError {
                path: reference(&self.path, id),
                location: Location::line(0),
                kind: ErrorKind::Unsupported,
                expected: "a photometric file stored in the container (File type=\"localFileName\"); photosolid \
                           does not download"
                    .into(),
                found: format!("the File of product.xml is {remote}"),
            }
            .into());
        }
        if self.archive.index_for_name(&p.member).is_none() {
            return Err(bad(
                &self.path,
                format!(
                    "the file {} that photometry {id} references (GeneralDefinitions/Files) in the container",
                    p.member
                ),
                "no such member",
            ));
        }
        let bytes = self.member(&p.member)?;
        let name = reference(&self.path, id);
        let format = Format::from_extension(Path::new(&p.member))
            .or(match p.content_type.as_str() {
                "ldc/eulumdat" => Some(Format::Ldt),
                "ldc/iesna" | "ldc/ies" => Some(Format::Ies),
                _ => None,
            })
            .unwrap_or_else(|| crate::formats::sniff(&bytes));
        let mut doc = crate::formats::parse(&bytes, &name, format, opts)?;
        doc.gldf = Some(p.declared);
        Ok(doc)
    }
}

/// The photometries of `product.xml`, each resolved to its zip member.
fn photometries(container: &Path, product: &[u8]) -> Result<Vec<GldfPhotometry>> {
    let name = PathBuf::from(format!("{}/product.xml", container.display()));
    let text = xml::decode(product, &name)?;
    let doc = xml::parse(text, &name, "GLDF product.xml")?;
    let root = doc.root_element();
    let general = child(root, &["GeneralDefinitions"]);
    let files_of = general.and_then(|g| child(g, &["Files"]));
    let mut out = Vec::new();
    let Some(list) = general.and_then(|g| child(g, &["Photometries"])) else {
        return Ok(out);
    };
    for ph in children(list, "Photometry") {
        let id = ph.attribute("id").unwrap_or("").trim();
        if id.is_empty() {
            return Err(error_at(&name, ph, ErrorKind::Invalid, "an id attribute", "none").into());
        }
        let Some(file_ref) = child(ph, &["PhotometryFileReference"]) else {
            // A photometry may carry only descriptive data; nothing to load.
            continue;
        };
        let file_id = file_ref.attribute("fileId").unwrap_or("").trim();
        let file = files_of
            .into_iter()
            .flat_map(|f| children(f, "File"))
            .find(|f| f.attribute("id") == Some(file_id))
            .ok_or_else(|| {
                error_at(
                    &name,
                    file_ref,
                    ErrorKind::Invalid,
                    "a GeneralDefinitions/Files/File whose id is the fileId",
                    format!("no File with id `{file_id}`"),
                )
            })?;
        let file_name = file.text().unwrap_or("").trim();
        let remote = file
            .attribute("type")
            .filter(|t| *t != "localFileName")
            .map(|t| format!("type=\"{t}\" `{file_name}` (line {})", xml::location(file).line));
        if file_name.is_empty() {
            return Err(error_at(&name, file, ErrorKind::Invalid, "a file name", "an empty File element").into());
        }
        let member = if file_name.contains('/') {
            file_name.to_string()
        } else {
            format!("ldc/{file_name}")
        };
        let declared = match child(ph, &["DescriptivePhotometry"]) {
            Some(d) => descriptive(&name, d, container, id, &member)?,
            None => GldfDeclared {
                container: container.to_path_buf(),
                id: id.to_string(),
                file: member.clone(),
                ..GldfDeclared::default()
            },
        };
        out.push(GldfPhotometry {
            id: id.to_string(),
            remote,
            member,
            content_type: file.attribute("contentType").unwrap_or("").to_string(),
            declared,
        });
    }
    Ok(out)
}

/// `DescriptivePhotometry` → [`GldfDeclared`].
fn descriptive(
    name: &Path,
    d: roxmltree::Node<'_, '_>,
    container: &Path,
    id: &str,
    member: &str,
) -> std::result::Result<GldfDeclared, ParseError> {
    let ugr = match child(d, &["UGR-4H8H-70-50-20-LQ"]) {
        Some(u) => match (child_number(name, u, &["X"])?, child_number(name, u, &["Y"])?) {
            (Some(x), Some(y)) => Some(DeclaredUgr {
                crosswise: x,
                endwise: y,
            }),
            _ => None,
        },
        None => None,
    };
    Ok(GldfDeclared {
        container: container.to_path_buf(),
        id: id.to_string(),
        file: member.to_string(),
        lor: child_number(name, d, &["LightOutputRatio"])?,
        dff: child_number(name, d, &["DownwardFluxFraction"])?,
        dlor: child_number(name, d, &["DownwardLightOutputRatio"])?,
        ulor: child_number(name, d, &["UpwardLightOutputRatio"])?,
        luminous_efficacy_lm_per_w: child_number(name, d, &["LuminousEfficacy"])?,
        luminaire_luminance_cd_m2: child_number(name, d, &["LuminaireLuminance"])?,
        cie_flux_code: child_text(d, &["CIE-FluxCode"]).map(str::to_string),
        ugr_4h8h_70_50_20: ugr,
        bug_rating: child_text(d, &["LightDistributionBUG-Rating"]).map(str::to_string),
        cut_off_angle_deg: child_number(name, d, &["CutOffAngle"])?,
    })
}

/// Load `FILE.gldf#ID`, or `FILE.gldf` when it holds exactly one photometry.
///
/// # Errors
/// As [`GldfContainer::open`] and [`GldfContainer::load`]; a container with
/// no photometry, or several when no id is given (the message lists the ids
/// and says to pick one as `FILE.gldf#ID`).
pub fn load(container: &Path, id: Option<&str>, opts: &ReadOptions) -> Result<Document> {
    load_from(GldfContainer::open(container)?, id, opts)
}

/// [`load`] from a container already opened (from its file or its bytes).
///
/// # Errors
/// As [`load`].
pub fn load_from(mut c: GldfContainer, id: Option<&str>, opts: &ReadOptions) -> Result<Document> {
    let container = c.path.clone();
    let container = container.as_path();
    let id = match (id, c.ids().as_slice()) {
        (Some(id), _) => id.to_string(),
        (None, [one]) => one.to_string(),
        (None, []) => {
            return Err(bad(
                container,
                "a GLDF container with a photometry (GeneralDefinitions/Photometries/Photometry with a \
                 PhotometryFileReference)",
                "none",
            ))
        }
        (None, ids) => {
            return Err(bad(
                container,
                format!(
                    "one photometry: this container holds {}; name one as {}#ID",
                    ids.len(),
                    container.display()
                ),
                format!("the ids {}", ids.join(", ")),
            ))
        }
    };
    c.load(&id, opts)
}

/// Every photometry of a container as `FILE.gldf#ID` paths; the container's
/// own path when it cannot be opened (so that loading it reports why).
pub fn expand(container: &Path) -> Vec<PathBuf> {
    match GldfContainer::open(container) {
        Ok(c) if !c.photometries.is_empty() => c.ids().iter().map(|id| reference(container, id)).collect(),
        _ => vec![container.to_path_buf()],
    }
}

#[cfg(test)]
mod tests;
