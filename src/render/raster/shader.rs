//! What the Z-buffer does with the covered pixels it finds: a [`Shader`] colours them, eight at
//! a time, in whichever lanes the CPU runs widest.

use glam::Vec3;

use super::fragments::Fragments;
use crate::render::simd::Lanes8;

/// Colours the covered pixels of a row, eight at a time. Written once over any [`Lanes8`]: the
/// Z-buffer runs it on one AVX register per eight lanes where the CPU has AVX2, else on two SSE
/// registers, and both give the same bits.
pub trait Shader: Sync {
    /// Writes the colours of `fragments`' pixels into `row`, the row's pixels.
    fn shade<L: Lanes8>(&self, fragments: &Fragments<L>, row: &mut [Vec3]);
}

/// The interpolated varying is the colour (Gouraud shading: lit vertex colours).
pub struct VaryingColor;

impl Shader for VaryingColor {
    #[inline(always)]
    fn shade<L: Lanes8>(&self, fragments: &Fragments<L>, row: &mut [Vec3]) {
        fragments.write(fragments.varying, row);
    }
}
