//! Reports: what the CLI prints and draws, as typed, serialisable values and PNG plots.

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
