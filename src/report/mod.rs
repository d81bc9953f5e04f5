//! Reports: what the CLI prints, as typed, serialisable values, and the PNG
//! plots that go with them.

pub mod font;
pub mod info;
pub mod plots;

pub use info::InfoReport;
