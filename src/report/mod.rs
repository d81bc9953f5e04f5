//! Reports: what the CLI prints, as typed, serialisable values.

pub mod compare_report;
pub mod info;
pub mod plots;

pub use info::InfoReport;
