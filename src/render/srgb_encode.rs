//! Linear values to 8-bit sRGB codes by table: the very codes of the curve's formula
//! ([`encode_srgb_by_formula`]), without its `powf` per channel.
//!
//! The formula's code is a step function of the linear value: it rises by one at each of 255
//! thresholds. The table holds, for each run of 2^16 neighbouring `f32` bit patterns in (0, 1],
//! the code where the run starts; a threshold inside the run (there is one at most) is then
//! stepped over. Both tables are made from the formula itself on first use (7,650 evaluations,
//! 17 KB), so the codes are the formula's wherever it rises monotonically. Checked once over every
//! `f32` in [0, 1]: no code differs; the tests check each threshold, either side of it, and
//! every 1,009th bit pattern.
//!
//! By formula on one thread, an 800×600 preview picture took 13 ms to encode and a 1920×1080
//! frame 58–92 ms, more than rendering it; by table, in parallel chunks (`Frame::srgb8_pixels`),
//! 3.7 and 15 ms (the README's figures).

use std::sync::OnceLock;

/// Bits of an `f32`'s pattern below one run of the table.
const RUN_SHIFT: u32 = 16;

/// Runs of bit patterns from 0 to 1.0 inclusive.
const RUNS: usize = (1.0f32.to_bits() >> RUN_SHIFT) as usize + 1;

/// The code of linear `linear` (clamped to [0, 1]; NaN reads as 0): the IEC 61966-2-1 curve,
/// scaled to 255 and rounded half up.
#[inline]
pub fn encode_srgb_by_formula(linear: f32) -> u8 {
    (srgb_curve(linear) * 255.0 + 0.5) as u8
}

/// The sRGB transfer function: linear [0, 1] (clamped) to encoded [0, 1].
#[inline]
pub fn srgb_curve(linear: f32) -> f32 {
    let c = linear.clamp(0.0, 1.0);
    if c <= 0.003_130_8 {
        12.92 * c
    } else {
        1.055 * c.powf(1.0 / 2.4) - 0.055
    }
}

/// Linear [0, 1] (clamped; NaN reads as 0) to an 8-bit sRGB code value: [`encode_srgb_by_formula`]'s
/// code, by table.
#[inline]
pub fn encode_srgb(linear: f32) -> u8 {
    SrgbEncoder::new().encode(linear)
}

/// The tables at hand, for encoding many values.
#[derive(Clone, Copy)]
pub struct SrgbEncoder {
    tables: &'static Tables,
}

impl SrgbEncoder {
    /// The encoder, its tables made on first use.
    #[inline]
    pub fn new() -> SrgbEncoder {
        SrgbEncoder { tables: tables() }
    }

    /// [`encode_srgb_by_formula`]'s code of `linear`.
    #[inline]
    pub fn encode(self, linear: f32) -> u8 {
        // Zero, −0, negatives and NaN all encode to 0.
        if linear.is_nan() || linear <= 0.0 {
            return 0;
        }
        let c = linear.min(1.0);
        let code = self.tables.run_start[(c.to_bits() >> RUN_SHIFT) as usize];
        // One threshold at most falls inside a run (the tests would see a second one missed).
        let next = self.tables.thresholds.get(code as usize + 1);
        code + u8::from(next.is_some_and(|&t| c >= t))
    }
}

/// The thresholds and the code at the start of each run.
struct Tables {
    /// `thresholds[k]`: the least `f32` whose code is `k` or more (`thresholds[0]` is 0).
    thresholds: [f32; 256],
    /// The code of the first bit pattern of each run.
    run_start: Vec<u8>,
}

/// The tables, made on first use.
fn tables() -> &'static Tables {
    static TABLES: OnceLock<Tables> = OnceLock::new();
    TABLES.get_or_init(|| {
        let mut thresholds = [0.0f32; 256];
        for (k, threshold) in thresholds.iter_mut().enumerate().skip(1) {
            *threshold = least_with_code(k as u8);
        }
        let mut code = 0u8;
        let run_start = (0..RUNS)
            .map(|run| {
                let first = f32::from_bits((run as u32) << RUN_SHIFT);
                while code < 255 && first >= thresholds[code as usize + 1] {
                    code += 1;
                }
                code
            })
            .collect();
        Tables {
            thresholds,
            run_start,
        }
    })
}

/// The least `f32` in [0, 1] whose formula code is `code` or more (1.0 when none is), by
/// bisection on bit patterns, which order non-negative `f32`s.
fn least_with_code(code: u8) -> f32 {
    let (mut below, mut at) = (0u32, 1.0f32.to_bits());
    while at - below > 1 {
        let middle = below + (at - below) / 2;
        if encode_srgb_by_formula(f32::from_bits(middle)) >= code {
            at = middle;
        } else {
            below = middle;
        }
    }
    f32::from_bits(at)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The `f32` just below `x` > 0.
    fn before(x: f32) -> f32 {
        f32::from_bits(x.to_bits() - 1)
    }

    #[test]
    fn the_table_gives_the_formulas_code_at_and_beside_every_threshold() {
        let t = tables();
        for k in 1..256 {
            let at = t.thresholds[k];
            assert_eq!(encode_srgb_by_formula(at), k as u8, "threshold {k}");
            assert_eq!(encode_srgb_by_formula(before(at)), k as u8 - 1, "below {k}");
            for x in [at, before(at), f32::from_bits(at.to_bits() + 1)] {
                assert_eq!(encode_srgb(x), encode_srgb_by_formula(x), "{x}");
            }
        }
    }

    #[test]
    fn the_table_gives_the_formulas_code_across_the_range() {
        // Every 1,009th bit pattern from 0 to 1, and the ends and what lies outside.
        for bits in (0..=1.0f32.to_bits()).step_by(1009) {
            let x = f32::from_bits(bits);
            assert_eq!(encode_srgb(x), encode_srgb_by_formula(x), "{x}");
        }
        for x in [
            0.0,
            -0.0,
            -1.0,
            1.0,
            1.5,
            f32::INFINITY,
            f32::NAN,
            f32::MIN_POSITIVE,
        ] {
            assert_eq!(encode_srgb(x), encode_srgb_by_formula(x), "{x}");
        }
        assert_eq!(encode_srgb(0.5), 188);
    }

    #[test]
    fn every_code_decoded_encodes_to_itself() {
        for code in 0..=255u8 {
            let linear = crate::mesh::srgb_byte_to_linear(code);
            assert_eq!(encode_srgb(linear), code);
        }
    }
}
