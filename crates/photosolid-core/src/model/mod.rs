//! One canonical model: a [`Luminaire`] holding a Type C [`Distribution`] in candela.

pub mod distribution;
pub mod field;
pub mod frame;
pub mod front;
pub mod luminaire;
pub mod opening;

pub use distribution::{
    check_intensities, flush_round_off, periodic_widths, wrap360, Distribution, GammaRange, Symmetry, ANGLE_EPS,
    MAX_CD, MIN_PEAK_CD,
};
pub use field::{Borrowed, ConstantCells, IntensityField, Rim, ZERO_FRACTION};
pub use front::{Front, FrontSource};
/// A progress report: `(done, total, what is being measured now)`.
pub type Progress<'a> = dyn Fn(usize, usize, &str) + Sync + 'a;

pub use luminaire::{
    Declared, Dimensions, Format, LampSet, Luminaire, LuminaireParts, Metadata, PhotometricType, SourceGrid, Tilt,
    TiltTable,
};
