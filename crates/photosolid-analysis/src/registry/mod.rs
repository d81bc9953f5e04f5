//! The registry: every choice a user makes by name, built from the layers
//! below. [`Recon`] names a reconstruction (`--recon`, the trade table's
//! rows) and [`Reconstructions`] builds each as an
//! [`IntensityField`](crate::model::IntensityField): filters and stored
//! textures from [`crate::reconstruct`], the fitted lights from
//! [`crate::fit`], the measured solid from [`crate::solid`], the GPU's
//! texture hardware from `crate::gpu` (feature `gpu`), the cropped and
//! re-stored grids a scene's plan offers ([`owned`]). [`render_on`]
//! renders a texture on the [`Backend`](crate::reconstruct::Backend) chosen
//! with `--backend`. A caller adds a representation of its own to a
//! [`Registry`], the value the jobs take ([`extension`]): its names then
//! parse as a [`Recon`], and the jobs given that registry list it.
//!
//! It sits above everything it chooses among, so that those never import
//! each other to offer a choice (ARCHITECTURE.md, "Layers").

pub mod builtin;
pub mod extension;
pub mod owned;
pub mod recon;
mod render;

pub use builtin::{Job, Visible};
pub use extension::{ExtensionId, Registry, Representation};
pub use owned::{crop, OwnedSampler};
pub use recon::{Recon, Reconstructions, GPU_SUFFIX, LOBES_PREFIX, SH_PREFIX};
pub use render::{render_on, RenderedOn};
