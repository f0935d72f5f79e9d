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
///
/// Where eight bytes follow each part (as they do inside a file's text), its digits are read
/// eight at a time ([`leading_digits`]); otherwise, or for a part of eight digits or more, one
/// at a time.
#[inline]
pub fn decimal_at(bytes: &[u8], at: &mut usize) -> Option<f32> {
    let negative = sign_at(bytes, at);
    let magnitude = match digits_in_place(bytes, *at) {
        Some((whole, whole_len)) => {
            let mut end = *at + whole_len;
            let (fraction, fraction_len) = match bytes.get(end) {
                Some(b'.') => {
                    end += 1;
                    let Some(part) = digits_in_place(bytes, end) else {
                        return decimal_by_bytes(bytes, at, negative);
                    };
                    part
                }
                _ => (0, 0),
            };
            end += fraction_len;
            // A second point makes no number; no digits at all neither.
            if bytes.get(end) == Some(&b'.') || whole_len + fraction_len == 0 {
                return None;
            }
            let mantissa = whole * POWERS[fraction_len] + fraction;
            if mantissa > EXACT_INTEGERS {
                return None;
            }
            *at = end;
            mantissa as f32 / POWERS_OF_TEN[fraction_len]
        }
        None => return decimal_by_bytes(bytes, at, negative),
    };
    Some(if negative { -magnitude } else { magnitude })
}

/// [`decimal_at`] after its sign, one byte at a time.
#[inline]
fn decimal_by_bytes(bytes: &[u8], at: &mut usize, negative: bool) -> Option<f32> {
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

/// `10ᵏ` for k = 0..=7, as integers.
const POWERS: [u64; 8] = [1, 10, 100, 1_000, 10_000, 100_000, 1_000_000, 10_000_000];

/// The digits at `bytes[at..]` read eight bytes at a time: their value and how many (0 to 7).
/// `None` when fewer than eight bytes follow or the eight are all digits.
#[inline]
fn digits_in_place(bytes: &[u8], at: usize) -> Option<(u64, usize)> {
    let chunk: [u8; 8] = bytes.get(at..at + 8)?.try_into().ok()?;
    let (value, len) = leading_digits(chunk);
    (len < 8).then_some((value, len))
}

/// The leading decimal digits of `chunk`: their value and how many (0 to 8; the value is 0
/// when there are 8, which the caller reads otherwise). Eight bytes are read as one
/// little-endian word, the first byte lowest, so that no loop stops at a length it did not
/// foresee: subtracting `'0'` from every byte leaves a digit as 0 to 9 and sets the top bit of
/// the first byte that is no digit (a byte below `'0'` wraps; one above `'9'` passes 127 when
/// 118 is added). A borrow or carry from it runs only into later bytes, which are dropped.
/// The digits are then moved to the top of the word (zeros before them) and joined pairwise:
/// pairs, fours, then eight.
#[inline]
fn leading_digits(chunk: [u8; 8]) -> (u64, usize) {
    let digits = u64::from_le_bytes(chunk).wrapping_sub(0x3030_3030_3030_3030);
    let no_digit = (digits.wrapping_add(0x7676_7676_7676_7676) | digits) & 0x8080_8080_8080_8080;
    let len = (no_digit.trailing_zeros() / 8) as usize;
    if len == 0 || len == 8 {
        return (0, len);
    }
    let v = digits << (64 - 8 * len);
    let v = (v.wrapping_mul(10).wrapping_add(v >> 8)) & 0x00FF_00FF_00FF_00FF;
    let v = (v.wrapping_mul(100).wrapping_add(v >> 16)) & 0x0000_FFFF_0000_FFFF;
    let v = (v.wrapping_mul(10_000).wrapping_add(v >> 32)) & 0xFFFF_FFFF;
    (v, len)
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
/// with `*at` moved past it; `None` where there are no digits or more than 18. Digits are read
/// eight at a time where eight bytes follow (see [`leading_digits`]).
#[inline]
pub fn index_at(bytes: &[u8], at: &mut usize) -> Option<i64> {
    let negative = sign_at(bytes, at);
    if let Some((value, len)) = digits_in_place(bytes, *at) {
        if len == 0 {
            return None;
        }
        *at += len;
        let value = value as i64;
        return Some(if negative { -value } else { value });
    }
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
    use crate::test_draws::draws;

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

    /// A decimal word of 1 to `most` digits drawn from `next`: maybe signed, maybe with a
    /// point among its digits or after them.
    fn decimal_word(next: &mut impl FnMut() -> u64, most: u64) -> String {
        let r = next();
        let digits = (r % most) as usize + 1;
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
        if r >> 18 & 7 == 0 {
            word.push('.');
        }
        word
    }

    #[test]
    fn random_decimals_read_as_str_parse_reads_them() {
        let mut next = draws(11);
        for _ in 0..200_000 {
            same_as_std(&decimal_word(&mut next, 20));
        }
    }

    #[test]
    fn leading_digits_of_every_length_before_any_byte() {
        let mut next = draws(17);
        for _ in 0..100_000 {
            let r = next();
            let len = (r % 9) as usize;
            let mut chunk = [0u8; 8];
            for (k, b) in chunk.iter_mut().enumerate() {
                let any = (next() >> 8) as u8;
                *b = if k < len {
                    b'0' + (next() % 10) as u8
                } else {
                    any
                };
            }
            let digits = chunk.iter().take_while(|b| b.is_ascii_digit()).count();
            let (value, read) = leading_digits(chunk);
            assert_eq!(read, digits, "{chunk:?}");
            if (1..8).contains(&digits) {
                let text = std::str::from_utf8(&chunk[..digits]).unwrap();
                assert_eq!(value, text.parse::<u64>().unwrap(), "{chunk:?}");
            }
        }
    }

    /// `word` read in place, as inside a file's text (more bytes after it), reads as
    /// `str::parse` reads it, whatever ends it.
    fn same_as_std_in_text(word: &str) {
        let std = word.parse::<f32>().ok().map(f32::to_bits);
        for end in [" 1234567890", "\n", "/0123456789", "\r\n v 1 2 3"] {
            let text = format!("{word}{end}");
            let mut at = 0;
            let read = decimal_at(text.as_bytes(), &mut at).filter(|_| at == word.len());
            if let Some(value) = read {
                assert_eq!(Some(value.to_bits()), std, "{text:?}");
            }
        }
    }

    #[test]
    fn decimals_in_text_read_as_str_parse_reads_them() {
        let mut next = draws(13);
        let mut read = 0;
        for _ in 0..200_000 {
            let word = decimal_word(&mut next, 16);
            same_as_std_in_text(&word);
            let text = format!("{word} 0123456789");
            read += decimal_at(text.as_bytes(), &mut 0).is_some() as usize;
        }
        assert!(read > 50_000, "{read} of 200000 read in place");
        for word in [
            "0", "-0.5", "1.", ".5", ".", "-", "+", "1.2.3", "16777216", "16777217",
        ] {
            same_as_std_in_text(word);
        }
    }

    /// Index words of every form: signed, empty, malformed, long, overflowing, not ASCII.
    const INDEX_WORDS: &[&str] = &[
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
        "1234567",
        "12345678",
        "999999999999999999",
        "9223372036854775807",
        "9223372036854775808",
        "-9223372036854775808",
        "00000000000000000000001",
        "１",
    ];

    #[test]
    fn indices_read_as_str_parse_reads_them() {
        for word in INDEX_WORDS {
            assert_eq!(parse_index(word), word.parse::<i64>().ok(), "{word:?}");
        }
    }

    #[test]
    fn indices_in_text_read_as_str_parse_reads_them() {
        for word in INDEX_WORDS {
            for end in ["/0123456789", " 12345678", "\n"] {
                let text = format!("{word}{end}");
                let mut at = 0;
                let read = index_at(text.as_bytes(), &mut at);
                let std = word.parse::<i64>().ok();
                match read {
                    Some(value) if at == word.len() => assert_eq!(Some(value), std, "{text:?}"),
                    _ => assert!(std.is_none() || word.len() > 18, "{text:?}"),
                }
            }
        }
    }
}
