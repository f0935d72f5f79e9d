//! DEC sixel graphics: the picture quantized to at most 256 colours (see [`super::median_cut`]),
//! sent in bands of six rows, one pass per colour in the band, with run-length encoding (`!n`).

use std::fmt::Write;

use super::median_cut::Palette;
use super::preview::PreviewImage;

/// Most colours in a sixel palette.
pub const MAX_COLOURS: usize = 256;

/// The DCS sequence that draws `image` at its own size in pixels.
pub fn encode(image: &PreviewImage) -> Vec<u8> {
    let palette = Palette::median_cut(&image.pixels, MAX_COLOURS);
    let indices: Vec<u8> = image.pixels.iter().map(|&p| palette.index_of(p)).collect();
    // P2 = 1: pixels left at zero keep the background; aspect 1:1 through the raster attributes.
    let mut out = format!("\x1bP0;1;0q\"1;1;{};{}", image.width, image.height);
    for (i, [r, g, b]) in palette.colours().iter().enumerate() {
        let pct = |c: u8| (u32::from(c) * 100 + 127) / 255;
        let _ = write!(out, "#{i};2;{};{};{}", pct(*r), pct(*g), pct(*b));
    }
    let (width, height) = (image.width as usize, image.height as usize);
    // The band's six-pixel columns for each colour, filled in one pass over its pixels: one
    // row of `width` per colour used, found through `row_of`.
    let mut row_of = [usize::MAX; MAX_COLOURS];
    let mut bits: Vec<u8> = Vec::new();
    for top in (0..height).step_by(6) {
        let rows = (height - top).min(6);
        let mut used: Vec<usize> = Vec::new();
        for dy in 0..rows {
            let y = top + dy;
            for (x, &c) in indices[y * width..(y + 1) * width].iter().enumerate() {
                let c = usize::from(c);
                if row_of[c] == usize::MAX {
                    row_of[c] = used.len();
                    used.push(c);
                    bits.resize(used.len() * width, 0);
                }
                bits[row_of[c] * width + x] |= 1 << dy;
            }
        }
        used.sort_unstable();
        for (n, &colour) in used.iter().enumerate() {
            if n > 0 {
                out.push('$');
            }
            let _ = write!(out, "#{colour}");
            let row = row_of[colour] * width;
            push_runs(&mut out, bits[row..row + width].iter().copied());
        }
        for &colour in &used {
            row_of[colour] = usize::MAX;
        }
        bits.clear();
        out.push('-');
    }
    out.push_str("\x1b\\");
    out.into_bytes()
}

/// Appends sixel characters for `bits` (six-pixel columns), runs of four or more as `!n`.
fn push_runs(out: &mut String, bits: impl Iterator<Item = u8>) {
    let mut run: Option<(u8, usize)> = None;
    let flush = |out: &mut String, (b, n): (u8, usize)| {
        let ch = char::from(0x3f + b);
        if n >= 4 {
            let _ = write!(out, "!{n}{ch}");
        } else {
            (0..n).for_each(|_| out.push(ch));
        }
    };
    for b in bits {
        run = match run {
            Some((prev, n)) if prev == b => Some((prev, n + 1)),
            Some(done) => {
                flush(out, done);
                Some((b, 1))
            }
            None => Some((b, 1)),
        };
    }
    if let Some(done) = run {
        flush(out, done);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn runs_of_four_or_more_are_compressed() {
        let mut out = String::new();
        push_runs(&mut out, [1, 1, 1, 1, 1, 0, 0, 63].into_iter());
        assert_eq!(out, "!5@??~");
    }

    #[test]
    fn a_two_colour_picture_has_two_palette_entries_and_one_band() {
        let image = PreviewImage {
            width: 2,
            height: 2,
            pixels: vec![[255, 0, 0], [0, 0, 255], [255, 0, 0], [0, 0, 255]],
        };
        let text = String::from_utf8(encode(&image)).unwrap();
        assert!(text.starts_with("\x1bP0;1;0q\"1;1;2;2"), "{text:?}");
        assert!(
            text.contains(";2;100;0;0") && text.contains(";2;0;0;100"),
            "{text:?}"
        );
        // Each colour fills rows 0 and 1 of its column: sixel bits 0b11 → 'B'.
        assert_eq!(text.matches('B').count(), 2, "{text:?}");
        assert!(text.ends_with("-\x1b\\"));
    }
}
