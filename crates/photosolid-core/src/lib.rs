//! The core of photosolid: what a program needs to read photometric files
//! and compute photometry, without the reconstruction, GPU, report or CLI
//! layers (and without their dependencies: no wgpu, Arrow/Parquet, clap or
//! tiny-skia).
//!
//! Layers, bottom up (each only uses the ones before it; the crate boundary
//! makes the compiler hold the line between this crate and the rest):
//! [`numfmt`] (number formatting) < [`minimize`] (derivative-free
//! minimisers) < [`error`] (errors, warnings, stable
//! codes) < [`model`] (the luminaire, its distribution, frames) <
//! [`formats`] (IES LM-63, EULUMDAT, TM-33-23, GLDF readers and writers) <
//! [`photometry`] (flux, zonal tables, beams, UGR, luminance, BUG) <
//! [`synth`] (analytic distributions).
//!
//! The `photosolid` crate re-exports every module here at its own root
//! (`photosolid::model::Luminaire` is `photosolid_core::model::Luminaire`).

#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod error;
pub mod formats;
pub mod minimize;
pub mod model;
pub mod numfmt;
pub mod photometry;
pub mod synth;

pub use error::{Error, ErrorKind, Location, ModelError, ParseError, Result, Warning};
pub use formats::{load, load_with, save, ReadOptions};
pub use model::{Distribution, Luminaire, Symmetry};
