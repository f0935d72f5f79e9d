//! Run-time choice of the instructions the scalar parts of the hot loops compile to.
//!
//! The build targets baseline x86-64. Where the CPU has AVX2, BMI1/2 and LZCNT, [`with_avx2`]
//! runs its work compiled for them: VEX three-operand forms for the `f64` and `i64` arithmetic
//! of triangle setup, BMI shifts and bit scans. Fused multiply-add is not enabled, and no
//! operation changes, so the results are the same bits either way.
//!
//! Measured gain, the reason for the `unsafe` here: see [`with_avx2`].
#![allow(unsafe_code)]

/// Runs `work` compiled for AVX2, BMI1/2 and LZCNT where this CPU has them (detected once, then
/// cached flags), else as built. `work` and what it calls must be inlined into it to gain
/// (`#[inline(always)]`); its results do not depend on the choice.
///
/// Measured on the bunny (`../shared/perf/bunny.toml`, 69k triangles) at 160×96 on 1 thread,
/// the Z-buffer's triangle setup, binning and planes of the varying run through it or not,
/// alternating three times, frames of a kept renderer (min of 1,000): Gouraud 1.20–1.25 →
/// 1.13–1.16 ms, Phong 1.15–1.17 → 1.09–1.11 ms; at 1920×1080 (min of 40) Phong 20.8–21.3 →
/// 20.2–20.8 ms. Code written with `wide`'s lanes gains nothing this way (they stay two SSE
/// registers per value): the shading of the Z-buffer's rows runs on AVX registers proper,
/// through [`run_on_best_lanes`](super::simd::run_on_best_lanes).
#[inline(always)]
pub(crate) fn with_avx2<R>(work: impl FnOnce() -> R) -> R {
    #[cfg(target_arch = "x86_64")]
    if has_avx2_bmi() {
        // SAFETY: the features `avx2_work` is compiled for were detected just above.
        return unsafe { avx2_work(work) };
    }
    work()
}

/// Set by tests that compare the two builds of the work: the baseline one is then used
/// everywhere in the process (which changes no result, so tests running beside it are not
/// disturbed).
#[cfg(test)]
pub(crate) static BASELINE_ONLY: std::sync::atomic::AtomicBool =
    std::sync::atomic::AtomicBool::new(false);

/// Held by tests that set [`BASELINE_ONLY`] or [`AVX2_AT_MOST`], and by tests that check
/// which build ran, so that they do not see each other's settings.
#[cfg(test)]
pub(crate) static BUILD_CHOICE: std::sync::Mutex<()> = std::sync::Mutex::new(());

/// Set by tests that compare the AVX-512 lanes with the AVX2 ones: AVX-512 is then not used
/// anywhere in the process (which changes no result either).
#[cfg(test)]
pub(crate) static AVX2_AT_MOST: std::sync::atomic::AtomicBool =
    std::sync::atomic::AtomicBool::new(false);

/// Whether this CPU has what [`avx2_work`] is compiled for: AVX2, BMI1/2 and LZCNT (detected
/// once, then cached flags; false in a test that asked for the baseline build).
#[cfg(target_arch = "x86_64")]
#[inline(always)]
pub(crate) fn has_avx2_bmi() -> bool {
    #[cfg(test)]
    if BASELINE_ONLY.load(std::sync::atomic::Ordering::Relaxed) {
        return false;
    }
    is_x86_feature_detected!("avx2")
        && is_x86_feature_detected!("bmi1")
        && is_x86_feature_detected!("bmi2")
        && is_x86_feature_detected!("lzcnt")
}

/// Whether this CPU has, beside [`has_avx2_bmi`]'s, what the widest lanes of
/// [`run_on_best_lanes`](super::simd::run_on_best_lanes) are compiled for: AVX-512 F, DQ and VL
/// (false in a test that asked for AVX2 at most, or for the baseline build).
#[cfg(target_arch = "x86_64")]
#[inline(always)]
pub(crate) fn has_avx512() -> bool {
    #[cfg(test)]
    if AVX2_AT_MOST.load(std::sync::atomic::Ordering::Relaxed) {
        return false;
    }
    has_avx2_bmi()
        && is_x86_feature_detected!("avx512f")
        && is_x86_feature_detected!("avx512dq")
        && is_x86_feature_detected!("avx512vl")
}

/// The instruction sets the renderer uses on this CPU, widest last: `AVX2` where
/// [`with_avx2`] and the eight-lane shading run on them, `AVX-512` where the sixteen-lane
/// shading does; empty on a CPU with neither (baseline x86-64 SSE2) or another architecture.
pub fn cpu_features() -> Vec<&'static str> {
    #[cfg(target_arch = "x86_64")]
    {
        let mut features = Vec::new();
        if has_avx2_bmi() {
            features.push("AVX2");
        }
        if has_avx512() {
            features.push("AVX-512");
        }
        features
    }
    #[cfg(not(target_arch = "x86_64"))]
    Vec::new()
}

/// `work()`, compiled for AVX2, BMI1/2 and LZCNT.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,bmi1,bmi2,lzcnt")]
fn avx2_work<R>(work: impl FnOnce() -> R) -> R {
    work()
}
