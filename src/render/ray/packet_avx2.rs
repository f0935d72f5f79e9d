//! The packet walk on AVX2 registers, chosen at run time where the CPU has AVX2.
//!
//! The build targets baseline x86-64, where `wide`'s eight lanes are two SSE registers. Here the
//! same walk ([`Bvh::walk`], generic over [`Lane8`]) runs on one 256-bit register per value:
//! the same IEEE operations in the same order, no fused multiply-add, so every hit is the one
//! the SSE walk finds, bit for bit.
//!
//! Measured gain, the reason for the `unsafe` here: `rastray bench throughput` at 1920×1080 on
//! 2 threads (shared, loaded machine), the SSE and AVX2 builds alternating in one run, tracing
//! time: bunny 219 → 163–167 ms, 1.31M-triangle icosphere 421–468 → 243–328 ms.
#![allow(unsafe_code)]

use glam::Vec3A;
use std::arch::x86_64::{
    __m128, __m256, _CMP_GE_OQ, _CMP_GT_OQ, _CMP_LE_OQ, _CMP_LT_OQ, _mm256_add_ps, _mm256_and_ps,
    _mm256_andnot_ps, _mm256_blendv_ps, _mm256_castps128_ps256, _mm256_cmp_ps, _mm256_div_ps,
    _mm256_insertf128_ps, _mm256_max_ps, _mm256_min_ps, _mm256_movemask_ps, _mm256_mul_ps,
    _mm256_shuffle_ps, _mm256_sub_ps, _mm256_unpackhi_ps, _mm256_unpacklo_ps,
};
use std::ops::{Add, BitAnd, Div, Mul, Sub};

use super::bvh::Bvh;
use super::packet::{Lane8, PacketHits, RayPacket};
use crate::render::simd::F32x8;

/// Eight lanes in one AVX register. Private to this module: every value is made inside
/// [`nearest_avx2`] or [`any_hit_avx2`], which run only once AVX2 has been detected, so the
/// intrinsics below always run on a CPU that has them.
#[derive(Clone, Copy)]
struct Avx(__m256);

/// `op(a, b)` on AVX registers.
macro_rules! avx {
    ($op:ident($($arg:expr),*)) => {
        // SAFETY: an `Avx` exists only inside the walks below, entered after
        // `is_x86_feature_detected!("avx2")` held (see `Avx`); the intrinsic takes registers,
        // no pointers.
        Avx(unsafe { $op($($arg.0),*) })
    };
}

/// `op(a, b)` as an AVX comparison with predicate `P`.
macro_rules! avx_cmp {
    ($p:ident, $a:expr, $b:expr) => {
        // SAFETY: as in `avx!`.
        Avx(unsafe { _mm256_cmp_ps::<$p>($a.0, $b.0) })
    };
}

impl Add for Avx {
    type Output = Avx;
    #[inline(always)]
    fn add(self, o: Avx) -> Avx {
        avx!(_mm256_add_ps(self, o))
    }
}

impl Sub for Avx {
    type Output = Avx;
    #[inline(always)]
    fn sub(self, o: Avx) -> Avx {
        avx!(_mm256_sub_ps(self, o))
    }
}

impl Mul for Avx {
    type Output = Avx;
    #[inline(always)]
    fn mul(self, o: Avx) -> Avx {
        avx!(_mm256_mul_ps(self, o))
    }
}

impl Div for Avx {
    type Output = Avx;
    #[inline(always)]
    fn div(self, o: Avx) -> Avx {
        avx!(_mm256_div_ps(self, o))
    }
}

impl BitAnd for Avx {
    type Output = Avx;
    #[inline(always)]
    fn bitand(self, o: Avx) -> Avx {
        avx!(_mm256_and_ps(self, o))
    }
}

impl Lane8 for Avx {
    #[inline(always)]
    fn from_wide(value: F32x8) -> Avx {
        Avx(bytemuck::cast(value))
    }
    #[inline(always)]
    fn to_wide(self) -> F32x8 {
        bytemuck::cast(self.0)
    }
    #[inline(always)]
    fn splat(value: f32) -> Avx {
        Avx(bytemuck::cast([value; 8]))
    }
    #[inline(always)]
    fn min(self, other: Avx) -> Avx {
        avx!(_mm256_min_ps(self, other))
    }
    #[inline(always)]
    fn max(self, other: Avx) -> Avx {
        avx!(_mm256_max_ps(self, other))
    }
    #[inline(always)]
    fn lt(self, other: Avx) -> Avx {
        avx_cmp!(_CMP_LT_OQ, self, other)
    }
    #[inline(always)]
    fn le(self, other: Avx) -> Avx {
        avx_cmp!(_CMP_LE_OQ, self, other)
    }
    #[inline(always)]
    fn gt(self, other: Avx) -> Avx {
        avx_cmp!(_CMP_GT_OQ, self, other)
    }
    #[inline(always)]
    fn ge(self, other: Avx) -> Avx {
        avx_cmp!(_CMP_GE_OQ, self, other)
    }
    #[inline(always)]
    fn and_not(self, mask: Avx) -> Avx {
        avx!(_mm256_andnot_ps(mask, self))
    }
    #[inline(always)]
    fn select(mask: Avx, t: Avx, f: Avx) -> Avx {
        avx!(_mm256_blendv_ps(f, t, mask))
    }
    #[inline(always)]
    fn any(self) -> bool {
        // SAFETY: as in `avx!`.
        unsafe { _mm256_movemask_ps(self.0) != 0 }
    }
    #[inline(always)]
    fn transpose(rows: [&Vec3A; 8]) -> [Avx; 3] {
        let r = rows.map(|v| __m128::from(*v));
        // SAFETY: as in `avx!`.
        unsafe {
            let pair =
                |a: __m128, b: __m128| _mm256_insertf128_ps::<1>(_mm256_castps128_ps256(a), b);
            let (a0, a1, a2, a3) = (
                pair(r[0], r[4]),
                pair(r[1], r[5]),
                pair(r[2], r[6]),
                pair(r[3], r[7]),
            );
            // x0 x1 y0 y1 | x4 x5 y4 y5, and z0 z1 w0 w1 | z4 z5 w4 w5; likewise 2, 3, 6, 7.
            let (lo01, hi01) = (_mm256_unpacklo_ps(a0, a1), _mm256_unpackhi_ps(a0, a1));
            let (lo23, hi23) = (_mm256_unpacklo_ps(a2, a3), _mm256_unpackhi_ps(a2, a3));
            [
                Avx(_mm256_shuffle_ps::<0x44>(lo01, lo23)),
                Avx(_mm256_shuffle_ps::<0xEE>(lo01, lo23)),
                Avx(_mm256_shuffle_ps::<0x44>(hi01, hi23)),
            ]
        }
    }
    #[inline(always)]
    fn bits(self) -> u32 {
        // SAFETY: as in `avx!`.
        unsafe { _mm256_movemask_ps(self.0) as u32 }
    }
}

/// Whether this CPU runs the AVX2 walk (detected once, then a cached flag).
#[inline]
fn available() -> bool {
    is_x86_feature_detected!("avx2")
}

/// [`Bvh::intersect_packet`] on AVX2 registers; false (nothing done) where the CPU lacks AVX2.
#[inline]
pub(super) fn intersect_packet(
    bvh: &Bvh,
    packet: &RayPacket,
    object: u32,
    hits: &mut PacketHits,
) -> bool {
    if !available() {
        return false;
    }
    // SAFETY: AVX2 was detected just above.
    unsafe { nearest_avx2(bvh, packet, object, hits) };
    true
}

/// [`Bvh::occluded_packet`] on AVX2 registers; `None` where the CPU lacks AVX2.
#[inline]
pub(super) fn occluded_packet(
    bvh: &Bvh,
    packet: &RayPacket,
    t_max: F32x8,
    pending: F32x8,
) -> Option<F32x8> {
    if !available() {
        return None;
    }
    // SAFETY: AVX2 was detected just above.
    Some(unsafe { any_hit_avx2(bvh, packet, t_max, pending) })
}

/// [`Bvh::intersect_packet`] compiled for AVX2.
#[target_feature(enable = "avx2")]
fn nearest_avx2(bvh: &Bvh, packet: &RayPacket, object: u32, hits: &mut PacketHits) {
    bvh.nearest_in::<Avx>(packet, object, hits);
}

/// [`Bvh::occluded_packet`] compiled for AVX2.
#[target_feature(enable = "avx2")]
fn any_hit_avx2(bvh: &Bvh, packet: &RayPacket, t_max: F32x8, pending: F32x8) -> F32x8 {
    bvh.any_hit_in::<Avx>(packet, t_max, pending)
}
