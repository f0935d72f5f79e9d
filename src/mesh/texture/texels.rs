//! How a mip level holds its texels: linear values in 16 bits a channel (8 bytes a texel),
//! compact enough that the texels a frame reads stay in the processor's caches, and laid out so
//! that eight texels unpack into lanes at once ([`crate::render::simd::Lanes8::rgb16`]): no
//! table look-up per channel, as the image's own sRGB bytes would need. An image's own level is
//! its decoded texels, each within half a step (1/131070) of the exact decode; averaged levels
//! are within half a step of the mean of the 2×2 texels above them. Filtering is done on linear
//! values. On the Duck's 512×512 texture: 2.8 MB, where linear `f32` texels took 5.6 MB.

use glam::Vec4;

/// Linear values per step of a 16-bit channel: 65535 steps from 0 to 1.
const STEPS16: f32 = 65_535.0;

/// A level's texels, row-major from the top row: linear RGBA in steps of 1/65535.
#[derive(Debug, Clone, PartialEq)]
pub struct Texels(Vec<[u16; 4]>);

impl Texels {
    /// `texels`, linear RGBA, each channel clamped to [0, 1] and rounded to the nearest step of
    /// 1/65535 (NaN reads as 0).
    pub fn linear(texels: impl IntoIterator<Item = [f32; 4]>) -> Texels {
        Texels(texels.into_iter().map(|t| t.map(to_u16)).collect())
    }

    /// Bytes they hold.
    pub fn memory_bytes(&self) -> usize {
        std::mem::size_of_val(&self.0[..])
    }

    /// The 16-bit codes of every texel, row-major.
    #[inline(always)]
    pub fn codes(&self) -> &[[u16; 4]] {
        &self.0
    }

    /// Texel `index` as linear RGBA.
    #[inline]
    pub fn get(&self, index: usize) -> [f32; 4] {
        from_u16(self.0[index]).to_array()
    }

    /// Whether any texel's alpha is below 1.
    pub fn any_translucent(&self) -> bool {
        self.0.iter().any(|t| t[3] < u16::MAX)
    }
}

/// Bytes a texel takes.
pub const TEXEL_BYTES: u64 = 8;

/// The linear value of one step of a 16-bit channel: a code reads as code × this.
pub const U16_STEP: f32 = 1.0 / STEPS16;

/// The linear RGBA of a 16-bit texel.
#[inline(always)]
pub fn from_u16([r, g, b, a]: [u16; 4]) -> Vec4 {
    Vec4::new(f32::from(r), f32::from(g), f32::from(b), f32::from(a)) * U16_STEP
}

/// `value` clamped to [0, 1] as the nearest 16-bit step (NaN reads as 0).
#[inline]
fn to_u16(value: f32) -> u16 {
    // `as` saturates and takes NaN to 0.
    (value.clamp(0.0, 1.0) * STEPS16 + 0.5) as u16
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::srgb_byte_to_linear;

    #[test]
    fn sixteen_bits_keep_values_within_half_a_step_and_the_ends_exactly() {
        assert_eq!(
            from_u16([0, u16::MAX, 0, u16::MAX]),
            Vec4::new(0.0, 1.0, 0.0, 1.0)
        );
        for i in 0..=10_000 {
            let v = i as f32 / 10_000.0;
            let back = from_u16([to_u16(v); 4]).x;
            assert!((back - v).abs() <= 0.5 / STEPS16 + 1e-7, "{v} -> {back}");
        }
        assert_eq!(to_u16(f32::NAN), 0);
        assert_eq!(to_u16(-1.0), 0);
        assert_eq!(to_u16(2.0), u16::MAX);
    }

    #[test]
    fn the_darkest_srgb_steps_stay_apart_in_sixteen_bits() {
        // sRGB codes 0..4 are 0.0003 linear apart: some 20 steps of 1/65535.
        let codes: Vec<u16> = (0..=4).map(|c| to_u16(srgb_byte_to_linear(c))).collect();
        assert_eq!(codes, [0, 20, 40, 60, 80]);
    }

    #[test]
    fn texels_read_as_linear_values_and_know_their_alpha() {
        let opaque = Texels::linear([[0.25, 0.5, 1.0, 1.0]; 3]);
        assert_eq!(
            opaque.get(1),
            [0.25, 0.5, 1.0, 1.0].map(|v| from_u16([to_u16(v); 4]).x)
        );
        assert!(!opaque.any_translucent());
        assert_eq!(opaque.memory_bytes(), 24);
        let translucent = Texels::linear([[0.0, 0.0, 0.0, 1.0], [0.0, 0.0, 0.0, 0.2]]);
        assert!(translucent.any_translucent());
    }
}
