//! Arithmetic on eight f32 lanes at a time, written once for one lane or eight: the lane types
//! (`lanes`), 3-vectors of lanes (`lane_vec`), `pow` for the specular highlight and a coarse
//! `log2` for the texture level of detail.

#[cfg(target_arch = "x86_64")]
mod avx;
#[cfg(target_arch = "x86_64")]
mod avx512;
mod coarse_log2;
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
pub(crate) use coarse_log2::coarse_log2;
pub(crate) use pow::pow;
