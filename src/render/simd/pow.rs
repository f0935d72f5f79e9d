//! x^p for the specular term, as exp2(p·log2 x) with polynomial log2 and exp2 over [`Lanes`].
//!
//! libm's `powf` is a call per value that cannot run on SIMD lanes; it took a fifth of a Phong
//! frame. These polynomials (the minimax coefficients of the Cephes library's `logf` and
//! `exp2f`) are accurate to a few units in the last place of log2 and exp2, so the result is
//! within 1e-5 relative or 1e-7 absolute of `powf` for x in [0, 1] and p in [0, 10 000] (the
//! range a material allows), far below what an 8-bit pixel resolves. Both widths run the same
//! operations, so the ray tracer's one-lane result equals a Z-buffer lane bit for bit.

use super::lanes::{Lanes, ROUND_MAGIC};

/// log2(e) − 1: log2 of 1 + f is computed as (f + y)·(1 + this), splitting off the exact 1.
const LOG2_E_MINUS_1: f32 = 0.442_695_04;

/// Base-2 logarithm of positive finite lanes (zero gives −127).
#[inline(always)]
pub fn log2<L: Lanes>(x: L) -> L {
    // m in [√½, √2) keeps f = m − 1 small, where the polynomial is accurate.
    let (e, m) = x.split_exponent();
    let f = m - L::splat(1.0);
    let z = f * f;
    // ln(1 + f) = f − f²/2 + f³·P(f).
    let mut p = L::splat(7.037_683_6e-2);
    for c in [
        -1.151_461_1e-1,
        1.167_699_9e-1,
        -1.242_014_1e-1,
        1.424_932_3e-1,
        -1.666_805_8e-1,
        2.000_071_4e-1,
        -2.499_999_4e-1,
        3.333_333e-1,
    ] {
        p = p * f + L::splat(c);
    }
    let y = p * f * z - L::splat(0.5) * z;
    // log2(1 + f) = (f + y)·log2(e), with log2(e) = 1 + LOG2_E_MINUS_1 applied in two parts.
    (f + y) * L::splat(LOG2_E_MINUS_1) + y + f + e
}

/// 2^y for y in [−126, 127].
#[inline(always)]
pub fn exp2<L: Lanes>(y: L) -> L {
    // y = i + f with i an integer and f in [−½, ½].
    let i = (y + L::splat(ROUND_MAGIC)) - L::splat(ROUND_MAGIC);
    let f = y - i;
    let mut p = L::splat(1.535_336_2e-4);
    for c in [
        1.339_887_4e-3,
        9.618_437e-3,
        5.550_332_5e-2,
        2.402_264_8e-1,
        6.931_472e-1,
    ] {
        p = p * f + L::splat(c);
    }
    (L::splat(1.0) + p * f).scale_by_pow2(i)
}

/// Smallest exponent [`pow`] computes: results below 2^−64 (5·10^−20) are returned as 2^−64.
/// Products of such a value with colours and intensities stay normal floats; the denormals that
/// 2^−126 would lead to cost about a hundred cycles per operation on x86 and slowed a Phong frame
/// down more than twofold.
const MIN_EXPONENT: f32 = -64.0;

/// x^p for x in [0, 1] and p ≥ 0, floored at 2^−64 (x^0 = 1). An x a rounding error above 1
/// gives 1.
#[inline(always)]
pub fn pow<L: Lanes>(x: L, p: L) -> L {
    exp2((p * log2(x)).max(L::splat(MIN_EXPONENT)).min(L::splat(0.0)))
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::pow;

    proptest! {
        #[test]
        fn pow_matches_libm_over_the_materials_range(x in 0.0f32..=1.0, p in 0.0f32..=10_000.0) {
            let (got, want) = (pow(x, p), x.powf(p));
            // The stated accuracy: 1e-5 relative or 1e-7 absolute (results below 2^-64 are floored).
            prop_assert!((got - want).abs() <= 1e-5 * want + 1e-7, "{x}^{p}: {got} vs {want}");
        }

        #[test]
        fn pow_near_one_keeps_tight_highlights(k in 1u32..7, p in 1.0f32..=10_000.0) {
            // Highlights of large exponents live in R·V just below 1: relative accuracy there.
            let x = 1.0 - 10f32.powi(-(k as i32));
            let (got, want) = (pow(x, p), x.powf(p));
            prop_assert!((got - want).abs() <= 1e-5 * want + 1e-7, "{x}^{p}: {got} vs {want}");
        }
    }

    #[test]
    fn pow_has_exact_anchors() {
        assert_eq!(pow(1.0f32, 60.0), 1.0, "1^p = 1: the centre of a highlight");
        assert_eq!(pow(0.5f32, 0.0), 1.0, "x^0 = 1");
        assert_eq!(pow(0.5f32, 1.0), 0.5);
        assert!(
            pow(0.0f32, 8.0) < 1e-19,
            "0^p is floored near 2^-64, not NaN"
        );
    }
}
