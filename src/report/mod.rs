//! Reports: what the CLI prints, as typed, serialisable values.

pub mod info;
pub mod plots;

pub use info::InfoReport;
