//! [`Sampler::sample`] run on eight Z-buffer fragments at once: the coordinates, levels, weights
//! and filtering in lanes, only the texel loads lane by lane. Every lane computes the very
//! operations the one-point sampler does, in the same order, so it gives the same bits (the
//! ray tracer's, which samples one point at a time): Phong and ray tracing keep agreeing.
//!
//! A batch whose lanes need different steps (some magnified and some minified, or trilinear
//! between different pairs of levels) or hold coordinates of 2^22 texels or more is left to the
//! one-point sampler (`None`); on the Duck at 1920×1080 that is a small share of the batches,
//! at the edges between levels.

use crate::mesh::texture::{
    Filter, MipFilter, MipLevel, Sampler, Texture, U16_STEP, Wrap, neighbours,
};
use crate::render::simd::{Lanes, Lanes8, ROUND_MAGIC, V3, WIDTH};

/// Largest magnitude a coordinate may have for [`floor`], the f32 just below 2^22: below 2^22
/// adding 1.5·2^23 rounds a number to a whole one exactly.
const LARGEST_SMALL: f32 = 4_194_303.5;

/// The linear RGB colour of `texture` read with `sampler` at (`u`, `v`) and level of detail
/// `lod`, lane by lane the bits of [`Sampler::sample`]'s first three components; `None` when
/// the lanes cannot take one path (see the module's notes).
#[inline(always)]
pub fn sample_rgb<L: Lanes8>(
    sampler: &Sampler,
    texture: &Texture,
    u: L,
    v: L,
    lod: L,
) -> Option<V3<L>> {
    let (u, v, lod) = (finite_or_zero(u), finite_or_zero(v), finite_or_zero(lod));
    let lods = lod.to_array();
    let mut magnified = 0;
    for l in lods {
        magnified += usize::from(l <= 0.0);
    }
    let level0 = &texture.levels[0];
    if magnified == WIDTH {
        return read_level(sampler, level0, u, v, sampler.magnify);
    }
    if sampler.mip == MipFilter::None {
        let filter = match magnified {
            0 => sampler.minify,
            _ if sampler.magnify == sampler.minify => sampler.minify,
            _ => return None,
        };
        return read_level(sampler, level0, u, v, filter);
    }
    if magnified > 0 {
        return None;
    }
    let deepest = (texture.levels.len() - 1) as f32;
    let lod = lod.min(L::splat(deepest));
    match sampler.mip {
        MipFilter::Nearest => {
            let mut levels = lod.to_array();
            for level in &mut levels {
                *level = level.round();
            }
            let level = same(levels)?;
            read_level(
                sampler,
                &texture.levels[level as usize],
                u,
                v,
                sampler.minify,
            )
        }
        _ => {
            let fine = floor(lod);
            let weight = lod - fine;
            let level = same(fine.to_array())? as usize;
            let a = read_level(sampler, &texture.levels[level], u, v, sampler.minify)?;
            if !L::any(weight.gt(L::splat(0.0))) {
                return Some(a);
            }
            // Where a lane's weight is 0 this is `a` to the bit: texels are finite.
            let b = read_level(sampler, &texture.levels[level + 1], u, v, sampler.minify)?;
            Some(a + (b - a) * weight)
        }
    }
}

/// The value every lane holds, if they all hold one.
#[inline(always)]
fn same(values: [f32; WIDTH]) -> Option<f32> {
    let first = values[0];
    values.iter().all(|&v| v == first).then_some(first)
}

/// `level` at (`u`, `v`) with `filter`, as `Sampler::read_level` reads it.
#[inline(always)]
fn read_level<L: Lanes8>(
    sampler: &Sampler,
    level: &MipLevel,
    u: L,
    v: L,
    filter: Filter,
) -> Option<V3<L>> {
    let (width, height) = (level.width, level.height);
    let x = u * L::splat(width as f32);
    let y = v * L::splat(height as f32);
    let [wrap_x, wrap_y] = sampler.wrap;
    match filter {
        Filter::Nearest => {
            let (i, j) = (floor_small(x)?, floor_small(y)?);
            if let Some(tiling) = Tiling::of(sampler, level) {
                return Some(texels(level, &tiling.index(i, j)));
            }
            let (column, _) = lane_neighbours(i, width, wrap_x);
            let (row, _) = lane_neighbours(j, height, wrap_y);
            // Whole numbers below width × height ≤ 2^24: exact.
            let index = (row * L::splat(width as f32) + column).to_whole_u32();
            Some(texels(level, &index))
        }
        Filter::Linear => {
            // Texel centres sit at half-integers.
            let half = L::splat(0.5);
            let (x, y) = (x - half, y - half);
            let (x0, y0) = (floor_small(x)?, floor_small(y)?);
            let (fx, fy) = (x - x0, y - y0);
            let index = match Tiling::of(sampler, level) {
                Some(tiling) => tiling.indices(x0, y0),
                None => {
                    let (i0, i1) = lane_neighbours(x0, width, wrap_x);
                    let (j0, j1) = lane_neighbours(y0, height, wrap_y);
                    // Whole numbers below width × height ≤ 2^24: exact.
                    let w = L::splat(width as f32);
                    let (row0, row1) = (j0 * w, j1 * w);
                    [
                        (row0 + i0).to_whole_u32(),
                        (row0 + i1).to_whole_u32(),
                        (row1 + i0).to_whole_u32(),
                        (row1 + i1).to_whole_u32(),
                    ]
                }
            };
            // Where every lane's right-hand texels follow its left-hand ones in memory (no wrap
            // falls between them), each pair is one load.
            let side_by_side = (0..WIDTH).all(|k| index[1][k] == index[0][k].wrapping_add(1));
            let ((t00, t10), (t01, t11)) = if side_by_side {
                (pairs(level, &index[0]), pairs(level, &index[2]))
            } else {
                // Four calls, not `index.map(..)`: the compiler leaves a map's closure out of line.
                (
                    (texels(level, &index[0]), texels(level, &index[1])),
                    (texels(level, &index[2]), texels(level, &index[3])),
                )
            };
            let top = t00 + (t10 - t00) * fx;
            let bottom = t01 + (t11 - t01) * fx;
            Some(top + (bottom - top) * fy)
        }
    }
}

/// A level of power-of-two sides repeated on both axes, whose texel indices are found with
/// masks and a shift on whole numbers: the indices the wrap in lanes ([`lane_neighbours`])
/// finds, with none of its divisions and conversions.
struct Tiling {
    /// Width − 1 and height − 1.
    masks: (u32, u32),
    /// log2 of the width.
    shift: u32,
}

impl Tiling {
    /// The tiling of `level` under `sampler`, when both of its sides are powers of two and both
    /// wrap by repeating.
    #[inline(always)]
    fn of(sampler: &Sampler, level: &MipLevel) -> Option<Tiling> {
        let (w, h) = (level.width, level.height);
        (sampler.wrap == [Wrap::Repeat; 2] && w.is_power_of_two() && h.is_power_of_two()).then(
            || Tiling {
                masks: (w - 1, h - 1),
                shift: w.trailing_zeros(),
            },
        )
    }

    /// The index of the texel at whole-number coordinates (`i`, `j`) (within ±2^22), lane by
    /// lane: the first of [`Tiling::indices`].
    #[inline(always)]
    fn index<L: Lanes8>(&self, i: L, j: L) -> [u32; WIDTH] {
        let (i, j) = (i.to_whole_u32(), j.to_whole_u32());
        let (mx, my) = self.masks;
        std::array::from_fn(|k| (j[k] & my) << self.shift | i[k] & mx)
    }

    /// The indices of the texels at whole-number coordinates (`i`, `j`) (within ±2^22), at
    /// (`i` + 1, `j`), (`i`, `j` + 1) and (`i` + 1, `j` + 1), lane by lane. A negative
    /// coordinate truncates to its two's complement, whose low bits are its remainder.
    #[inline(always)]
    fn indices<L: Lanes8>(&self, i: L, j: L) -> [[u32; WIDTH]; 4] {
        let (i, j) = (i.to_whole_u32(), j.to_whole_u32());
        let (mx, my) = self.masks;
        let mut index = [[0; WIDTH]; 4];
        for k in 0..WIDTH {
            let (i0, i1) = (i[k] & mx, i[k].wrapping_add(1) & mx);
            let (row0, row1) = (
                (j[k] & my) << self.shift,
                (j[k].wrapping_add(1) & my) << self.shift,
            );
            index[0][k] = row0 | i0;
            index[1][k] = row0 | i1;
            index[2][k] = row1 | i0;
            index[3][k] = row1 | i1;
        }
        index
    }
}

/// [`neighbours`] in lanes, for whole-number texel coordinates `texel` within ±2^22 in a row of
/// `size` texels: the indices (whole numbers in 0..size) that `texel` and `texel + 1` read, the
/// first of them what the one-point sampler's `wrapped_fast` gives. Repeat and clamp-to-edge
/// are worked out in lanes, every step exact on whole numbers below 2^24; mirrored repeat lane
/// by lane.
#[inline(always)]
fn lane_neighbours<L: Lanes8>(texel: L, size: u32, wrap: Wrap) -> (L, L) {
    let (zero, one) = (L::splat(0.0), L::splat(1.0));
    let (n, last) = (L::splat(size as f32), L::splat(size as f32 - 1.0));
    match wrap {
        Wrap::Repeat => {
            // texel − n·⌊texel / n⌋, the quotient's rounding put right by one step either way.
            let rest = texel - n * floor(texel / n);
            let rest = L::select(rest.lt(zero), rest + n, rest);
            let rest = L::select(rest.gt(last), rest - n, rest);
            let next = rest + one;
            (rest, L::select(next.gt(last), zero, next))
        }
        Wrap::ClampToEdge => (texel.max(zero).min(last), (texel + one).max(zero).min(last)),
        Wrap::MirroredRepeat => {
            let texel = texel.to_array();
            let (mut first, mut second) = ([0.0; WIDTH], [0.0; WIDTH]);
            for k in 0..WIDTH {
                let (a, b) = neighbours(texel[k], size, wrap);
                (first[k], second[k]) = (a as f32, b as f32);
            }
            (L::from_array(first), L::from_array(second))
        }
    }
}

/// The RGB of the texels at `index` of `level`, linear, lane k texel `index[k]`.
#[inline(always)]
fn texels<L: Lanes8>(level: &MipLevel, index: &[u32; WIDTH]) -> V3<L> {
    let codes = level.texels.codes();
    let mut eight = [[0; 4]; WIDTH];
    for k in 0..WIDTH {
        eight[k] = codes[index[k] as usize];
    }
    let [r, g, b] = L::rgb16(&eight);
    // As `from_u16`: the codes times one step.
    V3::new(r, g, b) * L::splat(U16_STEP)
}

/// The linear RGB of the texels of `level` at `index` and at the index after each, lane by
/// lane: each lane's two texels read as one 16-byte load.
#[inline(always)]
fn pairs<L: Lanes8>(level: &MipLevel, index: &[u32; WIDTH]) -> (V3<L>, V3<L>) {
    let codes = level.texels.codes();
    let mut eight = [[[0; 4]; 2]; WIDTH];
    for k in 0..WIDTH {
        let at = index[k] as usize;
        eight[k] = [codes[at], codes[at + 1]];
    }
    let ([r0, g0, b0], [r1, g1, b1]) = L::rgb16_pairs(&eight);
    let step = L::splat(U16_STEP);
    (V3::new(r0, g0, b0) * step, V3::new(r1, g1, b1) * step)
}

/// [`floor`] of `x`, or `None` where some lane is beyond ±[`LARGEST_SMALL`] (or infinite).
#[inline(always)]
fn floor_small<L: Lanes>(x: L) -> Option<L> {
    if L::any(x.max(-x).gt(L::splat(LARGEST_SMALL))) {
        return None;
    }
    Some(floor(x))
}

/// The largest whole number not above `x`, for |`x`| < [`LARGEST_SMALL`]: the bits of the one-point
/// sampler's `floor` (round to the nearest by adding and subtracting 1.5·2^23, then step down
/// where that went up).
#[inline(always)]
fn floor<L: Lanes>(x: L) -> L {
    let magic = L::splat(ROUND_MAGIC);
    let nearest = (x + magic) - magic;
    nearest - L::keep(nearest.gt(x), L::splat(1.0))
}

/// `x` where finite, else 0, lane by lane.
#[inline(always)]
fn finite_or_zero<L: Lanes>(x: L) -> L {
    // x − x is 0 for finite x and NaN otherwise.
    #[allow(clippy::eq_op)]
    let finite = (x - x).lt(L::splat(1.0));
    L::keep(finite, x)
}

#[cfg(test)]
mod tests {
    use glam::{Vec2, Vec3, Vec4};

    use super::*;
    use crate::mesh::texture::{MipLevel, mip_chain};
    use crate::render::simd::{F32x8, LanesJob, run_on_best_lanes};

    /// A `width × height` texture whose level 0 holds linear colours from `seed` (alpha 0),
    /// with its chain.
    fn texture(width: u32, height: u32, seed: u32) -> Texture {
        let mut draw = crate::test_draws::draws(seed.into());
        // 24 bits of a draw (below 2^31): exact in `f32`, in [0, 1).
        let mut channel = || (draw() >> 7) as f32 / (1u64 << 24) as f32;
        let texels: Vec<[f32; 4]> = (0..width * height)
            .map(|_| [channel(), channel(), channel(), 0.0])
            .collect();
        Texture {
            name: "noise".into(),
            file_size: (width, height),
            levels: mip_chain(MipLevel::linear(width, height, texels)),
        }
    }

    /// Samples eight points at once.
    #[derive(Clone, Copy)]
    struct Eight<'a> {
        sampler: &'a Sampler,
        texture: &'a Texture,
        u: [f32; WIDTH],
        v: [f32; WIDTH],
        lod: [f32; WIDTH],
    }

    impl LanesJob for Eight<'_> {
        type Output = Option<[Vec3; WIDTH]>;

        fn run<L: Lanes8>(self) -> Self::Output {
            let lanes = L::from_array;
            sample_rgb(
                self.sampler,
                self.texture,
                lanes(self.u),
                lanes(self.v),
                lanes(self.lod),
            )
            .map(V3::to_vec3s)
        }
    }

    #[test]
    fn eight_lanes_give_the_bits_of_the_one_point_sampler() {
        let mut seed = 0x2545_f491_u32;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 17;
            seed ^= seed << 5;
            seed
        };
        let wraps = [Wrap::Repeat, Wrap::ClampToEdge, Wrap::MirroredRepeat];
        let filters = [Filter::Nearest, Filter::Linear];
        let mips = [MipFilter::None, MipFilter::Nearest, MipFilter::Linear];
        let (mut lanes, mut fallbacks) = (0, 0);
        for (t, (width, height)) in [(8, 8), (16, 4), (5, 7), (1, 1), (12, 3)]
            .into_iter()
            .enumerate()
        {
            let texture = texture(width, height, t as u32 + 1);
            for round in 0..600 {
                let r = next();
                let sampler = Sampler {
                    wrap: [wraps[r as usize % 3], wraps[(r >> 2) as usize % 3]],
                    magnify: filters[(r >> 4) as usize % 2],
                    minify: filters[(r >> 5) as usize % 2],
                    mip: mips[(r >> 6) as usize % 3],
                };
                // Nearby points, as a batch of fragments is, around a point anywhere from -3 to 3,
                // at levels around one from -1 to 4; now and then a far or non-finite one.
                let unit = |bits: u32| (bits % 10_000) as f32 / 10_000.0;
                let (u0, v0) = (6.0 * unit(next()) - 3.0, 6.0 * unit(next()) - 3.0);
                let lod0 = 5.0 * unit(next()) - 1.0;
                let spread = [0.0, 0.01, 0.3][round % 3];
                let mut u = std::array::from_fn(|_| u0 + spread * unit(next()));
                let v = std::array::from_fn(|_| v0 + spread * unit(next()));
                let mut lod = std::array::from_fn(|_| lod0 + spread * unit(next()));
                if round % 50 == 7 {
                    (u[3], lod[5]) = (f32::NAN, f32::INFINITY);
                }
                if round % 50 == 9 {
                    u[2] = 1.0e7;
                }
                let eight = Eight {
                    sampler: &sampler,
                    texture: &texture,
                    u,
                    v,
                    lod,
                };
                let one = |k: usize| sampler.sample(&texture, Vec2::new(u[k], v[k]), lod[k]);
                let expected: [Vec4; WIDTH] = std::array::from_fn(one);
                for got in [run_on_best_lanes(eight), eight.run::<F32x8>()] {
                    match got {
                        Some(rgb) => {
                            lanes += 1;
                            for k in 0..WIDTH {
                                let want = expected[k].truncate().to_array().map(f32::to_bits);
                                let have = rgb[k].to_array().map(f32::to_bits);
                                assert_eq!(
                                    have, want,
                                    "lane {k} of {u:?} {v:?} {lod:?} {sampler:?}"
                                );
                            }
                        }
                        None => fallbacks += 1,
                    }
                }
            }
        }
        // Most batches take the lanes; the others are left to the one-point sampler.
        assert!(lanes > 4 * fallbacks, "{lanes} in lanes, {fallbacks} left");
    }
}
