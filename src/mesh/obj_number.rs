//! The numbers of OBJ text, read as `str::parse` reads them, bit for bit, only faster for the
//! plain forms exporters write.
//!
//! A coordinate such as `-0.5257311` (a sign, at most 18 digits, one point, no exponent) whose
//! digits make an integer m ≤ 2²⁴ with k ≤ 10 of them after the point is m / 10ᵏ: both are
//! exact in `f32`, so one IEEE division rounds the quotient correctly, as `str::parse` must
//! (it takes the same fast path, after more checks). Anything else (more digits, exponents,
//! `inf`, `nan`, words that are no number) goes to `str::parse`. On the 1.31M-triangle
//! icosphere's 2M coordinates this halves the time spent reading numbers.

/// `10ᵏ` for k = 0..=10, each exact in `f32`.
const POWERS_OF_TEN: [f32; 11] = [1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10];

/// Largest integer whose neighbours are all exact in `f32`: 2²⁴.
const EXACT_INTEGERS: u64 = 1 << 24;

/// `word` as `word.parse::<f32>().ok()` reads it.
#[inline]
pub fn parse_f32(word: &str) -> Option<f32> {
    plain_decimal(word.as_bytes()).or_else(|| word.parse().ok())
}

/// A plain decimal (`[+-]digits[.digits]`) that is exact as m / 10ᵏ; `None` for any other
/// word, which [`parse_f32`] hands to `str::parse`.
#[inline]
fn plain_decimal(bytes: &[u8]) -> Option<f32> {
    let mut at = 0;
    decimal_at(bytes, &mut at).filter(|_| at == bytes.len())
}

/// The plain decimal at `bytes[*at..]` (see [`plain_decimal`]), up to the first byte that is
/// neither a digit nor its point, with `*at` moved past it: the value `parse_f32` gives the
/// word when that byte ends it. `None` (`*at` anywhere) when it is no plain decimal.
#[inline]
pub fn decimal_at(bytes: &[u8], at: &mut usize) -> Option<f32> {
    let negative = sign_at(bytes, at);
    let (mut mantissa, mut count, mut point) = (0u64, 0usize, None);
    while let Some(&b) = bytes.get(*at) {
        match b {
            b'0'..=b'9' if count < 18 => {
                mantissa = mantissa * 10 + (b - b'0') as u64;
                count += 1;
            }
            b'0'..=b'9' => return None,
            b'.' if point.is_none() => point = Some(*at + 1),
            b'.' => return None,
            _ => break,
        }
        *at += 1;
    }
    let fraction = point.map_or(0, |from| *at - from);
    if count == 0 || mantissa > EXACT_INTEGERS || fraction >= POWERS_OF_TEN.len() {
        return None;
    }
    let magnitude = mantissa as f32 / POWERS_OF_TEN[fraction];
    Some(if negative { -magnitude } else { magnitude })
}

/// An index as written, as `word.parse::<i64>().ok()` reads it: an optional sign and decimal
/// digits, within `i64`.
#[inline]
pub fn parse_index(word: &str) -> Option<i64> {
    let mut at = 0;
    match index_at(word.as_bytes(), &mut at) {
        Some(value) if at == word.len() => Some(value),
        // Longer than 18 digits, or not an index: `str::parse`'s to judge.
        _ => word.parse().ok(),
    }
}

/// Whether `bytes[*at..]` starts with `-`; a sign (`-` or `+`) is stepped over.
#[inline]
fn sign_at(bytes: &[u8], at: &mut usize) -> bool {
    let negative = bytes.get(*at) == Some(&b'-');
    if matches!(bytes.get(*at), Some(b'-' | b'+')) {
        *at += 1;
    }
    negative
}

/// The index at `bytes[*at..]`, an optional sign and 1 to 18 digits (which cannot overflow),
/// with `*at` moved past it; `None` where there are no digits or more than 18.
#[inline]
pub fn index_at(bytes: &[u8], at: &mut usize) -> Option<i64> {
    let negative = sign_at(bytes, at);
    let start = *at;
    let mut value = 0i64;
    while let Some(&b) = bytes.get(*at).filter(|b| b.is_ascii_digit()) {
        if *at - start == 18 {
            return None;
        }
        value = value * 10 + (b - b'0') as i64;
        *at += 1;
    }
    if *at == start {
        return None;
    }
    Some(if negative { -value } else { value })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn same_as_std(word: &str) {
        let std = word.parse::<f32>().ok().map(f32::to_bits);
        assert_eq!(parse_f32(word).map(f32::to_bits), std, "{word:?}");
    }

    #[test]
    fn numbers_read_bit_for_bit_as_str_parse_reads_them() {
        for word in [
            "0",
            "-0",
            "+0",
            "0.0",
            "-0.0000000",
            "1",
            "-1",
            "0.5257311",
            "-0.8506508",
            "1.",
            ".5",
            "-.5",
            ".",
            "-",
            "+",
            "",
            "1e3",
            "1E-3",
            "inf",
            "-inf",
            "NaN",
            "nan",
            "1.2.3",
            "1,5",
            " 1",
            "1 ",
            "0x10",
            "16777216",
            "16777217",
            "16777215.5",
            "0.16777217",
            "123456789012345678",
            "1234567890123456789",
            "0.0000000001",
            "0.00000000001",
            "3.4028235e38",
            "3.5e38",
            "1e-46",
            "00000000000000000001",
            "１",
        ] {
            same_as_std(word);
        }
    }

    #[test]
    fn random_decimals_read_as_str_parse_reads_them() {
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        };
        for _ in 0..200_000 {
            let r = next();
            let digits = (r % 20) as usize + 1;
            let point = (r >> 8) as usize % (digits + 1);
            let mut word = String::new();
            if r >> 16 & 1 == 1 {
                word.push('-');
            }
            for k in 0..digits {
                if k == point && r >> 17 & 1 == 1 {
                    word.push('.');
                }
                word.push((b'0' + (next() % 10) as u8) as char);
            }
            same_as_std(&word);
        }
    }

    #[test]
    fn indices_read_as_str_parse_reads_them() {
        for word in [
            "1",
            "-1",
            "+7",
            "0",
            "-0",
            "",
            "-",
            "+",
            "1a",
            "a1",
            "1/2",
            "999999999999999999",
            "9223372036854775807",
            "9223372036854775808",
            "-9223372036854775808",
            "00000000000000000000001",
            "１",
        ] {
            assert_eq!(parse_index(word), word.parse::<i64>().ok(), "{word:?}");
        }
    }
}
