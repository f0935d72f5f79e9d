//! A base-2 logarithm to about 1e-4, for the texture level of detail: a level off by 5·10⁻⁵
//! moves a trilinear blend by that share of the difference between two levels, below a
//! hundredth of an 8-bit code. [`super::log2`], accurate to the last place for the specular
//! power, runs a chain three times as long, and took a fourteenth of a textured Gouraud frame.

use super::lanes::Lanes;

/// The coefficients of f, f², f³ and f⁴ in log2(1 + f) for f in [√½ − 1, √2 − 1], fitted to the
/// least largest error (1.03·10⁻⁴).
const COEFFICIENTS: [f32; 4] = [1.441_756_7, -0.724_905_1, 0.517_586_9, -0.329_716_18];

/// Base-2 logarithm of positive finite lanes, within 1.1·10⁻⁴ (zero gives −127). Exact on powers
/// of two, negative below 1 and positive above it.
#[inline(always)]
pub fn coarse_log2<L: Lanes>(x: L) -> L {
    // m in [√½, √2), so f = m − 1 is small, and its sign is that of log2(m).
    let (e, m) = x.split_exponent();
    let f = m - L::splat(1.0);
    let [c1, c2, c3, c4] = COEFFICIENTS;
    let p = (L::splat(c4) * f + L::splat(c3)) * f + L::splat(c2);
    (p * f + L::splat(c1)) * f + e
}

#[cfg(test)]
mod tests {
    use super::coarse_log2;

    /// Every f32 from 2⁻⁴⁰ to 2⁴⁰ in steps of about one part in 2¹⁶.
    fn samples() -> impl Iterator<Item = f32> {
        let (low, high) = (2f32.powi(-40).to_bits(), 2f32.powi(40).to_bits());
        (low..=high).step_by(1 << 7).map(f32::from_bits)
    }

    #[test]
    fn within_its_stated_error_of_libm() {
        let worst = samples()
            .map(|x| (coarse_log2(x) - x.log2()).abs())
            .fold(0.0f32, f32::max);
        assert!(worst <= 1.1e-4, "largest error {worst}");
        assert!(worst > 1e-5, "a fit this coarse errs by more than {worst}");
    }

    #[test]
    fn exact_on_powers_of_two_and_signed_as_the_logarithm() {
        for k in -60..=60 {
            let x = 2f32.powi(k);
            assert_eq!(coarse_log2(x), k as f32, "2^{k}");
        }
        for x in samples() {
            let got = coarse_log2(x);
            assert_eq!(got < 0.0, x < 1.0, "log2({x}) = {got}");
        }
    }

    #[test]
    fn never_decreases_within_an_octave() {
        // The octave the polynomial spans: [√½, √2).
        let octave = std::f32::consts::FRAC_1_SQRT_2..std::f32::consts::SQRT_2;
        let mut previous = coarse_log2(octave.start);
        for x in samples().filter(|x| octave.contains(x)) {
            let got = coarse_log2(x);
            assert!(got >= previous, "log2({x}) = {got} < {previous}");
            previous = got;
        }
    }
}
