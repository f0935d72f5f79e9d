//! The terminal guard: raw mode, the alternate screen and mouse capture while the editor runs,
//! restored on drop and on panic. Frames are wrapped in synchronized output so the terminal
//! shows each one whole.

use std::io::{self, Stdout, Write};

use super::compact_backend::CompactBackend;
use ratatui::Frame;
use ratatui::Terminal;
use ratatui::crossterm::cursor::{Hide, Show};
use ratatui::crossterm::event::{DisableMouseCapture, EnableMouseCapture};
use ratatui::crossterm::execute;
use ratatui::crossterm::terminal::{
    BeginSynchronizedUpdate, EndSynchronizedUpdate, EnterAlternateScreen, LeaveAlternateScreen,
    disable_raw_mode, enable_raw_mode,
};

/// Owns the terminal while the editor runs.
pub struct TerminalGuard {
    pub terminal: Terminal<CompactBackend<Stdout>>,
}

impl TerminalGuard {
    /// Switches the terminal to the editor's settings and installs the panic hook.
    pub fn enter() -> io::Result<TerminalGuard> {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            restore();
            previous(info);
        }));
        enable_raw_mode()?;
        let mut out = io::stdout();
        if let Err(e) = execute!(out, EnterAlternateScreen, EnableMouseCapture, Hide) {
            restore();
            return Err(e);
        }
        let terminal = Terminal::new(CompactBackend::new(out)).inspect_err(|_| restore())?;
        Ok(TerminalGuard { terminal })
    }

    /// Writes a query to the terminal (its answer comes back as input) and flushes it.
    pub fn ask(&mut self, query: &[u8]) -> io::Result<()> {
        let out = self.terminal.backend_mut();
        out.write_all(query)?;
        out.flush()
    }

    /// Draws one frame inside a synchronized update.
    pub fn draw(&mut self, render: impl FnOnce(&mut Frame)) -> io::Result<()> {
        execute!(self.terminal.backend_mut(), BeginSynchronizedUpdate)?;
        let result = self.terminal.draw(render).map(drop);
        execute!(self.terminal.backend_mut(), EndSynchronizedUpdate)?;
        result
    }
}

/// Puts the terminal back as the shell had it. Safe to call more than once; errors (a closed
/// terminal after SIGHUP) are ignored.
pub fn restore() {
    let _ = disable_raw_mode();
    let mut out = io::stdout();
    let _ = execute!(
        out,
        EndSynchronizedUpdate,
        DisableMouseCapture,
        LeaveAlternateScreen,
        Show
    );
    let _ = out.flush();
}

impl Drop for TerminalGuard {
    fn drop(&mut self) {
        restore();
    }
}
