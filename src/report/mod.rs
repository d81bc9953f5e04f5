//! Reports: what the CLI prints and draws, as typed, serialisable values and PNG plots.

pub mod color;
pub mod compare_report;
pub mod engines_report;
pub mod font;
pub mod info;
pub mod plots;

pub use info::InfoReport;
