//! The errors of scenes ([`SceneError`]), this crate's own.

use std::path::{Path, PathBuf};

use crate::error::{Error, LayerError, Layered, Location, ModelError};

/// Everything that can go wrong with a scene (it converts into [`Error`] with `From`; I/O and
/// encoding failures of scene reports are [`Error::Io`] and [`Error::Encode`]).
#[non_exhaustive]
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SceneError {
    /// A value in the scene file is malformed or outside its domain.
    #[error("{path}{line}: {message}", path = .path.display(), line = .location.suffix())]
    Invalid {
        /// The scene file.
        path: PathBuf,
        /// Line of the offending table or value (line 0: the whole file).
        location: Location,
        /// What was expected and what was found.
        message: String,
    },
    /// A receiver point lies on or inside a luminaire's luminous opening:
    /// the illuminance there is not defined.
    #[error(
        "receiver {receiver:?} point #{index} at ({x}, {y}, {z}) m lies inside the luminous opening of luminaire \
         {luminaire:?} ({opening}); move the point or the luminaire",
        x = .position[0], y = .position[1], z = .position[2]
    )]
    InsideOpening {
        /// Receiver name.
        receiver: String,
        /// 1-based point number within the receiver.
        index: usize,
        /// The point, world metres.
        position: [f64; 3],
        /// Luminaire name.
        luminaire: String,
        /// The opening, in words.
        opening: String,
    },
    /// A luminaire's model could not be built (e.g. a render past its size limit).
    #[error("luminaire {luminaire:?}: {source}")]
    Model {
        /// Luminaire name.
        luminaire: String,
        /// The model error.
        source: ModelError,
    },
}

impl SceneError {
    /// The stable code of this error in [`crate::error::ErrorRecord::code`]:
    /// `scene-invalid`, `inside-opening`, or the luminaire's [`ModelError::code`].
    pub fn code(&self) -> &'static str {
        match self {
            SceneError::Invalid { .. } => "scene-invalid",
            SceneError::InsideOpening { .. } => "inside-opening",
            SceneError::Model { source, .. } => source.code(),
        }
    }
}

impl LayerError for SceneError {
    fn code(&self) -> &'static str {
        SceneError::code(self)
    }

    fn location(&self) -> Option<Location> {
        match self {
            SceneError::Invalid { location, .. } => Some(*location),
            _ => None,
        }
    }

    fn path(&self) -> Option<&Path> {
        match self {
            SceneError::Invalid { path, .. } => Some(path),
            _ => None,
        }
    }
}

impl From<SceneError> for Error {
    fn from(e: SceneError) -> Self {
        Error::Layer(Layered::new(e))
    }
}
