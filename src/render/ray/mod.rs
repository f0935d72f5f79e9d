//! The Whitted ray tracer: rays (`half_line`, `packet`), their intersection tests, each mesh's
//! BVH (`bvh`, built by `bvh_build`), the scene's acceleration structure (`accel`), and the
//! tracer itself.

pub mod accel;
pub mod bvh;
mod bvh_build;
pub mod half_line;
pub mod intersect;
pub mod packet;
pub mod tracer;
