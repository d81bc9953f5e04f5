//! Reports: what the CLI prints, as typed, serialisable values.

pub mod color;
pub mod info;

pub use info::InfoReport;
