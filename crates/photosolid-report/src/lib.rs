//! Reports: what the CLI prints and draws, as typed, serialisable values and PNG plots.
//!
//! The presentation layer of photosolid, above `photosolid-scene` (the one crate that depends on
//! tiny-skia); `photosolid` re-exports it as `photosolid::report`.

#![forbid(unsafe_code)]
#![warn(missing_docs)]

// The layers below, under the names this crate's modules use (`crate::model`, ...).
use photosolid_analysis::{
    compare, device, engines, error, formats, metrics, model, numfmt, photometry, reconstruct, registry, solid,
};
use photosolid_analysis::{Error, Result};
use photosolid_scene as scene;

pub mod color;
pub mod compare_report;
pub mod declared;
pub mod engines_report;
pub mod font;
pub mod info;
pub mod plot;
pub mod road_report;
pub mod scene_report;
pub mod shading;
pub mod viewer;

pub use info::InfoReport;

pub use crate::numfmt::significant;
