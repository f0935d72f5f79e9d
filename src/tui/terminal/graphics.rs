//! Real pixels in the preview: which way the terminal shows a picture, chosen once at start-up.
//!
//! The terminal's answers decide (see [`super::color_probe`]): a kitty terminal answers the
//! kitty graphics query with `OK`, a sixel terminal lists attribute 4 in its device attributes,
//! and iTerm2 and WezTerm name themselves in XTVERSION. Environment hints only help where no
//! question exists (iTerm2's `TERM_PROGRAM`, once the terminal has answered at all). Inside tmux
//! an image reaches the outer terminal only through DCS passthrough, used when tmux allows it;
//! otherwise the preview stays in cells and the status line says why. Without pixels the preview
//! is drawn in the sharpest glyph set the terminal is known to draw (sextants where XTVERSION
//! names kitty, WezTerm, foot or Ghostty), else half blocks. `--graphics` picks a protocol or a
//! glyph set without asking.

use super::term_input::Reply;
use crate::terminal_image::{CellArea, CellSize, GlyphSet, Protocol};

/// Most pixels one preview image has: 800×600, which keeps one frame of the default scene near
/// 120 kB in every protocol (see the README); a larger pane is rendered smaller with its aspect
/// kept, and kitty and iTerm2 scale it up to fill the pane.
pub const PIXEL_BUDGET: u64 = 480_000;

/// What `--graphics` asks for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum GraphicsRequest {
    /// Ask the terminal, and use the best protocol it answers for.
    #[default]
    Auto,
    /// This protocol, without asking (the cell size is still asked for).
    Kitty,
    Sixel,
    Iterm2,
    /// Text cells of this glyph set, without asking for pixels (the cell size is still asked
    /// for).
    Cells(GlyphSet),
}

/// How the preview reaches the screen.
#[derive(Debug, Clone, PartialEq)]
pub struct Graphics {
    /// [`Protocol::Kitty`], [`Protocol::Sixel`] or [`Protocol::Iterm2`]; `None` for text cells.
    pub protocol: Option<Protocol>,
    /// The glyph set of the preview in text cells (without pixels, and for the frames drawn
    /// while keys arrive).
    pub cells: GlyphSet,
    /// One cell in screen pixels.
    pub cell: CellSize,
    /// Inside tmux with passthrough: images are wrapped for tmux and placed at the pane's
    /// offset in the outer terminal (column, row; 0-based).
    pub tmux_pane: Option<(u16, u16)>,
    /// Inside tmux, in kitty 0.28 or later: kitty pictures are shown through Unicode
    /// placeholder cells (see [`crate::terminal_image::kitty_placeholder`]), which tmux keeps
    /// with the pane; the value is the images' most significant id byte (1..=255, from the
    /// process id, so that two editors in one kitty window rarely share ids).
    pub placeholders: Option<u8>,
    /// Inside tmux in an older kitty (no placeholders): a picture belongs to the outer terminal,
    /// and tmux passes nothing on from a pane in a window not shown. The editor asks for focus
    /// reports, which tmux sends on a window switch (with its `focus-events` on); while the pane
    /// is unfocused the preview is drawn in text cells, and on losing the focus the pictures are
    /// deleted by writing to tmux's client terminal directly (see `tui::tmux_client`).
    pub hides_unfocused: bool,
    /// A word for the status line at start-up about how pictures behave.
    pub notice: Option<String>,
    /// Why text cells are used where pixels were asked for or hinted at.
    pub why: Option<String>,
}

impl Default for Graphics {
    fn default() -> Graphics {
        Graphics::half_blocks(None)
    }
}

impl Graphics {
    /// Half blocks on 1:2 cells, with the reason when pixels were wanted.
    pub fn half_blocks(why: Option<String>) -> Graphics {
        Graphics::in_cells(GlyphSet::HalfBlock, CellSize::default(), why)
    }

    /// Text cells of `set` on cells of `cell` pixels, with the reason when pixels were wanted.
    pub fn in_cells(set: GlyphSet, cell: CellSize, why: Option<String>) -> Graphics {
        Graphics {
            protocol: None,
            cells: set,
            cell,
            tmux_pane: None,
            placeholders: None,
            hides_unfocused: false,
            notice: None,
            why,
        }
    }

    /// The name the status line shows: `kitty`, `sixel`, `iTerm2`, or the glyph set's (`half
    /// blocks`, `quadrants`, `sextants`, `braille`).
    pub fn label(&self) -> &'static str {
        match self.protocol {
            Some(Protocol::Kitty) => "kitty",
            Some(Protocol::Sixel) => "sixel",
            Some(Protocol::Iterm2) => "iTerm2",
            _ => self.cells.label(),
        }
    }

    /// The image size to render for a picture of `cols`×`rows` text cells: square pixels in
    /// the cells' true shape ([`Graphics::cell`]), one pixel a column for half blocks (two rows
    /// a cell on 1:2 cells) and two for the finer sets, which the glyph encoder then samples.
    pub fn cells_size(&self, cols: u16, rows: u16) -> (u32, u32) {
        let across = match self.cells {
            GlyphSet::HalfBlock => 1,
            _ => 2,
        };
        let cell = self.cell;
        let down = u64::from(across) * u64::from(cell.height.max(1));
        let height = (u64::from(rows) * down + u64::from(cell.width.max(1)) / 2)
            / u64::from(cell.width.max(1));
        (
            u32::from(cols) * across,
            (height as u32).max(u32::from(rows)),
        )
    }

    /// The image size to render for a picture of `cols`×`rows` cells shown in real pixels: the
    /// cells' pixels, scaled down with their aspect kept to at most [`PIXEL_BUDGET`]; a sixel
    /// image's height is a whole number of six-pixel bands, so it never spills below its cells.
    /// `None` for half blocks.
    pub fn pixel_size(&self, cols: u16, rows: u16) -> Option<(u32, u32)> {
        self.pixel_size_within(cols, rows, PIXEL_BUDGET)
    }

    /// As [`Graphics::pixel_size`], with at most `budget` pixels (a slow link's share, see
    /// `tui::pacer::Link::picture_bytes`) instead of [`PIXEL_BUDGET`].
    pub fn pixel_size_within(&self, cols: u16, rows: u16, budget: u64) -> Option<(u32, u32)> {
        let protocol = self.protocol?;
        let area = CellArea {
            cols: u32::from(cols.max(1)),
            rows: u32::from(rows.max(1)),
        };
        let (w, h) = area.pixels_within(self.cell, budget.min(PIXEL_BUDGET));
        let h = match protocol {
            Protocol::Sixel if h >= 6 => h - h % 6,
            _ => h,
        };
        Some((w, h))
    }
}

/// What the terminal and the environment said at start-up.
#[derive(Debug, Clone, Default)]
pub struct Facts {
    /// The terminal's replies to the start-up questions.
    pub replies: Vec<Reply>,
    /// `TERM`, `TERM_PROGRAM`, and whether `KITTY_WINDOW_ID` is set.
    pub term: String,
    pub term_program: String,
    pub kitty_window: bool,
    /// Whether `TMUX` is set.
    pub in_tmux: bool,
    /// tmux's `allow-passthrough` (`on` or `all`); `None` when tmux could not be asked.
    pub tmux_passthrough: Option<bool>,
    /// The tmux pane's offset in the outer terminal, cells (column, row).
    pub tmux_pane: (u16, u16),
    /// tmux's `focus-events` option (focus reports reach the panes).
    pub tmux_focus_events: bool,
    /// The terminal outside tmux as tmux knows it from its XTVERSION answer
    /// (`#{client_termtype}`, `kitty(0.26.5)`); `None` outside tmux or when tmux does not say.
    pub tmux_client: Option<String>,
    /// The terminal's size from the kernel (TIOCGWINSZ): columns, rows, and pixels (0 when the
    /// terminal does not fill them in).
    pub winsize: Option<(u16, u16, u16, u16)>,
}

impl Facts {
    /// Whether the terminal answered the device-attributes question (it is listening).
    fn answered(&self) -> bool {
        self.replies
            .iter()
            .any(|r| matches!(r, Reply::DeviceAttributes(_)))
    }

    /// Whether the kitty graphics query was answered `OK`.
    fn kitty(&self) -> bool {
        self.replies
            .iter()
            .any(|r| matches!(r, Reply::Kitty(t) if t.contains("i=31") && t.ends_with(";OK")))
    }

    /// Whether the device attributes list sixel graphics (4).
    fn sixel(&self) -> bool {
        self.replies
            .iter()
            .any(|r| matches!(r, Reply::DeviceAttributes(a) if a.contains(&4)))
    }

    /// The terminal's name and version from XTVERSION (`kitty(0.26.5)`), if it answered.
    fn version(&self) -> Option<&str> {
        self.replies.iter().find_map(|r| match r {
            Reply::Dcs(t) => t.strip_prefix(">|"),
            _ => None,
        })
    }

    /// Whether the terminal outside tmux is kitty 0.28 or later, which draws Unicode
    /// placeholders: by an XTVERSION answer that passed through tmux, or by tmux's own record of
    /// the client's.
    fn kitty_placeholders(&self) -> bool {
        let named = |text: &str| {
            let Some(version) = text.strip_prefix("kitty(") else {
                return false;
            };
            let mut numbers = version
                .trim_end_matches(')')
                .split('.')
                .map(|n| n.parse::<u32>().unwrap_or(0));
            let (major, minor) = (numbers.next().unwrap_or(0), numbers.next().unwrap_or(0));
            (major, minor) >= (0, 28)
        };
        let answered = self.replies.iter().any(|r| match r {
            Reply::Dcs(t) => t.strip_prefix(">|").is_some_and(named),
            _ => false,
        });
        answered || self.tmux_client.as_deref().is_some_and(named)
    }

    /// The sharpest glyph set the terminal is known to draw: sextants in kitty, WezTerm, foot
    /// and Ghostty (by XTVERSION), else half blocks.
    fn sharpest_cells(&self) -> GlyphSet {
        let known = ["kitty", "wezterm", "foot", "ghostty"];
        let name = self.version().unwrap_or_default().to_ascii_lowercase();
        if known.iter().any(|k| name.starts_with(k)) {
            GlyphSet::Sextant
        } else {
            GlyphSet::HalfBlock
        }
    }

    /// Whether the terminal is iTerm2 or WezTerm: by XTVERSION, or by `TERM_PROGRAM` once the
    /// terminal has answered at all.
    fn iterm2(&self) -> bool {
        let named = |name: &str| name.starts_with("iTerm2") || name.starts_with("WezTerm");
        let version = self
            .replies
            .iter()
            .any(|r| matches!(r, Reply::Dcs(t) if t.strip_prefix(">|").is_some_and(named)));
        let hinted = self.term_program == "iTerm.app" || self.term_program == "WezTerm";
        version || (hinted && self.answered())
    }

    /// Whether the environment hints at a terminal with pixels.
    pub fn hints_pixels(&self) -> bool {
        self.kitty_window
            || matches!(self.term.as_str(), "xterm-kitty" | "xterm-ghostty")
            || self.term.starts_with("foot")
            || self.term.contains("sixel")
            || matches!(self.term_program.as_str(), "iTerm.app" | "WezTerm")
    }

    /// The text area in pixels (width, height): the `CSI 14 t` answer, else the kernel's pixel
    /// fields when filled in.
    pub fn text_area(&self) -> Option<(u32, u32)> {
        let positive = |w: u16, h: u16| (w > 0 && h > 0).then_some((u32::from(w), u32::from(h)));
        let asked = self.replies.iter().find_map(|r| match r {
            Reply::WindowSize { width, height } => positive(*width, *height),
            _ => None,
        });
        asked.or_else(|| self.winsize.and_then(|(_, _, w, h)| positive(w, h)))
    }

    /// The cell size in pixels: the `CSI 16 t` answer, else the text area (`CSI 14 t`, or the
    /// kernel's pixel fields) over the cells, else 10×20.
    pub fn cell(&self) -> CellSize {
        let positive = |w: u32, h: u32| {
            (w > 0 && h > 0).then_some(CellSize {
                width: w,
                height: h,
            })
        };
        let asked = self.replies.iter().find_map(|r| match r {
            Reply::CellSize { width, height } => positive(u32::from(*width), u32::from(*height)),
            _ => None,
        });
        let (cols, rows) = self
            .winsize
            .map_or((0, 0), |(c, r, _, _)| (u32::from(c), u32::from(r)));
        let per_cell = |w: u32, h: u32| {
            (cols > 0 && rows > 0)
                .then(|| positive(w / cols, h / rows))
                .flatten()
        };
        let window = self.replies.iter().find_map(|r| match r {
            Reply::WindowSize { width, height } => per_cell(u32::from(*width), u32::from(*height)),
            _ => None,
        });
        let kernel = self
            .winsize
            .and_then(|(_, _, w, h)| per_cell(u32::from(w), u32::from(h)));
        asked.or(window).or(kernel).unwrap_or_default()
    }
}

/// The way to draw the preview for `request`, given what the terminal and environment said.
pub fn choose(request: GraphicsRequest, facts: &Facts) -> Graphics {
    let cells = |why: Option<String>| {
        let set = match request {
            GraphicsRequest::Cells(set) => set,
            _ => facts.sharpest_cells(),
        };
        Graphics::in_cells(set, facts.cell(), why)
    };
    let wanted = match request {
        GraphicsRequest::Cells(_) => return cells(None),
        GraphicsRequest::Kitty => Some(Protocol::Kitty),
        GraphicsRequest::Sixel => Some(Protocol::Sixel),
        GraphicsRequest::Iterm2 => Some(Protocol::Iterm2),
        GraphicsRequest::Auto if facts.kitty() => Some(Protocol::Kitty),
        GraphicsRequest::Auto if facts.iterm2() => Some(Protocol::Iterm2),
        GraphicsRequest::Auto if facts.sixel() => Some(Protocol::Sixel),
        GraphicsRequest::Auto => None,
    };
    let passthrough = facts.tmux_passthrough == Some(true) || facts.kitty();
    let tmux_closed = || {
        cells(Some(
            "tmux allow-passthrough is off (tmux set -g allow-passthrough on)".into(),
        ))
    };
    let Some(protocol) = wanted else {
        // Inside tmux without passthrough the terminal outside could not even be asked.
        if facts.in_tmux && !passthrough {
            return tmux_closed();
        }
        let why = facts
            .hints_pixels()
            .then(|| "the terminal did not answer the graphics queries".to_string());
        return cells(why);
    };
    // tmux draws sixel itself when it answers with attribute 4; the others must pass through.
    let through_tmux = facts.in_tmux && !(protocol == Protocol::Sixel && facts.sixel());
    if through_tmux && !passthrough {
        return tmux_closed();
    }
    let kitty_in_tmux = through_tmux && protocol == Protocol::Kitty;
    let placeholders = kitty_in_tmux && facts.kitty_placeholders();
    let hides_unfocused = kitty_in_tmux && !placeholders;
    Graphics {
        protocol: Some(protocol),
        // Frames drawn while keys arrive stay cheap.
        cells: GlyphSet::HalfBlock,
        cell: facts.cell(),
        tmux_pane: through_tmux.then_some(facts.tmux_pane),
        placeholders: placeholders.then(|| (std::process::id() % 255 + 1) as u8),
        hides_unfocused,
        notice: (hides_unfocused && !facts.tmux_focus_events).then(|| {
            "tmux focus-events is off: a picture stays over other windows \
             (tmux set -s focus-events on)"
                .to_string()
        }),
        why: None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pixel_sizes_keep_the_cells_aspect_within_the_budget() {
        let mut g = Graphics {
            protocol: Some(Protocol::Kitty),
            cells: GlyphSet::HalfBlock,
            cell: CellSize {
                width: 8,
                height: 16,
            },
            tmux_pane: None,
            placeholders: None,
            hides_unfocused: false,
            notice: None,
            why: None,
        };
        assert_eq!(g.pixel_size(40, 12), Some((320, 192)));
        let (w, h) = g.pixel_size(122, 44).unwrap();
        assert!(u64::from(w) * u64::from(h) <= PIXEL_BUDGET);
        let aspect = (122.0 * 8.0) / (44.0 * 16.0);
        assert!((w as f32 / h as f32 - aspect).abs() < 0.01, "{w}x{h}");
        g.protocol = Some(Protocol::Sixel);
        assert_eq!(g.pixel_size(40, 12).unwrap().1 % 6, 0);
        assert_eq!(Graphics::default().pixel_size(40, 12), None);
    }
}
