//! The ray tracer's parts against answers worked out by hand or by brute force.

mod bvh;
mod bvh_partition;
mod intersect;
mod lane_leaves;
mod tracer;
mod watertight;
