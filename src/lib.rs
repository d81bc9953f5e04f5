//! photosolid: read, analyse, reconstruct and compare the photometric solids
//! of real luminaires.
//!
//! The pipeline is the architecture:
//! - [`formats`]: IES LM-63 and EULUMDAT readers and writers, in and out;
//! - [`model`]: the one canonical model, a [`Luminaire`] holding a Type C
//!   [`Distribution`] in absolute candela;
#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod error;
pub mod formats;
pub mod model;
pub mod reconstruct;

pub use error::{Error, ErrorKind, Location, ModelError, ParseError, Result, Warning};
pub use formats::{load, load_with, save, ReadOptions};
pub use model::{Distribution, Luminaire, Symmetry};
