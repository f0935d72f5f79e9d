//! [`Lanes`] on one AVX register per eight lanes, for work that [`run_on_best_lanes`] runs where
//! the CPU has AVX2.
//!
//! The build targets baseline x86-64, where [`F32x8`] is two SSE registers; `F32x8` stays that
//! even inside code compiled for AVX2, since its choice is made when the crate is compiled.
//! Here every operation is the one `F32x8` performs, the same IEEE operation lane by lane in
//! the same order (no fused multiply-add), so the results are the same bits.
//!
//! Measured gain, the reason for the `unsafe` here: see [`run_on_best_lanes`].
#![allow(unsafe_code)]

use std::arch::x86_64::{
    __m128i, __m256, __m256i, _CMP_GT_OQ, _CMP_LT_OQ, _mm256_add_epi32, _mm256_add_ps,
    _mm256_and_ps, _mm256_and_si256, _mm256_blendv_ps, _mm256_castps_si256, _mm256_castsi256_ps,
    _mm256_cmp_ps, _mm256_cvtepi32_ps, _mm256_cvttps_epi32, _mm256_div_ps, _mm256_max_ps,
    _mm256_min_ps, _mm256_movemask_ps, _mm256_mul_ps, _mm256_set_epi64x, _mm256_set_m128i,
    _mm256_set1_epi32, _mm256_set1_ps, _mm256_setzero_ps, _mm256_shuffle_ps, _mm256_slli_epi32,
    _mm256_sqrt_ps, _mm256_srai_epi32, _mm256_srli_epi32, _mm256_sub_epi32, _mm256_sub_ps,
    _mm256_unpackhi_epi64, _mm256_unpacklo_epi64, _mm256_xor_ps,
};
use std::ops::{Add, BitAnd, Div, Mul, Neg, Sub};

use super::avx512::Zmm;
use super::lanes::{F32x8, Lanes, Lanes8, LanesJob, SQRT_HALF_BITS, WIDTH};
use super::twice::Twice;

/// Eight lanes in one AVX register. Private to this module: generic work runs on it only
/// through [`run_on_best_lanes`], after AVX2 has been detected, so the intrinsics below always
/// run on a CPU that has them.
#[derive(Clone, Copy)]
struct Avx<const WIDE: bool>(__m256);

/// `op(args)` on AVX registers, as an [`Avx`].
macro_rules! avx {
    ($op:ident($($arg:expr),*)) => {
        // SAFETY: an `Avx` is only made inside work run by `run_on_best_lanes` after AVX2 was
        // detected (see `Avx`); the intrinsic takes registers, no pointers.
        Avx(unsafe { $op($($arg),*) })
    };
}

/// A lane-by-lane binary operator.
macro_rules! binary {
    ($trait:ident, $method:ident, $op:ident) => {
        impl<const WIDE: bool> $trait for Avx<WIDE> {
            type Output = Self;
            #[inline(always)]
            fn $method(self, other: Self) -> Self {
                avx!($op(self.0, other.0))
            }
        }
    };
}

binary!(Add, add, _mm256_add_ps);
binary!(Sub, sub, _mm256_sub_ps);
binary!(Mul, mul, _mm256_mul_ps);
binary!(Div, div, _mm256_div_ps);
binary!(BitAnd, bitand, _mm256_and_ps);

impl<const WIDE: bool> Neg for Avx<WIDE> {
    type Output = Self;
    /// 0 − self, as [`F32x8`] negates (−(+0) is +0).
    #[inline(always)]
    fn neg(self) -> Self {
        let zero = avx!(_mm256_setzero_ps());
        zero - self
    }
}

impl<const WIDE: bool> Lanes for Avx<WIDE> {
    type Mask = Self;

    #[inline(always)]
    fn splat(value: f32) -> Self {
        avx!(_mm256_set1_ps(value))
    }

    #[inline(always)]
    fn sqrt(self) -> Self {
        avx!(_mm256_sqrt_ps(self.0))
    }

    #[inline(always)]
    fn max(self, other: Self) -> Self {
        avx!(_mm256_max_ps(self.0, other.0))
    }

    #[inline(always)]
    fn min(self, other: Self) -> Self {
        avx!(_mm256_min_ps(self.0, other.0))
    }

    #[inline(always)]
    fn gt(self, other: Self) -> Self {
        // SAFETY: as in `avx!`.
        Avx(unsafe { _mm256_cmp_ps::<_CMP_GT_OQ>(self.0, other.0) })
    }

    #[inline(always)]
    fn lt(self, other: Self) -> Self {
        // SAFETY: as in `avx!`.
        Avx(unsafe { _mm256_cmp_ps::<_CMP_LT_OQ>(self.0, other.0) })
    }

    #[inline(always)]
    fn keep(mask: Self, value: Self) -> Self {
        mask & value
    }

    #[inline(always)]
    fn select(mask: Self, yes: Self, no: Self) -> Self {
        avx!(_mm256_blendv_ps(no.0, yes.0, mask.0))
    }

    #[inline(always)]
    fn negate_where(mask: Self, value: Self) -> Self {
        let sign = mask & Self::splat(-0.0);
        avx!(_mm256_xor_ps(value.0, sign.0))
    }

    #[inline(always)]
    fn any(mask: Self) -> bool {
        // SAFETY: as in `avx!`.
        unsafe { _mm256_movemask_ps(mask.0) != 0 }
    }

    #[inline(always)]
    fn split_exponent(self) -> (Self, Self) {
        // SAFETY: as in `avx!`.
        unsafe {
            let bits = _mm256_castps_si256(self.0);
            let shifted = _mm256_sub_epi32(bits, _mm256_set1_epi32(SQRT_HALF_BITS));
            let exponent = _mm256_srai_epi32::<23>(shifted);
            let mantissa = _mm256_sub_epi32(bits, _mm256_slli_epi32::<23>(exponent));
            (
                Avx(_mm256_cvtepi32_ps(exponent)),
                Avx(_mm256_castsi256_ps(mantissa)),
            )
        }
    }

    #[inline(always)]
    fn scale_by_pow2(self, n: Self) -> Self {
        // SAFETY: as in `avx!`.
        let scale = unsafe {
            let biased = _mm256_add_epi32(_mm256_cvttps_epi32(n.0), _mm256_set1_epi32(127));
            Avx(_mm256_castsi256_ps(_mm256_slli_epi32::<23>(biased)))
        };
        self * scale
    }
}

impl<const WIDE: bool> Lanes8 for Avx<WIDE>
where
    Avx<WIDE>: Pairs,
{
    #[inline(always)]
    fn from_array(values: [f32; WIDTH]) -> Self {
        Avx(bytemuck::cast(values))
    }

    #[inline(always)]
    fn to_array(self) -> [f32; WIDTH] {
        bytemuck::cast(self.0)
    }

    #[inline(always)]
    fn to_whole_u32(self) -> [u32; WIDTH] {
        // SAFETY: as in `avx!`.
        bytemuck::cast(unsafe { _mm256_cvttps_epi32(self.0) })
    }

    #[inline(always)]
    fn rgb16(texels: &[[u16; 4]; WIDTH]) -> [Self; 3] {
        // Each texel one 64-bit word, as `unpack_rgb16` takes them. Measured: with this, the
        // textured Duck's Gouraud frame at 1920×1080 on one thread took 9.7 ms, against 10.3 ms
        // reading sRGB bytes through a table lane by lane.
        let t: [i64; WIDTH] = bytemuck::cast(*texels);
        // SAFETY: as in `avx!`.
        unsafe {
            unpack_rgb16(
                _mm256_set_epi64x(t[5], t[4], t[1], t[0]),
                _mm256_set_epi64x(t[7], t[6], t[3], t[2]),
            )
        }
    }

    #[inline(always)]
    fn rgb16_pairs(pairs: &[[[u16; 4]; 2]; WIDTH]) -> ([Self; 3], [Self; 3]) {
        // Lane k's pair is one 128-bit word: its first texel low, its second high. Pairs k and
        // k + 4 share a register (k low), and unpacking the 64-bit halves of two such registers
        // lays out the first texels, and the second, as `rgb16` lays out its words. Measured
        // on the textured Duck's kept frame at 1920×1080, one thread (the least of 12 runs'
        // medians of 25 frames): Gouraud 9.79 → 9.58 ms and Phong 11.70 → 11.00 ms, against two
        // `rgb16` calls.
        let p: [__m128i; WIDTH] = pairs.map(bytemuck::cast);
        // SAFETY: as in `avx!`.
        unsafe {
            let x0 = _mm256_set_m128i(p[4], p[0]);
            let x1 = _mm256_set_m128i(p[5], p[1]);
            let x2 = _mm256_set_m128i(p[6], p[2]);
            let x3 = _mm256_set_m128i(p[7], p[3]);
            (
                unpack_rgb16(_mm256_unpacklo_epi64(x0, x1), _mm256_unpacklo_epi64(x2, x3)),
                unpack_rgb16(_mm256_unpackhi_epi64(x0, x1), _mm256_unpackhi_epi64(x2, x3)),
            )
        }
    }

    type Pair = <Self as Pairs>::Pair;

    #[inline(always)]
    fn pair(low: Self, high: Self) -> Self::Pair {
        <Self as Pairs>::pair(low, high)
    }

    #[inline(always)]
    fn halves(pair: Self::Pair) -> (Self, Self) {
        <Self as Pairs>::halves(pair)
    }
}

/// The red, green and blue codes of eight 16-bit RGBA texels, each one 64-bit word (red in its
/// low 16 bits): `a` holds texels 0, 1, 4 and 5, `b` texels 2, 3, 6 and 7. The shuffles take the
/// low (red and green) or high (blue and alpha) half of words 0 and 1 of `a`, then of `b`, in
/// each 128-bit half.
///
/// # Safety
/// The CPU must have AVX2 (as for every function here, see `avx!`).
#[inline(always)]
unsafe fn unpack_rgb16<const WIDE: bool>(a: __m256i, b: __m256i) -> [Avx<WIDE>; 3] {
    // SAFETY: the caller's.
    unsafe {
        let (a, b) = (_mm256_castsi256_ps(a), _mm256_castsi256_ps(b));
        let red_green = _mm256_castps_si256(_mm256_shuffle_ps::<0b10_00_10_00>(a, b));
        let blue_alpha = _mm256_castps_si256(_mm256_shuffle_ps::<0b11_01_11_01>(a, b));
        let low = _mm256_set1_epi32(0xffff);
        [
            Avx(_mm256_cvtepi32_ps(_mm256_and_si256(red_green, low))),
            Avx(_mm256_cvtepi32_ps(_mm256_srli_epi32::<16>(red_green))),
            Avx(_mm256_cvtepi32_ps(_mm256_and_si256(blue_alpha, low))),
        ]
    }
}

/// Where two batches of eight AVX lanes go when worked on at once.
trait Pairs: Sized {
    type Pair: Lanes;
    fn pair(low: Self, high: Self) -> Self::Pair;
    fn halves(pair: Self::Pair) -> (Self, Self);
}

/// Compiled for AVX2 alone: side by side.
impl Pairs for Avx<false> {
    type Pair = Twice<Self>;

    #[inline(always)]
    fn pair(low: Self, high: Self) -> Twice<Self> {
        Twice(low, high)
    }

    #[inline(always)]
    fn halves(pair: Twice<Self>) -> (Self, Self) {
        (pair.0, pair.1)
    }
}

/// Compiled for AVX-512 too: one 512-bit register.
impl Pairs for Avx<true> {
    type Pair = Zmm;

    #[inline(always)]
    fn pair(low: Self, high: Self) -> Zmm {
        Zmm::join(low.0, high.0)
    }

    #[inline(always)]
    fn halves(pair: Zmm) -> (Self, Self) {
        let (low, high) = pair.halves();
        (Avx(low), Avx(high))
    }
}

/// Runs `job` on one AVX register per eight lanes, compiled for AVX2 (with BMI1/2 and LZCNT for
/// its scalar parts, no fused multiply-add), where this CPU has them; on [`F32x8`] otherwise.
/// Either way the job computes the same bits.
///
/// Measured on the bunny (`../shared/perf/bunny.toml`) on 1 thread, frames of a kept renderer,
/// the Z-buffer's rows (fragments and shading) run through this or on `F32x8` alone,
/// alternating in one session: at 1920×1080 (median of 30, three alternations) Phong 15.5–15.7
/// → 13.7–14.2 ms and Gouraud 12.7–13.3 → 12.4–12.7 ms; at 160×96 (median of 1,000) Phong
/// 0.90 → 0.86–0.87 ms, Gouraud unchanged. A whole-program build for x86-64-v3 read Phong 13.7
/// ms in the same session: this is what of it the rows can have at run time. (Eight lanes as
/// plain arrays left to the compiler's vectorizer stayed mostly on 128-bit and scalar
/// instructions, and were slower.)
///
/// Where the CPU has AVX-512 (F, DQ, VL) as well, the job is compiled for it too: 32 vector
/// registers, and pairs of eight lanes in one 512-bit register, in which Phong lights two
/// batches at once. Bunny at 1920×1080, 1 thread, Phong, kept renderer, median of 60, four
/// alternations with the AVX2 build on an AMD EPYC with AVX-512: 12.8–13.15 → 12.0–12.3 ms.
#[inline(always)]
pub(crate) fn run_on_best_lanes<J: LanesJob>(job: J) -> J::Output {
    if crate::render::cpu::has_avx512() {
        // SAFETY: the features `on_avx512` is compiled for were detected just above.
        return unsafe { on_avx512(job) };
    }
    if crate::render::cpu::has_avx2_bmi() {
        // SAFETY: the features `on_avx` is compiled for were detected just above.
        return unsafe { on_avx(job) };
    }
    job.run::<F32x8>()
}

/// `job.run()` on eight lanes of an AVX register, compiled for AVX2, BMI1/2 and LZCNT.
#[target_feature(enable = "avx2,bmi1,bmi2,lzcnt")]
fn on_avx<J: LanesJob>(job: J) -> J::Output {
    job.run::<Avx<false>>()
}

/// `job.run()` on eight lanes of an AVX register, pairs of them in a 512-bit one, compiled for
/// AVX-512 (F, DQ, VL) as well: 32 vector registers where AVX2 has 16.
#[target_feature(enable = "avx2,bmi1,bmi2,lzcnt,avx512f,avx512dq,avx512vl")]
fn on_avx512<J: LanesJob>(job: J) -> J::Output {
    job.run::<Avx<true>>()
}

#[cfg(test)]
mod tests {
    use super::{F32x8, Lanes, Lanes8, LanesJob, WIDTH, run_on_best_lanes};
    use crate::render::simd::{coarse_log2, pow};

    /// Sixteen lanes' values.
    type Sixteen = [f32; 2 * WIDTH];

    /// The bits of every lane operation on `a` and `b`, on eight lanes (the first eight values)
    /// and on pairs of them, and the name of the lanes they ran on.
    struct EveryOperation {
        a: Sixteen,
        b: Sixteen,
    }

    impl LanesJob for EveryOperation {
        type Output = (&'static str, Vec<Vec<u32>>, Vec<Vec<u32>>);

        fn run<L: Lanes8>(self) -> Self::Output {
            let eight = |v: &Sixteen| L::from_array(v[..WIDTH].try_into().expect("eight"));
            let bits = |v: L| v.to_array().map(f32::to_bits).to_vec();
            let pair = |v: &Sixteen| {
                let (low, high) = v.split_at(WIDTH);
                let lanes = |half: &[f32]| L::from_array(half.try_into().expect("eight"));
                L::pair(lanes(low), lanes(high))
            };
            let pair_bits = |v: L::Pair| {
                let (low, high) = L::halves(v);
                [bits(low), bits(high)].concat()
            };
            (
                std::any::type_name::<L>(),
                every_operation(self.a, self.b, eight, bits),
                every_operation(self.a, self.b, pair, pair_bits),
            )
        }
    }

    /// The bits of every operation of [`Lanes`] on lanes made of `a` and `b` by `lanes`.
    fn every_operation<P: Lanes>(
        a: Sixteen,
        b: Sixteen,
        lanes: impl Fn(&Sixteen) -> P,
        bits: impl Fn(P) -> Vec<u32>,
    ) -> Vec<Vec<u32>> {
        let (x, y) = (lanes(&a), lanes(&b));
        let positive = lanes(&a.map(|v| v.abs().max(1.0e-30)));
        let unit = lanes(&a.map(|v| v.abs().fract()));
        let exponent = lanes(&b.map(|v| (v % 100.0).trunc()));
        let shininess = lanes(&b.map(|v| v.abs() * 10.0));
        let (e, m) = positive.split_exponent();
        let any = |mask| vec![u32::from(P::any(mask))];
        vec![
            bits(x + y),
            bits(x - y),
            bits(x * y),
            bits(x / y),
            bits(-x),
            bits(positive.sqrt()),
            bits(x.max(y)),
            bits(x.min(y)),
            bits(P::keep(x.gt(y), x)),
            bits(P::keep(x.lt(y), y)),
            bits(P::keep(x.gt(y) & y.gt(x * x), x)),
            bits(P::select(x.gt(y), x, y)),
            bits(P::negate_where(x.lt(y), x)),
            any(x.gt(y)),
            any(x.gt(P::splat(f32::MAX))),
            bits(e),
            bits(m),
            bits(x.scale_by_pow2(exponent)),
            bits(pow(unit, shininess)),
            bits(coarse_log2(positive)),
        ]
    }

    /// The red, green and blue of eight texels as [`Lanes8::rgb16`] unpacks them, lane by lane,
    /// and the name of the lanes they ran on.
    struct Unpack([[u16; 4]; WIDTH]);

    impl LanesJob for Unpack {
        type Output = (&'static str, [[f32; WIDTH]; 3]);

        fn run<L: Lanes8>(self) -> Self::Output {
            let [r, g, b] = L::rgb16(&self.0);
            let name = std::any::type_name::<L>();
            (name, [r.to_array(), g.to_array(), b.to_array()])
        }
    }

    #[test]
    fn each_lane_unpacks_its_own_texel() {
        let mut draw = crate::test_draws::draws(7);
        for round in 0..500 {
            let mut texels: [[u16; 4]; WIDTH] =
                std::array::from_fn(|_| std::array::from_fn(|_| draw() as u16));
            if round == 0 {
                // The ends of the range, and alpha that must not leak into blue.
                texels[0] = [0, u16::MAX, 0, u16::MAX];
                texels[7] = [u16::MAX, 0, u16::MAX, 0];
            }
            let (lanes, got) = run_on_best_lanes(Unpack(texels));
            if crate::render::cpu::has_avx2_bmi() {
                assert!(lanes.contains("Avx"), "ran on {lanes}");
            }
            let want: [[f32; WIDTH]; 3] =
                std::array::from_fn(|c| std::array::from_fn(|k| f32::from(texels[k][c])));
            assert_eq!(got, want, "{texels:?}");
            assert_eq!(Unpack(texels).run::<F32x8>().1, want, "{texels:?}");
        }
    }

    #[test]
    fn avx_lanes_compute_the_bits_of_sse_lanes() {
        // Where the CPU has AVX2 the job runs on AVX registers, and where it has AVX-512 pairs of
        // them are 512-bit registers; every operation must give the bits `F32x8` gives (on other
        // CPUs both sides are `F32x8`).
        let mut seed = 0x9e37_79b9_u32;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 17;
            seed ^= seed << 5;
            let magnitude = 10f32.powi((seed % 13) as i32 - 6);
            let sign = if seed & 1 << 20 == 0 { 1.0 } else { -1.0 };
            sign * magnitude * (seed >> 8) as f32 / (1 << 24) as f32
        };
        let _choice = crate::render::cpu::BUILD_CHOICE
            .lock()
            .unwrap_or_else(|e| e.into_inner());
        for round in 0..2_000 {
            let mut a: Sixteen = std::array::from_fn(|_| next());
            let b: Sixteen = std::array::from_fn(|_| next());
            if round == 0 {
                // Signed zeros and exact ties.
                a[..WIDTH].copy_from_slice(&[0.0, -0.0, 1.0, -1.0, b[4], b[5], 0.5, 2.0]);
                a[WIDTH..].copy_from_slice(&[-0.0, 0.0, b[10], b[11], -2.0, 0.25, 3.0, b[15]]);
            }
            let (lanes, eight, pairs) = run_on_best_lanes(EveryOperation { a, b });
            if crate::render::cpu::has_avx2_bmi() {
                assert!(lanes.contains("Avx"), "ran on {lanes}");
            }
            let (_, sse_eight, sse_pairs) = EveryOperation { a, b }.run::<F32x8>();
            assert_eq!(eight, sse_eight, "{a:?} {b:?}");
            assert_eq!(pairs, sse_pairs, "{a:?} {b:?}");
        }
    }
}
