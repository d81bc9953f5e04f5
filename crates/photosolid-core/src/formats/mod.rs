//! Formats in: IES LM-63, EULUMDAT and TM-33 readers and writers, and GLDF
//! containers (`FILE.gldf`, `FILE.gldf#ID`) read through them.
//!
//! Readers resolve everything once (units, multipliers, angle order,
//! symmetry, Type A/B conversion, tilt files) and return a [`Luminaire`];
//! nothing downstream looks at file details again. Writers take a
//! `Luminaire` and return text; [`save`] writes it atomically.

pub mod angles;
pub mod files;
pub mod gldf;
pub mod ies;
pub mod ldt;
pub mod roundtrip;
pub mod scan;
pub mod text;
pub mod tm33;
pub(crate) mod xml;

pub use files::{write_atomic, write_atomic_with};
use std::path::Path;

use crate::error::{Error, ErrorKind, Location, ParseError, Result};
use crate::model::{Format, Luminaire};

/// Largest file the readers accept (bytes). The biggest real photometric
/// files are a few MB; anything far larger is not a photometric file and is
/// refused before it is read into memory.
pub const MAX_FILE_BYTES: u64 = 256 * 1024 * 1024;

/// Rotation sense of the C (horizontal) angles.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Handedness {
    /// C increases counter-clockwise seen from above: C90 = +y (default; LM-63 Type C, EULUMDAT).
    #[default]
    CounterClockwise,
    /// C increases clockwise seen from above: C90 = −y.
    Clockwise,
}

/// How a lamp-set count > 1 is interpreted in EULUMDAT.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum LampSetFlux {
    /// cd/klm refer to the flux of lamp set 1 (most tools).
    #[default]
    First,
    /// cd/klm refer to the summed flux of all sets.
    Sum,
}

impl Handedness {
    /// The word the CLI's `--handedness` and the Python `load(handedness=)` take.
    pub fn as_str(self) -> &'static str {
        match self {
            Handedness::CounterClockwise => "ccw",
            Handedness::Clockwise => "cw",
        }
    }
}

impl std::str::FromStr for Handedness {
    type Err = crate::error::ModelError;
    /// `ccw` or `cw`.
    fn from_str(s: &str) -> std::result::Result<Self, Self::Err> {
        match s.trim() {
            "ccw" => Ok(Handedness::CounterClockwise),
            "cw" => Ok(Handedness::Clockwise),
            other => Err(crate::error::ModelError::Parameter {
                name: "handedness",
                value: other.to_string(),
                reason: "expected ccw (C90 = +y, the default) or cw".into(),
            }),
        }
    }
}

impl LampSetFlux {
    /// The word the CLI's `--lamp-sets` and the Python `load(lamp_sets=)` take.
    pub fn as_str(self) -> &'static str {
        match self {
            LampSetFlux::First => "first",
            LampSetFlux::Sum => "sum",
        }
    }
}

impl std::str::FromStr for LampSetFlux {
    type Err = crate::error::ModelError;
    /// `first` or `sum`.
    fn from_str(s: &str) -> std::result::Result<Self, Self::Err> {
        match s.trim() {
            "first" => Ok(LampSetFlux::First),
            "sum" => Ok(LampSetFlux::Sum),
            other => Err(crate::error::ModelError::Parameter {
                name: "lamp_sets",
                value: other.to_string(),
                reason: "expected first (the default: cd/klm refer to the first lamp set) or sum".into(),
            }),
        }
    }
}

/// A read photometric file: the canonical [`Luminaire`] and what only its
/// format knows (the raw header a lossless write-back needs, what a GLDF
/// container declares). Readers return one; writers take one.
#[derive(Debug, Clone, PartialEq)]
pub struct Document {
    /// The luminaire, format-free.
    pub luminaire: Luminaire,
    /// The format's own header, when the file had one this crate keeps.
    pub header: Header,
    /// What the GLDF container declares about this photometry, when it was
    /// read from one (`FILE.gldf#ID`).
    pub gldf: Option<gldf::GldfDeclared>,
}

/// A format's raw header, kept so that a file is written back losslessly in
/// its own format.
#[derive(Debug, Clone, PartialEq, Default)]
pub enum Header {
    /// No header: a synthetic luminaire, a TM-33 document (its model is the
    /// whole document), or one built in code.
    #[default]
    None,
    /// The IES LM-63 header (labels and keywords, as written).
    Ies(ies::IesHeader),
    /// The EULUMDAT header fields the model does not hold.
    Ldt(ldt::LdtHeader),
}

impl Document {
    /// A document with no header: writers derive every header field from
    /// the luminaire.
    pub fn bare(luminaire: Luminaire) -> Self {
        Self {
            luminaire,
            header: Header::None,
            gldf: None,
        }
    }
    /// The IES header, when read from an IES file.
    pub fn ies_header(&self) -> Option<&ies::IesHeader> {
        match &self.header {
            Header::Ies(h) => Some(h),
            _ => None,
        }
    }
    /// The EULUMDAT header, when read from an LDT file.
    pub fn ldt_header(&self) -> Option<&ldt::LdtHeader> {
        match &self.header {
            Header::Ldt(h) => Some(h),
            _ => None,
        }
    }
}

/// A document is its luminaire plus format details: every luminaire query
/// answers on the document directly.
impl std::ops::Deref for Document {
    type Target = Luminaire;
    fn deref(&self) -> &Luminaire {
        &self.luminaire
    }
}

impl From<Luminaire> for Document {
    fn from(luminaire: Luminaire) -> Self {
        Self::bare(luminaire)
    }
}

/// A reader's result: the checked luminaire with its header. A part the
/// reader built inconsistently is a bug in that reader, reported as an error
/// on the file rather than a panic.
pub(crate) fn document(
    path: &Path,
    parts: crate::model::LuminaireParts,
    header: Header,
) -> Result<Document, ParseError> {
    let luminaire = Luminaire::from_parts(parts).map_err(|e| ParseError {
        path: path.to_path_buf(),
        location: Location::line(0),
        kind: ErrorKind::Invalid,
        expected: "a luminaire the reader can build (a bug in photosolid's reader, please report it)".into(),
        found: e.to_string(),
    })?;
    Ok(Document {
        luminaire,
        header,
        gldf: None,
    })
}

/// Options of the readers. `Default` is lenient: recoverable problems become warnings.
#[derive(Debug, Clone, Default)]
pub struct ReadOptions {
    /// Repair duplicate / unsorted angle lists (sort, drop duplicates, warn)
    /// instead of failing. Default: false.
    pub repair: bool,
    /// Handedness of Type A/B horizontal angles when converting to Type C. Default: counter-clockwise.
    pub handedness: Handedness,
    /// Which lamp flux EULUMDAT cd/klm values refer to. Default: set 1.
    pub lamp_set_flux: LampSetFlux,
    /// The luminaire's front, C degrees in the file's frame (`--front`),
    /// instead of its format's convention ([`crate::model::front`]). A
    /// value that is not finite is ignored (the CLI refuses it first).
    pub front_c_deg: Option<f64>,
}

impl ReadOptions {
    /// Give `doc` the front these options name, if any.
    fn apply_front(&self, mut doc: Document) -> Document {
        if let Some(front) = self.front_c_deg.and_then(crate::model::Front::flag) {
            doc.luminaire.set_front(front);
        }
        doc
    }
}

/// Read a photometric file, format from its extension (or, failing that,
/// its content). `FILE.gldf#ID` reads one photometry of a GLDF container,
/// `FILE.gldf` its only one (see [`gldf`]).
pub fn load(path: impl AsRef<Path>) -> Result<Luminaire> {
    load_with(path, &ReadOptions::default())
}

/// [`load`] with options.
pub fn load_with(path: impl AsRef<Path>, opts: &ReadOptions) -> Result<Luminaire> {
    load_document_with(path, opts).map(|d| d.luminaire)
}

/// Read a photometric file with its format header and container
/// declarations (see [`load`] for the paths accepted).
pub fn load_document(path: impl AsRef<Path>) -> Result<Document> {
    load_document_with(path, &ReadOptions::default())
}

/// [`load_document`] with options.
pub fn load_document_with(path: impl AsRef<Path>, opts: &ReadOptions) -> Result<Document> {
    load_document_as_read(path.as_ref(), opts).map(|doc| opts.apply_front(doc))
}

/// The bytes [`load_document`] reads for `path`: the file's, the GLDF
/// container's for `FILE.gldf#ID`, the TM-33 document's for `FILE.xml#ID`
/// (each refused over [`MAX_FILE_BYTES`]). With
/// [`load_document_from_bytes`], a document that travels as bytes (a Python
/// pickle) and is parsed again where no file is.
///
/// # Errors
/// [`Error::Io`] naming the file; a [`ParseError`] for a file that is too
/// large or not a regular file.
pub fn document_source_bytes(path: &Path) -> Result<Vec<u8>> {
    if let Some((container, _)) = gldf::split_reference(path) {
        return read_photometric_file(&container);
    }
    if let Some((file, _)) = tm33::split_reference(path) {
        return read_photometric_file(&file);
    }
    read_photometric_file(path)
}

/// [`load_document_with`] on the bytes [`document_source_bytes`] gives for
/// `path`, already read: the same document, nothing read from disk (`path`
/// names the file in messages and decides the format as it does there).
///
/// # Errors
/// As [`load_document_with`], but for reading the file.
pub fn load_document_from_bytes(path: &Path, bytes: Vec<u8>, opts: &ReadOptions) -> Result<Document> {
    parse_document(path, bytes, opts).map(|doc| opts.apply_front(doc))
}

/// [`load_document_with`] before the options' front is applied.
fn load_document_as_read(path: &Path, opts: &ReadOptions) -> Result<Document> {
    if let Some((container, id)) = gldf::split_reference(path) {
        return gldf::load(&container, id.as_deref(), opts);
    }
    parse_document(path, document_source_bytes(path)?, opts)
}

/// The document `path` names, from `bytes` (those of [`document_source_bytes`]).
fn parse_document(path: &Path, bytes: Vec<u8>, opts: &ReadOptions) -> Result<Document> {
    if let Some((container, id)) = gldf::split_reference(path) {
        return gldf::load_from(gldf::GldfContainer::from_bytes(&container, bytes)?, id.as_deref(), opts);
    }
    if let Some((_, id)) = tm33::split_reference(path) {
        return Ok(tm33::read_emitter(&bytes, path, Some(&id), opts)?);
    }
    let by_extension = Format::from_extension(path);
    let format = by_extension.unwrap_or_else(|| sniff(&bytes));
    parse(&bytes, path, format, opts).map_err(|mut e| {
        // A file renamed to the other format's extension: say what it looks like.
        let content = sniff(&bytes);
        if by_extension.is_some() && content != format && looks_like(&bytes, content) {
            let name = |f: Format| match f {
                Format::Ies => "IES LM-63 (it has a TILT= line)",
                Format::Ldt => "EULUMDAT (it has no TILT= line)",
                Format::Tm33 => "TM-33 XML (its root element is LuminaireOpticalData or IESTM33-22)",
            };
            let ext = |f: Format| match f {
                Format::Ies => ".ies",
                Format::Ldt => ".ldt",
                Format::Tm33 => ".xml",
            };
            e.found = format!(
                "{}; the extension says {} but the content looks like {}: rename it to {}",
                e.found,
                ext(format),
                name(content),
                ext(content)
            );
        }
        e.into()
    })
}

/// The bytes of the file at `path`, refused over [`MAX_FILE_BYTES`] or when it is not a regular file.
fn read_photometric_file(path: &Path) -> Result<Vec<u8>> {
    files::read_capped(path, MAX_FILE_BYTES).map_err(|e| match e {
        files::ReadCappedError::Io(e) => Error::io(path, e),
        other => ParseError {
            path: path.to_path_buf(),
            location: Location::line(0),
            kind: ErrorKind::Invalid,
            expected: format!("a regular photometric file of at most {MAX_FILE_BYTES} bytes"),
            found: other.to_string(),
        }
        .into(),
    })
}

/// The photometries a path names, each as a path [`load`] reads: every
/// photometry of a GLDF container given without an id (`FILE.gldf#ID`,
/// [`gldf::expand`]), every emitter of a TM-33 document that holds several
/// (`FILE.xml#ID`, [`tm33::expand`]); any other path as it is.
pub fn photometries_in(path: &Path) -> Vec<std::path::PathBuf> {
    if let Some((container, None)) = gldf::split_reference(path) {
        return gldf::expand(&container);
    }
    if Format::from_extension(path) == Some(Format::Tm33) && path.is_file() {
        return tm33::expand(path);
    }
    vec![path.to_path_buf()]
}

/// Positive evidence that `bytes` are `format` (used only to explain a failed
/// read): a `TILT=` line for IES; for EULUMDAT, lines 2, 3, 4 and 6 (type,
/// symmetry, number of C-planes, number of gamma angles) are integers; for
/// TM-33, its root element.
fn looks_like(bytes: &[u8], format: Format) -> bool {
    let head = String::from_utf8_lossy(&bytes[..bytes.len().min(4096)]);
    match format {
        Format::Tm33 => tm33::looks_like(bytes),
        Format::Ies => head.to_ascii_uppercase().contains("TILT="),
        Format::Ldt => {
            let lines: Vec<&str> = head.lines().take(6).collect();
            lines.len() == 6 && [1, 2, 3, 5].iter().all(|&i| lines[i].trim().parse::<u32>().is_ok())
        }
    }
}

/// Parse bytes as the given format; `path` is used for messages and, for
/// `TILT=<file>`, to find the tilt file next to it.
pub fn parse(bytes: &[u8], path: &Path, format: Format, opts: &ReadOptions) -> Result<Document, ParseError> {
    match format {
        Format::Ies => ies::read(bytes, path, opts),
        Format::Ldt => ldt::read(bytes, path, opts),
        Format::Tm33 => tm33::read(bytes, path, opts),
    }
    .map(|doc| opts.apply_front(doc))
}

/// Guess the format of content with no telling extension: TM-33 documents
/// have their root element, IES files carry `TILT=`, EULUMDAT files do not.
pub fn sniff(bytes: &[u8]) -> Format {
    let head = &bytes[..bytes.len().min(64 * 1024)];
    if tm33::looks_like(head) {
        Format::Tm33
    } else if head.windows(5).any(|w| w.eq_ignore_ascii_case(b"TILT=")) {
        Format::Ies
    } else {
        Format::Ldt
    }
}

/// What a conversion of `lum` to `target` cannot keep as the file says it,
/// one [`WarningCode::FieldNotKept`](crate::error::WarningCode::FieldNotKept) each (plus `front-differs`, [`Front::differs_in`]),
/// each message ending with the `info --json` keys whose values change, so a
/// check of a conversion knows which keys to leave out:
/// - the luminous opening a target cannot hold ([`Opening::to_ldt`] / [`Opening::to_ies`]),
///   or one whose LM-63 signs match no shape;
/// - the light output ratio: EULUMDAT requires one (written as the computed
///   flux over the lamp flux when the file declares none), LM-63 holds none;
/// - the tilt table: EULUMDAT and TM-33-23 hold none, LM-63 writes a
///   `TILT=<file>` table inline;
/// - Type B measurements, which EULUMDAT and TM-33-23 hold only resampled to
///   C-γ, and with them the floodlight spreads measured on the Type B planes;
/// - a lamp flux of 0 lm, which cannot scale EULUMDAT's or TM-33's relative
///   values (written as absolute photometry).
///
/// [`Front::differs_in`]: crate::model::Front::differs_in
/// [`Opening::to_ldt`]: crate::model::opening::Opening::to_ldt
/// [`Opening::to_ies`]: crate::model::opening::Opening::to_ies
pub fn conversion_warnings(lum: &Luminaire, target: Format) -> Vec<crate::error::Warning> {
    use crate::error::{Warning, WarningCode};
    let mut out: Vec<Warning> = lum.front().differs_in(target).into_iter().collect();
    let mut not_kept = |note: String, keys: &str| {
        out.push(Warning::new(
            WarningCode::FieldNotKept,
            format!("{note} (changes info keys: {keys})"),
        ));
    };
    let name = match target {
        Format::Ies => "LM-63",
        Format::Ldt => "EULUMDAT",
        Format::Tm33 => "TM-33-23",
    };
    if let Some(note) = opening_not_kept(lum, target, name) {
        not_kept(note, "luminous_dimensions_m, luminance_table, ugr_table");
    }
    let d = lum.declared();
    let lor_keys = "declared_lor, declared_flux_lm, flux_ratio";
    match (target, d.lor) {
        (Format::Ldt, None) if lum.format() != Format::Ldt => not_kept(
            "EULUMDAT requires a light output ratio and this file declares none: the computed one is written, \
             and the converted file declares it"
                .into(),
            lor_keys,
        ),
        (Format::Ies, Some(lor)) => not_kept(
            format!(
                "LM-63 holds no light output ratio: the declared {} % is not kept",
                crate::numfmt::trimmed(100.0 * lor, 4)
            ),
            lor_keys,
        ),
        _ => {}
    }
    match (lum.tilt(), target) {
        (crate::model::Tilt::None, _) => {}
        (crate::model::Tilt::File { name: file, .. }, Format::Ies) => not_kept(
            format!("the TILT={file} table is written into the file (TILT=INCLUDE)"),
            "tilt",
        ),
        (_, Format::Ies) => {}
        (_, _) => not_kept(
            format!("{name} holds no tilt table: the file's tilt table is not kept"),
            "tilt",
        ),
    }
    let type_b = lum
        .source_grid()
        .is_some_and(|g| g.kind == crate::model::PhotometricType::B);
    if type_b && target != Format::Ies {
        not_kept(
            format!(
                "{name} holds C-γ photometry: the Type B measurements are written resampled to C-γ planes, and \
                 the floodlight spreads measured on the Type B planes are not reported for the converted file"
            ),
            "beam_spread_deg, field_spread_deg, nema_type",
        );
    }
    if target != Format::Ies && !d.absolute && d.lamp_flux_lm.is_some_and(|f| f.is_nan() || f <= 0.0) {
        not_kept(
            format!("a lamp flux of 0 lm cannot scale {name}'s relative values: written as absolute photometry"),
            "lamp_flux_lm, absolute",
        );
    }
    out
}

/// What `target` (named `name`) cannot hold of `lum`'s luminous opening, in
/// words: a shape it has no term for, or LM-63 signs that match no shape.
fn opening_not_kept(lum: &Luminaire, target: Format, name: &str) -> Option<String> {
    if target == lum.format() {
        return None;
    }
    match crate::model::opening::Opening::of_luminaire(lum) {
        Ok(shape) => match target {
            Format::Ldt => shape.to_ldt().3,
            Format::Ies => shape.to_ies().3,
            Format::Tm33 => None,
        },
        Err(e) if target != Format::Tm33 || lum.format() == Format::Ldt => {
            Some(format!("{e}: {name} is given its absolute dimensions"))
        }
        Err(_) => None,
    }
}

/// Options of the writers.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct WriteOptions {
    /// IES version to write (2002 default, or 2019).
    pub ies_version: ies::IesWriteVersion,
}

/// Write `doc` to `path` in the format of its extension, atomically (a
/// [`Luminaire`] converts into a header-less [`Document`]: `&lum.into()`).
pub fn save(doc: &Document, path: &Path, opts: &WriteOptions) -> Result<()> {
    let format = Format::from_extension(path).ok_or_else(|| Error::UnknownExtension {
        path: path.to_path_buf(),
        what: "output format",
        accepted: &[".ies", ".ldt", ".xml (TM-33-23)"],
    })?;
    let text = match format {
        Format::Ies => ies::write(doc, opts.ies_version),
        Format::Ldt => ldt::write(doc),
        Format::Tm33 => tm33::write(doc),
    };
    write_atomic(path, text.as_bytes())
}

/// The photometric files at `path`: a file named explicitly, whatever its
/// extension, or every `.ies`/`.ldt` file, TM-33 `.xml` file (by its root
/// element) and `.gldf` container below a directory (recursive, sorted by
/// path), appended to `out`; files below a directory with no or another
/// extension are read by their content ([`sniff_photometric`]). A container
/// becomes one `FILE.gldf#ID` path per photometry ([`gldf::expand`]), a TM-33
/// document with several emitters one `FILE.xml#ID` path per emitter
/// ([`tm33::expand`]). [`collect`] also counts what was read by content and
/// what was skipped.
///
/// # Errors
/// [`Error::Io`] naming the directory that cannot be read.
pub fn collect_files(path: &std::path::Path, out: &mut Vec<std::path::PathBuf>) -> Result<()> {
    let mut c = Collected::default();
    collect_into(path, &mut c)?;
    out.append(&mut c.files);
    Ok(())
}

/// What walking paths found: the photometric files (as [`collect_files`]
/// lists them), how many of those were recognised by content because their
/// name has no photometric extension, and the files below a directory that
/// were skipped as not photometric.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Collected {
    /// The paths to load, in walking order.
    pub files: Vec<std::path::PathBuf>,
    /// Files found in directories without a `.ies`/`.ldt`/`.xml`/`.gldf`
    /// extension whose first bytes are a photometric file (counted in `files`).
    pub by_content: usize,
    /// Files found in directories that are not photometric (by extension
    /// and content), in walking order.
    pub skipped: Vec<std::path::PathBuf>,
}

impl Collected {
    /// The summary lines of a walk, plurals right: `N files without a
    /// photometric extension read by content`, `N files skipped: not
    /// photometric (a, b, c, ...)`; none when there is nothing to say.
    pub fn summary(&self) -> Vec<String> {
        let mut lines = Vec::new();
        if self.by_content > 0 {
            lines.push(format!(
                "{} without a photometric extension read by content",
                crate::error::count(self.by_content, "file", "files")
            ));
        }
        if !self.skipped.is_empty() {
            let names: Vec<String> = self.skipped.iter().take(3).map(|p| p.display().to_string()).collect();
            let more = if self.skipped.len() > 3 { ", ..." } else { "" };
            lines.push(format!(
                "{} skipped: not photometric ({}{more})",
                crate::error::count(self.skipped.len(), "file", "files"),
                names.join(", ")
            ));
        }
        lines
    }
}

/// Walk every path of `paths` (see [`collect_files`]), counting what was read
/// by content and what was skipped.
///
/// # Errors
/// [`Error::Io`] naming the directory that cannot be read.
pub fn collect(paths: &[std::path::PathBuf]) -> Result<Collected> {
    let mut c = Collected::default();
    for p in paths {
        collect_into(p, &mut c)?;
    }
    Ok(c)
}

/// How many leading bytes [`collect`] reads of a file whose extension does
/// not say its format.
pub const SNIFF_BYTES: usize = 4096;

fn collect_into(path: &std::path::Path, c: &mut Collected) -> Result<()> {
    if !path.is_dir() {
        c.files.extend(photometries_in(path));
        return Ok(());
    }
    let mut entries: Vec<std::path::PathBuf> = std::fs::read_dir(path)
        .map_err(|e| Error::io(path, e))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .collect();
    entries.sort();
    for e in entries {
        if e.is_dir() {
            collect_into(&e, c)?;
        } else if gldf::split_reference(&e).is_some() {
            c.files.extend(gldf::expand(&e));
        } else {
            match Format::from_extension(&e) {
                // Other XML files (a GLDF's product.xml unpacked, say) are not photometry.
                Some(Format::Tm33) if e.is_file() && tm33::looks_like(&head(&e, 64 * 1024)) => {
                    c.files.extend(tm33::expand(&e))
                }
                Some(Format::Tm33) => c.skipped.push(e),
                Some(Format::Ies | Format::Ldt) => c.files.push(e),
                // Only regular files are opened: a FIFO would block.
                None if e.is_file() && sniff_photometric(&head(&e, SNIFF_BYTES as u64)).is_some() => {
                    c.by_content += 1;
                    c.files.push(e);
                }
                None => c.skipped.push(e),
            }
        }
    }
    Ok(())
}

/// The format of `bytes` when their start is a photometric file, `None`
/// when it is not (binary data, a PDF, an image, other text). Only the
/// first [`SNIFF_BYTES`] are looked at: IES LM-63 starts with `IESNA` or
/// `IES:`, or has a `TILT=` line; TM-33 is XML with its root element;
/// EULUMDAT has no magic, so its header lines must have the structure of
/// one (type 0-3, symmetry 0-4, plane and angle counts, numbers where the
/// format has numbers). [`sniff`] instead always picks a format.
pub fn sniff_photometric(bytes: &[u8]) -> Option<Format> {
    let head = &bytes[..bytes.len().min(SNIFF_BYTES)];
    if head.is_empty() || head.contains(&0) {
        return None;
    }
    if tm33::looks_like(head) {
        return Some(Format::Tm33);
    }
    let text = String::from_utf8_lossy(head);
    let text = text.trim_start_matches('\u{feff}');
    let mut lines = text.lines().map(str::trim);
    let first = lines.clone().find(|l| !l.is_empty()).unwrap_or("").to_ascii_uppercase();
    if first.starts_with("IESNA")
        || first.starts_with("IES:")
        || lines.any(|l| l.to_ascii_uppercase().starts_with("TILT="))
    {
        return Some(Format::Ies);
    }
    looks_like_ldt_header(text).then_some(Format::Ldt)
}

/// The EULUMDAT header structure (lines 2 to 7 and 13 to 24): cheap and
/// strict enough that no text that is not EULUMDAT passes by chance.
fn looks_like_ldt_header(text: &str) -> bool {
    let lines: Vec<&str> = text.lines().map(str::trim).take(26).collect();
    if lines.len() < 26 {
        return false;
    }
    let num = |i: usize| lines[i].replace(',', ".").parse::<f64>().ok().filter(|x| x.is_finite());
    let int_in =
        |i: usize, r: std::ops::RangeInclusive<f64>| num(i).is_some_and(|x| x.fract() == 0.0 && r.contains(&x));
    int_in(1, 0.0..=3.0)
        && int_in(2, 0.0..=4.0)
        && int_in(3, 0.0..=3600.0)
        && num(4).is_some()
        && int_in(5, 0.0..=3600.0)
        && num(6).is_some()
        && (12..=23).all(|i| num(i).is_some())
        && int_in(25, 0.0..=1000.0)
}

/// The first `cap` bytes of a regular file (empty when it cannot be read).
fn head(path: &Path, cap: u64) -> Vec<u8> {
    use std::io::Read;
    let mut b = Vec::new();
    if let Ok(f) = std::fs::File::open(path) {
        let _ = f.take(cap).read_to_end(&mut b);
    }
    b
}

/// Relative distance outside the model's intensity range ([`MAX_CD`],
/// [`MIN_PEAK_CD`]) within which a reader moves values onto the range's end
/// (with a warning) instead of refusing them: the writers print values with
/// 8 to 15 significant digits, so a value written at the end of the range can
/// read back that far outside it.
///
/// [`MAX_CD`]: crate::model::MAX_CD
/// [`MIN_PEAK_CD`]: crate::model::MIN_PEAK_CD
pub const RANGE_SNAP: f64 = 1e-6;

/// Bring intensities read from a file into the model's range: values within
/// [`RANGE_SNAP`] (relative) outside it are moved onto its end, a peak just
/// below [`crate::model::MIN_PEAK_CD`] by scaling the whole table (the
/// shape is kept); a table of round-off only becomes zero. Returns the warning text when something moved, or the
/// offending index and why when the table is out of range
/// ([`crate::model::check_intensities`]).
pub(crate) fn into_model_range(cd: &mut [f64]) -> std::result::Result<Option<String>, (usize, String)> {
    use crate::model::{check_intensities, MAX_CD, MIN_PEAK_CD};
    // Order: snap onto the ends first, so a written minimum peak is not flushed.
    let mut moved = 0usize;
    for v in cd.iter_mut() {
        if v.is_finite() && v.abs() > MAX_CD && v.abs() <= MAX_CD * (1.0 + RANGE_SNAP) {
            *v = MAX_CD.copysign(*v);
            moved += 1;
        }
    }
    let peak = cd.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let mut note = (moved > 0).then(|| format!("{moved} value(s) just above {MAX_CD:e} cd set to it"));
    if (MIN_PEAK_CD * (1.0 - RANGE_SNAP)..MIN_PEAK_CD).contains(&peak) {
        // A few ulps more, so that rounding cannot leave the new peak a hair below the bound.
        let k = MIN_PEAK_CD / peak * (1.0 + 4.0 * f64::EPSILON);
        cd.iter_mut().for_each(|v| *v *= k);
        note = Some(format!(
            "the peak {peak:e} cd, just below {MIN_PEAK_CD:e} cd, scaled up to it"
        ));
    }
    if crate::model::flush_round_off(cd) {
        note = Some(format!(
            "every value is below {MIN_PEAK_CD:e} cd (round-off): read as an all-zero distribution"
        ));
    }
    check_intensities(cd)?;
    Ok(note)
}

/// The `negative-intensity` warning text of every reader, `None` when no
/// value is negative. Negative values are kept as they are: files hold small
/// negative noise around 0 from the measurement, and clamping it would change
/// the flux. The text gives their count and the lowest, in `unit` (the
/// values' unit as the file states them: cd, cd/klm).
pub(crate) fn negative_intensities(values: &[f64], unit: &str) -> Option<String> {
    let n = values.iter().filter(|&&v| v < 0.0).count();
    (n > 0).then(|| {
        let lowest = values.iter().copied().fold(f64::INFINITY, f64::min);
        format!(
            "{n} negative intensities kept as they are (lowest {} {unit})",
            crate::error::Num(lowest)
        )
    })
}

/// What a file that declares a lamp flux (none for absolute photometry) and
/// input watts, but no luminaire flux, LOR or DFF, declares (IES, TM-33).
/// `lamp_flux_lm` in lumens, `input_watts` in watts.
pub(crate) fn declared_lamp_flux(
    lamp_flux_lm: Option<f64>,
    absolute: bool,
    input_watts: Option<f64>,
) -> crate::model::Declared {
    crate::model::Declared {
        lamp_flux_lm,
        luminaire_flux_lm: None,
        lor: None,
        dff: None,
        absolute,
        input_watts,
    }
}
