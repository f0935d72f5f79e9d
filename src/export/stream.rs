//! Writing to a FIFO, a character device or standard output without ever blocking beyond the
//! reach of a signal. Such a stream can wait forever: a FIFO for a reader to open it, a pipe for
//! a reader that stopped reading. Both waits here are polls of at most [`POLL_MS`], between which
//! the render's cancel flag (set by SIGINT or SIGTERM) is checked, so a signal always ends them.

use std::fs::File;
use std::io::Write;
use std::os::fd::{AsFd, BorrowedFd};
use std::path::Path;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

use rustix::event::{PollFd, PollFlags, Timespec, poll};
use rustix::fs::{Mode, OFlags};
use rustix::io::Errno;

/// Longest single wait before the cancel flag is checked again, milliseconds.
const POLL_MS: i64 = 50;

/// Most bytes written at once: a pipe that polls writable takes at least this many (POSIX's
/// `PIPE_BUF`) without blocking.
const PIPE_BUF: usize = 4096;

/// Where a stream writes: a FIFO or device rastray opened, or standard output.
#[derive(Debug)]
enum Target {
    Opened(File),
    Stdout,
}

/// A stream whose writes wait only while `cancel` is unset.
#[derive(Debug)]
pub struct Stream {
    target: Target,
    cancel: Arc<AtomicBool>,
}

impl Stream {
    /// Opens the FIFO or character device at `path` for writing. A FIFO with no reader yet is
    /// retried until one comes or `cancel` is set (then the error says the export was cancelled).
    pub fn open(path: &Path, cancel: Arc<AtomicBool>) -> std::io::Result<Stream> {
        let flags = OFlags::WRONLY | OFlags::NONBLOCK | OFlags::CLOEXEC | OFlags::NOCTTY;
        let fd = loop {
            match rustix::fs::open(path, flags, Mode::empty()) {
                Ok(fd) => break fd,
                // A FIFO that no process has open for reading.
                Err(Errno::NXIO) => {
                    if cancel.load(Ordering::Relaxed) {
                        return Err(cancelled());
                    }
                    std::thread::sleep(std::time::Duration::from_millis(POLL_MS as u64));
                }
                Err(Errno::INTR) => {}
                Err(error) => return Err(error.into()),
            }
        };
        // Writes wait in `poll`, not in `write`: the descriptor itself may block again.
        rustix::fs::fcntl_setfl(&fd, OFlags::empty())?;
        Ok(Stream {
            target: Target::Opened(File::from(fd)),
            cancel,
        })
    }

    /// Standard output as a stream.
    pub fn stdout(cancel: Arc<AtomicBool>) -> Stream {
        Stream {
            target: Target::Stdout,
            cancel,
        }
    }

    fn fd(&self) -> BorrowedFd<'_> {
        match &self.target {
            Target::Opened(file) => file.as_fd(),
            Target::Stdout => rustix::stdio::stdout(),
        }
    }

    /// Waits until the stream takes bytes, or the cancel flag is set.
    fn wait_writable(&self) -> std::io::Result<()> {
        let timeout = Timespec {
            tv_sec: 0,
            tv_nsec: POLL_MS * 1_000_000,
        };
        loop {
            if self.cancel.load(Ordering::Relaxed) {
                return Err(cancelled());
            }
            let fd = self.fd();
            let mut fds = [PollFd::new(&fd, PollFlags::OUT)];
            match poll(&mut fds, Some(&timeout)) {
                Ok(0) | Err(Errno::INTR) => continue,
                // Writable, or an error or hang-up that the write will report.
                Ok(_) => return Ok(()),
                Err(error) => return Err(error.into()),
            }
        }
    }
}

/// The error a cancelled wait ends with (not `Interrupted`, which `write_all` would retry).
fn cancelled() -> std::io::Error {
    std::io::Error::other("cancelled while waiting for the reader")
}

impl Write for Stream {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        if buf.is_empty() {
            return Ok(0);
        }
        self.wait_writable()?;
        let piece = &buf[..buf.len().min(PIPE_BUF)];
        loop {
            match rustix::io::write(self.fd(), piece) {
                Ok(written) => return Ok(written),
                Err(Errno::INTR) => {}
                Err(error) => return Err(error.into()),
            }
        }
    }

    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}
