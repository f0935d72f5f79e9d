//! sRGB-encoded colour values from model files decoded to the linear values rastray renders
//! with (the IEC 61966-2-1 curve; `render` has the encoder for output).

use std::sync::OnceLock;

/// An sRGB-encoded value in [0, 1] (clamped; NaN reads as 0) to linear [0, 1].
#[inline]
pub fn srgb_to_linear(encoded: f32) -> f32 {
    let s = if encoded.is_nan() {
        0.0
    } else {
        encoded.clamp(0.0, 1.0)
    };
    if s <= 0.04045 {
        s / 12.92
    } else {
        ((s + 0.055) / 1.055).powf(2.4)
    }
}

/// An 8-bit sRGB code value to linear [0, 1], from [`srgb_byte_table`].
#[inline]
pub fn srgb_byte_to_linear(code: u8) -> f32 {
    srgb_byte_table()[code as usize]
}

/// The linear [0, 1] value of each 8-bit sRGB code, made on first use.
#[inline]
pub(crate) fn srgb_byte_table() -> &'static [f32; 256] {
    static TABLE: OnceLock<[f32; 256]> = OnceLock::new();
    TABLE.get_or_init(|| std::array::from_fn(|i| srgb_to_linear(i as f32 / 255.0)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_curve_has_its_known_values() {
        assert_eq!(srgb_byte_to_linear(0), 0.0);
        assert_eq!(srgb_byte_to_linear(255), 1.0);
        // 50% grey in sRGB is about 21.4% linear.
        assert!((srgb_byte_to_linear(128) - 0.2158605).abs() < 1e-6);
        assert!((srgb_to_linear(0.5) - 0.2140411).abs() < 1e-6);
        assert_eq!(srgb_to_linear(f32::NAN), 0.0);
        assert_eq!(srgb_to_linear(2.0), 1.0);
    }
}
