//! The luminaire: metadata around one [`Distribution`].
//!
//! Whatever the file format, a loaded luminaire has:
//! - a Type C [`Distribution`] in absolute candela, with every multiplier
//!   (IES candela multiplier, ballast factor, BLPF; EULUMDAT cd/klm × lamp
//!   flux / 1000) already applied, untilted;
//! - Type A and B data converted to Type C through direction vectors, the
//!   original grid kept in [`Luminaire::source_grid`] for writing back;
//! - nothing of any one format's header: a reader returns the luminaire with
//!   its header in a `formats::Document`, so a file is written back
//!   losslessly in its own format while the model stays format-free;
//! - every recoverable oddity as a [`Warning`].

use std::path::PathBuf;

use serde::Serialize;

use crate::error::{ModelError, Warning};
use crate::model::distribution::Distribution;
use crate::model::front::Front;

/// File format of a photometric file.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Format {
    /// IES LM-63 (.ies).
    Ies,
    /// EULUMDAT (.ldt).
    Ldt,
    /// ANSI/IES TM-33-18 or TM-33-23 XML (.xml).
    Tm33,
}

impl Format {
    /// From a file extension (any case): `ies`, `ldt` or `xml` (TM-33).
    pub fn from_extension(path: &std::path::Path) -> Option<Self> {
        let e = path.extension()?.to_str()?.to_ascii_lowercase();
        match e.as_str() {
            "ies" => Some(Format::Ies),
            "ldt" => Some(Format::Ldt),
            "xml" => Some(Format::Tm33),
            _ => None,
        }
    }
}

/// Photometric type of the measurement grid (LM-63 codes 1 = C, 2 = B, 3 = A).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum PhotometricType {
    /// Type A: horizontal axis through the luminaire, planes share it (automotive).
    A,
    /// Type B: planes share a horizontal axis (floodlights).
    B,
    /// Type C: planes share the vertical axis (architectural, road).
    C,
}

/// One lamp set (EULUMDAT lines 26a-f; an IES file has one).
#[derive(Debug, Clone, PartialEq, Serialize, Default)]
pub struct LampSet {
    /// Number of lamps; negative in EULUMDAT means absolute photometry.
    pub count: f64,
    /// Lamp type / description.
    pub lamp_type: String,
    /// Total lamp flux of the set in lm (the luminaire flux when absolute).
    pub flux_lm: f64,
    /// Colour appearance or colour temperature as written (e.g. "3000K", "830").
    pub color: String,
    /// Colour rendering group or index as written.
    pub cri: String,
    /// Wattage including ballast, W.
    pub watts: f64,
}

/// Physical dimensions in metres (converted from feet or millimetres).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Default)]
pub struct Dimensions {
    /// Along C0 (the luminaire's length), m.
    pub length_m: f64,
    /// Along C90, m (0 for a circular luminaire of diameter `length_m` in EULUMDAT).
    pub width_m: f64,
    /// Vertical, m.
    pub height_m: f64,
}

/// What the file declares about its photometry, as opposed to what we compute.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Default)]
pub struct Declared {
    /// Total bare-lamp flux, lm (None for absolute photometry).
    pub lamp_flux_lm: Option<f64>,
    /// Declared luminaire flux, lm: lamp flux × LOR for relative files, the
    /// stated flux for absolute EULUMDAT files; None when the file says nothing.
    pub luminaire_flux_lm: Option<f64>,
    /// Declared light output ratio, as a fraction (EULUMDAT LORL / 100).
    pub lor: Option<f64>,
    /// Declared downward flux fraction, as a fraction (EULUMDAT DFF / 100).
    pub dff: Option<f64>,
    /// Absolute photometry (IES lm/lamp = −1, EULUMDAT lamp count < 0).
    pub absolute: bool,
    /// Input power, W.
    pub input_watts: Option<f64>,
}

/// A tilt table: multipliers of the whole distribution against the
/// installed tilt angle (degrees), linearly interpolated between pairs.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TiltTable {
    /// Lamp-to-luminaire geometry code 1, 2 or 3 (LM-63).
    pub geometry: u8,
    /// Tilt angles, degrees, ascending.
    pub angles: Vec<f64>,
    /// Multipliers, one per angle.
    pub multipliers: Vec<f64>,
}

impl TiltTable {
    /// Multiplier at `angle` (degrees): linear between pairs, the end value
    /// beyond the ends (a table covers the angles the lab measured).
    pub fn multiplier_at(&self, angle: f64) -> f64 {
        let a = &self.angles;
        let m = &self.multipliers;
        if a.is_empty() {
            return 1.0;
        }
        if angle <= a[0] {
            return m[0];
        }
        if angle >= a[a.len() - 1] {
            return m[a.len() - 1];
        }
        let i = a.partition_point(|&x| x <= angle).max(1) - 1;
        let t = (angle - a[i]) / (a[i + 1] - a[i]);
        m[i] + t * (m[i + 1] - m[i])
    }
}

/// The TILT declaration of an IES file.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "lowercase")]
pub enum Tilt {
    /// `TILT=NONE` (and every EULUMDAT file).
    None,
    /// `TILT=INCLUDE`: the table follows in the file.
    Include {
        /// The table.
        table: TiltTable,
    },
    /// `TILT=<file>`: the table was read from a file next to the photometric file.
    File {
        /// The file name as written.
        name: String,
        /// The table read from it.
        table: TiltTable,
    },
}

impl Tilt {
    /// The tilt table, if any.
    pub fn table(&self) -> Option<&TiltTable> {
        match self {
            Tilt::None => None,
            Tilt::Include { table } | Tilt::File { table, .. } => Some(table),
        }
    }
}

/// The measured grid of a Type A or B file, as it was in the file (degrees, cd).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SourceGrid {
    /// A or B.
    pub kind: PhotometricType,
    /// Vertical angles, degrees.
    pub vertical: Vec<f64>,
    /// Horizontal angles, degrees.
    pub horizontal: Vec<f64>,
    /// Candela (multipliers applied), horizontal-major: `cd[ih * vertical.len() + iv]`.
    pub cd: Vec<f64>,
}

/// Descriptive text of a luminaire.
#[derive(Debug, Clone, PartialEq, Serialize, Default)]
pub struct Metadata {
    /// Manufacturer (IES `[MANUFAC]`, EULUMDAT line 1).
    pub manufacturer: String,
    /// Catalogue number (IES `[LUMCAT]`, EULUMDAT line 10).
    pub catalogue: String,
    /// Luminaire description (IES `[LUMINAIRE]`, EULUMDAT line 9).
    pub luminaire: String,
    /// Lamp description (IES `[LAMP]`, EULUMDAT lamp type of set 1).
    pub lamp: String,
    /// Test report number (IES `[TEST]`, EULUMDAT line 8).
    pub test_report: String,
    /// Date / user (IES `[ISSUEDATE]`/`[DATE]`, EULUMDAT line 12).
    pub date: String,
}

/// Everything a [`Luminaire`] is made of, as plain data: what a reader fills
/// in before [`Luminaire::from_parts`] checks it, and what
/// [`Luminaire::into_parts`] gives back.
#[derive(Debug, Clone, PartialEq)]
pub struct LuminaireParts {
    /// The file it was read from, when it was read from a file.
    pub path: Option<PathBuf>,
    /// File format.
    pub format: Format,
    /// Format version as a short string (`LM-63-2002`, `LM-63-1986`, `EULUMDAT`).
    pub version: String,
    /// Photometric type of the file's grid.
    pub photometric_type: PhotometricType,
    /// Descriptive text.
    pub metadata: Metadata,
    /// Lamp sets (at least one).
    pub lamp_sets: Vec<LampSet>,
    /// Luminaire dimensions, m.
    pub dimensions: Dimensions,
    /// Luminous opening dimensions, m.
    pub luminous_opening: Dimensions,
    /// Heights of the luminous area at C0, C90, C180 and C270, m (EULUMDAT
    /// lines 19-22); `None` when the file gives one height (IES, TM-33).
    pub luminous_heights_m: Option<[f64; 4]>,
    /// What the file declares.
    pub declared: Declared,
    /// The file's TILT declaration.
    pub tilt: Tilt,
    /// Type C distribution, absolute cd, untilted.
    pub distribution: Distribution,
    /// Original Type A/B grid (None for Type C files).
    pub source_grid: Option<SourceGrid>,
    /// Recoverable oddities found while reading.
    pub warnings: Vec<Warning>,
    /// The luminaire's front (its format's convention unless the user gave one).
    pub front: Front,
}

/// A loaded luminaire. See the module docs for what is guaranteed.
///
/// The fields are private so that the guarantees hold: at least one lamp
/// set, a tilt table with one multiplier per angle, a source grid of the
/// size its angle lists say and that describes the distribution (replacing
/// the distribution with [`Luminaire::set_distribution`] drops it).
#[derive(Debug, Clone, PartialEq)]
pub struct Luminaire {
    parts: LuminaireParts,
}

impl Luminaire {
    /// A luminaire around `distribution` with empty metadata (one lamp set,
    /// absolute photometry), as synthetic distributions need.
    pub fn from_distribution(distribution: Distribution) -> Self {
        Self {
            parts: LuminaireParts {
                path: None,
                format: Format::Ldt,
                version: String::new(),
                photometric_type: PhotometricType::C,
                metadata: Metadata::default(),
                lamp_sets: vec![LampSet {
                    count: 1.0,
                    ..LampSet::default()
                }],
                dimensions: Dimensions::default(),
                luminous_opening: Dimensions::default(),
                luminous_heights_m: None,
                declared: Declared {
                    absolute: true,
                    ..Declared::default()
                },
                tilt: Tilt::None,
                distribution,
                source_grid: None,
                warnings: Vec::new(),
                front: Front::convention(Format::Ldt),
            },
        }
    }

    /// A luminaire from its parts, checking what the type guarantees.
    ///
    /// # Errors
    /// [`ModelError::Parameter`] for no lamp set, a tilt table whose angle and
    /// multiplier lists differ in length, or a source grid whose table does
    /// not have one value per (horizontal, vertical) pair.
    pub fn from_parts(parts: LuminaireParts) -> Result<Self, ModelError> {
        let bad = |name: &'static str, value: String, reason: &str| ModelError::Parameter {
            name,
            value,
            reason: reason.into(),
        };
        if parts.lamp_sets.is_empty() {
            return Err(bad("lamp_sets", "[]".into(), "a luminaire has at least one lamp set"));
        }
        if let Some(t) = parts.tilt.table() {
            if t.angles.len() != t.multipliers.len() {
                return Err(bad(
                    "tilt",
                    format!("{} angles, {} multipliers", t.angles.len(), t.multipliers.len()),
                    "a tilt table has one multiplier per angle",
                ));
            }
        }
        if let Some(g) = &parts.source_grid {
            if g.vertical.len().checked_mul(g.horizontal.len()) != Some(g.cd.len()) {
                return Err(bad(
                    "source_grid",
                    format!(
                        "{} x {} angles, {} values",
                        g.horizontal.len(),
                        g.vertical.len(),
                        g.cd.len()
                    ),
                    "one value per (horizontal, vertical) angle pair",
                ));
            }
        }
        Ok(Self { parts })
    }

    /// The parts, to rebuild a changed luminaire with [`Luminaire::from_parts`].
    pub fn into_parts(self) -> LuminaireParts {
        self.parts
    }

    /// The file it was read from, when it was read from a file.
    pub fn path(&self) -> Option<&std::path::Path> {
        self.parts.path.as_deref()
    }
    /// File format.
    pub fn format(&self) -> Format {
        self.parts.format
    }
    /// Format version as a short string (`LM-63-2002`, `LM-63-1986`, `EULUMDAT`).
    pub fn version(&self) -> &str {
        &self.parts.version
    }
    /// Photometric type of the file's grid.
    pub fn photometric_type(&self) -> PhotometricType {
        self.parts.photometric_type
    }
    /// Descriptive text.
    pub fn metadata(&self) -> &Metadata {
        &self.parts.metadata
    }
    /// Lamp sets (at least one).
    pub fn lamp_sets(&self) -> &[LampSet] {
        &self.parts.lamp_sets
    }
    /// Luminaire dimensions, m.
    pub fn dimensions(&self) -> Dimensions {
        self.parts.dimensions
    }
    /// Luminous opening dimensions, m.
    pub fn luminous_opening(&self) -> Dimensions {
        self.parts.luminous_opening
    }
    /// Heights of the luminous area at C0, C90, C180 and C270, m, when the
    /// file gives four (EULUMDAT).
    pub fn luminous_heights_m(&self) -> Option<[f64; 4]> {
        self.parts.luminous_heights_m
    }
    /// What the file declares.
    pub fn declared(&self) -> &Declared {
        &self.parts.declared
    }
    /// The file's TILT declaration.
    pub fn tilt(&self) -> &Tilt {
        &self.parts.tilt
    }
    /// Type C distribution, absolute cd, untilted.
    pub fn distribution(&self) -> &Distribution {
        &self.parts.distribution
    }
    /// The distribution, without the rest of the luminaire.
    pub fn into_distribution(self) -> Distribution {
        self.parts.distribution
    }
    /// Original Type A/B grid (None for Type C files and after
    /// [`Luminaire::set_distribution`]).
    pub fn source_grid(&self) -> Option<&SourceGrid> {
        self.parts.source_grid.as_ref()
    }
    /// The luminaire's front: the C angle (degrees, file frame) at the middle
    /// of its forward half, and where that came from ([`crate::model::front`]).
    pub fn front(&self) -> Front {
        self.parts.front
    }
    /// Replace the front (a user's `--front`, or a conversion's).
    pub fn set_front(&mut self, front: Front) {
        self.parts.front = front;
    }
    /// Recoverable oddities found while reading.
    pub fn warnings(&self) -> &[Warning] {
        &self.parts.warnings
    }

    /// Descriptive text, to edit.
    pub fn metadata_mut(&mut self) -> &mut Metadata {
        &mut self.parts.metadata
    }
    /// What the file declares, to edit.
    pub fn declared_mut(&mut self) -> &mut Declared {
        &mut self.parts.declared
    }
    /// Set the format version string.
    pub fn set_version(&mut self, version: impl Into<String>) {
        self.parts.version = version.into();
    }
    /// Set the luminous opening, m (and drop per-side heights, which belong
    /// to the old opening).
    pub fn set_luminous_opening(&mut self, opening: Dimensions) {
        self.parts.luminous_opening = opening;
        self.parts.luminous_heights_m = None;
    }
    /// Replace the distribution. The Type A/B source grid no longer
    /// describes it and is dropped, so a writer writes the new Type C grid.
    pub fn set_distribution(&mut self, distribution: Distribution) {
        self.parts.distribution = distribution;
        self.parts.source_grid = None;
    }
    /// Replace the lamp sets.
    ///
    /// # Errors
    /// [`ModelError::Parameter`] when `lamp_sets` is empty.
    pub fn set_lamp_sets(&mut self, lamp_sets: Vec<LampSet>) -> Result<(), ModelError> {
        if lamp_sets.is_empty() {
            return Err(ModelError::Parameter {
                name: "lamp_sets",
                value: "[]".into(),
                reason: "a luminaire has at least one lamp set".into(),
            });
        }
        self.parts.lamp_sets = lamp_sets;
        Ok(())
    }
    /// Add a warning.
    pub fn push_warning(&mut self, warning: Warning) {
        self.parts.warnings.push(warning);
    }
    /// Set the path it was read from (a GLDF member is named `FILE.gldf#ID`).
    pub fn set_path(&mut self, path: PathBuf) {
        self.parts.path = Some(path);
    }

    /// The distribution as installed at `tilt_deg` degrees: every value
    /// multiplied by the tilt table's multiplier at that angle. Fails when
    /// the file has no tilt table.
    pub fn tilted_distribution(&self, tilt_deg: f64) -> Result<Distribution, ModelError> {
        match self.parts.tilt.table() {
            Some(t) => self.parts.distribution.scaled(t.multiplier_at(tilt_deg)),
            None => Err(ModelError::Parameter {
                name: "tilt",
                value: tilt_deg.to_string(),
                reason: "the file has no tilt table (TILT=NONE)".into(),
            }),
        }
    }
}
