//! A decoded texture: linear RGBA texels with their mip chain.

/// One level of a mip chain: `width × height` texels, rows top to bottom.
///
/// Invariant: `texels.len() == width × height`, both ≥ 1.
#[derive(Debug, Clone, PartialEq)]
pub struct MipLevel {
    pub width: u32,
    pub height: u32,
    /// Linear RGB (decoded from sRGB) and alpha, each in [0, 1], row-major from the top row.
    pub texels: Vec<[f32; 4]>,
}

impl MipLevel {
    /// The texel at column `x`, row `y` (both in range).
    #[inline]
    pub fn texel(&self, x: u32, y: u32) -> [f32; 4] {
        self.texels[(y * self.width + x) as usize]
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
        self.levels[0].texels.iter().any(|t| t[3] < 1.0)
    }

    /// Bytes held by all levels.
    pub fn memory_bytes(&self) -> usize {
        self.levels
            .iter()
            .map(|l| l.texels.len() * std::mem::size_of::<[f32; 4]>())
            .sum()
    }
}
