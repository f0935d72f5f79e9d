//! Pictures drawn in character cells: each cell is one glyph from a set of block patterns, in a
//! foreground colour over a background colour. For every cell the encoder tries each pattern of
//! the set and keeps the glyph and the two colours with the least squared error against the
//! pixels under the cell (the colours are then the means of the pixels each part covers).
//!
//! The picture comes at [`SAMPLES_X`]×[`SAMPLES_Y`] pixels a cell, a grid that every set's
//! sub-cells divide: half blocks and quadrants 2×2 (3×6 pixels each), sextants 2×3 (3×4),
//! braille 2×4 (3×3). So each sub-cell averages its own pixels, a box filter, and the choice sees
//! the detail inside a sub-cell too.

use std::fmt::Write;

use crate::tui::preview::{ColorMode, PreviewImage, nearest_256};

/// Pixels across one cell in the picture an encoder takes.
pub const SAMPLES_X: u32 = 6;
/// Pixels down one cell in the picture an encoder takes.
pub const SAMPLES_Y: u32 = 12;

/// A set of glyphs that split a cell into sub-cells.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum GlyphSet {
    /// `▀ ▄ ▌ ▐`, full block and space: halves of a 2×2 grid.
    HalfBlock,
    /// The quadrants `▘▝▖▗▚▞▙▛▜▟` with the half blocks, full block and space: every pattern
    /// of a 2×2 grid.
    Quadrant,
    /// Sextants U+1FB00–U+1FB3B with `▌ ▐`, full block and space: every pattern of a 2×3 grid.
    Sextant,
    /// Braille U+2800–U+28FF: every pattern of a 2×4 grid of dots.
    Braille,
}

impl GlyphSet {
    /// Every set, sharpest last.
    pub const ALL: [GlyphSet; 4] = [
        GlyphSet::HalfBlock,
        GlyphSet::Quadrant,
        GlyphSet::Sextant,
        GlyphSet::Braille,
    ];

    /// The set's name, as `--graphics` spells it.
    pub fn name(self) -> &'static str {
        match self {
            GlyphSet::HalfBlock => "halfblock",
            GlyphSet::Quadrant => "quadrant",
            GlyphSet::Sextant => "sextant",
            GlyphSet::Braille => "braille",
        }
    }

    /// Sub-cells across and down one cell.
    fn grid(self) -> (u32, u32) {
        match self {
            GlyphSet::HalfBlock | GlyphSet::Quadrant => (2, 2),
            GlyphSet::Sextant => (2, 3),
            GlyphSet::Braille => (2, 4),
        }
    }

    /// The patterns the set can draw on its grid, as masks of sub-cells (bit `row * 2 +
    /// column`), each with its glyph and the glyph of its complement where the set has one. A
    /// pattern and its complement draw the same picture with the colours swapped, so only one of
    /// each pair is tried; the empty pattern stands for a cell of one colour.
    fn patterns(self) -> Vec<Pattern> {
        let all = 1u32 << (self.grid().0 * self.grid().1);
        (0..all)
            .filter_map(|mask| self.glyph(mask).map(|glyph| (mask, glyph)))
            .filter(|&(mask, _)| {
                mask != all - 1
                    && (mask == 0 || mask & 1 == 1 || self.glyph(!mask & (all - 1)).is_none())
            })
            .map(|(mask, glyph)| Pattern {
                mask,
                glyph,
                complement: self.glyph(!mask & (all - 1)),
            })
            .collect()
    }

    /// Patterns the set draws beyond its grid's, on a grid of their own: chafa's sextant set
    /// (and so this one) also has the upper and lower half blocks, which split a cell into two
    /// rows where sextants have three.
    fn extra_layer(self) -> Option<Layer> {
        (self == GlyphSet::Sextant).then(|| Layer {
            grid: (2, 2),
            patterns: vec![Pattern {
                mask: 0b0011,
                glyph: '▀',
                complement: Some('▄'),
            }],
        })
    }

    /// Every grid the set's patterns lie on, with those patterns.
    fn layers(self) -> Vec<Layer> {
        let mut layers = vec![Layer {
            grid: self.grid(),
            patterns: self.patterns(),
        }];
        layers.extend(self.extra_layer());
        layers
    }

    /// The glyph that fills the sub-cells of `mask` with the foreground, if the set has one.
    fn glyph(self, mask: u32) -> Option<char> {
        match self {
            GlyphSet::HalfBlock => match mask {
                0 => Some(' '),
                0b0011 => Some('▀'),
                0b1100 => Some('▄'),
                0b0101 => Some('▌'),
                0b1010 => Some('▐'),
                0b1111 => Some('█'),
                _ => None,
            },
            GlyphSet::Quadrant => Some(QUADRANTS[mask as usize]),
            GlyphSet::Sextant => Some(sextant(mask)),
            GlyphSet::Braille => {
                // Braille numbers its dots down the left column first (1, 2, 3, then 7 at the
                // bottom), then the right (4, 5, 6, then 8).
                let mut bits = 0u32;
                for (sub, dot) in [0, 3, 1, 4, 2, 5, 6, 7].into_iter().enumerate() {
                    if mask >> sub & 1 == 1 {
                        bits |= 1 << dot;
                    }
                }
                char::from_u32(0x2800 + bits)
            }
        }
    }
}

/// A split of a cell into sub-cells drawn in the foreground (`mask`) and the rest.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Pattern {
    mask: u32,
    glyph: char,
    /// The glyph of the complementary mask, which draws the same split with the colours swapped.
    complement: Option<char>,
}

/// Patterns on one grid of sub-cells.
#[derive(Debug, Clone)]
struct Layer {
    grid: (u32, u32),
    patterns: Vec<Pattern>,
}

/// Quadrant glyphs by mask (bit 0 upper left, 1 upper right, 2 lower left, 3 lower right).
const QUADRANTS: [char; 16] = [
    ' ', '▘', '▝', '▀', '▖', '▌', '▞', '▛', '▗', '▚', '▐', '▜', '▄', '▙', '▟', '█',
];

/// The sextant glyph of `mask` (bits 0–5 for sextants 1–6, numbered across then down). Unicode
/// leaves out the four patterns that older blocks already have: empty, the left and right
/// columns (`▌ ▐`) and full.
fn sextant(mask: u32) -> char {
    match mask {
        0 => ' ',
        0b010101 => '▌',
        0b101010 => '▐',
        0b111111 => '█',
        _ => {
            let skipped = u32::from(mask > 0b010101) + u32::from(mask > 0b101010);
            char::from_u32(0x1FB00 + mask - 1 - skipped).unwrap_or('█')
        }
    }
}

/// One cell's pixels summed per sub-cell: colour sums, and the sum of squared values over all.
struct CellSums {
    /// Per sub-cell, the sums of r, g and b.
    sums: Vec<[f32; 3]>,
    /// Pixels per sub-cell.
    per_sub: f32,
}

impl CellSums {
    fn of(image: &PreviewImage, col: u32, row: u32, (gx, gy): (u32, u32)) -> CellSums {
        let (sw, sh) = (SAMPLES_X / gx, SAMPLES_Y / gy);
        let mut sums = vec![[0.0f32; 3]; (gx * gy) as usize];
        for y in 0..SAMPLES_Y {
            for x in 0..SAMPLES_X {
                let pixel = image
                    .pixel(col * SAMPLES_X + x, row * SAMPLES_Y + y)
                    .unwrap_or([0; 3]);
                let sub = &mut sums[((y / sh) * gx + x / sw) as usize];
                for c in 0..3 {
                    sub[c] += f32::from(pixel[c]);
                }
            }
        }
        CellSums {
            sums,
            per_sub: (sw * sh) as f32,
        }
    }

    /// For the sub-cells of `mask`: the colour sum and the pixel count.
    fn part(&self, mask: u32, inside: bool) -> ([f32; 3], f32) {
        let mut total = [0.0; 3];
        let mut count = 0.0;
        for (sub, sum) in self.sums.iter().enumerate() {
            if (mask >> sub & 1 == 1) == inside {
                for c in 0..3 {
                    total[c] += sum[c];
                }
                count += self.per_sub;
            }
        }
        (total, count)
    }
}

/// How much a split into the two parts lowers the squared error below zero colours: Σ|S|²/n over
/// the parts (the error is Σ|p|² less this, and Σ|p|² is the same for every split).
fn gain((sum, count): ([f32; 3], f32)) -> f32 {
    if count == 0.0 {
        0.0
    } else {
        (sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]) / count
    }
}

/// The mean colour of a part, rounded to 8-bit codes.
fn mean((sum, count): ([f32; 3], f32)) -> [u8; 3] {
    if count == 0.0 {
        return [0; 3];
    }
    sum.map(|s| (s / count).round().clamp(0.0, 255.0) as u8)
}

/// One cell as drawn: glyph, foreground and background, and the other way to draw it (the
/// complement's glyph with the colours swapped), when the set has one.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Cell {
    glyph: char,
    fg: [u8; 3],
    bg: [u8; 3],
    complement: Option<char>,
}

/// The best cell for the pixels of cell (`col`, `row`) over the patterns of every layer: the
/// one whose two parts' means leave the least squared error.
fn best_cell(image: &PreviewImage, col: u32, row: u32, layers: &[Layer]) -> Cell {
    let mut best: Option<(f32, Cell)> = None;
    for layer in layers {
        let sums = CellSums::of(image, col, row, layer.grid);
        for pattern in &layer.patterns {
            let (inside, outside) = (
                sums.part(pattern.mask, true),
                sums.part(pattern.mask, false),
            );
            let g = gain(inside) + gain(outside);
            if best.is_none_or(|(b, _)| g > b + 1e-3) {
                let cell = Cell {
                    glyph: pattern.glyph,
                    fg: mean(inside),
                    bg: mean(outside),
                    complement: pattern.complement,
                };
                best = Some((g, cell));
            }
        }
    }
    best.map(|(_, cell)| cell).expect("every set has patterns")
}

/// What the terminal's pen holds: the SGR colour parameters last sent.
#[derive(Debug, Default)]
struct Pen {
    fg: Option<String>,
    bg: Option<String>,
}

impl Pen {
    /// The SGR parameters to send to draw with `fg` (when the glyph shows any) and `bg`.
    fn changes(&self, fg: Option<&String>, bg: Option<&String>) -> Vec<String> {
        let mut params = Vec::new();
        if let Some(fg) = fg
            && self.fg.as_ref() != Some(fg)
        {
            params.push(fg.clone());
        }
        if let Some(bg) = bg
            && self.bg.as_ref() != Some(bg)
        {
            params.push(bg.clone());
        }
        params
    }
}

/// Appends `cell` to `out` in whichever of its two spellings costs fewer bytes with the pen as it
/// is, and updates the pen. A cell of one colour is a space on that background or a full block
/// in that foreground; any other cell is its glyph, or its complement with the colours swapped.
fn draw(out: &mut String, pen: &mut Pen, cell: Cell, mode: ColorMode) {
    let fg = sgr(cell.fg, 38, mode);
    let bg = sgr(cell.bg, 48, mode);
    let swapped = (sgr(cell.bg, 38, mode), sgr(cell.fg, 48, mode));
    let mut options: Vec<(char, Option<&String>, Option<&String>)> = Vec::with_capacity(2);
    if cell.glyph == ' ' {
        options.push((' ', None, Some(&bg)));
        options.push(('█', Some(&swapped.0), None));
    } else {
        options.push((cell.glyph, Some(&fg), Some(&bg)));
        if let Some(complement) = cell.complement {
            options.push((complement, Some(&swapped.0), Some(&swapped.1)));
        }
    }
    let cost = |params: &[String]| -> usize {
        match params.len() {
            0 => 0,
            _ => 3 + params.iter().map(String::len).sum::<usize>() + params.len() - 1,
        }
    };
    let (glyph, fg, bg) = options
        .into_iter()
        .min_by_key(|&(_, fg, bg)| cost(&pen.changes(fg, bg)))
        .expect("one option at least");
    let params = pen.changes(fg, bg);
    if !params.is_empty() {
        let _ = write!(out, "\x1b[{}m", params.join(";"));
    }
    if let Some(fg) = fg {
        pen.fg = Some(fg.clone());
    }
    if let Some(bg) = bg {
        pen.bg = Some(bg.clone());
    }
    out.push(glyph);
}

/// `image` (at [`SAMPLES_X`]×[`SAMPLES_Y`] pixels a cell, `cols` × `rows` cells) as lines of
/// `set`'s glyphs with SGR colours in `mode`; every line ends with a reset. A colour is sent only
/// when it changes, and each cell is spelled the way that changes the fewest.
pub fn encode(
    image: &PreviewImage,
    cols: u32,
    rows: u32,
    set: GlyphSet,
    mode: ColorMode,
) -> String {
    let layers = set.layers();
    let mut out = String::with_capacity((cols * rows * 8) as usize);
    for row in 0..rows {
        let mut pen = Pen::default();
        for col in 0..cols {
            draw(
                &mut out,
                &mut pen,
                best_cell(image, col, row, &layers),
                mode,
            );
        }
        out.push_str("\x1b[0m\n");
    }
    out
}

/// The SGR parameters that set `rgb` as foreground (`base` 38) or background (48).
fn sgr([r, g, b]: [u8; 3], base: u8, mode: ColorMode) -> String {
    match mode {
        ColorMode::Truecolor => format!("{base};2;{r};{g};{b}"),
        ColorMode::Ansi256 => format!("{base};5;{}", nearest_256([r, g, b])),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A picture of `cols` × `rows` cells whose pixel colour is `f(x, y)`.
    fn picture(cols: u32, rows: u32, f: impl Fn(u32, u32) -> [u8; 3]) -> PreviewImage {
        let (width, height) = (cols * SAMPLES_X, rows * SAMPLES_Y);
        PreviewImage {
            width,
            height,
            pixels: (0..height)
                .flat_map(|y| (0..width).map(move |x| (x, y)))
                .map(|(x, y)| f(x, y))
                .collect(),
        }
    }

    fn glyphs(text: &str) -> String {
        let mut out = String::new();
        let mut chars = text.chars();
        while let Some(c) = chars.next() {
            if c == '\x1b' {
                for d in chars.by_ref() {
                    if d == 'm' {
                        break;
                    }
                }
            } else if c != '\n' {
                out.push(c);
            }
        }
        out
    }

    #[test]
    fn every_set_has_a_glyph_for_each_pattern_or_its_complement() {
        for set in GlyphSet::ALL {
            let (gx, gy) = set.grid();
            let all = 1u32 << (gx * gy);
            let patterns = set.patterns();
            let expected = match set {
                GlyphSet::HalfBlock => 3,
                _ => all as usize / 2,
            };
            assert_eq!(patterns.len(), expected, "{set:?}");
            assert!(patterns.iter().all(|p| p.mask < all));
            // Where a complement glyph is named, it is the glyph of the complement mask.
            for p in &patterns {
                assert_eq!(
                    p.complement,
                    set.glyph(!p.mask & (all - 1)),
                    "{set:?} {}",
                    p.glyph
                );
            }
        }
        assert_eq!(sextant(0b000001), '\u{1FB00}');
        assert_eq!(sextant(0b111110), '\u{1FB3B}');
        assert_eq!(sextant(0b010100), '\u{1FB13}', "sextant-35");
        assert_eq!(
            GlyphSet::Braille.glyph(0b0000_0011),
            Some('\u{2809}'),
            "dots 1 and 4"
        );
        assert_eq!(
            GlyphSet::Braille.glyph(0b1100_0000),
            Some('\u{28C0}'),
            "dots 7 and 8"
        );
    }

    #[test]
    fn a_cell_split_along_a_pattern_is_drawn_exactly() {
        let red = [255, 0, 0];
        let blue = [0, 0, 255];
        // Left column red, right blue: ▌ in every set that has it, with exact colours.
        let image = picture(1, 1, |x, _| if x < 3 { red } else { blue });
        for set in GlyphSet::ALL {
            let text = encode(&image, 1, 1, set, ColorMode::Truecolor);
            let glyph = glyphs(&text);
            let expected = match set {
                GlyphSet::Braille => "\u{2847}",
                _ => "▌",
            };
            assert_eq!(glyph, expected, "{set:?}: {text:?}");
            assert!(text.contains("38;2;255;0;0"), "{set:?}: {text:?}");
            assert!(text.contains("48;2;0;0;255"), "{set:?}: {text:?}");
        }
        // A diagonal: only quadrants (and finer) can draw it.
        let diagonal = picture(1, 1, |x, y| if (x < 3) == (y < 6) { red } else { blue });
        assert_eq!(
            glyphs(&encode(
                &diagonal,
                1,
                1,
                GlyphSet::Quadrant,
                ColorMode::Truecolor
            )),
            "▚"
        );
        // The middle third of the cell: a sextant row, drawn as the rows above and below it in
        // the background's colour (a pattern and its complement are the same picture).
        let band = picture(1, 1, |_, y| if (4..8).contains(&y) { red } else { blue });
        let text = encode(&band, 1, 1, GlyphSet::Sextant, ColorMode::Truecolor);
        assert_eq!(glyphs(&text), sextant(0b110011).to_string());
        assert!(text.contains("38;2;0;0;255;48;2;255;0;0"), "{text:?}");
    }

    #[test]
    fn one_colour_is_a_space_and_colours_are_sent_only_when_they_change() {
        let grey = picture(3, 1, |_, _| [90, 90, 90]);
        let text = encode(&grey, 3, 1, GlyphSet::Sextant, ColorMode::Truecolor);
        assert_eq!(text, "\x1b[48;2;90;90;90m   \x1b[0m\n");
        let text = encode(&grey, 3, 1, GlyphSet::Quadrant, ColorMode::Ansi256);
        assert!(text.starts_with("\x1b[48;5;"), "{text:?}");
        assert_eq!(text.matches('\x1b').count(), 2, "{text:?}");
    }

    #[test]
    fn the_best_pattern_beats_every_other_on_a_random_cell() {
        // Brute force: the chosen cell's squared error is the least over all patterns.
        let mut seed = 7u32;
        let mut next = move || {
            seed = seed.wrapping_mul(1_103_515_245).wrapping_add(12345);
            (seed >> 16) as u8
        };
        for set in GlyphSet::ALL {
            let pixels: Vec<[u8; 3]> = (0..SAMPLES_X * SAMPLES_Y)
                .map(|_| [next(), next(), next()])
                .collect();
            let image = PreviewImage {
                width: SAMPLES_X,
                height: SAMPLES_Y,
                pixels,
            };
            let layers = set.layers();
            let chosen = best_cell(&image, 0, 0, &layers);
            // The squared error of drawing `mask` of a grid in `fg` and the rest in `bg`.
            let error = |grid: (u32, u32), mask: u32, fg: [u8; 3], bg: [u8; 3]| -> f64 {
                let (sw, sh) = (SAMPLES_X / grid.0, SAMPLES_Y / grid.1);
                image
                    .pixels
                    .iter()
                    .enumerate()
                    .map(|(i, p)| {
                        let (x, y) = (i as u32 % SAMPLES_X, i as u32 / SAMPLES_X);
                        let sub = (y / sh) * grid.0 + x / sw;
                        let c = if mask >> sub & 1 == 1 { fg } else { bg };
                        (0..3)
                            .map(|k| (f64::from(p[k]) - f64::from(c[k])).powi(2))
                            .sum::<f64>()
                    })
                    .sum()
            };
            let (chosen_grid, chosen_mask) = layers
                .iter()
                .find_map(|l| {
                    l.patterns
                        .iter()
                        .find(|p| p.glyph == chosen.glyph)
                        .map(|p| (l.grid, p.mask))
                })
                .expect("the chosen glyph is one of the set's");
            let chosen_error = error(chosen_grid, chosen_mask, chosen.fg, chosen.bg);
            for layer in &layers {
                let sums = CellSums::of(&image, 0, 0, layer.grid);
                for p in &layer.patterns {
                    let (fg, bg) = (
                        mean(sums.part(p.mask, true)),
                        mean(sums.part(p.mask, false)),
                    );
                    let other = error(layer.grid, p.mask, fg, bg);
                    assert!(chosen_error <= other + 1.0, "{set:?} {}", p.glyph);
                }
            }
        }
    }
}
