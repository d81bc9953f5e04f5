//! Errors whose types the layers above this crate define ([`LayerError`]), carried by
//! [`super::Error::Layer`] and [`super::ModelError::Gpu`].
//!
//! Each crate owns its errors: the GPU's `GpuError` and the mesh files' `MeshError` live in
//! `photosolid-fields`, `SceneError` in `photosolid-scene`. They convert into this crate's
//! [`super::Error`] with `From`, so `?` works across the layers, and keep their type: a caller
//! gets it back with [`super::Error::downcast_ref`]. Their codes are in the one table,
//! [`super::ERROR_CODES`].

use std::fmt;
use std::path::Path;
use std::sync::Arc;

use super::Location;

/// An error type of a layer above this crate.
pub trait LayerError: std::error::Error + Send + Sync + 'static {
    /// Its stable code, one of [`super::ERROR_CODES`].
    fn code(&self) -> &'static str;

    /// Where in its file it is, when it names a line.
    fn location(&self) -> Option<Location> {
        None
    }

    /// The file it is about, when it names one.
    fn path(&self) -> Option<&Path> {
        None
    }
}

/// A [`LayerError`] of any type, shared: cloned with the error that carries it, and equal to
/// another when both give the same code and message.
#[derive(Clone)]
pub struct Layered(Arc<dyn LayerError>);

impl Layered {
    /// Carry `error`.
    pub fn new(error: impl LayerError) -> Self {
        Self(Arc::new(error))
    }

    /// The carried error's stable code.
    pub fn code(&self) -> &'static str {
        self.0.code()
    }

    /// Where in its file the carried error is, when it names a line.
    pub fn location(&self) -> Option<Location> {
        self.0.location()
    }

    /// The file the carried error is about, when it names one.
    pub fn path(&self) -> Option<&Path> {
        self.0.path()
    }

    /// The carried error as its own type `T`, when it is one.
    pub fn downcast_ref<T: LayerError>(&self) -> Option<&T> {
        let error: &(dyn std::error::Error + 'static) = &*self.0;
        error.downcast_ref()
    }
}

impl fmt::Debug for Layered {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Debug::fmt(&*self.0, f)
    }
}

impl fmt::Display for Layered {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Display::fmt(&*self.0, f)
    }
}

impl PartialEq for Layered {
    fn eq(&self, other: &Self) -> bool {
        self.code() == other.code() && self.to_string() == other.to_string()
    }
}

impl std::error::Error for Layered {
    /// The carried error's own source: a [`Layered`] is transparent (it prints as the carried
    /// error), so a chain printed from it does not repeat that error's message.
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        self.0.source()
    }
}
