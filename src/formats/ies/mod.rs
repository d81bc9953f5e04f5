//! IES LM-63 (1986, 1991, 1995, 2002, 2019 and the 1994/1995 drafts): reader and writer.

use std::path::Path;

use serde::Serialize;

use crate::error::{ErrorKind, Location, ParseError};
use crate::formats::ReadOptions;
use crate::model::Luminaire;

/// The raw IES header, kept so a file is written back losslessly.
#[derive(Debug, Clone, PartialEq, Serialize, Default)]
pub struct IesHeader {}

/// Which LM-63 version the writer produces.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
pub enum IesWriteVersion {
    /// `IESNA:LM-63-2002` (default).
    #[default]
    Lm63_2002,
    /// `IES:LM-63-2019`.
    Lm63_2019,
}

/// Read an IES file's bytes. `path` names the file in errors and locates `TILT=<file>`.
pub fn read(_bytes: &[u8], path: &Path, _opts: &ReadOptions) -> Result<Luminaire, ParseError> {
    Err(ParseError {
        path: path.to_path_buf(),
        location: Location::line(0),
        kind: ErrorKind::Unsupported,
        expected: "an IES reader".into(),
        found: "none yet".into(),
    })
}

/// Write `lum` as IES text.
pub fn write(_lum: &Luminaire, _version: IesWriteVersion) -> String {
    String::new()
}
