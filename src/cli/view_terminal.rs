//! How `rastray view` draws: asked of the terminal when stdout is one, with the editor's
//! start-up probe (the kitty query, the device attributes, XTVERSION, the cell and text-area
//! sizes) under a short time limit.

use std::io::IsTerminal;
use std::time::Duration;

use rastray::terminal_image::{CellSize, Protocol};
use rastray::tui::terminal::color_probe;
use rastray::tui::terminal::graphics::{self, Facts, GraphicsRequest};

use super::graphics_arg::GraphicsArg;

/// How long `view` waits for a terminal that does not answer (one that does ends the wait with
/// its device attributes).
pub const TIMEOUT: Duration = Duration::from_millis(300);

/// The way to print, and the terminal's geometry.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Drawing {
    pub protocol: Protocol,
    /// One cell in screen pixels: the terminal's answer, else 10×20.
    pub cell: CellSize,
    /// The text area's width in pixels, when the terminal or the kernel tells it.
    pub window_width: Option<u32>,
}

/// The drawing for `arg` on stdout (`is_terminal`): plain text off a terminal or on `TERM=dumb`
/// unless a protocol is forced; else what the terminal answers (when stdin is a terminal too,
/// to read the answers from), else what the environment hints.
pub fn decide(arg: GraphicsArg, is_terminal: bool) -> Drawing {
    let plain = |protocol: Option<Protocol>| Drawing {
        protocol: protocol.unwrap_or(Protocol::Plain),
        cell: CellSize::default(),
        window_width: None,
    };
    let dumb = std::env::var("TERM").is_ok_and(|t| t == "dumb");
    let Some(request) = arg.request() else {
        return plain(None);
    };
    if !is_terminal || dumb {
        return plain(arg.view_protocol());
    }
    if !std::io::stdin().is_terminal() {
        let guessed = Protocol::from_env(|k| std::env::var(k).ok());
        return plain(Some(arg.view_protocol().unwrap_or(guessed)));
    }
    let facts = color_probe::facts(Some(TIMEOUT));
    from_facts(request, &facts, std::env::var("COLORTERM").ok().as_deref())
}

/// The drawing for `request` given what the terminal said (`facts`) and `COLORTERM`. A picture
/// that would have to pass through tmux is drawn in text cells instead (`view` prints at the
/// cursor, which tmux does not share with the terminal outside).
pub fn from_facts(request: GraphicsRequest, facts: &Facts, colorterm: Option<&str>) -> Drawing {
    let chosen = graphics::choose(request, facts);
    let color =
        color_probe::from_env(colorterm).unwrap_or_else(|| color_probe::decide(&facts.replies));
    let protocol = match chosen.protocol {
        Some(p) if chosen.tmux_pane.is_none() => p,
        _ => Protocol::Cells(chosen.cells, color),
    };
    Drawing {
        protocol,
        cell: chosen.cell,
        window_width: facts.text_area().map(|(w, _)| w),
    }
}
