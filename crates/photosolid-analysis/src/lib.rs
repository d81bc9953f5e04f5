//! The analysis layers of photosolid, above [`photosolid_fields`]:
//! [`registry`] (every representation by name: `--recon`, the trade table's
//! rows, scene files; the representations a caller registers) < [`compare`]
//! (fields against a reference: `Comparison`, the trade table, hold-out
//! folds) < [`engines`] (each renderer's light-profile layout, written out
//! and its lookup emulated). Each module only uses the ones before it and the
//! crates below.
//!
//! The `photosolid` crate re-exports every module here at its own root.

#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub use photosolid_fields::{device, error, fit, formats, metrics, minimize, model, numfmt, photometry, reconstruct};
pub use photosolid_fields::{load, load_with, save, ReadOptions};
pub use photosolid_fields::{solid, synth};
pub use photosolid_fields::{Distribution, Luminaire, Symmetry};
pub use photosolid_fields::{Error, ErrorKind, Location, ModelError, ParseError, Result, Warning};

pub mod compare;
pub mod engines;
pub mod registry;
