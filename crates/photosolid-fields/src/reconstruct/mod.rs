//! Reconstruction of the photometric solid between measured directions.
//!
//! One [`Filter`] type serves every consumer. A [`LightTexture`] (Wallner
//! 2008) stores the measured grid normalised by I_max, only as large as the
//! data needs; a [`Sampler`] looks it up by angle or direction in f64 (the
//! reference), [`render`] resamples it into a denser f32 texture through
//! per-axis tap tables ([`AxisTaps`], [`RenderPlan`]) that a GPU shader
//! consumes unchanged.
//!
//! # On the sphere
//! - C is periodic: the C axis is the full-circle plane list
//!   ([`crate::model::Distribution::full_planes`]), queries are wrapped, so
//!   C = 0 and C = 360 are one plane whatever the symmetry.
//! - Across the poles the γ axis reads ghost rows from the plane C + 180
//!   (see [`texture`] for the non-uniform case and the band edges).
//! - Outside the measured γ band the intensity is 0; nothing is extrapolated.
//! - Tensor order: γ first (within each of the C taps' planes), then C.
//! - Interpolating filters (nearest, bilinear, catmull-rom, pchip) use the
//!   knots' own positions and return every measured value at its direction;
//!   approximating ones (mitchell, bspline) use the fraction between knots.
//! - Cubic overshoot below 0 is clamped to 0 by default, and counted.

mod axis;
pub mod backend;
pub mod bc6h;
pub mod compact;
pub mod exr_io;
mod filter;
pub mod holdout;
pub mod lobes;
mod lookup;
mod sampler;
pub mod sh;
mod spec;
pub mod texture;

pub use axis::AxisTaps;
pub use backend::Backend;
pub use compact::Compact;
pub use filter::{combine, Filter, Real, FILTER_NAMES};
pub use holdout::{holdout, holdout_split, kfold, Fold, HoldoutReport, HoldoutSpec, HoldoutSplit};
pub use lobes::{Lobe, Lobes};
pub use lookup::{Lookup, Precision, StoredTexture};
pub use sampler::Sampler;
pub use sh::{ShField, ShWindow, MAX_SH_DEGREE, MAX_ZONAL_SH_DEGREE};
pub use spec::TextureSpec;
pub use texture::{
    render, render_planned, render_with, GhostKind, LightTexture, RenderOptions, RenderPlan, Rendered, TexelMapping,
    DEFAULT_FACTOR, MAX_RENDER_TEXELS,
};

use crate::model::IntensityField;

/// Evaluate `field` at every (C, γ) of `dirs` (degrees): in parallel, or as
/// one batch for a field that answers batches ([`IntensityField::intensity_batch_cd`]).
pub fn eval_all(field: &dyn IntensityField, dirs: &[(f64, f64)]) -> Vec<f64> {
    field.intensity_batch_cd(dirs)
}
