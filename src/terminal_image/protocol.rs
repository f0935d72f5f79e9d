//! Which way to draw a picture, chosen by the user or guessed from the environment.

use super::preview::{ColorMode, PreviewImage};
use super::{CellArea, CellSize, GlyphSet, glyph_cells, halfblock, iterm2, kitty, sixel};

/// A way to put a picture on a terminal.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Protocol {
    /// kitty graphics protocol (kitty, Ghostty, recent WezTerm and Konsole).
    Kitty,
    /// DEC sixel graphics (xterm -ti vt340, foot, mlterm, WezTerm).
    Sixel,
    /// iTerm2 inline images (iTerm2, WezTerm).
    Iterm2,
    /// Text cells of a glyph set with SGR colours.
    Cells(GlyphSet, ColorMode),
    /// A character ramp with no escape sequence.
    Plain,
}

impl Protocol {
    /// Whether the protocol shows real pixels (rendered at cell × cell-pixel size).
    pub fn has_pixels(self) -> bool {
        matches!(self, Protocol::Kitty | Protocol::Sixel | Protocol::Iterm2)
    }

    /// The best protocol for stdout: plain text when it is not a terminal, else by the
    /// environment hints ([`Protocol::from_env`]).
    pub fn detect(is_terminal: bool, env: impl Fn(&str) -> Option<String>) -> Protocol {
        if is_terminal {
            Protocol::from_env(env)
        } else {
            Protocol::Plain
        }
    }

    /// The protocol a terminal announces in its environment: `KITTY_WINDOW_ID` or
    /// `TERM=xterm-kitty` / `xterm-ghostty` → kitty; `TERM_PROGRAM=iTerm.app` or `WezTerm` →
    /// iTerm2; `TERM=foot*`, `mlterm*` or `*sixel*` → sixel; otherwise half blocks in the colours
    /// `COLORTERM` promises.
    pub fn from_env(env: impl Fn(&str) -> Option<String>) -> Protocol {
        let term = env("TERM").unwrap_or_default();
        let program = env("TERM_PROGRAM").unwrap_or_default();
        if env("KITTY_WINDOW_ID").is_some() || term == "xterm-kitty" || term == "xterm-ghostty" {
            Protocol::Kitty
        } else if program == "iTerm.app" || program == "WezTerm" {
            Protocol::Iterm2
        } else if term.starts_with("foot") || term.starts_with("mlterm") || term.contains("sixel") {
            Protocol::Sixel
        } else {
            let truecolor = env("COLORTERM")
                .is_some_and(|v| v.eq_ignore_ascii_case("truecolor") || v == "24bit");
            Protocol::Cells(
                GlyphSet::HalfBlock,
                if truecolor {
                    ColorMode::Truecolor
                } else {
                    ColorMode::Ansi256
                },
            )
        }
    }

    /// The size of the picture to render for `area` with cells of `cell` pixels, always in
    /// square pixels: the cells' pixels for a pixel protocol; for glyph cells
    /// [`glyph_cells::SAMPLES_X`] a cell across and as many down as the cell's shape makes
    /// square ([`glyph_cells::SAMPLES_Y`] on 1:2 cells; the encoder resamples to that);
    /// one pixel a column and two a row for the plain ramp.
    pub fn picture_size(self, area: CellArea, cell: CellSize) -> (u32, u32) {
        match self {
            Protocol::Kitty | Protocol::Sixel | Protocol::Iterm2 => area.pixels(cell),
            Protocol::Cells(..) => {
                let across = u64::from(glyph_cells::SAMPLES_X);
                let (w, h) = (u64::from(cell.width.max(1)), u64::from(cell.height.max(1)));
                let down = (u64::from(area.rows) * across * h + w / 2) / w;
                (area.cols * glyph_cells::SAMPLES_X, down.max(1) as u32)
            }
            Protocol::Plain => area.half_block_pixels(),
        }
    }

    /// The bytes that draw `image` over `area`; `image` is of [`Protocol::picture_size`].
    pub fn encode(
        self,
        image: &PreviewImage,
        area: CellArea,
    ) -> Result<Vec<u8>, image::ImageError> {
        Ok(match self {
            Protocol::Kitty => kitty::encode(image, area)?,
            Protocol::Iterm2 => iterm2::encode(image, area)?,
            Protocol::Sixel => sixel::encode(image),
            Protocol::Cells(set, mode) => {
                glyph_cells::encode(image, area.cols, area.rows, set, mode).into_bytes()
            }
            Protocol::Plain => halfblock::encode_plain(image).into_bytes(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn env<'a>(vars: &'a [(&'a str, &'a str)]) -> impl Fn(&str) -> Option<String> + 'a {
        move |k| {
            vars.iter()
                .find(|(n, _)| *n == k)
                .map(|(_, v)| v.to_string())
        }
    }

    #[test]
    fn environment_hints_pick_the_protocol() {
        assert_eq!(
            Protocol::from_env(env(&[("KITTY_WINDOW_ID", "1")])),
            Protocol::Kitty
        );
        assert_eq!(
            Protocol::from_env(env(&[("TERM", "xterm-kitty")])),
            Protocol::Kitty
        );
        assert_eq!(
            Protocol::from_env(env(&[("TERM_PROGRAM", "WezTerm")])),
            Protocol::Iterm2
        );
        assert_eq!(
            Protocol::from_env(env(&[("TERM", "foot-extra")])),
            Protocol::Sixel
        );
        assert_eq!(
            Protocol::from_env(env(&[
                ("TERM", "xterm-256color"),
                ("COLORTERM", "truecolor")
            ])),
            Protocol::Cells(GlyphSet::HalfBlock, ColorMode::Truecolor)
        );
        assert_eq!(
            Protocol::from_env(env(&[("TERM", "xterm")])),
            Protocol::Cells(GlyphSet::HalfBlock, ColorMode::Ansi256)
        );
        assert_eq!(
            Protocol::detect(false, env(&[("TERM", "xterm-kitty")])),
            Protocol::Plain
        );
    }
}
