//! The errors of mesh files ([`MeshError`]): reading a solid back, writing one.

use std::path::{Path, PathBuf};

use super::{Error, LayerError, Layered, Location, ModelError};

/// A mesh file that cannot be read, or a mesh that cannot be written.
#[non_exhaustive]
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MeshError {
    /// A mesh file (OBJ, PLY, STL or GLB) whose content is not a mesh the readers read:
    /// the file, the line (or byte), what was expected.
    #[error("{path}: cannot read the mesh: {source}", path = .path.display())]
    File {
        /// The file.
        path: PathBuf,
        /// What the mesh reader found wrong, and where (boxed: it is the largest variant).
        source: Box<MeshFileError>,
    },
    /// A mesh with no triangles where one with triangles is needed (a solid
    /// is never empty, and glTF cannot hold an empty mesh).
    #[error("{path}: the mesh has no triangles; expected at least one", path = .path.display())]
    Empty {
        /// The file that was to be written.
        path: PathBuf,
    },
}

impl LayerError for MeshError {
    fn code(&self) -> &'static str {
        match self {
            MeshError::File { .. } => "mesh-file",
            MeshError::Empty { .. } => "empty-mesh",
        }
    }

    fn location(&self) -> Option<Location> {
        match self {
            MeshError::File { source, .. } => Some(source.location()),
            MeshError::Empty { .. } => None,
        }
    }

    fn path(&self) -> Option<&Path> {
        match self {
            MeshError::File { path, .. } | MeshError::Empty { path } => Some(path),
        }
    }
}

impl From<MeshError> for Error {
    fn from(e: MeshError) -> Self {
        Error::Layer(Layered::new(e))
    }
}

/// What a mesh reader found wrong in a mesh file ([`MeshError::File`]).
#[non_exhaustive]
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MeshFileError {
    /// The bytes are not a mesh file of the format: where, what was expected, what was found.
    #[error("{format}{at}: expected {expected}, found {found}", at = mesh_at(.location, *.offset))]
    Syntax {
        /// "OBJ", "PLY", "STL" or "glTF".
        format: &'static str,
        /// The line of a text file or text header (line 0: binary data or the file as a whole).
        location: Location,
        /// The byte offset in the file, for binary data.
        offset: Option<usize>,
        /// What the reader expected, e.g. "3 numbers after `v`".
        expected: String,
        /// What it found, e.g. "`v 1 2`" or "end of file".
        found: String,
    },
    /// The file reads, but what it holds is not a mesh (a face indexing a
    /// vertex that does not exist, a coordinate that is not finite).
    #[error("{format}: {source}")]
    Mesh {
        /// "OBJ", "PLY", "STL" or "glTF".
        format: &'static str,
        /// The mesh invariant violated.
        source: ModelError,
    },
}

/// ` line N`, ` byte B`, both or nothing.
fn mesh_at(location: &Location, offset: Option<usize>) -> String {
    let mut s = String::new();
    if location.line > 0 {
        s.push_str(&format!(" line {}", location.line));
    }
    if let Some(b) = offset {
        s.push_str(&format!(" byte {b}"));
    }
    s
}

impl MeshFileError {
    /// A syntax error on `line` (0: none) of a text format.
    pub fn at_line(format: &'static str, line: usize, expected: impl Into<String>, found: impl Into<String>) -> Self {
        MeshFileError::Syntax {
            format,
            location: Location::line(line),
            offset: None,
            expected: expected.into(),
            found: found.into(),
        }
    }

    /// A syntax error at byte `offset` (`None`: the file as a whole) of a binary format.
    pub fn at_byte(
        format: &'static str,
        offset: Option<usize>,
        expected: impl Into<String>,
        found: impl Into<String>,
    ) -> Self {
        MeshFileError::Syntax {
            format,
            location: Location::default(),
            offset,
            expected: expected.into(),
            found: found.into(),
        }
    }

    /// Where the error is, as a [`Location`] (line 0 when it has no line).
    pub fn location(&self) -> Location {
        match self {
            MeshFileError::Syntax { location, .. } => *location,
            MeshFileError::Mesh { .. } => Location::default(),
        }
    }
}
