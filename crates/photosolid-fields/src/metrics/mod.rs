//! Metrics between photometric solids and distributions.

pub mod bvh;
pub mod cells;
pub mod cost;
pub mod hausdorff;
pub mod largest;
pub mod nearest;
pub mod profile;
pub mod radial;
mod refine;
mod walls;

pub use bvh::Bvh;
pub use cost::{pareto_front, random_directions, time_per_sample_ns};
pub use hausdorff::{
    corresponding_bounds, hausdorff, hausdorff_bvh, hausdorff_bvh_below_bounds, hausdorff_bvh_bounded,
    hausdorff_bvh_bounded_within, one_sided, one_sided_below_bounds, one_sided_bounded, one_sided_bounded_within,
    Hausdorff, MeshRef, OneSided, Side,
};
pub use largest::{largest_of, LargestDistance};
pub use nearest::{distance_to_solid, distances_to_solid, largest_distance_to_solid, NearestSearch};
pub use radial::{
    field_radial_errors, radial_errors, refine_max, DirectionSet, MaxRefinement, RadialErrors, RefinedMax,
    MAX_REFINEMENT, ZOTTI_C,
};
