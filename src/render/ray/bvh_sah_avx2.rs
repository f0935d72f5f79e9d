//! The binning of `bvh_sah` on AVX registers, chosen at run time where the CPU has AVX2.
//!
//! A bin's box is one 256-bit register while binning: its `lo` in lanes 0–2 and its `−hi` in
//! lanes 4–6, so that adding a prim is one `min` over the eight lanes (−max(a, b) is
//! min(−a, −b) exactly, and picks the same operand on ties, signed zeros included), and one
//! add that counts the prim in lane 7 (downwards: lane 7 holds −count). That is one load, one
//! store and two operations per prim and axis, where the four-lane boxes of `bvh_sah` take two
//! loads, two stores and three operations (`min`, `max`, add). The bins, their counts and the order in which prims join them are those of
//! [`Binning::fill_run`](super::bvh_sah::Binning), so the bins, and the tree, are the same bits.
//!
//! Measured gain, the reason for the `unsafe` here: see [`fill_run`].
#![allow(unsafe_code)]

use std::arch::x86_64::{
    __m256, _mm256_add_ps, _mm256_and_ps, _mm256_castps256_ps128, _mm256_extractf128_ps,
    _mm256_min_ps, _mm256_xor_ps,
};

use super::bvh_prims::{Aabb, Prim};
use super::bvh_sah::{AxisBins, BINS, Binning, Bins};

/// A bin's box as one register: lo in lanes 0–2, 0 in lane 3, −hi in lanes 4–6, −count in
/// lane 7.
type WideBox = [f32; 8];

/// Lanes: lo (+∞ while empty), 0, −hi (+∞ while empty), −count.
const EMPTY: WideBox = [
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
const NEGATE_HI: WideBox = [0.0, 0.0, 0.0, 0.0, -0.0, -0.0, -0.0, -0.0];
/// Keeps every lane of a prim but lane 3, its mesh index, which is not a coordinate.
const DROP_INDEX: [u32; 8] = [!0, !0, !0, 0, !0, !0, !0, !0];
/// Added after each prim: −0 leaves every other lane bit for bit as it is, lane 7 counts.
const COUNT_ONE: WideBox = [-0.0, -0.0, -0.0, -0.0, -0.0, -0.0, -0.0, -1.0];

/// The bins of one axis while binning, as registers.
type WideAxis = [__m256; BINS];

/// Two sets of bins for each axis: even prims go to the first, odd ones to the second.
#[derive(Clone, Copy)]
pub(super) struct WideBins {
    sets: [[WideAxis; 3]; 2],
}

impl WideBins {
    pub(super) fn new() -> WideBins {
        let empty: __m256 = bytemuck::cast(EMPTY);
        WideBins {
            sets: [[[empty; BINS]; 3]; 2],
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

/// A prim as a bin's box: lo, 0, −hi, −0.
#[target_feature(enable = "avx2")]
#[inline]
fn wide_prim(p: &Prim) -> __m256 {
    let p: __m256 = bytemuck::cast(*p);
    _mm256_and_ps(
        _mm256_xor_ps(p, bytemuck::cast(NEGATE_HI)),
        bytemuck::cast(DROP_INDEX),
    )
}

/// Adds the prim `p` (as [`wide_prim`]) to `bin`.
#[target_feature(enable = "avx2")]
#[inline]
fn add(bin: &mut __m256, p: __m256) {
    *bin = _mm256_add_ps(_mm256_min_ps(*bin, p), bytemuck::cast(COUNT_ONE));
}

#[target_feature(enable = "avx2")]
fn fill_run_avx2(binning: &Binning, prims: &[Prim], wide: &mut WideBins, bins: &mut Bins) {
    let used = binning.count();
    let axes = binning.axes();
    let empty: __m256 = bytemuck::cast(EMPTY);
    let [even, odd] = &mut wide.sets;
    let one_set = binning.one_set(prims.len());
    for axis in axes.clone() {
        even[axis][..used].fill(empty);
        if !one_set {
            odd[axis][..used].fill(empty);
        }
    }
    let pairs = prims.chunks_exact(2);
    let rest = pairs.remainder();
    let bin = |b: i32| b as usize & (BINS - 1);
    if one_set {
        let (axis, even) = (axes.start, &mut even[axes.start]);
        for p in prims {
            add(&mut even[bin(binning.bins(p)[axis])], wide_prim(p));
        }
    } else if axes.len() == 1 {
        let axis = axes.start;
        let (even, odd) = (&mut even[axis], &mut odd[axis]);
        for pair in pairs {
            let (a, b) = (&pair[0], &pair[1]);
            add(&mut even[bin(binning.bins(a)[axis])], wide_prim(a));
            add(&mut odd[bin(binning.bins(b)[axis])], wide_prim(b));
        }
        for p in rest {
            add(&mut even[bin(binning.bins(p)[axis])], wide_prim(p));
        }
    } else {
        for pair in pairs {
            let (a, b) = (&pair[0], &pair[1]);
            let (ba, bb) = (binning.bins(a), binning.bins(b));
            let (wa, wb) = (wide_prim(a), wide_prim(b));
            for axis in 0..3 {
                add(&mut even[axis][bin(ba[axis])], wa);
                add(&mut odd[axis][bin(bb[axis])], wb);
            }
        }
        for p in rest {
            let (bp, wp) = (binning.bins(p), wide_prim(p));
            for (axis, bins) in even.iter_mut().enumerate() {
                add(&mut bins[bin(bp[axis])], wp);
            }
        }
    }
    for axis in axes {
        let odd = if one_set { &[empty; BINS] } else { &odd[axis] };
        settle(&even[axis][..used], &odd[..used], &mut bins.0[axis]);
    }
}

/// Joins the two sets of one axis' bins into `out`, as [`AxisBins`] joins its own two sets:
/// the even set's box first in every `min`.
#[target_feature(enable = "avx2")]
fn settle(even: &[__m256], odd: &[__m256], out: &mut AxisBins) {
    for (b, (&e, &o)) in even.iter().zip(odd).enumerate() {
        let count = |w: __m256| -bytemuck::cast::<__m256, WideBox>(w)[7] as u32;
        out.counts[b] = count(e) + count(o);
        // Back to lo and hi; the sign flipped bit for bit (`0 − x` would turn −0 into +0).
        let joined = _mm256_xor_ps(_mm256_min_ps(e, o), bytemuck::cast(NEGATE_HI));
        out.boxes[b] = Aabb {
            lo: bytemuck::cast(_mm256_castps256_ps128(joined)),
            hi: bytemuck::cast(_mm256_extractf128_ps::<1>(joined)),
        };
    }
}
