//! The `--graphics` values, shared by the editor and `rastray view`.

use clap::ValueEnum;
use rastray::terminal_image::Protocol;
use rastray::tui::ColorMode;
use rastray::tui::graphics::GraphicsRequest;

/// How to draw pictures: asked of the terminal, or one protocol.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum GraphicsArg {
    /// The best the terminal has: kitty, iTerm2 or sixel, else half blocks (`view`: plain text
    /// when stdout is not a terminal).
    Auto,
    Kitty,
    Sixel,
    Iterm2,
    /// Half-block text.
    Halfblock,
    /// A character ramp with no escape sequences (`view` only).
    Plain,
}

impl GraphicsArg {
    /// The editor's request; `plain` is refused, since the editor draws a full screen.
    pub fn editor_request(self) -> anyhow::Result<GraphicsRequest> {
        Ok(match self {
            GraphicsArg::Auto => GraphicsRequest::Auto,
            GraphicsArg::Kitty => GraphicsRequest::Kitty,
            GraphicsArg::Sixel => GraphicsRequest::Sixel,
            GraphicsArg::Iterm2 => GraphicsRequest::Iterm2,
            GraphicsArg::Halfblock => GraphicsRequest::HalfBlock,
            GraphicsArg::Plain => anyhow::bail!(
                "--graphics plain is for `rastray view`; the editor takes auto, kitty, sixel, iterm2 or halfblock"
            ),
        })
    }

    /// The protocol `view` prints with; `None` for `auto`.
    pub fn view_protocol(self) -> Option<Protocol> {
        match self {
            GraphicsArg::Auto => None,
            GraphicsArg::Kitty => Some(Protocol::Kitty),
            GraphicsArg::Sixel => Some(Protocol::Sixel),
            GraphicsArg::Iterm2 => Some(Protocol::Iterm2),
            GraphicsArg::Halfblock => Some(Protocol::HalfBlock(ColorMode::Truecolor)),
            GraphicsArg::Plain => Some(Protocol::Plain),
        }
    }
}
