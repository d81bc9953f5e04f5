//! Metrics between photometric solids and distributions.

pub mod bvh;
pub mod cost;
pub mod hausdorff;
pub mod profile;
pub mod radial;

pub use bvh::Bvh;
pub use cost::{pareto_front, random_directions, time_per_sample_ns};
pub use hausdorff::{hausdorff, hausdorff_bvh, one_sided, Hausdorff, MeshRef, OneSided};
pub use radial::{radial_errors, DirectionSet, RadialErrors, ZOTTI_C};
