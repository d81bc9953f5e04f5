//! Metrics between photometric solids and distributions.

pub mod bvh;
pub mod hausdorff;
pub mod radial;

pub use bvh::Bvh;
pub use hausdorff::{hausdorff, one_sided, Hausdorff, MeshRef, OneSided};
pub use radial::{radial_errors, DirectionSet, RadialErrors, ZOTTI_C};
