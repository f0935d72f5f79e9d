//! A decoded texture: its texels, read as linear RGBA, with their mip chain.

use super::texels::Texels;

/// One level of a mip chain: `width × height` texels, rows top to bottom.
///
/// Invariant: `texels.len() == width × height`, both ≥ 1.
#[derive(Debug, Clone, PartialEq)]
pub struct MipLevel {
    pub width: u32,
    pub height: u32,
    /// Row-major from the top row; they read as linear RGB (decoded from sRGB) and alpha, each
    /// in [0, 1].
    pub texels: Texels,
}

impl MipLevel {
    /// A `width × height` level of linear RGBA `texels` (row-major from the top row), each channel
    /// clamped to [0, 1] and kept in 16 bits.
    pub fn linear(width: u32, height: u32, texels: impl IntoIterator<Item = [f32; 4]>) -> MipLevel {
        MipLevel {
            width,
            height,
            texels: Texels::linear(texels),
        }
    }

    /// The texel at column `x`, row `y` (both in range), linear RGBA.
    #[inline]
    pub fn texel(&self, x: u32, y: u32) -> [f32; 4] {
        self.texels.get((y * self.width + x) as usize)
    }
}

/// A colour texture: level 0 is the image (or the image halved until it fits the limits), each
/// next level half the size of the one before, down to 1×1.
///
/// Invariant: at least one level; level k+1 is `max(1, w/2) × max(1, h/2)` of level k's `w × h`.
#[derive(Debug, Clone, PartialEq)]
pub struct Texture {
    /// The file it came from, as the model names it (for messages and `info`).
    pub name: String,
    /// The image's own size, texels (before any halving to fit the limits).
    pub file_size: (u32, u32),
    /// Finest first.
    pub levels: Vec<MipLevel>,
}

impl Texture {
    /// The finest level's size, texels.
    pub fn size(&self) -> (u32, u32) {
        (self.levels[0].width, self.levels[0].height)
    }

    /// Whether any texel is less than fully opaque.
    pub fn has_alpha(&self) -> bool {
        self.levels[0].texels.any_translucent()
    }

    /// Bytes held by all levels.
    pub fn memory_bytes(&self) -> usize {
        self.levels.iter().map(|l| l.texels.memory_bytes()).sum()
    }
}
