//! Lanes: `f32` arithmetic written once and run either on one value or on eight at a time.
//!
//! The lighting function and the maths under it are generic over [`Lanes`]. The ray tracer shades
//! one hit at a time with `f32`, while the Z-buffer shades eight pixels or vertices at a time
//! with [`F32x8`] (SIMD: two SSE registers on baseline x86-64, one AVX register where the build
//! enables AVX, NEON on ARM). Every operation here is correctly rounded IEEE arithmetic, applied
//! in the same order for both widths, so a lane of `F32x8` gives the same bits as `f32`.

use std::ops::{Add, BitAnd, Div, Mul, Neg, Sub};

use wide::{CmpGt, CmpLt, i32x8};

use super::twice::Twice;

/// Eight `f32` lanes.
pub type F32x8 = wide::f32x8;

/// Number of lanes in [`F32x8`].
pub const WIDTH: usize = 8;

/// `f32` values processed in lock step.
pub trait Lanes:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    /// A per-lane condition.
    type Mask: Copy + BitAnd<Output = Self::Mask>;

    /// Every lane set to `value`.
    fn splat(value: f32) -> Self;
    /// Square root, correctly rounded.
    fn sqrt(self) -> Self;
    /// Larger of the two, lane by lane (neither may be NaN).
    fn max(self, other: Self) -> Self;
    /// Smaller of the two, lane by lane (neither may be NaN).
    fn min(self, other: Self) -> Self;
    /// Where `self > other`.
    fn gt(self, other: Self) -> Self::Mask;
    /// Where `self < other`.
    fn lt(self, other: Self) -> Self::Mask;
    /// `value` where `mask` holds, else 0.
    fn keep(mask: Self::Mask, value: Self) -> Self;
    /// `yes` where `mask` holds, else `no`, bit for bit.
    fn select(mask: Self::Mask, yes: Self, no: Self) -> Self;
    /// −`value` where `mask` holds, else `value`.
    fn negate_where(mask: Self::Mask, value: Self) -> Self;
    /// Whether `mask` holds in any lane.
    fn any(mask: Self::Mask) -> bool;
    /// For positive finite lanes: (e, m) with self = m·2^e, e an integer and m in [√½, √2).
    /// Zero gives e = −127, m = 1.
    fn split_exponent(self) -> (Self, Self);
    /// self·2^n for integer-valued `n` in [−126, 127].
    fn scale_by_pow2(self, n: Self) -> Self;
}

/// The bits of √½ as an f32: subtracting them from a float's bits and shifting right by 23 gives
/// the exponent that leaves a mantissa in [√½, √2).
pub(super) const SQRT_HALF_BITS: i32 = 0x3f35_04f3;

/// 1.5·2^23: adding and subtracting it rounds an f32 of magnitude below 2^22 to the nearest
/// integer (ties to even), with no rounding-mode or libm dependence.
pub const ROUND_MAGIC: f32 = 12_582_912.0;

impl Lanes for f32 {
    type Mask = bool;

    #[inline(always)]
    fn splat(value: f32) -> f32 {
        value
    }

    #[inline(always)]
    fn sqrt(self) -> f32 {
        f32::sqrt(self)
    }

    #[inline(always)]
    fn max(self, other: f32) -> f32 {
        if self > other { self } else { other }
    }

    #[inline(always)]
    fn min(self, other: f32) -> f32 {
        if self < other { self } else { other }
    }

    #[inline(always)]
    fn gt(self, other: f32) -> bool {
        self > other
    }

    #[inline(always)]
    fn lt(self, other: f32) -> bool {
        self < other
    }

    #[inline(always)]
    fn keep(mask: bool, value: f32) -> f32 {
        if mask { value } else { 0.0 }
    }

    #[inline(always)]
    fn select(mask: bool, yes: f32, no: f32) -> f32 {
        if mask { yes } else { no }
    }

    #[inline(always)]
    fn negate_where(mask: bool, value: f32) -> f32 {
        if mask { -value } else { value }
    }

    #[inline(always)]
    fn any(mask: bool) -> bool {
        mask
    }

    #[inline(always)]
    fn split_exponent(self) -> (f32, f32) {
        let bits = self.to_bits() as i32;
        let exponent = (bits - SQRT_HALF_BITS) >> 23;
        (
            exponent as f32,
            f32::from_bits((bits - (exponent << 23)) as u32),
        )
    }

    #[inline(always)]
    fn scale_by_pow2(self, n: f32) -> f32 {
        self * f32::from_bits(((n as i32 + 127) << 23) as u32)
    }
}

impl Lanes for F32x8 {
    type Mask = F32x8;

    #[inline(always)]
    fn splat(value: f32) -> F32x8 {
        F32x8::splat(value)
    }

    #[inline(always)]
    fn sqrt(self) -> F32x8 {
        F32x8::sqrt(self)
    }

    #[inline(always)]
    fn max(self, other: F32x8) -> F32x8 {
        self.fast_max(other)
    }

    #[inline(always)]
    fn min(self, other: F32x8) -> F32x8 {
        self.fast_min(other)
    }

    #[inline(always)]
    fn gt(self, other: F32x8) -> F32x8 {
        self.cmp_gt(other)
    }

    #[inline(always)]
    fn lt(self, other: F32x8) -> F32x8 {
        self.cmp_lt(other)
    }

    #[inline(always)]
    fn keep(mask: F32x8, value: F32x8) -> F32x8 {
        mask & value
    }

    #[inline(always)]
    fn select(mask: F32x8, yes: F32x8, no: F32x8) -> F32x8 {
        mask.blend(yes, no)
    }

    #[inline(always)]
    fn negate_where(mask: F32x8, value: F32x8) -> F32x8 {
        value ^ (mask & F32x8::splat(-0.0))
    }

    #[inline(always)]
    fn any(mask: F32x8) -> bool {
        mask.any()
    }

    #[inline(always)]
    fn split_exponent(self) -> (F32x8, F32x8) {
        let bits: i32x8 = bytemuck::cast(self);
        let exponent: i32x8 = (bits - i32x8::splat(SQRT_HALF_BITS)) >> 23;
        (
            exponent.round_float(),
            bytemuck::cast(bits - (exponent << 23)),
        )
    }

    #[inline(always)]
    fn scale_by_pow2(self, n: F32x8) -> F32x8 {
        let biased = n.fast_trunc_int() + i32x8::splat(127);
        self * bytemuck::cast::<_, F32x8>(biased << 23)
    }
}

/// Eight lanes, loaded from and stored to arrays: [`F32x8`], or one AVX register where the CPU
/// has AVX2 (see [`run_on_best_lanes`](super::run_on_best_lanes)). The same operations give the
/// same bits on either.
pub trait Lanes8: Lanes {
    /// Lane k = `values[k]`.
    fn from_array(values: [f32; WIDTH]) -> Self;
    /// The lanes in order.
    fn to_array(self) -> [f32; WIDTH];
    /// The lanes as integers, for lanes that hold whole numbers in [0, 2^24] (where `f32` is
    /// exact): the conversion in one instruction, not one a lane.
    fn to_whole_u32(self) -> [u32; WIDTH];
    /// The red, green and blue codes of eight 16-bit RGBA texels as whole numbers, lane k
    /// texel k: the eight unpacked together, not three conversions a lane.
    #[inline(always)]
    fn rgb16(texels: &[[u16; 4]; WIDTH]) -> [Self; 3] {
        std::array::from_fn(|c| {
            let mut codes = [0.0; WIDTH];
            for (code, texel) in codes.iter_mut().zip(texels) {
                *code = f32::from(texel[c]);
            }
            Self::from_array(codes)
        })
    }

    /// [`Lanes8::rgb16`] of the first texel of each of eight pairs, and of the second.
    #[inline(always)]
    fn rgb16_pairs(pairs: &[[[u16; 4]; 2]; WIDTH]) -> ([Self; 3], [Self; 3]) {
        (
            Self::rgb16(&pairs.map(|[first, _]| first)),
            Self::rgb16(&pairs.map(|[_, second]| second)),
        )
    }

    /// Sixteen lanes: two batches of eight worked on at once. One AVX-512 register where the
    /// CPU has it, else the two halves side by side ([`Twice`]).
    type Pair: Lanes;
    /// `low`'s lanes, then `high`'s.
    fn pair(low: Self, high: Self) -> Self::Pair;
    /// The low eight lanes and the high eight.
    fn halves(pair: Self::Pair) -> (Self, Self);
}

impl Lanes8 for F32x8 {
    #[inline(always)]
    fn from_array(values: [f32; WIDTH]) -> F32x8 {
        F32x8::from(values)
    }

    #[inline(always)]
    fn to_array(self) -> [f32; WIDTH] {
        F32x8::to_array(self)
    }

    #[inline(always)]
    fn to_whole_u32(self) -> [u32; WIDTH] {
        bytemuck::cast(self.fast_trunc_int())
    }

    type Pair = Twice<F32x8>;

    #[inline(always)]
    fn pair(low: F32x8, high: F32x8) -> Twice<F32x8> {
        Twice(low, high)
    }

    #[inline(always)]
    fn halves(pair: Twice<F32x8>) -> (F32x8, F32x8) {
        (pair.0, pair.1)
    }
}

/// Work written over any [`Lanes8`], run by [`run_on_best_lanes`](super::run_on_best_lanes) on
/// the widest registers this CPU has.
pub trait LanesJob {
    /// The result of the work.
    type Output;
    /// Does the work on lanes `L`.
    fn run<L: Lanes8>(self) -> Self::Output;
}

/// Lanes from eight consecutive values.
#[inline(always)]
pub fn load(values: &[f32]) -> F32x8 {
    let lanes: [f32; WIDTH] = values[..WIDTH].try_into().expect("eight values");
    F32x8::from(lanes)
}
