//! The errors of this crate's layers beside the core's, under one path: everything of
//! [`photosolid_core::error`], and [`GpuError`] (the GPU a [`crate::device::GpuDevice`] drives)
//! and [`MeshError`] (mesh files: reading and writing solids), which this crate defines.
//! Both convert into [`Error`] with `From` ([`Error::Layer`]); [`Error::downcast_ref`] gives
//! them back.

pub use photosolid_core::error::*;

mod gpu;
mod mesh;

pub use gpu::GpuError;
pub use mesh::{MeshError, MeshFileError};
