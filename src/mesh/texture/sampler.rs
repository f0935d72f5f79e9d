//! How a texture is read at a point: wrapping per axis, and filtering, from the level of detail
//! the renderer works out of the pixel's footprint.

use glam::{Vec2, Vec4};

use super::texture::{MipLevel, Texture};

/// What a coordinate outside [0, 1] reads (glTF's and OpenGL's three modes).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Wrap {
    /// The image tiles the plane.
    #[default]
    Repeat,
    /// The edge texels extend outward.
    ClampToEdge,
    /// The image tiles, every other copy mirrored.
    MirroredRepeat,
}

/// Within one level: the nearest texel, or the four nearest weighted (bilinear).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Filter {
    Nearest,
    #[default]
    Linear,
}

/// Between levels, when the footprint is larger than a texel.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum MipFilter {
    /// Level 0 only (glTF's `NEAREST` and `LINEAR` minification).
    None,
    /// The nearest level.
    Nearest,
    /// The two nearest levels, weighted (with a linear filter within each: trilinear).
    #[default]
    Linear,
}

/// A texture's sampler state. The default is repeat on both axes and trilinear filtering, what
/// rastray uses when a file does not say.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Sampler {
    /// Wrap of u (horizontal, 0 = the image's left edge) and v (vertical, 0 = its top edge).
    pub wrap: [Wrap; 2],
    /// Filter when a texel covers more than a pixel (level of detail ≤ 0).
    pub magnify: Filter,
    /// Filter within a level when a pixel covers more than a texel.
    pub minify: Filter,
    /// Filter between levels when a pixel covers more than a texel.
    pub mip: MipFilter,
}

impl Sampler {
    /// The colour of `texture` at `uv` ((0, 0) the image's top-left corner, (1, 1) its
    /// bottom-right), linear RGBA, for a pixel whose footprint spans 2^`lod` texels of level 0.
    /// A non-finite coordinate or level reads as 0.
    pub fn sample(&self, texture: &Texture, uv: Vec2, lod: f32) -> Vec4 {
        let uv = Vec2::new(finite_or_zero(uv.x), finite_or_zero(uv.y));
        let lod = finite_or_zero(lod);
        let deepest = (texture.levels.len() - 1) as f32;
        if lod <= 0.0 || self.mip == MipFilter::None {
            let filter = if lod <= 0.0 {
                self.magnify
            } else {
                self.minify
            };
            return self.read_level(&texture.levels[0], uv, filter);
        }
        let lod = lod.min(deepest);
        match self.mip {
            MipFilter::Nearest => {
                self.read_level(&texture.levels[lod.round() as usize], uv, self.minify)
            }
            _ => {
                let fine = lod.floor();
                let weight = lod - fine;
                let a = self.read_level(&texture.levels[fine as usize], uv, self.minify);
                if weight == 0.0 {
                    return a;
                }
                let b = self.read_level(&texture.levels[fine as usize + 1], uv, self.minify);
                a + (b - a) * weight
            }
        }
    }

    /// `level` at `uv` with `filter`.
    fn read_level(&self, level: &MipLevel, uv: Vec2, filter: Filter) -> Vec4 {
        let x = uv.x * level.width as f32;
        let y = uv.y * level.height as f32;
        match filter {
            Filter::Nearest => {
                let i = wrapped(x.floor(), level.width, self.wrap[0]);
                let j = wrapped(y.floor(), level.height, self.wrap[1]);
                Vec4::from_array(level.texel(i, j))
            }
            Filter::Linear => {
                // Texel centres sit at half-integers.
                let (x, y) = (x - 0.5, y - 0.5);
                let (x0, y0) = (x.floor(), y.floor());
                let (fx, fy) = (x - x0, y - y0);
                let i0 = wrapped(x0, level.width, self.wrap[0]);
                let i1 = wrapped(x0 + 1.0, level.width, self.wrap[0]);
                let j0 = wrapped(y0, level.height, self.wrap[1]);
                let j1 = wrapped(y0 + 1.0, level.height, self.wrap[1]);
                let t = |i, j| Vec4::from_array(level.texel(i, j));
                let top = t(i0, j0) + (t(i1, j0) - t(i0, j0)) * fx;
                let bottom = t(i0, j1) + (t(i1, j1) - t(i0, j1)) * fx;
                top + (bottom - top) * fy
            }
        }
    }
}

/// `v` when finite, else 0.
#[inline]
fn finite_or_zero(v: f32) -> f32 {
    if v.is_finite() { v } else { 0.0 }
}

/// The texel index in `0..size` that integer texel coordinate `texel` (a whole number as an
/// `f32`, of any size) reads under `wrap`.
#[inline]
fn wrapped(texel: f32, size: u32, wrap: Wrap) -> u32 {
    // Saturating: coordinates far outside behave as the nearest representable ones.
    let i = texel as i64;
    let n = i64::from(size);
    let index = match wrap {
        Wrap::Repeat => i.rem_euclid(n),
        Wrap::ClampToEdge => i.clamp(0, n - 1),
        Wrap::MirroredRepeat => {
            let m = i.rem_euclid(2 * n);
            if m >= n { 2 * n - 1 - m } else { m }
        }
    };
    index as u32
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::texture::mip_chain::mip_chain;

    /// A 4×1 texture of red values 0, 1, 2, 3.
    fn ramp() -> Texture {
        Texture {
            name: "ramp".into(),
            file_size: (4, 1),
            levels: mip_chain(MipLevel {
                width: 4,
                height: 1,
                texels: (0..4).map(|i| [i as f32, 0.0, 0.0, 1.0]).collect(),
            }),
        }
    }

    fn nearest(wrap: Wrap) -> Sampler {
        Sampler {
            wrap: [wrap; 2],
            magnify: Filter::Nearest,
            ..Sampler::default()
        }
    }

    #[test]
    fn wrap_modes_read_the_texels_they_name() {
        let t = ramp();
        let red = |s: Sampler, u: f32| s.sample(&t, Vec2::new(u, 0.5), 0.0).x;
        // u = 1.1 is texel 4.4: repeat reads texel 0, clamp texel 3, mirror texel 3.
        assert_eq!(red(nearest(Wrap::Repeat), 1.1), 0.0);
        assert_eq!(red(nearest(Wrap::ClampToEdge), 1.1), 3.0);
        assert_eq!(red(nearest(Wrap::MirroredRepeat), 1.1), 3.0);
        // u = 1.3 is texel 5.2: mirror reads texel 2; u = -0.1 (texel -0.4) reads 3, 0, 0.
        assert_eq!(red(nearest(Wrap::MirroredRepeat), 1.3), 2.0);
        assert_eq!(red(nearest(Wrap::Repeat), -0.1), 3.0);
        assert_eq!(red(nearest(Wrap::ClampToEdge), -0.1), 0.0);
        assert_eq!(red(nearest(Wrap::MirroredRepeat), -0.1), 0.0);
    }

    #[test]
    fn linear_filtering_weighs_neighbours_and_levels() {
        let t = ramp();
        let s = Sampler {
            wrap: [Wrap::ClampToEdge; 2],
            ..Sampler::default()
        };
        // Halfway between the centres of texels 1 and 2.
        assert_eq!(s.sample(&t, Vec2::new(0.5, 0.5), 0.0).x, 1.5);
        // Level 1 is (0.5, 2.5). At u = 0.125, texel 0's centre, level 0 reads 0 and level 1
        // (clamped at its edge) 0.5: a level of 0.5 reads halfway.
        assert_eq!(s.sample(&t, Vec2::new(0.125, 0.5), 1.0).x, 0.5);
        assert_eq!(s.sample(&t, Vec2::new(0.125, 0.5), 0.5).x, 0.25);
        // The coarsest level is the mean, whatever lies beyond it.
        assert_eq!(s.sample(&t, Vec2::new(0.9, 0.5), 40.0).x, 1.5);
        assert_eq!(s.sample(&t, Vec2::new(f32::NAN, 0.5), f32::NAN).x, 0.0);
    }
}
