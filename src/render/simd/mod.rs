//! Arithmetic on eight f32 lanes at a time, written once for one lane or eight: the lane types
//! (`lanes`), 3-vectors of lanes (`lane_vec`), and `pow` for the specular highlight.

#[cfg(target_arch = "x86_64")]
mod avx;
#[cfg(target_arch = "x86_64")]
mod avx512;
mod lane_vec;
mod lanes;
mod pow;
mod twice;

pub(crate) use lane_vec::V3;
pub(crate) use lanes::{F32x8, Lanes, Lanes8, LanesJob, ROUND_MAGIC, WIDTH, load};

#[cfg(target_arch = "x86_64")]
pub(crate) use avx::run_on_best_lanes;

/// Runs `job` on [`F32x8`]: there are no wider registers to choose on this architecture.
#[cfg(not(target_arch = "x86_64"))]
#[inline(always)]
pub(crate) fn run_on_best_lanes<J: LanesJob>(job: J) -> J::Output {
    job.run::<F32x8>()
}
pub(crate) use pow::{log2, pow};
