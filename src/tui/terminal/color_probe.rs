//! Asking the terminal at start-up, once, what it can show: 24-bit colour when the environment
//! does not say (plain `ssh` forwards no `COLORTERM`), pixel graphics and the cell size in
//! pixels. Questions a terminal may ignore: XTGETTCAP for the `RGB` and `Tc` capabilities,
//! DECRQSS for the background just set to a truecolor value, the kitty graphics query, XTVERSION
//! and the cell and text-area sizes in pixels (`CSI 16 t`, `CSI 14 t`). Primary device
//! attributes (`CSI c`), which every terminal answers, come last and end the wait; they also
//! list sixel graphics (4).

use std::io::{self, IsTerminal, Write};
use std::os::fd::AsFd;
use std::time::{Duration, Instant};

use ratatui::crossterm::terminal::{
    disable_raw_mode, enable_raw_mode, is_raw_mode_enabled, window_size,
};
use rustix::event::{PollFd, PollFlags, Timespec, poll};

use super::graphics::{self, Facts, Graphics, GraphicsRequest};
use super::term_input::{Decoder, Reply, TermInput};
use crate::terminal_image::preview::ColorMode;
use crate::terminal_image::{kitty, passthrough};

/// The colour questions: XTGETTCAP `RGB` and `Tc` (names hex-encoded), a truecolor background
/// then DECRQSS for the current SGR, and a reset.
pub const COLOR_QUERY: &[u8] = b"\x1bP+q524742;5463\x1b\\\x1b[48;2;1;2;3m\x1bP$qm\x1b\\\x1b[0m";

/// The graphics questions after the kitty query: XTVERSION, the cell size and the text area in
/// pixels.
const SIZE_QUERY: &[u8] = b"\x1b[>0q\x1b[16t\x1b[14t";

/// XTVERSION alone.
const VERSION_QUERY: &[u8] = b"\x1b[>0q";

/// The cell size and the text area in pixels alone.
const CELL_QUERY: &[u8] = b"\x1b[16t\x1b[14t";

/// Primary device attributes: the sentinel every terminal answers.
const DA1: &[u8] = b"\x1b[c";

/// Everything asked at start-up, in order, DA1 last. Inside tmux (`in_tmux`) the kitty query,
/// XTVERSION and the size questions go through passthrough when tmux allows it
/// (`passthrough`), since tmux answers none of them for the terminal outside (its own XTVERSION
/// answer is asked for too); when it does not allow it the kitty query is left out, as tmux would
/// show it in the pane's title.
pub fn query(in_tmux: bool, passthrough: bool) -> Vec<u8> {
    match (in_tmux, passthrough) {
        (false, _) => [COLOR_QUERY, kitty::QUERY, SIZE_QUERY, DA1].concat(),
        (true, true) => {
            let outside = passthrough::tmux(&[kitty::QUERY, VERSION_QUERY, CELL_QUERY].concat());
            [COLOR_QUERY, &outside, VERSION_QUERY, DA1].concat()
        }
        (true, false) => [COLOR_QUERY, SIZE_QUERY, DA1].concat(),
    }
}

/// How long to keep listening after DA1 inside tmux with passthrough: tmux answers DA1 itself
/// at once, and the outer terminal's answers to what passed through come after it.
pub const TMUX_GRACE: Duration = Duration::from_millis(500);

/// How long to wait for the sentinel before deciding on what has arrived.
pub const TIMEOUT: Duration = Duration::from_millis(300);

/// How long to wait for the sentinel when the environment hints at a terminal with pixels.
pub const HINTED_TIMEOUT: Duration = Duration::from_millis(1500);

/// The colour depth the environment states: truecolor for `COLORTERM=truecolor|24bit`,
/// `None` when it is silent.
pub fn from_env(colorterm: Option<&str>) -> Option<ColorMode> {
    colorterm
        .filter(|v| v.eq_ignore_ascii_case("truecolor") || v.eq_ignore_ascii_case("24bit"))
        .map(|_| ColorMode::Truecolor)
}

/// The depth the terminal's `replies` to [`query`] show: truecolor when XTGETTCAP reports
/// `RGB` or `Tc` as present, or DECRQSS echoes the truecolor background; 256 colours otherwise
/// (only DA1, or nothing at all).
pub fn decide(replies: &[Reply]) -> ColorMode {
    let truecolor = replies.iter().any(|reply| match reply {
        Reply::Dcs(text) => has_rgb_capability(text) || echoes_truecolor_sgr(text),
        _ => false,
    });
    if truecolor {
        ColorMode::Truecolor
    } else {
        ColorMode::Ansi256
    }
}

/// `1+r NAME[=VALUE];…`: a valid XTGETTCAP answer naming `RGB` (524742) or `Tc` (5463).
fn has_rgb_capability(text: &str) -> bool {
    text.strip_prefix("1+r").is_some_and(|caps| {
        caps.split(';').any(|cap| {
            let name = cap.split('=').next().unwrap_or_default();
            name.eq_ignore_ascii_case("524742") || name.eq_ignore_ascii_case("5463")
        })
    })
}

/// `1$r … m`: a valid DECRQSS answer whose SGR holds the background set by [`COLOR_QUERY`], written
/// with colons or semicolons.
fn echoes_truecolor_sgr(text: &str) -> bool {
    text.strip_prefix("1$r")
        .is_some_and(|sgr| sgr.contains("48:2:1:2:3") || sgr.contains("48;2;1;2;3"))
}

/// What the editor starts with: the colour depth and the way to draw the preview.
#[derive(Debug, Clone, PartialEq)]
pub struct Startup {
    pub color: ColorMode,
    pub graphics: Graphics,
}

/// Decides the colour depth (`color` when given, else what `COLORTERM` states, else what the
/// terminal answers, else 256 colours) and the graphics for `request`, from [`facts`].
pub fn detect(color: Option<ColorMode>, request: GraphicsRequest) -> Startup {
    let color = color.or_else(|| from_env(std::env::var("COLORTERM").ok().as_deref()));
    let facts = facts(None);
    Startup {
        color: color.unwrap_or_else(|| decide(&facts.replies)),
        graphics: graphics::choose(request, &facts),
    }
}

/// What the environment says, with the terminal's answers to [`query`] when standard input and
/// output are a terminal. The wait ends at DA1 (inside tmux with passthrough, a little after:
/// [`TMUX_GRACE`]), or after `timeout`; by default [`TIMEOUT`], or [`HINTED_TIMEOUT`] where the
/// environment hints at pixels. Raw mode is on while it waits and back as it was afterwards.
pub fn facts(timeout: Option<Duration>) -> Facts {
    let var = |name: &str| std::env::var(name).unwrap_or_default();
    let in_tmux = std::env::var_os("TMUX").is_some();
    let tmux_passthrough = in_tmux.then(tmux_allows_passthrough).flatten();
    let mut facts = Facts {
        term: var("TERM"),
        term_program: var("TERM_PROGRAM"),
        kitty_window: std::env::var_os("KITTY_WINDOW_ID").is_some(),
        in_tmux,
        tmux_passthrough,
        tmux_pane: (0, 0),
        tmux_focus_events: false,
        tmux_client: None,
        winsize: window_size()
            .ok()
            .map(|w| (w.columns, w.rows, w.width, w.height)),
        replies: Vec::new(),
    };
    if in_tmux {
        (facts.tmux_pane, facts.tmux_focus_events, facts.tmux_client) = tmux_pane();
    }
    // Asked even when everything is forced: the cell size gives every picture its aspect.
    if io::stdin().is_terminal() && io::stdout().is_terminal() {
        let passthrough = tmux_passthrough == Some(true);
        // A terminal that says it has pixels is given longer to answer: one just opened may
        // still be starting up (kitty takes about a second on a loaded machine).
        let timeout = timeout.unwrap_or(if facts.hints_pixels() || passthrough {
            HINTED_TIMEOUT
        } else {
            TIMEOUT
        });
        let grace = (in_tmux && passthrough).then_some(TMUX_GRACE);
        facts.replies = ask_raw(&query(in_tmux, passthrough), timeout, grace);
    }
    facts
}

/// tmux's `allow-passthrough` for this pane: `on` or `all` allow it. `None` when tmux cannot be
/// asked.
fn tmux_allows_passthrough() -> Option<bool> {
    let out = std::process::Command::new("tmux")
        .args(["show", "-Apv", "allow-passthrough"])
        .output()
        .ok()?;
    let value = String::from_utf8_lossy(&out.stdout);
    out.status
        .success()
        .then(|| matches!(value.trim(), "on" | "all"))
}

/// The current tmux pane's offset in the outer terminal ((0, 0) when tmux cannot say), whether
/// tmux's `focus-events` is on, and the outer terminal's XTVERSION answer as tmux recorded it
/// (`#{client_termtype}`, when not empty).
fn tmux_pane() -> ((u16, u16), bool, Option<String>) {
    let out = std::process::Command::new("tmux")
        .args([
            "display",
            "-p",
            "#{pane_left},#{pane_top},#{focus-events},#{client_termtype}",
        ])
        .output();
    let text = out
        .ok()
        .map(|o| String::from_utf8_lossy(&o.stdout).into_owned())
        .unwrap_or_default();
    let mut fields = text.trim().splitn(4, ',');
    let mut number = || fields.next().and_then(|n| n.parse().ok()).unwrap_or(0);
    let offset = (number(), number());
    let focus_events = number() == 1;
    let client = fields.next().filter(|t| !t.is_empty()).map(str::to_string);
    (offset, focus_events, client)
}

/// Writes `query` with raw mode on and collects the replies for at most `timeout` (see
/// [`ask`]).
fn ask_raw(query: &[u8], timeout: Duration, grace: Option<Duration>) -> Vec<Reply> {
    let was_raw = is_raw_mode_enabled().unwrap_or(false);
    if !was_raw && enable_raw_mode().is_err() {
        return Vec::new();
    }
    let replies = ask(query, timeout, grace).unwrap_or_default();
    if !was_raw {
        let _ = disable_raw_mode();
    }
    replies
}

/// Writes `query` and collects the replies until DA1 arrives or `timeout` passes. With a
/// `grace`, the wait goes on after DA1 for at most that long, until the answers that passed
/// through tmux are in (see [`outside_answered`]).
fn ask(query: &[u8], timeout: Duration, grace: Option<Duration>) -> io::Result<Vec<Reply>> {
    let mut out = io::stdout();
    out.write_all(query)?;
    out.flush()?;
    let stdin = io::stdin();
    let fd = stdin.as_fd();
    let mut decoder = Decoder::new();
    let mut decoded = Vec::new();
    let mut replies = Vec::new();
    let mut buffer = [0u8; 1024];
    let mut deadline = Instant::now() + timeout;
    let mut sentinel_seen = false;
    loop {
        let left = deadline.saturating_duration_since(Instant::now());
        if left.is_zero() {
            return Ok(replies);
        }
        let wait = Timespec {
            tv_sec: left.as_secs() as _,
            tv_nsec: left.subsec_nanos() as _,
        };
        let mut fds = [PollFd::new(&fd, PollFlags::IN)];
        match poll(&mut fds, Some(&wait)) {
            Ok(0) => return Ok(replies),
            Ok(_) => match rustix::io::read(fd, &mut buffer) {
                Ok(0) => return Ok(replies),
                Ok(n) => decoder.feed(&buffer[..n], &mut decoded),
                Err(rustix::io::Errno::INTR | rustix::io::Errno::AGAIN) => continue,
                Err(e) => return Err(e.into()),
            },
            Err(rustix::io::Errno::INTR) => continue,
            Err(e) => return Err(e.into()),
        }
        for input in decoded.drain(..) {
            if let TermInput::Reply(reply) = input {
                let sentinel = matches!(reply, Reply::DeviceAttributes(_));
                replies.push(reply);
                if sentinel && !sentinel_seen {
                    sentinel_seen = true;
                    match grace {
                        None => return Ok(replies),
                        Some(g) => deadline = deadline.min(Instant::now() + g),
                    }
                }
                if sentinel_seen && outside_answered(&replies) {
                    return Ok(replies);
                }
            }
        }
    }
}

/// Whether the terminal outside tmux has answered what passed through: its text area (the last
/// question), or the kitty query and the cell size.
pub fn outside_answered(replies: &[Reply]) -> bool {
    let has = |f: fn(&Reply) -> bool| replies.iter().any(f);
    has(|r| matches!(r, Reply::WindowSize { .. }))
        || (has(|r| matches!(r, Reply::Kitty(_))) && has(|r| matches!(r, Reply::CellSize { .. })))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The replies a terminal sends for `bytes`.
    fn replies(bytes: &[u8]) -> Vec<Reply> {
        let mut decoder = Decoder::new();
        let mut out = Vec::new();
        decoder.feed(bytes, &mut out);
        out.into_iter()
            .filter_map(|i| match i {
                TermInput::Reply(r) => Some(r),
                TermInput::Event(_) => None,
            })
            .collect()
    }

    #[test]
    fn a_terminal_reporting_the_rgb_capability_gets_truecolor() {
        let answer = replies(b"\x1bP1+r524742=382F382F38\x1b\\\x1bP0+r5463\x1b\\\x1b[?62;22c");
        assert_eq!(decide(&answer), ColorMode::Truecolor);
        let tc_only = replies(b"\x1bP0+r524742\x1b\\\x1bP1+r5463\x1b\\\x1b[?1;2c");
        assert_eq!(decide(&tc_only), ColorMode::Truecolor);
    }

    #[test]
    fn a_terminal_echoing_the_background_with_colons_or_semicolons_gets_truecolor() {
        let colons = replies(b"\x1bP1$r0;48:2::1:2:3m\x1b\\\x1bP1$r48:2:1:2:3m\x1b\\\x1b[?64c");
        assert_eq!(decide(&colons), ColorMode::Truecolor);
        let semicolons = replies(b"\x1bP1$r0;48;2;1;2;3m\x1b\\\x1b[?64c");
        assert_eq!(decide(&semicolons), ColorMode::Truecolor);
    }

    #[test]
    fn refusals_only_da1_or_silence_keep_256_colours() {
        let refused = replies(b"\x1bP0+r524742;5463\x1b\\\x1bP0$r\x1b\\\x1b[?62c");
        assert_eq!(decide(&refused), ColorMode::Ansi256);
        // A palette-mapped echo is not truecolor.
        let mapped = replies(b"\x1bP1$r0;48;5;16m\x1b\\\x1b[?62c");
        assert_eq!(decide(&mapped), ColorMode::Ansi256);
        let only_da1 = replies(b"\x1b[?1;2c");
        assert_eq!(only_da1.len(), 1);
        assert_eq!(decide(&only_da1), ColorMode::Ansi256);
        assert_eq!(decide(&[]), ColorMode::Ansi256);
    }

    #[test]
    fn the_environment_decides_only_when_it_names_truecolor() {
        assert_eq!(from_env(Some("truecolor")), Some(ColorMode::Truecolor));
        assert_eq!(from_env(Some("24BIT")), Some(ColorMode::Truecolor));
        assert_eq!(from_env(Some("yes")), None);
        assert_eq!(from_env(None), None);
    }
}
