//! The luminaire: metadata around one [`Distribution`].
//!
//! Whatever the file format, a loaded luminaire has:
//! - a Type C [`Distribution`] in absolute candela, with every multiplier
//!   (IES candela multiplier, ballast factor, BLPF; EULUMDAT cd/klm × lamp
//!   flux / 1000) already applied, untilted;
//! - Type A and B data converted to Type C through direction vectors, the
//!   original grid kept in [`Luminaire::source_grid`] for writing back;
//! - the format's raw header (`ies` or `ldt`) so that a file is written back
//!   losslessly in its own format;
//! - every recoverable oddity as a [`Warning`].

use std::path::PathBuf;

use serde::Serialize;

use crate::error::{ModelError, Warning};
use crate::model::distribution::Distribution;

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

/// A loaded luminaire. See the module docs for what is guaranteed.
#[derive(Debug, Clone, PartialEq)]
pub struct Luminaire {
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
    /// Luminaire dimensions.
    pub dimensions: Dimensions,
    /// Luminous opening dimensions.
    pub luminous_opening: Dimensions,
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
    /// Raw IES header, when read from an IES file.
    pub ies: Option<crate::formats::ies::IesHeader>,
    /// Raw EULUMDAT header, when read from an LDT file.
    pub ldt: Option<crate::formats::ldt::LdtHeader>,
    /// What the GLDF container declares about this photometry, when it was
    /// read from one (`FILE.gldf#ID`).
    pub gldf: Option<crate::formats::gldf::GldfDeclared>,
}

impl Luminaire {
    /// A luminaire around `distribution` with empty metadata (one lamp set,
    /// absolute photometry), as synthetic distributions need.
    pub fn from_distribution(distribution: Distribution) -> Self {
        Self {
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
            declared: Declared {
                absolute: true,
                ..Declared::default()
            },
            tilt: Tilt::None,
            distribution,
            source_grid: None,
            warnings: Vec::new(),
            ies: None,
            ldt: None,
            gldf: None,
        }
    }

    /// The distribution as installed at `tilt_deg` degrees: every value
    /// multiplied by the tilt table's multiplier at that angle. Fails when
    /// the file has no tilt table.
    pub fn tilted_distribution(&self, tilt_deg: f64) -> Result<Distribution, ModelError> {
        match self.tilt.table() {
            Some(t) => self.distribution.scaled(t.multiplier_at(tilt_deg)),
            None => Err(ModelError::Parameter {
                name: "tilt",
                value: tilt_deg.to_string(),
                reason: "the file has no tilt table (TILT=NONE)".into(),
            }),
        }
    }
}
