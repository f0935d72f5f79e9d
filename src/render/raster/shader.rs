//! What the Z-buffer does with the covered pixels it finds: a [`Shader`] colours them, eight at
//! a time, in whichever lanes the CPU runs widest.

use glam::Vec3;

use super::fragments::Fragments;
use crate::render::simd::Lanes8;

/// Colours the covered pixels of a row, eight at a time, from their `K` interpolated varyings.
/// Written once over any [`Lanes8`]: the Z-buffer runs it on one AVX register per eight lanes
/// where the CPU has AVX2, else on two SSE registers, and both give the same bits.
pub trait Shader<const K: usize = 1>: Sync {
    /// Writes the colours of `fragments`' pixels into `row`, the row's pixels.
    fn shade<L: Lanes8>(&self, fragments: &Fragments<L, K>, row: &mut [Vec3]);

    /// Whether [`Shader::shade_two`] does more than shade each batch: the Z-buffer then hands
    /// the batches of a row over two at a time.
    const SHADES_TWO: bool = false;

    /// Writes the colours of two batches of one row: the same colours as [`Shader::shade`]
    /// gives each, and a shader with much work per pixel may do both in sixteen lanes.
    fn shade_two<L: Lanes8>(
        &self,
        low: &Fragments<L, K>,
        high: &Fragments<L, K>,
        row: &mut [Vec3],
    ) {
        self.shade(low, row);
        self.shade(high, row);
    }
}

/// The interpolated varying is the colour (Gouraud shading: lit vertex colours).
pub struct VaryingColor;

impl Shader for VaryingColor {
    #[inline(always)]
    fn shade<L: Lanes8>(&self, fragments: &Fragments<L>, row: &mut [Vec3]) {
        fragments.write(fragments.varying[0], row);
    }
}
