//! The Whitted ray tracer: rays (`half_line`, `packet`), their intersection tests, each mesh's
//! BVH (`bvh`, built by `bvh_build`), the scene's acceleration structure (`accel`), and the
//! tracer itself.

mod accel;
mod alpha_cut;
mod bvh;
mod bvh_buffer;
mod bvh_build;
mod bvh_prims;
mod bvh_sah;
#[cfg(target_arch = "x86_64")]
mod bvh_sah_avx2;
mod half_line;
mod intersect;
mod packet;
#[cfg(target_arch = "x86_64")]
mod packet_avx2;
mod primary;
mod top_level;
mod tracer;
mod triangle_lanes;

pub(crate) use accel::SceneAccel;
pub(crate) use primary::{primary_coverage, primary_hits};
pub(crate) use tracer::trace_into;

#[cfg(test)]
mod tests;
