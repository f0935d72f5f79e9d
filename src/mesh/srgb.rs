//! The sRGB transfer curve, decoded: colours that files store encoded (OBJ vertex colours, 8-bit
//! texels and PLY colours) become the linear values the renderers light with.

/// An sRGB-encoded value in [0, 1] to linear light in [0, 1] (IEC 61966-2-1).
#[inline]
pub fn srgb_to_linear(s: f32) -> f32 {
    if s <= 0.04045 {
        s / 12.92
    } else {
        ((s + 0.055) / 1.055).powf(2.4)
    }
}
