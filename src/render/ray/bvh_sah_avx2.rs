//! The binning of `bvh_sah` on AVX registers, chosen at run time where the CPU has AVX2.
//!
//! A bin's box is one 256-bit register while binning ([`WideBox`]): its `lo` in lanes 0–2 and
//! its `−hi` in lanes 4–6, so that adding a prim is one `min` over the eight lanes (−max(a, b)
//! is min(−a, −b) exactly, and picks the same operand on ties, signed zeros included), and one
//! add that counts the prim in lane 7 (downwards: lane 7 holds −count). That is one load, one
//! store and two operations per prim and axis, where the four-lane boxes of `bvh_sah` take two
//! loads, two stores and three operations (`min`, `max`, add). The loop that feeds the prims
//! and joins the sets is `bvh_sah`'s own ([`Binning::fill_sets`]), so the bins, and the tree,
//! are the same bits.
//!
//! Measured gain, the reason for the `unsafe` here: see [`fill_run`].
#![allow(unsafe_code)]

use std::arch::x86_64::{
    __m256, _mm256_add_ps, _mm256_and_ps, _mm256_castps256_ps128, _mm256_extractf128_ps,
    _mm256_min_ps, _mm256_xor_ps,
};

use super::bvh_prims::{Aabb, Prim};
use super::bvh_sah::{BINS, BinBox, BinSets, Binning, Bins};

/// Lanes of a bin's box: lo (+∞ while empty), 0, −hi (+∞ while empty), −count.
const EMPTY: [f32; 8] = [
    f32::INFINITY,
    f32::INFINITY,
    f32::INFINITY,
    0.0,
    f32::INFINITY,
    f32::INFINITY,
    f32::INFINITY,
    0.0,
];
/// Flips the sign of a prim's `hi`, lanes 4–7 (lane 7 becomes −0).
const NEGATE_HI: [f32; 8] = [0.0, 0.0, 0.0, 0.0, -0.0, -0.0, -0.0, -0.0];
/// Keeps every lane of a prim but lane 3, its mesh index, which is not a coordinate.
const DROP_INDEX: [u32; 8] = [!0, !0, !0, 0, !0, !0, !0, !0];
/// Added after each prim: −0 leaves every other lane bit for bit as it is, lane 7 counts.
const COUNT_ONE: [f32; 8] = [-0.0, -0.0, -0.0, -0.0, -0.0, -0.0, -0.0, -1.0];

/// A bin's box as one AVX register: lo in lanes 0–2, 0 in lane 3, −hi in lanes 4–6, −count in
/// lane 7. Private to this module: its operations run only inside [`fill_run_avx2`], entered
/// after AVX2 was detected, so the intrinsics below always run on a CPU that has them.
#[derive(Clone, Copy)]
struct WideBox(__m256);

/// `op(args)` on AVX registers.
macro_rules! avx {
    ($op:ident $(::<$k:literal>)? ($($arg:expr),*)) => {
        // SAFETY: a `WideBox` is only worked on inside `fill_run_avx2`, after AVX2 was
        // detected (see `WideBox`); the intrinsic takes registers, no pointers.
        unsafe { $op $(::<$k>)? ($($arg),*) }
    };
}

impl BinBox for WideBox {
    /// A prim as a bin's box: lo, 0, −hi, −0.
    type Prim = __m256;

    #[inline(always)]
    fn empty() -> WideBox {
        WideBox(bytemuck::cast(EMPTY))
    }

    #[inline(always)]
    fn prim(p: &Prim) -> __m256 {
        let p: __m256 = bytemuck::cast(*p);
        let negated = avx!(_mm256_xor_ps(p, bytemuck::cast(NEGATE_HI)));
        avx!(_mm256_and_ps(negated, bytemuck::cast(DROP_INDEX)))
    }

    #[inline(always)]
    fn add(&mut self, p: __m256) {
        let grown = avx!(_mm256_min_ps(self.0, p));
        self.0 = avx!(_mm256_add_ps(grown, bytemuck::cast(COUNT_ONE)));
    }

    #[inline(always)]
    fn settle(self) -> (Aabb, u32) {
        let count = -bytemuck::cast::<__m256, [f32; 8]>(self.0)[7] as u32;
        // The sign of −hi flipped bit for bit (`0 − x` would turn −0 into +0).
        let w = avx!(_mm256_xor_ps(self.0, bytemuck::cast(NEGATE_HI)));
        let lo = avx!(_mm256_castps256_ps128(w));
        let hi = avx!(_mm256_extractf128_ps::<1>(w));
        (
            Aabb {
                lo: bytemuck::cast(lo),
                hi: bytemuck::cast(hi),
            },
            count,
        )
    }
}

/// The sets of bins of a thread, as AVX registers.
#[derive(Clone, Copy)]
pub(super) struct WideBins {
    sets: BinSets<WideBox>,
}

impl WideBins {
    pub(super) fn new() -> WideBins {
        WideBins {
            sets: [[[WideBox::empty(); BINS]; 3]; 2],
        }
    }
}

impl std::fmt::Debug for WideBins {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("WideBins")
    }
}

/// [`Binning::fill_run`] on AVX registers, into `bins`; false (nothing done) where the CPU
/// lacks AVX2.
///
/// Measured on the 1.31M-triangle icosphere (`../shared/perf/icosphere.toml`), whole builds
/// in one process (min of 15), alternating three times with the four-lane binning: 271–278 →
/// 234–237 ms on 1 thread, 137–157 → 125–137 ms on 2 threads.
#[inline]
pub(super) fn fill_run(
    binning: &Binning,
    prims: &[Prim],
    wide: &mut WideBins,
    bins: &mut Bins,
) -> bool {
    if !is_x86_feature_detected!("avx2") {
        return false;
    }
    // SAFETY: AVX2 was detected just above.
    unsafe { fill_run_avx2(binning, prims, wide, bins) };
    true
}

/// [`Binning::fill_sets`] on [`WideBox`], compiled for AVX2.
#[target_feature(enable = "avx2")]
fn fill_run_avx2(binning: &Binning, prims: &[Prim], wide: &mut WideBins, bins: &mut Bins) {
    binning.fill_sets(prims, &mut wide.sets, bins);
}
