//! IES LM-63 (1986, 1991, 1995, 2002, 2019 and the 1994/1995 drafts): reader and writer.
//!
//! # Reading
//! Lines up to `TILT=` are text: an optional version line, `[KEYWORD] value`
//! lines (kept in order in [`IesHeader::labels`]) and, in 1986 files, free-form
//! label lines. Everything after `TILT=` is one stream of numbers separated by
//! blanks, commas or line ends (in IES a comma never is a decimal point).
//! Candela values become absolute: value × candela multiplier × ballast factor
//! (× ballast-lamp photometric factor for 1986 and 1991 files only). Type A and
//! B grids are converted to Type C through direction vectors (see
//! [`type_ab`]) and the original grid is kept in [`crate::model::Luminaire::source_grid`].
//! The tilt table is parsed and kept in [`crate::model::Luminaire::tilt`], never applied.
//!
//! # Warning codes
//! `unknown-version`, `missing-ballast-line`, `extra-values`, `angles-repaired`,
//! `pole-mismatch`, `negative-intensity`, `seam-mismatch`, `single-plane`,
//! `invalid-ballast-factor`, `invalid-blpf`, `invalid-lumens`, `tilt-file-keyword`,
//! `tilt-extra-values`.
//!
//! # Writing
//! See [`write()`]: LM-63-2002 or LM-63-2019 text with CRLF line ends.

mod grid;
mod read;
mod tilt;
pub mod type_ab;
mod write;

use serde::Serialize;

pub use read::read;
pub use tilt::MAX_TILT_FILE_BYTES;
pub use write::{type_c_planes, write};

/// One text line before `TILT=`, kept for lossless write-back.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
#[serde(tag = "kind", rename_all = "lowercase")]
pub enum IesLabel {
    /// `[KEY] value` (also `[MORE]` continuations and user keywords `[_NAME]`).
    Keyword {
        /// The keyword as written, without brackets (e.g. `MANUFAC`, `_Electric Parameters`).
        key: String,
        /// The value, decoded and trimmed (may be empty).
        value: String,
    },
    /// A free-form label line (1986 files, or non-keyword lines such as `GEOM=x.mgf`).
    Text(String),
}

/// The raw IES header, kept so a file is written back losslessly.
///
/// Numbers are as written in the file (no unit conversion, no multipliers applied).
#[derive(Debug, Clone, PartialEq, Serialize, Default)]
pub struct IesHeader {
    /// The version line as written (`IESNA:LM-63-2002`, `IESNA91`, ...); None for 1986 files.
    pub version_line: Option<String>,
    /// Keyword and label lines in file order.
    pub labels: Vec<IesLabel>,
    /// The value after `TILT=` as written (`NONE`, `INCLUDE`, a file name).
    pub tilt: String,
    /// Number of lamps.
    pub lamps: f64,
    /// Lumens per lamp, lm (−1: absolute photometry).
    pub lumens_per_lamp: f64,
    /// Candela multiplier.
    pub multiplier: f64,
    /// Number of vertical angles in the file.
    pub n_vertical: usize,
    /// Number of horizontal angles in the file.
    pub n_horizontal: usize,
    /// Photometric type code: 1 = C, 2 = B, 3 = A.
    pub photometric_type: u8,
    /// Units code: 1 = feet, 2 = metres.
    pub units: u8,
    /// Width of the luminous opening (along C90 / Y) in file units; the sign encodes shapes.
    pub width: f64,
    /// Length of the luminous opening (along C0 / X) in file units.
    pub length: f64,
    /// Height of the luminous opening (Z) in file units.
    pub height: f64,
    /// Ballast factor as written.
    pub ballast_factor: f64,
    /// Second value of the second record: ballast-lamp photometric factor (1986, 1991),
    /// future use (1995, 2002) or file-generation type (2019).
    pub future_use: f64,
    /// Input watts, W.
    pub input_watts: f64,
    /// False when the file omitted the ballast / future-use / watts record (non-conformant).
    pub ballast_record: bool,
}

impl IesHeader {
    /// Value of the first keyword `key` (case-insensitive), with `[MORE]`
    /// continuations appended after a space.
    pub fn keyword(&self, key: &str) -> Option<String> {
        let mut out: Option<String> = None;
        let mut in_key = false;
        for l in &self.labels {
            match l {
                IesLabel::Keyword { key: k, value } if out.is_none() && k.eq_ignore_ascii_case(key) => {
                    out = Some(value.clone());
                    in_key = true;
                }
                IesLabel::Keyword { key: k, value } if in_key && k.eq_ignore_ascii_case("MORE") => {
                    if let Some(o) = out.as_mut() {
                        if !o.is_empty() && !value.is_empty() {
                            o.push(' ');
                        }
                        o.push_str(value);
                    }
                }
                _ => {
                    if out.is_some() {
                        return out;
                    }
                }
            }
        }
        out
    }
}

/// Which LM-63 version the writer produces.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
pub enum IesWriteVersion {
    /// `IESNA:LM-63-2002` (default).
    #[default]
    Lm63_2002,
    /// `IES:LM-63-2019`.
    Lm63_2019,
}

impl std::str::FromStr for IesWriteVersion {
    type Err = crate::error::ModelError;
    /// `2002` or `2019`, as `convert --ies-version` writes it.
    fn from_str(s: &str) -> std::result::Result<Self, Self::Err> {
        match s.trim() {
            "2002" => Ok(IesWriteVersion::Lm63_2002),
            "2019" => Ok(IesWriteVersion::Lm63_2019),
            other => Err(crate::error::ModelError::Parameter {
                name: "ies_version",
                value: other.to_string(),
                reason: "expected 2002 (LM-63-2002, the default) or 2019".into(),
            }),
        }
    }
}
