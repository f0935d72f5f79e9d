//! Frames as terminal cells: each cell shows two stacked pixels with '▀', the upper pixel as the
//! foreground colour and the lower as the background, in truecolor or the xterm 256-colour palette.

use ratatui::style::Color;

use crate::render::Frame;

/// The terminal's own colour: what a cell shows where the editor sets none.
pub const TERMINAL_DEFAULT: Color = Color::Reset;

/// How colours reach the terminal.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ColorMode {
    /// 24-bit RGB escape sequences.
    #[default]
    Truecolor,
    /// The nearest entry of the xterm 256-colour palette.
    Ansi256,
}

impl ColorMode {
    /// The terminal colour for an 8-bit sRGB triple.
    pub fn color(self, [r, g, b]: [u8; 3]) -> Color {
        match self {
            ColorMode::Truecolor => Color::Rgb(r, g, b),
            ColorMode::Ansi256 => Color::Indexed(nearest_256([r, g, b])),
        }
    }
}

/// A frame encoded once to 8-bit sRGB, ready to be drawn many times.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct PreviewImage {
    /// Width in pixels (= cells).
    pub width: u32,
    /// Height in pixels (= 2 × rows).
    pub height: u32,
    /// Row-major sRGB pixels from the top-left.
    pub pixels: Vec<[u8; 3]>,
}

impl PreviewImage {
    /// Encodes `frame` to sRGB.
    pub fn from_frame(frame: &Frame) -> PreviewImage {
        let pixels = frame.srgb8_pixels();
        PreviewImage {
            width: frame.width,
            height: frame.height,
            pixels,
        }
    }

    /// The pixel at (`x`, `y`), or `None` outside the image.
    pub fn pixel(&self, x: u32, y: u32) -> Option<[u8; 3]> {
        (x < self.width && y < self.height).then(|| self.pixels[(y * self.width + x) as usize])
    }
}

/// What one terminal cell shows: a symbol with foreground and background colours.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct HalfBlock {
    pub symbol: &'static str,
    pub fg: Color,
    pub bg: Color,
}

/// Largest difference per 8-bit sRGB channel at which two halves count as the same colour:
/// 4/255 is invisible, and drawing such cells as one background colour cuts a truecolor frame of
/// the default scene at 160×48 cells from about 70 kB to 39 kB, which matters over SSH.
pub const MATCH_TOLERANCE: u8 = 4;

/// Whether two pixels are close enough to share one cell colour.
pub fn halves_match(a: [u8; 3], b: [u8; 3]) -> bool {
    (0..3).all(|i| a[i].abs_diff(b[i]) <= MATCH_TOLERANCE)
}

/// The cell for an upper and a lower pixel. Four cases: both present and matching (same terminal
/// colour, or within [`MATCH_TOLERANCE`]) → a space on the upper colour (half the escape codes);
/// both present → '▀' upper on lower; only the upper one (odd image height) → '▀' on the default
/// background; none → an empty cell.
pub fn half_block(upper: Option<[u8; 3]>, lower: Option<[u8; 3]>, mode: ColorMode) -> HalfBlock {
    half_block_each(upper.map(|c| (c, mode)), lower.map(|c| (c, mode)))
}

/// As [`half_block`], with a colour mode for each pixel (a motion frame draws some pixels in the
/// 256-colour palette, see the editor's motion frames).
pub fn half_block_each(
    upper: Option<([u8; 3], ColorMode)>,
    lower: Option<([u8; 3], ColorMode)>,
) -> HalfBlock {
    let lower = match (upper, lower) {
        (Some(u), Some(l)) if halves_match(u.0, l.0) => Some(u),
        _ => lower,
    };
    let (upper, lower) = (
        upper.map(|(c, mode)| mode.color(c)),
        lower.map(|(c, mode)| mode.color(c)),
    );
    match (upper, lower) {
        (Some(u), Some(l)) if u == l => HalfBlock {
            symbol: " ",
            fg: TERMINAL_DEFAULT,
            bg: u,
        },
        (Some(u), l) => HalfBlock {
            symbol: "▀",
            fg: u,
            bg: l.unwrap_or(TERMINAL_DEFAULT),
        },
        (None, _) => HalfBlock {
            symbol: " ",
            fg: TERMINAL_DEFAULT,
            bg: TERMINAL_DEFAULT,
        },
    }
}

/// The six levels of each channel in the xterm 6×6×6 colour cube (indices 16..=231).
const CUBE: [u8; 6] = [0, 95, 135, 175, 215, 255];

/// Index of the cube level nearest to `v`, the lower one on a tie (115, 155, 195 and 235 lie
/// halfway). By the midpoints, not a search: the search was most of a 256-colour frame's time.
fn cube_level(v: u8) -> usize {
    match v {
        0..48 => 0,
        48..116 => 1,
        _ => 2 + usize::from(v - 116) / 40,
    }
}

fn distance2(a: [u8; 3], b: [u8; 3]) -> i32 {
    (0..3).map(|i| (a[i] as i32 - b[i] as i32).pow(2)).sum()
}

/// The xterm 256-colour index nearest to an sRGB triple: the best of the colour cube and the
/// 24-step grey ramp (232..=255, grey 8 + 10·k). The 16 system colours vary between terminals
/// and are never chosen.
pub fn nearest_256(rgb: [u8; 3]) -> u8 {
    let levels = rgb.map(cube_level);
    let cube_rgb = levels.map(|l| CUBE[l]);
    let cube_index = 16 + 36 * levels[0] + 6 * levels[1] + levels[2];
    let mean = (rgb.iter().map(|&c| c as i32).sum::<i32>() / 3).clamp(8, 238);
    let step = ((mean - 8 + 5) / 10).clamp(0, 23);
    let grey = (8 + 10 * step) as u8;
    if distance2(rgb, [grey; 3]) < distance2(rgb, cube_rgb) {
        232 + step as u8
    } else {
        cube_index as u8
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every byte value gets the level a search of [`CUBE`] gives, the first of equals.
    #[test]
    fn cube_level_is_the_nearest_level_for_every_value() {
        for v in 0..=255u8 {
            let searched = CUBE
                .iter()
                .enumerate()
                .min_by_key(|(_, l)| (i32::from(**l) - i32::from(v)).abs())
                .map(|(i, _)| i);
            assert_eq!(Some(cube_level(v)), searched, "value {v}");
        }
    }
}
