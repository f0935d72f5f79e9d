//! How a texture is read at a point: wrapping per axis, and filtering, from the level of detail
//! the renderer works out of the pixel's footprint.

use glam::{Vec2, Vec4};

use super::texels::from_u16;
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
    ///
    /// Inlined into its callers, so that it runs in the Z-buffer's wide-register code.
    #[inline(always)]
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
                let fine = floor(lod);
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
    #[inline(always)]
    fn read_level(&self, level: &MipLevel, uv: Vec2, filter: Filter) -> Vec4 {
        let codes = level.texels.codes();
        // Texel `i`, row-major, as linear RGBA.
        let texel = |i: usize| from_u16(codes[i]);
        let x = uv.x * level.width as f32;
        let y = uv.y * level.height as f32;
        match filter {
            Filter::Nearest => {
                let i = wrapped_fast(floor(x), level.width, self.wrap[0]);
                let j = wrapped_fast(floor(y), level.height, self.wrap[1]);
                texel((j * level.width + i) as usize)
            }
            Filter::Linear => {
                // Texel centres sit at half-integers.
                let (x, y) = (x - 0.5, y - 0.5);
                let (x0, y0) = (floor(x), floor(y));
                let (fx, fy) = (x - x0, y - y0);
                let (i0, i1) = neighbours(x0, level.width, self.wrap[0]);
                let (j0, j1) = neighbours(y0, level.height, self.wrap[1]);
                let (row0, row1) = (j0 * level.width, j1 * level.width);
                let t = |row: u32, i: u32| texel((row + i) as usize);
                let (t00, t10) = (t(row0, i0), t(row0, i1));
                let (t01, t11) = (t(row1, i0), t(row1, i1));
                let top = t00 + (t10 - t00) * fx;
                let bottom = t01 + (t11 - t01) * fx;
                top + (bottom - top) * fy
            }
        }
    }
}

/// Largest integer texel coordinate whose neighbour is found by adding 1 to its index: below
/// 2^23 an `f32` holds every integer and its successor exactly.
const EXACT_TEXEL: f32 = 8_388_608.0;

/// Whether `x` lies strictly within ±[`EXACT_TEXEL`] (false for NaN).
#[inline]
fn is_small(x: f32) -> bool {
    x.abs() < EXACT_TEXEL
}

/// [`wrapped`] of integer texel coordinate `texel`, without its 64-bit remainder (four
/// divisions a pixel on the Duck, whose minification reads the nearest texel of two levels)
/// where `texel` is small: a 32-bit one, or a mask on power-of-two sizes.
#[inline(always)]
fn wrapped_fast(texel: f32, size: u32, wrap: Wrap) -> u32 {
    if !is_small(texel) {
        return wrapped(texel, size, wrap);
    }
    // Sizes are at most MAX_TEXTURE_SIDE, so 2·size and |texel| + 1 fit an i32.
    let (i, n) = (texel as i32, size as i32);
    let index = match wrap {
        Wrap::Repeat => modulo(i, n),
        Wrap::ClampToEdge => i.clamp(0, n - 1),
        Wrap::MirroredRepeat => mirrored(modulo(i, 2 * n), n),
    };
    index as u32
}

/// The texel indices that integer texel coordinates `texel` and `texel + 1` read under `wrap`
/// in a row of `size`: [`wrapped`] of each, with one remainder rather than two, and none on
/// power-of-two sizes (a mask), as [`wrapped_fast`].
#[inline(always)]
pub(crate) fn neighbours(texel: f32, size: u32, wrap: Wrap) -> (u32, u32) {
    if !is_small(texel) {
        return (wrapped(texel, size, wrap), wrapped(texel + 1.0, size, wrap));
    }
    let (i, n) = (texel as i32, size as i32);
    // The index after `k` in 0..m, going round.
    let next = |k: i32, m: i32| if k + 1 == m { 0 } else { k + 1 };
    let (a, b) = match wrap {
        Wrap::Repeat => {
            let a = modulo(i, n);
            (a, next(a, n))
        }
        Wrap::ClampToEdge => (i.clamp(0, n - 1), (i + 1).clamp(0, n - 1)),
        Wrap::MirroredRepeat => {
            let m = modulo(i, 2 * n);
            (mirrored(m, n), mirrored(next(m, 2 * n), n))
        }
    };
    (a as u32, b as u32)
}

/// `i` modulo `m` (> 0), in 0..m: a mask when `m` is a power of two.
#[inline]
fn modulo(i: i32, m: i32) -> i32 {
    if m & (m - 1) == 0 {
        i & (m - 1)
    } else {
        i.rem_euclid(m)
    }
}

/// The texel that index `m` in 0..2·`n` of a mirrored pair of copies of a row of `n` reads.
#[inline]
fn mirrored(m: i32, n: i32) -> i32 {
    if m >= n { 2 * n - 1 - m } else { m }
}

/// The largest whole number not above `x`, as `f32::floor` gives it (up to the sign of a zero),
/// without its call into libm: the baseline x86-64 build has no rounding instruction, and the
/// calls took 2% of the samples of `rastray render` on the textured Duck at 1920×1080 (perf).
#[inline]
fn floor(x: f32) -> f32 {
    if !is_small(x) {
        // Whole already (or not finite).
        return x;
    }
    let t = x as i32 as f32;
    if t > x { t - 1.0 } else { t }
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

    /// A 4×1 texture of red values 0, 1/3, 2/3, 1.
    fn ramp() -> Texture {
        let texels = (0..4).map(|i| [i as f32 / 3.0, 0.0, 0.0, 1.0]);
        Texture {
            name: "ramp".into(),
            file_size: (4, 1),
            levels: mip_chain(MipLevel::linear(4, 1, texels)),
        }
    }

    /// Thirds of red in `sample` (the ramp's texel index at a texel's centre), to within the
    /// texels' 16-bit rounding.
    fn thirds(sample: Vec4) -> f32 {
        let thirds = 3.0 * sample.x;
        let nearest_hundredth = (thirds * 100.0).round() / 100.0;
        assert!((thirds - nearest_hundredth).abs() < 1e-4, "{thirds}");
        nearest_hundredth
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
        let red = |s: Sampler, u: f32| thirds(s.sample(&t, Vec2::new(u, 0.5), 0.0));
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
        let red = |u: f32, lod: f32| thirds(s.sample(&t, Vec2::new(u, 0.5), lod));
        // Halfway between the centres of texels 1 and 2.
        assert_eq!(red(0.5, 0.0), 1.5);
        // Level 1 is (0.5, 2.5). At u = 0.125, texel 0's centre, level 0 reads 0 and level 1
        // (clamped at its edge) 0.5: a level of 0.5 reads halfway.
        assert_eq!(red(0.125, 1.0), 0.5);
        assert_eq!(red(0.125, 0.5), 0.25);
        // The coarsest level is the mean, whatever lies beyond it.
        assert_eq!(red(0.9, 40.0), 1.5);
        assert_eq!(s.sample(&t, Vec2::new(f32::NAN, 0.5), f32::NAN).x, 0.0);
    }

    #[test]
    fn floor_is_f32_floor() {
        let odd = [
            -8_388_609.5,
            -8_388_608.0,
            8_388_607.5,
            1e20,
            -1e20,
            f32::INFINITY,
        ];
        let values = (-4000..4000).map(|i| i as f32 * 0.37).chain(odd);
        for x in values {
            assert_eq!(floor(x), x.floor(), "{x}");
        }
        assert!(floor(f32::NAN).is_nan());
    }

    #[test]
    fn fast_wraps_are_the_wrapped_texels() {
        let wraps = [Wrap::Repeat, Wrap::ClampToEdge, Wrap::MirroredRepeat];
        for size in [1, 2, 3, 4, 5, 7, 8, 512, 1000] {
            for wrap in wraps {
                let far = [-1e9, -8_388_609.0, 8_388_607.0, 8_388_608.0, 3e9];
                for texel in (-3000..3000).map(|t| t as f32).chain(far) {
                    assert_eq!(wrapped_fast(texel, size, wrap), wrapped(texel, size, wrap));
                    assert_eq!(
                        neighbours(texel, size, wrap),
                        (wrapped(texel, size, wrap), wrapped(texel + 1.0, size, wrap)),
                        "texel {texel}, size {size}, {wrap:?}"
                    );
                }
            }
        }
    }
}
