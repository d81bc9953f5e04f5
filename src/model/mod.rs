//! One canonical model: a [`Luminaire`] holding a Type C [`Distribution`] in candela.

pub mod distribution;
pub mod field;
pub mod frame;
pub mod luminaire;

pub use distribution::{periodic_widths, wrap360, Distribution, GammaRange, Symmetry, ANGLE_EPS};
pub use field::{Borrowed, IntensityField};
pub use luminaire::{
    Declared, Dimensions, Format, LampSet, Luminaire, Metadata, PhotometricType, SourceGrid, Tilt, TiltTable,
};
