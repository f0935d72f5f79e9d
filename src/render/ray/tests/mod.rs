//! The ray tracer's parts against answers worked out by hand or by brute force.

mod bvh;
#[cfg(target_arch = "x86_64")]
mod bvh_bins;
mod bvh_partition;
mod instances;
mod intersect;
mod lane_leaves;
mod top_level;
mod tracer;
mod watertight;
