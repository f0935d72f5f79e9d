//! The editor's input thread: reads the terminal's bytes from standard input, decodes them with
//! [`Decoder`], and hands each key, mouse event, resize and query reply to the event loop.

use std::io;
use std::os::fd::AsFd;
use std::time::Duration;

use ratatui::crossterm::event::Event;
use rustix::event::{PollFd, PollFlags, Timespec, poll};
use signal_hook::consts::SIGWINCH;
use signal_hook::iterator::Signals;

use super::term_input::{Decoder, TermInput};

/// How long a lone ESC waits for the rest of a sequence before it counts as the Escape key.
/// Terminals send a sequence in one write; over a slow link its bytes can still arrive apart.
const ESC_WAIT: Duration = Duration::from_millis(40);

/// Starts the threads that read standard input and watch for resizes. `send` returns false
/// once nobody listens any more, which ends the threads. Reading ends when the terminal goes
/// away (end of file or an error, as after a hang-up).
pub fn spawn(send: impl Fn(TermInput) -> bool + Send + Clone + 'static) -> io::Result<()> {
    let mut signals = Signals::new([SIGWINCH])?;
    let on_resize = send.clone();
    std::thread::Builder::new()
        .name("rastray-resize".into())
        .spawn(move || {
            for _ in signals.forever() {
                let Ok((columns, rows)) = ratatui::crossterm::terminal::size() else {
                    continue;
                };
                if !on_resize(TermInput::Event(Event::Resize(columns, rows))) {
                    break;
                }
            }
        })?;
    std::thread::Builder::new()
        .name("rastray-input".into())
        .spawn(move || read_loop(send))?;
    Ok(())
}

fn read_loop(send: impl Fn(TermInput) -> bool) {
    let stdin = io::stdin();
    let fd = stdin.as_fd();
    let mut decoder = Decoder::new();
    let mut buffer = [0u8; 4096];
    let mut decoded = Vec::new();
    let esc_wait = Timespec {
        tv_sec: 0,
        tv_nsec: ESC_WAIT.as_nanos() as _,
    };
    loop {
        let timeout = decoder.has_pending().then_some(&esc_wait);
        let mut fds = [PollFd::new(&fd, PollFlags::IN)];
        match poll(&mut fds, timeout) {
            Ok(0) => decoder.flush(&mut decoded),
            Ok(_) => match rustix::io::read(fd, &mut buffer) {
                Ok(0) => return,
                Ok(n) => decoder.feed(&buffer[..n], &mut decoded),
                Err(rustix::io::Errno::INTR | rustix::io::Errno::AGAIN) => continue,
                Err(_) => return,
            },
            Err(rustix::io::Errno::INTR) => continue,
            Err(_) => return,
        }
        for input in decoded.drain(..) {
            if !send(input) {
                return;
            }
        }
    }
}
