//! The terminal guard: raw mode, the alternate screen and mouse reporting while the editor runs,
//! restored on drop and on panic. Frames are wrapped in synchronized output so the terminal
//! shows each one whole. Nothing here fails or panics when the terminal has gone away.

use std::cell::Cell;
use std::fmt;
use std::io::{self, Stdout, Write};
use std::rc::Rc;
use std::sync::Mutex;

use super::compact_backend::CompactBackend;
use ratatui::Frame;
use ratatui::Terminal;
use ratatui::crossterm::cursor::{Hide, Show};
use ratatui::crossterm::terminal::{
    BeginSynchronizedUpdate, EndSynchronizedUpdate, EnterAlternateScreen, LeaveAlternateScreen,
    disable_raw_mode, enable_raw_mode,
};
use ratatui::crossterm::{Command, execute, queue};

/// Mouse reporting for clicks, the wheel and drags, in SGR encoding: normal tracking (1000),
/// button-event tracking (1002: motion only while a button is held) and SGR coordinates (1006).
/// Any-motion tracking (1003) is left off: a terminal left in it by a dropped session would
/// type every mouse move into the shell.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct EnableDragReporting;

impl Command for EnableDragReporting {
    fn write_ansi(&self, f: &mut impl fmt::Write) -> fmt::Result {
        f.write_str("\x1b[?1000h\x1b[?1002h\x1b[?1006h")
    }

    #[cfg(windows)]
    fn execute_winapi(&self) -> io::Result<()> {
        ratatui::crossterm::event::EnableMouseCapture.execute_winapi()
    }
}

/// Turns off what [`EnableDragReporting`] turned on, in reverse order.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct DisableDragReporting;

impl Command for DisableDragReporting {
    fn write_ansi(&self, f: &mut impl fmt::Write) -> fmt::Result {
        f.write_str("\x1b[?1006l\x1b[?1002l\x1b[?1000l")
    }

    #[cfg(windows)]
    fn execute_winapi(&self) -> io::Result<()> {
        ratatui::crossterm::event::DisableMouseCapture.execute_winapi()
    }
}

/// Writes the sequences that set the terminal up for the editor: the alternate screen, mouse
/// reporting, a hidden cursor.
pub fn write_enter(out: &mut impl Write) -> io::Result<()> {
    queue!(out, EnterAlternateScreen, EnableDragReporting, Hide)?;
    out.flush()
}

/// Writes the sequences that undo [`write_enter`] (and end a frame cut short).
pub fn write_leave(out: &mut impl Write) -> io::Result<()> {
    queue!(
        out,
        EndSynchronizedUpdate,
        DisableDragReporting,
        LeaveAlternateScreen,
        Show
    )?;
    out.flush()
}

/// Where frames go: the terminal, until the guard lets go of it; from then on writes are
/// dropped. Counts the bytes written, for the pacer's estimate of the link.
pub struct Output {
    stdout: Stdout,
    released: Rc<Cell<bool>>,
    written: Rc<Cell<u64>>,
}

impl Write for Output {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        match self.released.get() {
            false => {
                let n = self.stdout.write(buf)?;
                self.written.set(self.written.get() + n as u64);
                Ok(n)
            }
            true => Ok(buf.len()),
        }
    }

    fn flush(&mut self) -> io::Result<()> {
        match self.released.get() {
            false => self.stdout.flush(),
            true => Ok(()),
        }
    }
}

/// Owns the terminal while the editor runs.
pub struct TerminalGuard {
    pub terminal: Terminal<CompactBackend<Output>>,
    /// Set on drop: the terminal's [`Output`] stops writing.
    released: Rc<Cell<bool>>,
    /// Bytes written to the terminal so far.
    written: Rc<Cell<u64>>,
}

impl TerminalGuard {
    /// Switches the terminal to the editor's settings and installs the panic hook.
    pub fn enter() -> io::Result<TerminalGuard> {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            restore();
            // The standard hook ignores a failed write to a closed stderr.
            previous(info);
        }));
        enable_raw_mode()?;
        if let Err(e) = write_enter(&mut io::stdout()) {
            restore();
            return Err(e);
        }
        let released = Rc::new(Cell::new(false));
        let written = Rc::new(Cell::new(0));
        let backend = CompactBackend::new(Output {
            stdout: io::stdout(),
            released: released.clone(),
            written: written.clone(),
        });
        let terminal = Terminal::new(backend).inspect_err(|_| restore())?;
        Ok(TerminalGuard {
            terminal,
            released,
            written,
        })
    }

    /// Writes a query to the terminal (its answer comes back as input) and flushes it.
    pub fn ask(&mut self, query: &[u8]) -> io::Result<()> {
        let out = self.terminal.backend_mut();
        out.write_all(query)?;
        out.flush()
    }

    /// Bytes written to the terminal since the editor started.
    pub fn written(&self) -> u64 {
        self.written.get()
    }

    /// Draws one frame inside a synchronized update, then `pictures` (the bytes that draw
    /// pictures in real pixels over the cells, see `tui::terminal::image_layer`) inside the same update.
    pub fn draw(&mut self, render: impl FnOnce(&mut Frame), pictures: &[u8]) -> io::Result<()> {
        execute!(self.terminal.backend_mut(), BeginSynchronizedUpdate)?;
        let mut result = self.terminal.draw(render).map(drop);
        if result.is_ok() && !pictures.is_empty() {
            // The next frame places its first cell itself, wherever a picture left the cursor.
            result = self.terminal.backend_mut().write_all(pictures);
        }
        execute!(self.terminal.backend_mut(), EndSynchronizedUpdate)?;
        result
    }
}

/// What takes the editor's pictures off the screen before it leaves (see
/// `tui::terminal::image_layer::ImageLayer::cleanup`); written on every way out, the panic hook included.
static CLEAN_UP: Mutex<Vec<u8>> = Mutex::new(Vec::new());

/// Sets what [`restore`] writes before leaving the alternate screen to take pictures off it.
pub fn clean_up_with(bytes: Vec<u8>) {
    if let Ok(mut clean_up) = CLEAN_UP.lock() {
        *clean_up = bytes;
    }
}

/// Puts the terminal back as the shell had it, pictures taken off the screen first. Safe to
/// call more than once; errors (a terminal that has gone away) are ignored.
pub fn restore() {
    let _ = disable_raw_mode();
    let mut out = io::stdout();
    if let Ok(clean_up) = CLEAN_UP.try_lock() {
        let _ = out.write_all(&clean_up);
    }
    let _ = write_leave(&mut out);
}

impl Drop for TerminalGuard {
    fn drop(&mut self) {
        restore();
        // `restore` showed the cursor. Ratatui's own drop would show it again and print an
        // error when that fails, which panics when stderr is the terminal that went away.
        self.released.set(true);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn written(write: fn(&mut Vec<u8>) -> io::Result<()>) -> String {
        let mut bytes = Vec::new();
        write(&mut bytes).unwrap();
        String::from_utf8(bytes).unwrap()
    }

    /// The private modes (`ESC [ ? n h`) a sequence sets, or resets with `l`.
    fn modes(text: &str, set: char) -> Vec<u32> {
        text.split("\x1b[?")
            .skip(1)
            .filter_map(|rest| {
                let end = rest.find(|c: char| !c.is_ascii_digit())?;
                (rest[end..].starts_with(set))
                    .then(|| rest[..end].parse().ok())
                    .flatten()
            })
            .collect()
    }

    #[test]
    fn mouse_reports_drags_not_every_motion() {
        let enter = written(write_enter);
        assert!(enter.contains("\x1b[?1002h"), "{enter:?}");
        assert!(enter.contains("\x1b[?1006h"), "{enter:?}");
        assert!(!enter.contains("?1003h"), "{enter:?}");
        assert!(!enter.contains("?1015h"), "{enter:?}");
    }

    #[test]
    fn leaving_resets_every_mode_entering_set() {
        let set = modes(&written(write_enter), 'h');
        let reset = modes(&written(write_leave), 'l');
        assert!(set.contains(&1049), "alternate screen: {set:?}");
        for mode in &set {
            assert!(reset.contains(mode), "mode {mode} is left on: {reset:?}");
        }
        // The cursor is hidden on entry (?25l) and shown on leaving (?25h).
        assert!(modes(&written(write_enter), 'l').contains(&25));
        assert!(modes(&written(write_leave), 'h').contains(&25));
    }
}
