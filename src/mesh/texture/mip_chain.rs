//! Each level of a mip chain from the one before: 2×2 texels averaged in linear space (an odd
//! last row or column is averaged with itself), kept in 16 bits a channel.

use super::texture::MipLevel;

/// The levels below `base`, halving down to 1×1, finest first; `base` comes first.
pub fn mip_chain(base: MipLevel) -> Vec<MipLevel> {
    let mut levels = vec![base];
    loop {
        let last = levels.last().expect("the chain starts with the base");
        if last.width == 1 && last.height == 1 {
            return levels;
        }
        let next = halved(last);
        levels.push(next);
    }
}

/// `level` at half its size (at least 1×1), each texel the mean of the 2×2 it covers.
pub fn halved(level: &MipLevel) -> MipLevel {
    halved_with(level.width, level.height, |x, y| level.texel(x, y))
}

/// A `width × height` level whose texel at (x, y) is `texel(x, y)`, at half its size (at least
/// 1×1), each texel the mean of the 2×2 it covers, rounded to 16 bits.
pub fn halved_with(
    width_in: u32,
    height_in: u32,
    texel: impl Fn(u32, u32) -> [f32; 4],
) -> MipLevel {
    let width = (width_in / 2).max(1);
    let height = (height_in / 2).max(1);
    let texel = &texel;
    let texels = (0..height).flat_map(move |y| {
        let (y0, y1) = (2 * y, (2 * y + 1).min(height_in - 1));
        (0..width).map(move |x| {
            let (x0, x1) = (2 * x, (2 * x + 1).min(width_in - 1));
            let quad = [texel(x0, y0), texel(x1, y0), texel(x0, y1), texel(x1, y1)];
            std::array::from_fn(|c| 0.25 * (quad[0][c] + quad[1][c] + quad[2][c] + quad[3][c]))
        })
    });
    MipLevel::linear(width, height, texels)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_chain_halves_down_to_one_texel_and_keeps_the_mean() {
        // Red 0, 1/7, …, 7/7: sevenths are not whole 16-bit steps.
        let base = MipLevel::linear(4, 2, (0..8).map(|i| [i as f32 / 7.0, 0.0, 1.0, 1.0]));
        let chain = mip_chain(base);
        let sizes: Vec<(u32, u32)> = chain.iter().map(|l| (l.width, l.height)).collect();
        assert_eq!(sizes, [(4, 2), (2, 1), (1, 1)]);
        let red = |level: usize| chain[level].texel(0, 0)[0];
        let step = 1.0 / 65535.0;
        assert!((red(1) - 2.5 / 7.0).abs() <= step); // (0 + 1 + 4 + 5) / 4 sevenths
        assert!((red(2) - 3.5 / 7.0).abs() <= step); // the mean of 0..8 sevenths
        assert_eq!(chain[2].texel(0, 0)[2..], [1.0, 1.0]);
    }
}
