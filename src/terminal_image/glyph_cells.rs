//! Pictures drawn in character cells: each cell is one glyph from a set of block patterns, in a
//! foreground colour over a background colour. For every cell the encoder tries each pattern of
//! the set and keeps the glyph and the two colours with the least squared error against the
//! pixels under the cell (the colours are then the means of the pixels each part covers).
//!
//! The picture comes at [`SAMPLES_X`]×[`SAMPLES_Y`] pixels a cell, a grid that every set's
//! sub-cells divide: half blocks and quadrants 2×2 (3×6 pixels each), sextants 2×3 (3×4),
//! braille 2×4 (3×3). So each sub-cell averages its own pixels, a box filter, and the choice sees
//! the detail inside a sub-cell too.

use super::preview::{ColorMode, PreviewImage, nearest_256};

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

    /// The set's name in the editor's status line.
    pub fn label(self) -> &'static str {
        match self {
            GlyphSet::HalfBlock => "half blocks",
            GlyphSet::Quadrant => "quadrants",
            GlyphSet::Sextant => "sextants",
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
        (self == GlyphSet::Sextant).then(|| {
            let upper_half = Pattern {
                mask: 0b0011,
                glyph: '▀',
                complement: Some('▄'),
            };
            Layer::new((2, 2), vec![upper_half])
        })
    }

    /// Every grid the set's patterns lie on, with those patterns.
    fn layers(self) -> Vec<Layer> {
        let mut layers = vec![Layer::new(self.grid(), self.patterns())];
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
    /// 1/n for the part a mask covers (n its pixels), by mask over every subset of the grid's
    /// sub-cells; 0 for the empty mask. Read by [`SubsetTables::fill`] without a branch.
    reciprocals: Vec<f64>,
    /// For a layer whose patterns are every split of its grid ([`Layer::is_complete`]): 1/n of
    /// the part that mask `2j + 1` covers, and of the part it leaves, by `j`. Else empty.
    split_reciprocals: (Vec<f64>, Vec<f64>),
}

impl Layer {
    fn new(grid: (u32, u32), patterns: Vec<Pattern>) -> Layer {
        let mut layer = Layer {
            grid,
            patterns,
            reciprocals: Vec::new(),
            split_reciprocals: (Vec::new(), Vec::new()),
        };
        let by_count = layer.reciprocals();
        layer.reciprocals = (0..1u32 << layer.sub_cells())
            .map(|mask| by_count[mask.count_ones() as usize])
            .collect();
        if layer.is_complete() {
            let full = (1usize << layer.sub_cells()) - 1;
            let odd_masks = || (0..=full / 2).map(|j| 2 * j + 1);
            layer.split_reciprocals = (
                odd_masks().map(|m| layer.reciprocals[m]).collect(),
                odd_masks().map(|m| layer.reciprocals[full ^ m]).collect(),
            );
        }
        layer
    }

    /// Whether the patterns are every split of the grid, one of each complementary pair, in
    /// the order [`GlyphSet::patterns`] gives: the empty mask, then every mask with sub-cell 0
    /// in the foreground but the full one, rising. Such a layer is searched by
    /// [`SubsetTables::fill_splits`], over half the subsets.
    fn is_complete(&self) -> bool {
        let full = (1u32 << self.sub_cells()) - 1;
        let every_split = std::iter::once(0).chain((1..full).step_by(2));
        self.patterns.iter().map(|p| p.mask).eq(every_split)
    }

    /// Sub-cells in the grid, at most 8.
    fn sub_cells(&self) -> u32 {
        self.grid.0 * self.grid.1
    }

    /// Pixels in one sub-cell.
    fn pixels_per_sub(&self) -> u32 {
        SAMPLES_X * SAMPLES_Y / (self.grid.0 * self.grid.1)
    }

    /// 1/n for a part of k sub-cells (n its pixels), by k from 0 to 8; 0 for an empty part.
    fn reciprocals(&self) -> [f64; 9] {
        const fn table(per_sub: u32) -> [f64; 9] {
            let mut r = [0.0; 9];
            let mut k = 1;
            while k < 9 {
                r[k] = 1.0 / (k as u32 * per_sub) as f64;
                k += 1;
            }
            r
        }
        // The four grids' sub-cells hold 18 (2×2), 12 (2×3) or 9 (2×4) pixels.
        const HALVES: [f64; 9] = table(18);
        const THIRDS: [f64; 9] = table(12);
        const QUARTERS: [f64; 9] = table(9);
        match self.pixels_per_sub() {
            18 => HALVES,
            12 => THIRDS,
            9 => QUARTERS,
            per_sub => table(per_sub),
        }
    }
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

/// One cell's pixels summed over its finest strips: 2 columns × 12 rows of 3 pixels, the grid
/// every set's sub-cells are made of. Integer sums: exact, and cheap to add up.
struct FineSums {
    /// Colour sums per strip, index `row * 2 + column`.
    strips: [[u32; 3]; 24],
}

impl FineSums {
    /// The sums of cell (`col`, `row`); pixels beyond the image count as black.
    fn of(image: &PreviewImage, col: u32, row: u32) -> FineSums {
        let mut strips = [[0u32; 3]; 24];
        let x0 = (col * SAMPLES_X).min(image.width) as usize;
        let x1 = ((col + 1) * SAMPLES_X).min(image.width) as usize;
        let y0 = row * SAMPLES_Y;
        let rows = SAMPLES_Y.min(image.height.saturating_sub(y0)) as usize;
        // Each pixel row of the cell as one slice: no bounds check per pixel.
        let start = (y0 as usize).saturating_mul(image.width as usize);
        let lines = image
            .pixels
            .get(start..)
            .unwrap_or_default()
            .chunks(image.width.max(1) as usize)
            .take(rows);
        for (pair, line) in strips.chunks_exact_mut(2).zip(lines) {
            for (x, pixel) in line[x0..x1].iter().enumerate() {
                let strip = &mut pair[x / 3];
                strip[0] += u32::from(pixel[0]);
                strip[1] += u32::from(pixel[1]);
                strip[2] += u32::from(pixel[2]);
            }
        }
        FineSums { strips }
    }

    /// Sums per sub-cell of a 2 × `rows` grid (`rows` divides 12), index `row * 2 + column`;
    /// the first `2 * rows` entries are used.
    fn grid(&self, rows: u32) -> [[u32; 3]; 8] {
        let mut subs = [[0u32; 3]; 8];
        // Strips to sub-cells in whole runs of rows, without a division per strip.
        let per = (SAMPLES_Y / rows) as usize;
        for (row, strips) in self.strips.chunks_exact(2 * per).enumerate() {
            for pair in strips.chunks_exact(2) {
                for (column, strip) in pair.iter().enumerate() {
                    let sub = &mut subs[row * 2 + column];
                    sub[0] += strip[0];
                    sub[1] += strip[1];
                    sub[2] += strip[2];
                }
            }
        }
        subs
    }
}

/// The gain of every part a layer's patterns can cover in one cell, by the part's mask.
///
/// The gain of a part is |S|² / n, S its colour sum and n its pixels: how much the part drawn in
/// its mean colour lowers the squared error below drawing it black. The error of a split is Σ|p|²
/// less its two parts' gains, and Σ|p|² is the same for every split of a cell, so the best split
/// has the greatest gain `gains[mask] + gains[full ^ mask]`.
///
/// Invariant: a colour sum is a whole number at most 72 × 255, exact in f64 however it is added
/// up, so each entry is bit for bit `(r * r + g * g + b * b) * (1 / n)` of the integer sums.
/// The tables are plain arrays, one per channel, filled by loops without branches that the
/// compiler turns into vector code: this is what makes 256 braille patterns a cell affordable.
#[derive(Debug, Clone)]
struct SubsetTables {
    /// Colour sums of every subset of the sub-cells, by mask.
    red: [f64; 256],
    green: [f64; 256],
    blue: [f64; 256],
    /// The gain of every subset, by mask; the first 2^sub-cells entries are filled.
    gains: [f64; 256],
    /// The gain of each split of a complete layer, by `j` for the split whose foreground is
    /// mask `2j + 1` ([`SubsetTables::fill_splits`]); the first 2^(sub-cells − 1) are filled.
    splits: [f64; 128],
}

impl SubsetTables {
    fn new() -> SubsetTables {
        SubsetTables {
            red: [0.0; 256],
            green: [0.0; 256],
            blue: [0.0; 256],
            gains: [0.0; 256],
            splits: [0.0; 128],
        }
    }

    /// Fills `splits` for a complete layer's cell whose sub-cells sum to `subs`, with the
    /// layer's `split_reciprocals` (each of length 2^(len(`subs`) − 1)).
    ///
    /// Only the subsets that hold sub-cell 0 are summed: the other part of a split is the
    /// cell's total less that sum, exact in whole numbers. Each split gain is bit for bit
    /// `gains[mask] + gains[full ^ mask]` of [`SubsetTables::fill`], with half its work.
    fn fill_splits(&mut self, subs: &[[u32; 3]], reciprocals: &(Vec<f64>, Vec<f64>)) {
        let half = reciprocals.0.len();
        debug_assert_eq!(half, 1 << (subs.len() - 1));
        let mut total = [0.0f64; 3];
        for (channel, table) in [&mut self.red, &mut self.green, &mut self.blue]
            .into_iter()
            .enumerate()
        {
            // Entry j holds sub-cell 0 and the sub-cells k ≥ 1 whose bit k − 1 of j is set.
            table[0] = f64::from(subs[0][channel]);
            for (k, sub) in subs[1..].iter().enumerate() {
                let (low, high) = table[..2 << k].split_at_mut(1 << k);
                let add = f64::from(sub[channel]);
                for (h, l) in high.iter_mut().zip(low.iter()) {
                    *h = l + add;
                }
            }
            total[channel] = table[half - 1];
        }
        let [total_r, total_g, total_b] = total;
        let sums = self.red[..half]
            .iter()
            .zip(&self.green[..half])
            .zip(&self.blue[..half]);
        let parts = reciprocals.0.iter().zip(&reciprocals.1);
        for ((split, ((r, g), b)), (inside, outside)) in
            self.splits[..half].iter_mut().zip(sums).zip(parts)
        {
            let (rest_r, rest_g, rest_b) = (total_r - r, total_g - g, total_b - b);
            *split = (r * r + g * g + b * b) * inside
                + (rest_r * rest_r + rest_g * rest_g + rest_b * rest_b) * outside;
        }
    }

    /// Fills the first 2^len(`subs`) entries for a cell whose sub-cells sum to `subs`, with
    /// `reciprocals` (1/n by mask, [`Layer::reciprocals`]) of the same length.
    fn fill(&mut self, subs: &[[u32; 3]], reciprocals: &[f64]) {
        let len = reciprocals.len();
        debug_assert_eq!(len, 1 << subs.len());
        // The sums of the subsets of the first k sub-cells are the first 2^k entries; adding
        // sub-cell k to each gives the next 2^k.
        for (channel, table) in [&mut self.red, &mut self.green, &mut self.blue]
            .into_iter()
            .enumerate()
        {
            table[0] = 0.0;
            for (k, sub) in subs.iter().enumerate() {
                let (low, high) = table[..2 << k].split_at_mut(1 << k);
                let add = f64::from(sub[channel]);
                for (h, l) in high.iter_mut().zip(low.iter()) {
                    *h = l + add;
                }
            }
        }
        let sums = self.red[..len]
            .iter()
            .zip(&self.green[..len])
            .zip(&self.blue[..len]);
        for ((gain, ((r, g), b)), reciprocal) in
            self.gains[..len].iter_mut().zip(sums).zip(reciprocals)
        {
            *gain = (r * r + g * g + b * b) * reciprocal;
        }
    }
}

/// The mean colour of a part, rounded to 8-bit codes.
fn mean(sum: [u32; 3], count: u32) -> [u8; 3] {
    if count == 0 {
        return [0; 3];
    }
    sum.map(|s| ((s + count / 2) / count).min(255) as u8)
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

/// The best cell for `sums` over the patterns of every layer: the one whose two parts' means
/// leave the least squared error. Patterns are tried in order, and a later one replaces the best
/// so far only when its gain is greater by more than 1e-3, so that near ties keep the earlier
/// (simpler) pattern. `scratch` holds the subset tables between calls.
fn best_cell(sums: &FineSums, layers: &[Layer], scratch: &mut SubsetTables) -> Cell {
    let mut best: Option<(f64, &Layer, &Pattern)> = None;
    for layer in layers {
        let count = layer.sub_cells() as usize;
        if !layer.split_reciprocals.0.is_empty() {
            scratch.fill_splits(&sums.grid(layer.grid.1)[..count], &layer.split_reciprocals);
            let half = layer.split_reciprocals.0.len();
            // The empty pattern first: its split is the full mask's, the last entry.
            let threshold = best.map_or(f64::NEG_INFINITY, |b| b.0 + 1e-3);
            if scratch.splits[half - 1] > threshold {
                best = Some((scratch.splits[half - 1], layer, &layer.patterns[0]));
            }
            // Then pattern 1 + j for the split of mask 2j + 1, as in the general search below.
            let mut start = 0;
            loop {
                let threshold = best.map_or(f64::NEG_INFINITY, |b| b.0 + 1e-3);
                let Some(next) = scratch.splits[start..half - 1]
                    .iter()
                    .position(|&gain| gain > threshold)
                else {
                    break;
                };
                let j = start + next;
                best = Some((scratch.splits[j], layer, &layer.patterns[1 + j]));
                start = j + 1;
            }
            continue;
        }
        scratch.fill(&sums.grid(layer.grid.1)[..count], &layer.reciprocals);
        let full = (1 << count) - 1;
        let split_gain = |pattern: &Pattern| {
            let mask = pattern.mask as usize;
            scratch.gains[mask] + scratch.gains[full ^ mask]
        };
        // Skips to the next pattern that beats the threshold: the rare replacement is a
        // branch, and the scan between two has no dependency from one pattern to the next.
        let mut rest = &layer.patterns[..];
        loop {
            let threshold = best.map_or(f64::NEG_INFINITY, |b| b.0 + 1e-3);
            let Some(next) = rest.iter().position(|p| split_gain(p) > threshold) else {
                break;
            };
            best = Some((split_gain(&rest[next]), layer, &rest[next]));
            rest = &rest[next + 1..];
        }
    }
    let (_, layer, pattern) = best.expect("every set has patterns");
    // The two parts' sums and pixel counts, from the chosen layer's sub-cells.
    let subs = sums.grid(layer.grid.1);
    let mut parts = [[0u32; 3]; 2];
    for (sub, colour) in subs[..layer.sub_cells() as usize].iter().enumerate() {
        let part = &mut parts[usize::from(pattern.mask >> sub & 1 == 0)];
        for (p, c) in part.iter_mut().zip(colour) {
            *p += c;
        }
    }
    let k = pattern.mask.count_ones();
    let per_sub = layer.pixels_per_sub();
    Cell {
        glyph: pattern.glyph,
        fg: mean(parts[0], k * per_sub),
        bg: mean(parts[1], (layer.sub_cells() - k) * per_sub),
        complement: pattern.complement,
    }
}

/// A colour as the terminal is told it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Ink {
    Rgb([u8; 3]),
    Indexed(u8),
}

impl Ink {
    fn new(rgb: [u8; 3], mode: ColorMode) -> Ink {
        match mode {
            ColorMode::Truecolor => Ink::Rgb(rgb),
            ColorMode::Ansi256 => Ink::Indexed(nearest_256(rgb)),
        }
    }

    /// Bytes of its SGR parameters (`38;2;R;G;B` or `38;5;N`).
    fn len(self) -> usize {
        let digits = |v: u8| 1 + usize::from(v >= 10) + usize::from(v >= 100);
        match self {
            Ink::Rgb([r, g, b]) => 7 + digits(r) + digits(g) + digits(b),
            Ink::Indexed(i) => 5 + digits(i),
        }
    }

    /// Appends its SGR parameters with `base` (38 foreground, 48 background).
    fn push(self, out: &mut String, base: u8) {
        push_number(out, base);
        match self {
            Ink::Rgb([r, g, b]) => {
                out.push_str(";2;");
                push_number(out, r);
                out.push(';');
                push_number(out, g);
                out.push(';');
                push_number(out, b);
            }
            Ink::Indexed(i) => {
                out.push_str(";5;");
                push_number(out, i);
            }
        }
    }
}

/// Appends `value` in decimal (the formatter's machinery costs more than the whole choice of a
/// cell).
fn push_number(out: &mut String, value: u8) {
    if value >= 100 {
        out.push(char::from(b'0' + value / 100));
    }
    if value >= 10 {
        out.push(char::from(b'0' + value / 10 % 10));
    }
    out.push(char::from(b'0' + value % 10));
}

/// What the terminal's pen holds: the colours last sent.
#[derive(Debug, Default, Clone, Copy)]
struct Pen {
    fg: Option<Ink>,
    bg: Option<Ink>,
}

impl Pen {
    /// Bytes of the escape that sets `fg` (when the glyph shows any) and `bg` (when it shows any),
    /// 0 when both are set already.
    fn cost(self, fg: Option<Ink>, bg: Option<Ink>) -> usize {
        let fg = fg.filter(|&f| self.fg != Some(f));
        let bg = bg.filter(|&b| self.bg != Some(b));
        match (fg, bg) {
            (None, None) => 0,
            (Some(f), None) => 3 + f.len(),
            (None, Some(b)) => 3 + b.len(),
            (Some(f), Some(b)) => 4 + f.len() + b.len(),
        }
    }

    /// Sends what `fg` and `bg` change.
    fn set(&mut self, out: &mut String, fg: Option<Ink>, bg: Option<Ink>) {
        let fg = fg.filter(|&f| self.fg != Some(f));
        let bg = bg.filter(|&b| self.bg != Some(b));
        if fg.is_none() && bg.is_none() {
            return;
        }
        out.push_str("\x1b[");
        if let Some(f) = fg {
            f.push(out, 38);
            self.fg = Some(f);
        }
        if let Some(b) = bg {
            if fg.is_some() {
                out.push(';');
            }
            b.push(out, 48);
            self.bg = Some(b);
        }
        out.push('m');
    }
}

/// Appends `cell` to `out` in whichever of its two spellings costs fewer bytes with the pen as it
/// is. A cell of one colour (a space, or braille's blank pattern) is that blank on its background
/// or a full block in that foreground, never braille's full pattern: its dots leave gaps where
/// the background, which a one-colour cell does not set, would show through. Any other cell is
/// its glyph, or its complement with the colours swapped.
fn draw(out: &mut String, pen: &mut Pen, cell: Cell, mode: ColorMode) {
    let (fg, bg) = (Ink::new(cell.fg, mode), Ink::new(cell.bg, mode));
    let options = if cell.glyph == ' ' || cell.glyph == BRAILLE_BLANK {
        [(cell.glyph, None, Some(bg)), ('█', Some(bg), None)]
    } else {
        let swapped = cell
            .complement
            .map_or((cell.glyph, Some(fg), Some(bg)), |c| {
                (c, Some(bg), Some(fg))
            });
        [(cell.glyph, Some(fg), Some(bg)), swapped]
    };
    let (glyph, fg, bg) =
        if pen.cost(options[1].1, options[1].2) < pen.cost(options[0].1, options[0].2) {
            options[1]
        } else {
            options[0]
        };
    pen.set(out, fg, bg);
    out.push(glyph);
}

/// Braille's pattern without dots (U+2800): a cell of its background colour alone.
const BRAILLE_BLANK: char = '\u{2800}';

/// One row of cells as text, ending with a reset and a newline.
fn encode_row(
    image: &PreviewImage,
    cols: u32,
    row: u32,
    layers: &[Layer],
    mode: ColorMode,
) -> String {
    let mut out = String::with_capacity(cols as usize * 12);
    let mut pen = Pen::default();
    let mut scratch = SubsetTables::new();
    for col in 0..cols {
        let cell = best_cell(&FineSums::of(image, col, row), layers, &mut scratch);
        draw(&mut out, &mut pen, cell, mode);
    }
    out.push_str("\x1b[0m\n");
    out
}

/// One cell as a terminal buffer holds it: a glyph in a foreground over a background colour
/// (8-bit sRGB). A cell of one colour is a space, its `fg` unused.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct GlyphCell {
    pub glyph: char,
    pub fg: [u8; 3],
    pub bg: [u8; 3],
}

/// Chooses cells of one set, one at a time (for a cell buffer such as the editor's).
#[derive(Debug, Clone)]
pub struct CellChooser {
    layers: Vec<Layer>,
    scratch: Box<SubsetTables>,
}

impl CellChooser {
    pub fn new(set: GlyphSet) -> CellChooser {
        CellChooser {
            layers: set.layers(),
            scratch: Box::new(SubsetTables::new()),
        }
    }

    /// The best cell (`col`, `row`) of `image`, which is at [`SAMPLES_X`]×[`SAMPLES_Y`] pixels
    /// a cell (see [`fit`]).
    pub fn choose(&mut self, image: &PreviewImage, col: u32, row: u32) -> GlyphCell {
        let cell = best_cell(
            &FineSums::of(image, col, row),
            &self.layers,
            &mut self.scratch,
        );
        GlyphCell {
            glyph: cell.glyph,
            fg: cell.fg,
            bg: cell.bg,
        }
    }
}

/// `image` on the grid the encoder samples for `cols` × `rows` cells: itself when it has that
/// size, else resampled (a render with square pixels on cells that are not 1:2).
pub fn fit(image: &PreviewImage, cols: u32, rows: u32) -> std::borrow::Cow<'_, PreviewImage> {
    let (width, height) = (cols * SAMPLES_X, rows * SAMPLES_Y);
    if image.width == width && image.height == height {
        std::borrow::Cow::Borrowed(image)
    } else {
        std::borrow::Cow::Owned(super::resample::nearest(image, width, height))
    }
}

/// `image` (`cols` × `rows` cells, resampled by [`fit`] to [`SAMPLES_X`]×[`SAMPLES_Y`] pixels
/// a cell) as lines of `set`'s glyphs with SGR colours in `mode`; every line ends with a reset.
/// A colour is sent only when it changes, and each cell is spelled the way that changes the
/// fewest. Rows are encoded in parallel; the text is the same on any number of threads.
pub fn encode(
    image: &PreviewImage,
    cols: u32,
    rows: u32,
    set: GlyphSet,
    mode: ColorMode,
) -> String {
    use rayon::prelude::*;
    let image = &*fit(image, cols, rows);
    let layers = set.layers();
    let lines: Vec<String> = (0..rows)
        .into_par_iter()
        .map(|row| encode_row(image, cols, row, &layers, mode))
        .collect();
    lines.concat()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_draws::draws;

    /// A picture of `cols` × `rows` cells whose pixel colour is `f(x, y)`.
    fn picture(cols: u32, rows: u32, mut f: impl FnMut(u32, u32) -> [u8; 3]) -> PreviewImage {
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
    fn a_braille_cell_of_one_colour_never_shows_braille_dots_over_another() {
        // A yellow cell after one that sets the pen's foreground to the same yellow: the cheap
        // spelling reuses the foreground, but braille's full pattern leaves gaps between its
        // dots, so it must be a full block (or the blank pattern on a yellow background).
        let yellow = [250, 210, 20];
        // The first cell: its left column of dots yellow, its right one dark blue.
        let image = picture(2, 1, |x, _| {
            if (SAMPLES_X / 2..SAMPLES_X).contains(&x) {
                [20, 30, 60]
            } else {
                yellow
            }
        });
        let text = encode(&image, 2, 1, GlyphSet::Braille, ColorMode::Truecolor);
        assert!(!text.contains('\u{28FF}'), "{text:?}");
        let second = text.chars().filter(|c| !c.is_ascii()).nth(1).unwrap();
        assert!(second == '█' || second == BRAILLE_BLANK, "{text:?}");
        // Nothing in the output is black: no colour is left unset.
        assert!(!text.contains(";0;0;0m"), "{text:?}");
    }

    #[test]
    fn the_best_pattern_beats_every_other_on_a_random_cell() {
        // Brute force over the pixels themselves: the chosen cell's squared error is the least
        // of every pattern of every layer, each drawn in its parts' mean colours.
        let mut draw = draws(7);
        let mut next = move || draw() as u8;
        for set in GlyphSet::ALL {
            for _ in 0..20 {
                let image = picture(1, 1, |_, _| [next(), next(), next()]);
                let layers = set.layers();
                let chosen = best_cell(
                    &FineSums::of(&image, 0, 0),
                    &layers,
                    &mut SubsetTables::new(),
                );
                // The parts of a split: which pixels the foreground covers.
                let covered = |rows: u32, mask: u32, i: usize| {
                    let (x, y) = (i as u32 % SAMPLES_X, i as u32 / SAMPLES_X);
                    let sub = (y / (SAMPLES_Y / rows)) * 2 + x / 3;
                    mask >> sub & 1 == 1
                };
                let error = |rows: u32, mask: u32, fg: [u8; 3], bg: [u8; 3]| -> f64 {
                    let squares = image.pixels.iter().enumerate().map(|(i, p)| {
                        let c = if covered(rows, mask, i) { fg } else { bg };
                        (0..3)
                            .map(|k| (f64::from(p[k]) - f64::from(c[k])).powi(2))
                            .sum::<f64>()
                    });
                    squares.sum()
                };
                let means = |rows: u32, mask: u32| -> ([u8; 3], [u8; 3]) {
                    let mut sums = [[0.0f64; 3]; 2];
                    let mut counts = [0.0f64; 2];
                    for (i, p) in image.pixels.iter().enumerate() {
                        let part = usize::from(!covered(rows, mask, i));
                        counts[part] += 1.0;
                        for k in 0..3 {
                            sums[part][k] += f64::from(p[k]);
                        }
                    }
                    let mean =
                        |part: usize| sums[part].map(|v| (v / counts[part].max(1.0)).round() as u8);
                    (mean(0), mean(1))
                };
                let (chosen_rows, chosen_mask) = layers
                    .iter()
                    .find_map(|l| {
                        l.patterns
                            .iter()
                            .find(|p| p.glyph == chosen.glyph)
                            .map(|p| (l.grid.1, p.mask))
                    })
                    .expect("the chosen glyph is one of the set's");
                assert_eq!((chosen.fg, chosen.bg), means(chosen_rows, chosen_mask));
                let chosen_error = error(chosen_rows, chosen_mask, chosen.fg, chosen.bg);
                for layer in &layers {
                    for p in &layer.patterns {
                        let (fg, bg) = means(layer.grid.1, p.mask);
                        let other = error(layer.grid.1, p.mask, fg, bg);
                        assert!(chosen_error <= other + 1.0, "{set:?} {}", p.glyph);
                    }
                }
            }
        }
    }

    /// The search as it was first written, one pattern at a time on integer sums: the same
    /// rule (a later pattern wins only by more than 1e-3), so the table search must pick the
    /// same pattern of the same layer on every cell.
    fn plain_best(sums: &FineSums, layers: &[Layer]) -> (u32, u32) {
        let mut best: Option<(f64, u32, u32)> = None;
        for layer in layers {
            let count = layer.sub_cells();
            let subs = sums.grid(layer.grid.1);
            let reciprocal = layer.reciprocals();
            let sum_of = |mask: u32| {
                let mut sum = [0u32; 3];
                for (sub, colour) in subs[..count as usize].iter().enumerate() {
                    if mask >> sub & 1 == 1 {
                        (0..3).for_each(|c| sum[c] += colour[c]);
                    }
                }
                sum
            };
            let gain = |sum: [u32; 3], r: f64| {
                let [a, b, c] = sum.map(f64::from);
                (a * a + b * b + c * c) * r
            };
            for pattern in &layer.patterns {
                let k = pattern.mask.count_ones();
                let outside = !pattern.mask & ((1 << count) - 1);
                let g = gain(sum_of(pattern.mask), reciprocal[k as usize])
                    + gain(sum_of(outside), reciprocal[(count - k) as usize]);
                if best.is_none_or(|b| g > b.0 + 1e-3) {
                    best = Some((g, layer.grid.1, pattern.mask));
                }
            }
        }
        best.map(|(_, rows, mask)| (rows, mask)).unwrap()
    }

    #[test]
    fn the_table_search_picks_what_the_plain_search_picks() {
        let mut next = draws(11);
        for set in GlyphSet::ALL {
            let layers = set.layers();
            let mut tables = SubsetTables::new();
            // Noise, two-colour cells with noise, and flat cells (ties everywhere).
            for case in 0..600 {
                let (a, b) = ([0u8, 40, 200], [250u8, 120, 10]);
                let image = picture(1, 1, |x, y| match case % 3 {
                    0 => [next() as u8, next() as u8, next() as u8],
                    1 => {
                        let c = if (x * 7 + y * 3 + case) % 5 < 2 { a } else { b };
                        c.map(|v| v.saturating_add((next() % 9) as u8))
                    }
                    _ => [(case % 256) as u8; 3],
                });
                let sums = FineSums::of(&image, 0, 0);
                let cell = best_cell(&sums, &layers, &mut tables);
                let (rows, mask) = plain_best(&sums, &layers);
                let layer = layers.iter().find(|l| l.grid.1 == rows).unwrap();
                let pattern = layer.patterns.iter().find(|p| p.mask == mask).unwrap();
                assert_eq!(cell.glyph, pattern.glyph, "{set:?} case {case}");
            }
        }
    }

    #[test]
    fn quadrants_sextants_and_braille_are_searched_by_their_splits() {
        let complete =
            |set: GlyphSet| -> Vec<bool> { set.layers().iter().map(Layer::is_complete).collect() };
        assert_eq!(complete(GlyphSet::HalfBlock), vec![false]);
        assert_eq!(complete(GlyphSet::Quadrant), vec![true]);
        assert_eq!(complete(GlyphSet::Sextant), vec![true, false]);
        assert_eq!(complete(GlyphSet::Braille), vec![true]);
        // Each split gain is bit for bit the sum of the two parts' gains of the full tables.
        let mut draw = draws(5);
        let mut next = move || draw() as u8;
        for set in [GlyphSet::Quadrant, GlyphSet::Sextant, GlyphSet::Braille] {
            let layer = &set.layers()[0];
            let count = layer.sub_cells() as usize;
            let full = (1usize << count) - 1;
            for _ in 0..50 {
                let image = picture(1, 1, |_, _| [next(), next(), next()]);
                let subs = FineSums::of(&image, 0, 0).grid(layer.grid.1);
                let mut tables = SubsetTables::new();
                tables.fill(&subs[..count], &layer.reciprocals);
                tables.fill_splits(&subs[..count], &layer.split_reciprocals);
                for j in 0..=full / 2 {
                    let mask = 2 * j + 1;
                    let expected = tables.gains[mask] + tables.gains[full ^ mask];
                    assert_eq!(
                        tables.splits[j].to_bits(),
                        expected.to_bits(),
                        "{set:?} {mask}"
                    );
                }
            }
        }
    }

    /// The exact bytes of a small frame in every set and colour mode, pinned (FNV-1a of the
    /// text and its length) from the encoder as it was before its colours were made faster: a
    /// speed-up must not change a byte. The frame is a smooth colour ramp with a hard diagonal
    /// edge, so that every set picks many glyphs and both modes many colours.
    #[test]
    fn a_small_frames_bytes_are_pinned_in_every_set_and_mode() {
        let image = picture(8, 3, |x, y| {
            let edge = x + 2 * y > 30;
            let r = (x * 255 / 47) as u8;
            let g = (y * 255 / 35) as u8;
            let b = if edge { 220 } else { 40 + (x * y % 97) as u8 };
            [r, g, b]
        });
        let mut text = String::new();
        for mode in [ColorMode::Truecolor, ColorMode::Ansi256] {
            for set in GlyphSet::ALL {
                text.push_str(&encode(&image, 8, 3, set, mode));
            }
        }
        let hash = text.bytes().fold(0xcbf2_9ce4_8422_2325u64, |h, b| {
            (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
        });
        assert_eq!(
            (text.len(), hash),
            (5548, 5_768_063_708_871_852_975),
            "{text:?}"
        );
    }

    /// A cell partly or wholly outside the picture reads its missing pixels as black and does
    /// not panic.
    #[test]
    fn cells_beyond_the_picture_count_as_black() {
        let white = picture(1, 1, |_, _| [255; 3]);
        let mut chooser = CellChooser::new(GlyphSet::Quadrant);
        for (col, row) in [(1, 0), (0, 1), (3, 5)] {
            let cell = chooser.choose(&white, col, row);
            assert_eq!((cell.fg, cell.bg), ([0; 3], [0; 3]), "cell {col},{row}");
        }
        let empty = PreviewImage::default();
        assert_eq!(chooser.choose(&empty, 0, 0).bg, [0; 3]);
    }
}
