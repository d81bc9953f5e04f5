//! photosolid: read, analyse, reconstruct and compare the photometric solids
//! of real luminaires.
//!
//! The pipeline is the architecture:
//! - [`formats`]: IES LM-63 and EULUMDAT readers and writers, in and out;
//! - [`model`]: the one canonical model, a [`Luminaire`] holding a Type C
//!   [`Distribution`] in absolute candela;
//! - [`photometry`]: flux, light output ratios, beam and field angles;
//! - [`synth`]: analytic distributions with closed-form answers;
//! - [`engines`]: renderers' light-profile layouts and emulated lookups;
//! - [`jobs`]: what each command computes, from loaded documents and its options.
//!
//! ```
//! use photosolid::{photometry, synth};
//! let grid = synth::GridSpec::uniform(15.0, 5.0).unwrap();
//! let lum = synth::Synth::Isotropic.build(&grid, 1.0).unwrap();
//! let flux = photometry::flux(lum.distribution()).total_lm;
//! assert!((flux - 4.0 * std::f64::consts::PI).abs() < 1e-9); // 4π lm per cd
//! ```
#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod batch;
pub mod jobs;

pub use photosolid_analysis::{compare, engines, registry};
pub use photosolid_core::{formats, minimize, model, numfmt, photometry, synth};

/// Every error of the library under one path: the core's [`Error`] with its kinds, codes
/// and warnings, and the error types the layers above define, each in its own crate
/// ([`error::GpuError`] and [`error::MeshError`] in `photosolid-fields`,
/// [`error::SceneError`] in `photosolid-scene`), which convert into [`Error`] with `From`.
pub mod error {
    pub use photosolid_fields::error::*;
    pub use photosolid_scene::SceneError;
}
pub use photosolid_fields::{device, fit, metrics, reconstruct, solid};
#[cfg(feature = "gpu")]
pub use photosolid_gpu as gpu;
pub use photosolid_report as report;
pub use photosolid_scene as scene;

pub use error::{Error, ErrorKind, Location, ModelError, ParseError, Result, Warning};
pub use formats::{load, load_with, save, ReadOptions};
pub use model::{Distribution, Luminaire, Symmetry};
