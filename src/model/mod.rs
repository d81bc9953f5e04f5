//! One canonical model: a [`Luminaire`] holding a Type C [`Distribution`] in candela.

pub mod distribution;
pub mod field;
pub mod frame;
pub mod luminaire;

pub use distribution::{
    check_intensities, flush_round_off, periodic_widths, wrap360, Distribution, GammaRange, Symmetry, ANGLE_EPS,
    MAX_CD, MIN_PEAK_CD,
};
pub use field::{Borrowed, IntensityField};
pub use luminaire::{
    Declared, Dimensions, Format, LampSet, Luminaire, LuminaireParts, Metadata, PhotometricType, SourceGrid, Tilt,
    TiltTable,
};
