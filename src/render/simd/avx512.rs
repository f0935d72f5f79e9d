//! [`Lanes`] on one AVX-512 register per sixteen lanes: two batches of eight worked on at once,
//! where [`run_on_best_lanes`](super::run_on_best_lanes) found AVX-512.
//!
//! Every operation is the one [`F32x8`](super::F32x8) performs, the same IEEE operation lane by
//! lane in the same order (no fused multiply-add), so the results are the same bits.
//!
//! Measured gain, the reason for the `unsafe` here: see
//! [`run_on_best_lanes`](super::run_on_best_lanes).
#![allow(unsafe_code)]

use std::arch::x86_64::{
    __m256, __m512, __mmask16, _CMP_GT_OQ, _CMP_LT_OQ, _mm512_add_epi32, _mm512_add_ps,
    _mm512_castps_si512, _mm512_castps256_ps512, _mm512_castps512_ps256, _mm512_castsi512_ps,
    _mm512_cmp_ps_mask, _mm512_cvtepi32_ps, _mm512_cvttps_epi32, _mm512_div_ps,
    _mm512_extractf32x8_ps, _mm512_insertf32x8, _mm512_mask_blend_ps, _mm512_mask_xor_ps,
    _mm512_maskz_mov_ps, _mm512_max_ps, _mm512_min_ps, _mm512_mul_ps, _mm512_set1_epi32,
    _mm512_set1_ps, _mm512_setzero_ps, _mm512_slli_epi32, _mm512_sqrt_ps, _mm512_srai_epi32,
    _mm512_sub_epi32, _mm512_sub_ps,
};
use std::ops::{Add, Div, Mul, Neg, Sub};

use super::lanes::{Lanes, SQRT_HALF_BITS};

/// Sixteen lanes in one AVX-512 register. Made only from the eight-lane AVX registers of work
/// that `run_on_best_lanes` runs compiled for AVX-512 after detecting it, so the intrinsics
/// below always run on a CPU that has them.
#[derive(Clone, Copy)]
pub(super) struct Zmm(__m512);

/// `op(args)` on AVX-512 registers, as a [`Zmm`].
macro_rules! zmm {
    ($op:ident($($arg:expr),*)) => {
        // SAFETY: a `Zmm` only exists inside work run by `run_on_best_lanes` after AVX-512 was
        // detected (see `Zmm`); the intrinsic takes registers, no pointers.
        Zmm(unsafe { $op($($arg),*) })
    };
}

/// A lane-by-lane binary operator.
macro_rules! binary {
    ($trait:ident, $method:ident, $op:ident) => {
        impl $trait for Zmm {
            type Output = Zmm;
            #[inline(always)]
            fn $method(self, other: Zmm) -> Zmm {
                zmm!($op(self.0, other.0))
            }
        }
    };
}

binary!(Add, add, _mm512_add_ps);
binary!(Sub, sub, _mm512_sub_ps);
binary!(Mul, mul, _mm512_mul_ps);
binary!(Div, div, _mm512_div_ps);

impl Zmm {
    /// `low`'s lanes, then `high`'s.
    #[inline(always)]
    pub(super) fn join(low: __m256, high: __m256) -> Zmm {
        // SAFETY: as in `zmm!`.
        Zmm(unsafe { _mm512_insertf32x8::<1>(_mm512_castps256_ps512(low), high) })
    }

    /// The low eight lanes and the high eight.
    #[inline(always)]
    pub(super) fn halves(self) -> (__m256, __m256) {
        // SAFETY: as in `zmm!`.
        unsafe {
            (
                _mm512_castps512_ps256(self.0),
                _mm512_extractf32x8_ps::<1>(self.0),
            )
        }
    }
}

impl Neg for Zmm {
    type Output = Zmm;
    /// 0 − self, as `F32x8` negates (−(+0) is +0).
    #[inline(always)]
    fn neg(self) -> Zmm {
        zmm!(_mm512_setzero_ps()) - self
    }
}

impl Lanes for Zmm {
    /// One bit per lane.
    type Mask = __mmask16;

    #[inline(always)]
    fn splat(value: f32) -> Zmm {
        zmm!(_mm512_set1_ps(value))
    }

    #[inline(always)]
    fn sqrt(self) -> Zmm {
        zmm!(_mm512_sqrt_ps(self.0))
    }

    #[inline(always)]
    fn max(self, other: Zmm) -> Zmm {
        zmm!(_mm512_max_ps(self.0, other.0))
    }

    #[inline(always)]
    fn min(self, other: Zmm) -> Zmm {
        zmm!(_mm512_min_ps(self.0, other.0))
    }

    #[inline(always)]
    fn gt(self, other: Zmm) -> __mmask16 {
        // SAFETY: as in `zmm!`.
        unsafe { _mm512_cmp_ps_mask::<_CMP_GT_OQ>(self.0, other.0) }
    }

    #[inline(always)]
    fn lt(self, other: Zmm) -> __mmask16 {
        // SAFETY: as in `zmm!`.
        unsafe { _mm512_cmp_ps_mask::<_CMP_LT_OQ>(self.0, other.0) }
    }

    #[inline(always)]
    fn keep(mask: __mmask16, value: Zmm) -> Zmm {
        zmm!(_mm512_maskz_mov_ps(mask, value.0))
    }

    #[inline(always)]
    fn select(mask: __mmask16, yes: Zmm, no: Zmm) -> Zmm {
        zmm!(_mm512_mask_blend_ps(mask, no.0, yes.0))
    }

    #[inline(always)]
    fn negate_where(mask: __mmask16, value: Zmm) -> Zmm {
        let sign = Zmm::splat(-0.0);
        zmm!(_mm512_mask_xor_ps(value.0, mask, value.0, sign.0))
    }

    #[inline(always)]
    fn any(mask: __mmask16) -> bool {
        mask != 0
    }

    #[inline(always)]
    fn split_exponent(self) -> (Zmm, Zmm) {
        // SAFETY: as in `zmm!`.
        unsafe {
            let bits = _mm512_castps_si512(self.0);
            let shifted = _mm512_sub_epi32(bits, _mm512_set1_epi32(SQRT_HALF_BITS));
            let exponent = _mm512_srai_epi32::<23>(shifted);
            let mantissa = _mm512_sub_epi32(bits, _mm512_slli_epi32::<23>(exponent));
            (
                Zmm(_mm512_cvtepi32_ps(exponent)),
                Zmm(_mm512_castsi512_ps(mantissa)),
            )
        }
    }

    #[inline(always)]
    fn scale_by_pow2(self, n: Zmm) -> Zmm {
        // SAFETY: as in `zmm!`.
        let scale = unsafe {
            let biased = _mm512_add_epi32(_mm512_cvttps_epi32(n.0), _mm512_set1_epi32(127));
            Zmm(_mm512_castsi512_ps(_mm512_slli_epi32::<23>(biased)))
        };
        self * scale
    }
}
