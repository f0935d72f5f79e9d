//! The signals that end the editor (SIGTERM, SIGHUP, SIGINT) and the exit status each gives.
//!
//! A handler only notes the signal; the event loop looks between events, saves what needs
//! saving and returns [`Exit::Signal`], so the process exits with 128 + the signal's number as
//! shells and supervisors expect.

use std::io;
use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};

use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};

/// The signals that end the editor. Raw mode turns Ctrl-C into a key, so SIGINT only comes
/// from `kill`; SIGHUP comes when the terminal goes away (SSH drop, closed window, tmux
/// kill-session).
pub const ENDING: [i32; 3] = [SIGTERM, SIGHUP, SIGINT];

/// How the editor ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Exit {
    /// The user quit.
    Quit,
    /// One of the [`ENDING`] signals arrived; its number.
    Signal(i32),
}

impl Exit {
    /// The process exit status: 0 after quitting, 128 + the signal's number after a signal
    /// (143 for SIGTERM, 129 for SIGHUP, 130 for SIGINT).
    pub fn code(self) -> u8 {
        match self {
            Exit::Quit => 0,
            Exit::Signal(number) => u8::try_from(128 + number).unwrap_or(u8::MAX),
        }
    }
}

/// Notes which of the [`ENDING`] signals arrived (the latest, when several do).
pub struct Signals {
    /// The signal's number; 0 until one arrives.
    received: Arc<AtomicUsize>,
}

impl Signals {
    /// Starts watching; from now on these signals no longer end the process by themselves.
    pub fn watch() -> io::Result<Signals> {
        let received = Arc::new(AtomicUsize::new(0));
        for signal in ENDING {
            signal_hook::flag::register_usize(signal, received.clone(), signal as usize)?;
        }
        Ok(Signals { received })
    }

    /// The signal that arrived, if any.
    pub fn received(&self) -> Option<i32> {
        match self.received.load(Ordering::Relaxed) {
            0 => None,
            number => i32::try_from(number).ok(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exit_status_is_128_plus_the_signal() {
        assert_eq!(Exit::Quit.code(), 0);
        assert_eq!(Exit::Signal(SIGHUP).code(), 129);
        assert_eq!(Exit::Signal(SIGINT).code(), 130);
        assert_eq!(Exit::Signal(SIGTERM).code(), 143);
    }
}
