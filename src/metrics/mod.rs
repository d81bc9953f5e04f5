//! Metrics between photometric solids and distributions.

pub mod bvh;
pub mod hausdorff;

pub use bvh::Bvh;
pub use hausdorff::{hausdorff, one_sided, Hausdorff, MeshRef, OneSided};
