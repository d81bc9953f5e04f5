//! The middle layers of photosolid, above [`photosolid_core`]:
//! [`reconstruct`] (filters, light textures, stored lookups, compact
//! forms) < [`device`] (what the layers above ask of a GPU: a trait that
//! `photosolid-gpu` implements and a program installs at start-up, so no
//! crate here depends on wgpu) < [`fit`] (fitted OpenGL lights, lobe mixtures) <
//! [`metrics`] (certified Hausdorff distance, profiles, radial errors,
//! costs) < [`solid`] (meshes of any field, adaptive grids, the measured
//! solid, exports). Each module only uses the ones before it and the core.
//!
//! The `photosolid` crate re-exports every module here at its own root.

#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub use photosolid_core::{formats, minimize, model, numfmt, photometry, synth};
pub use photosolid_core::{load, load_with, save, ReadOptions};
pub use photosolid_core::{Distribution, Luminaire, Symmetry};
pub use photosolid_core::{Error, ErrorKind, Location, ModelError, ParseError, Result, Warning};

pub mod device;
pub mod error;
pub mod fit;
pub mod metrics;
pub mod reconstruct;
pub mod solid;
