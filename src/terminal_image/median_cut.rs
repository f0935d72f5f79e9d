//! Colour quantization by median cut: the box of colours with the most pixels times the widest
//! channel range is split at its median until there are enough boxes; each box's mean is a
//! palette entry, and a pixel maps to its nearest entry.

use std::collections::HashMap;

/// A palette of at most 256 sRGB colours, with the nearest entry of every colour it was built
/// from.
#[derive(Debug, Clone)]
pub struct Palette {
    colours: Vec<[u8; 3]>,
    nearest: HashMap<[u8; 3], u8>,
}

impl Palette {
    /// A palette of at most `max` (≤ 256) colours for `pixels`; exact when they have no more
    /// distinct colours than that.
    pub fn median_cut(pixels: &[[u8; 3]], max: usize) -> Palette {
        let max = max.clamp(1, 256);
        let mut counts: HashMap<[u8; 3], u32> = HashMap::new();
        for &p in pixels {
            *counts.entry(p).or_default() += 1;
        }
        let mut boxes: Vec<Vec<([u8; 3], u32)>> = vec![counts.into_iter().collect()];
        while boxes.len() < max {
            let Some((i, channel)) = boxes
                .iter()
                .enumerate()
                .filter(|(_, b)| b.len() > 1)
                .map(|(i, b)| {
                    let (channel, range) = widest_channel(b);
                    let weight: u64 = b.iter().map(|(_, n)| u64::from(*n)).sum();
                    (i, channel, weight * u64::from(range))
                })
                .max_by_key(|&(i, _, score)| (score, std::cmp::Reverse(i)))
                .map(|(i, channel, _)| (i, channel))
            else {
                break;
            };
            let mut b = boxes.swap_remove(i);
            b.sort_unstable_by_key(|(c, _)| (c[channel], *c));
            let half: u64 = b.iter().map(|(_, n)| u64::from(*n)).sum::<u64>() / 2;
            let mut seen = 0u64;
            let cut = b
                .iter()
                .position(|(_, n)| {
                    seen += u64::from(*n);
                    seen >= half
                })
                .map_or(1, |p| p + 1)
                .clamp(1, b.len() - 1);
            let upper = b.split_off(cut);
            boxes.push(b);
            boxes.push(upper);
        }
        let colours: Vec<[u8; 3]> = boxes.iter().map(|b| mean(b)).collect();
        let nearest = boxes
            .iter()
            .flatten()
            .map(|&(c, _)| (c, nearest_index(&colours, c)))
            .collect();
        Palette { colours, nearest }
    }

    /// The palette's colours, at most 256.
    pub fn colours(&self) -> &[[u8; 3]] {
        &self.colours
    }

    /// Index of the entry nearest to `colour` (squared distance in sRGB codes).
    pub fn index_of(&self, colour: [u8; 3]) -> u8 {
        self.nearest
            .get(&colour)
            .copied()
            .unwrap_or_else(|| nearest_index(&self.colours, colour))
    }
}

/// The channel with the widest range in `b`, and that range.
fn widest_channel(b: &[([u8; 3], u32)]) -> (usize, u8) {
    (0..3)
        .map(|ch| {
            let lo = b.iter().map(|(c, _)| c[ch]).min().unwrap_or(0);
            let hi = b.iter().map(|(c, _)| c[ch]).max().unwrap_or(0);
            (ch, hi - lo)
        })
        .max_by_key(|&(ch, range)| (range, std::cmp::Reverse(ch)))
        .unwrap_or((0, 0))
}

/// The pixel-weighted mean colour of a box.
fn mean(b: &[([u8; 3], u32)]) -> [u8; 3] {
    let total: u64 = b.iter().map(|(_, n)| u64::from(*n)).sum::<u64>().max(1);
    std::array::from_fn(|ch| {
        let sum: u64 = b
            .iter()
            .map(|(c, n)| u64::from(c[ch]) * u64::from(*n))
            .sum();
        ((sum + total / 2) / total) as u8
    })
}

fn nearest_index(colours: &[[u8; 3]], c: [u8; 3]) -> u8 {
    let d2 = |p: &[u8; 3]| -> i32 { (0..3).map(|i| (p[i] as i32 - c[i] as i32).pow(2)).sum() };
    colours
        .iter()
        .enumerate()
        .min_by_key(|(_, p)| d2(p))
        .map_or(0, |(i, _)| i as u8)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn few_colours_are_kept_exactly() {
        let pixels = [[1, 2, 3], [200, 10, 10], [1, 2, 3], [0, 255, 0]];
        let palette = Palette::median_cut(&pixels, 256);
        assert_eq!(palette.colours().len(), 3);
        for p in pixels {
            assert_eq!(palette.colours()[usize::from(palette.index_of(p))], p);
        }
    }

    #[test]
    fn a_grey_ramp_in_sixteen_colours_is_within_eight_codes() {
        let pixels: Vec<[u8; 3]> = (0..=255).map(|v| [v; 3]).collect();
        let palette = Palette::median_cut(&pixels, 16);
        assert_eq!(palette.colours().len(), 16);
        for p in pixels {
            let q = palette.colours()[usize::from(palette.index_of(p))];
            assert!(p[0].abs_diff(q[0]) <= 8, "{p:?} → {q:?}");
        }
    }
}
