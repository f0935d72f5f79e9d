//! How large a texture may be. A file declares its size in its header: that is checked before
//! anything is decoded or allocated, so a 100000×100000 image costs nothing to refuse.

/// Longest side a texture file may declare, texels.
pub const MAX_TEXTURE_SIDE: u32 = 16_384;

/// Most texels a texture file may declare (8192×8192): decoding one takes 4 bytes a texel
/// while it is read.
pub const MAX_TEXTURE_DECLARED_TEXELS: u64 = 1 << 26;

/// Most texels the finest level keeps (4096×4096): a larger image is halved until it fits.
/// The base holds 8 bytes a texel (16-bit linear RGBA) and its mip chain a third more, so a
/// texture takes at most about 179 MB.
pub const MAX_TEXTURE_BASE_TEXELS: u64 = 1 << 24;
