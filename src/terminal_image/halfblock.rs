//! Pictures as text: half-block cells with SGR colours (the editor's preview cells, see
//! [`half_block`]), or a character ramp with no escape at all for logs and pipes.

use std::fmt::Write;

use ratatui::style::Color;

use super::preview::{ColorMode, PreviewImage, half_block};

/// Characters from dark to light for plain text.
pub const RAMP: &[u8] = b" .:-=+*#%@";

/// `image` (two pixel rows per text row) as half-block lines with SGR colours in `mode`; every
/// line ends with a reset.
pub fn encode(image: &PreviewImage, mode: ColorMode) -> String {
    let mut out = String::new();
    for row in 0..image.height.div_ceil(2) {
        let mut last: Option<(Color, Color)> = None;
        for x in 0..image.width {
            let cell = half_block(image.pixel(x, 2 * row), image.pixel(x, 2 * row + 1), mode);
            if last != Some((cell.fg, cell.bg)) {
                let _ = write!(out, "\x1b[{};{}m", sgr(cell.fg, 38), sgr(cell.bg, 48));
                last = Some((cell.fg, cell.bg));
            }
            out.push_str(cell.symbol);
        }
        out.push_str("\x1b[0m\n");
    }
    out
}

/// The SGR parameters for `color` as foreground (`base` 38) or background (`base` 48).
fn sgr(color: Color, base: u8) -> String {
    match color {
        Color::Rgb(r, g, b) => format!("{base};2;{r};{g};{b}"),
        Color::Indexed(i) => format!("{base};5;{i}"),
        _ => format!("{}", base + 1),
    }
}

/// `image` (two pixel rows per text row) as a character ramp by luminance: plain ASCII, no
/// escapes.
pub fn encode_plain(image: &PreviewImage) -> String {
    let mut out = String::new();
    for row in 0..image.height.div_ceil(2) {
        let line: String = (0..image.width)
            .map(|x| {
                let pixels = [image.pixel(x, 2 * row), image.pixel(x, 2 * row + 1)];
                let present: Vec<f32> = pixels.iter().flatten().map(|&p| luma(p)).collect();
                let mean = present.iter().sum::<f32>() / present.len().max(1) as f32;
                let i = (mean * (RAMP.len() - 1) as f32).round() as usize;
                RAMP[i.min(RAMP.len() - 1)] as char
            })
            .collect();
        out.push_str(line.trim_end());
        out.push('\n');
    }
    out
}

/// Relative luminance of an sRGB pixel on its 8-bit codes, in [0, 1].
fn luma([r, g, b]: [u8; 3]) -> f32 {
    (0.2126 * r as f32 + 0.7152 * g as f32 + 0.0722 * b as f32) / 255.0
}

#[cfg(test)]
mod tests {
    use super::*;

    fn image() -> PreviewImage {
        PreviewImage {
            width: 2,
            height: 3,
            pixels: vec![
                [255, 0, 0],
                [0, 0, 0],
                [0, 0, 255],
                [0, 0, 0],
                [255; 3],
                [0; 3],
            ],
        }
    }

    #[test]
    fn half_blocks_carry_both_pixels_colours() {
        let text = encode(&image(), ColorMode::Truecolor);
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines.len(), 2);
        assert!(lines[0].contains("38;2;255;0;0;48;2;0;0;255m▀"), "{text:?}");
        // The odd last row: upper pixel only, on the terminal's background.
        assert!(lines[1].contains("38;2;255;255;255;49m▀"), "{text:?}");
        assert!(lines.iter().all(|l| l.ends_with("\x1b[0m")));
    }

    #[test]
    fn plain_text_is_a_ramp_with_no_escape() {
        let text = encode_plain(&image());
        assert!(!text.contains('\x1b'));
        // Red over blue: mean luminance (0.2126 + 0.0722) / 2 ≈ 0.14 → '.', the second step;
        // white over nothing is the lightest character; black is blank and trimmed.
        assert_eq!(text, ".\n@\n");
    }
}
