//! EULUMDAT (.ldt): reader and writer.

use std::path::Path;

use serde::Serialize;

use crate::error::{ErrorKind, Location, ParseError};
use crate::formats::ReadOptions;
use crate::model::Luminaire;

/// The raw EULUMDAT header, kept so a file is written back losslessly.
#[derive(Debug, Clone, PartialEq, Serialize, Default)]
pub struct LdtHeader {}

/// Read an EULUMDAT file's bytes. `path` names the file in errors.
pub fn read(_bytes: &[u8], path: &Path, _opts: &ReadOptions) -> Result<Luminaire, ParseError> {
    Err(ParseError {
        path: path.to_path_buf(),
        location: Location::line(0),
        kind: ErrorKind::Unsupported,
        expected: "an EULUMDAT reader".into(),
        found: "none yet".into(),
    })
}

/// Write `lum` as EULUMDAT text.
pub fn write(_lum: &Luminaire) -> String {
    String::new()
}
