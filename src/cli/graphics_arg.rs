//! The `--graphics` values, shared by the editor and `rastray view`.

use clap::ValueEnum;
use rastray::terminal_image::ColorMode;
use rastray::terminal_image::{GlyphSet, Protocol};
use rastray::tui::terminal::graphics::GraphicsRequest;

/// How to draw pictures: asked of the terminal, or one protocol.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, ValueEnum)]
pub enum GraphicsArg {
    /// The best the terminal has: kitty, iTerm2 or sixel, else the sharpest glyph set it is
    /// known to draw (sextants in kitty, WezTerm, foot, Ghostty), else half blocks (`view`:
    /// plain text when stdout is not a terminal or TERM=dumb).
    #[default]
    Auto,
    Kitty,
    Sixel,
    Iterm2,
    /// Half blocks `▀▄▌▐`: 2×2 sub-cells a cell, two colours.
    Halfblock,
    /// Quadrants `▘▝▖▗▚▞▙▛▜▟`: 2×2 sub-cells in any pattern.
    Quadrant,
    /// Sextants (Unicode 13, U+1FB00…): 2×3 sub-cells.
    Sextant,
    /// Braille dots: 2×4.
    Braille,
    /// A character ramp with no escape sequences (`view` only).
    Plain,
}

impl GraphicsArg {
    /// The request for the terminal's probe; `None` for `plain`, which asks nothing.
    pub fn request(self) -> Option<GraphicsRequest> {
        Some(match self {
            GraphicsArg::Auto => GraphicsRequest::Auto,
            GraphicsArg::Kitty => GraphicsRequest::Kitty,
            GraphicsArg::Sixel => GraphicsRequest::Sixel,
            GraphicsArg::Iterm2 => GraphicsRequest::Iterm2,
            GraphicsArg::Halfblock => GraphicsRequest::Cells(GlyphSet::HalfBlock),
            GraphicsArg::Quadrant => GraphicsRequest::Cells(GlyphSet::Quadrant),
            GraphicsArg::Sextant => GraphicsRequest::Cells(GlyphSet::Sextant),
            GraphicsArg::Braille => GraphicsRequest::Cells(GlyphSet::Braille),
            GraphicsArg::Plain => return None,
        })
    }

    /// The editor's request; `plain` is refused, since the editor draws a full screen.
    pub fn editor_request(self) -> anyhow::Result<GraphicsRequest> {
        self.request().ok_or_else(|| {
            anyhow::anyhow!(
                "--graphics plain is for `rastray view`; the editor takes auto, kitty, sixel, iterm2, halfblock, quadrant, sextant or braille"
            )
        })
    }

    /// The protocol `view` prints with when the terminal cannot be asked (stdout is not a
    /// terminal); `None` for `auto`. Text cells are in truecolor.
    pub fn view_protocol(self) -> Option<Protocol> {
        match self {
            GraphicsArg::Auto => None,
            GraphicsArg::Kitty => Some(Protocol::Kitty),
            GraphicsArg::Sixel => Some(Protocol::Sixel),
            GraphicsArg::Iterm2 => Some(Protocol::Iterm2),
            GraphicsArg::Halfblock => Some(cells(GlyphSet::HalfBlock)),
            GraphicsArg::Quadrant => Some(cells(GlyphSet::Quadrant)),
            GraphicsArg::Sextant => Some(cells(GlyphSet::Sextant)),
            GraphicsArg::Braille => Some(cells(GlyphSet::Braille)),
            GraphicsArg::Plain => Some(Protocol::Plain),
        }
    }
}

/// Text cells of `set` in truecolor.
fn cells(set: GlyphSet) -> Protocol {
    Protocol::Cells(set, ColorMode::Truecolor)
}
