//! The editor behind a slow link, as over SSH: it runs on a pty whose output is read at once
//! into an unbounded buffer (as sshd does, into its channel window), and that buffer drains to
//! a "terminal" at a fixed byte rate. The terminal answers cursor-position queries when they
//! reach it, after everything written before them, as a real terminal does.
//!
//! Shared by the slow-link test and the `slow_link` benchmark; each uses part of it.
#![allow(dead_code)]

use std::collections::VecDeque;
use std::os::fd::OwnedFd;
use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use rustix::event::{PollFd, PollFlags, poll};
use rustix::fs::{Mode, OFlags};
use rustix::pty::{OpenptFlags, grantpt, openpt, ptsname, unlockpt};
use rustix::termios::{Winsize, tcsetwinsize};

/// The pacing query the editor writes after each frame, and the answer the terminal gives.
const QUERY: &[u8] = b"\x1b[6n";
const ANSWER: &[u8] = b"\x1b[1;1R";

/// One frame as the terminal received it: the bytes up to and including its query.
#[derive(Debug, Clone)]
pub struct Frame {
    /// When the frame's last byte reached the terminal.
    pub shown_at: Instant,
    pub bytes: Vec<u8>,
}

impl Frame {
    /// Whether the frame draws any cell in the 256-colour palette (a cheap motion frame).
    pub fn has_palette_colours(&self) -> bool {
        let b = &self.bytes;
        b.windows(5).any(|w| w == b"38;5;" || w == b"48;5;")
    }
}

/// The editor on a pty behind a link of `rate` bytes per second.
pub struct SlowLink {
    child: Child,
    master: OwnedFd,
    rate: f64,
    /// Read from the editor, not yet through the link.
    queue: VecDeque<u8>,
    /// When the link may send its next byte.
    credit: Instant,
    /// What reached the terminal since the last query.
    partial: Vec<u8>,
    /// Frames that reached the terminal, in order.
    pub frames: Vec<Frame>,
    /// Queries read from the editor that the terminal has not answered yet.
    unanswered: usize,
    /// Bytes the editor wrote while one of its queries was unanswered: a frame in flight.
    pub written_in_flight: usize,
    /// When the editor last wrote anything.
    pub last_write: Instant,
}

impl SlowLink {
    /// Starts `rastray ARGS` in `dir` on a `columns`×`rows` truecolor terminal behind the link.
    pub fn start(dir: &Path, args: &[&str], columns: u16, rows: u16, rate: f64) -> SlowLink {
        let master = openpt(OpenptFlags::RDWR | OpenptFlags::NOCTTY).expect("open a pty");
        grantpt(&master).expect("grantpt");
        unlockpt(&master).expect("unlockpt");
        let name = ptsname(&master, Vec::new()).expect("ptsname");
        let slave = rustix::fs::open(
            name.as_c_str(),
            OFlags::RDWR | OFlags::NOCTTY,
            Mode::empty(),
        )
        .expect("open the pty's terminal side");
        let size = Winsize {
            ws_row: rows,
            ws_col: columns,
            ws_xpixel: 0,
            ws_ypixel: 0,
        };
        tcsetwinsize(&slave, size).expect("set the pty's size");
        rustix::fs::fcntl_setfl(&master, OFlags::NONBLOCK).expect("non-blocking master");
        let child = Command::new(env!("CARGO_BIN_EXE_rastray"))
            .args(args)
            .current_dir(dir)
            .env("TERM", "xterm-256color")
            .env("COLORTERM", "truecolor")
            .stdin(Stdio::from(slave.try_clone().expect("dup")))
            .stdout(Stdio::from(slave.try_clone().expect("dup")))
            .stderr(Stdio::from(slave))
            .spawn()
            .expect("start the editor");
        let now = Instant::now();
        SlowLink {
            child,
            master,
            rate,
            queue: VecDeque::new(),
            credit: now,
            partial: Vec::new(),
            frames: Vec::new(),
            unanswered: 0,
            written_in_flight: 0,
            last_write: now,
        }
    }

    /// Types `bytes` as keys.
    pub fn keys(&mut self, bytes: &[u8]) {
        rustix::io::write(&self.master, bytes).expect("type into the pty");
    }

    /// Runs the link for `duration`.
    pub fn run_for(&mut self, duration: Duration) {
        let end = Instant::now() + duration;
        while Instant::now() < end {
            self.step();
        }
    }

    /// Runs the link until the editor has written nothing for `quiet` and everything it wrote
    /// has reached the terminal, or until `limit`; returns whether it went quiet.
    pub fn run_until_quiet(&mut self, quiet: Duration, limit: Duration) -> bool {
        let end = Instant::now() + limit;
        while Instant::now() < end {
            self.step();
            if self.queue.is_empty() && self.last_write.elapsed() >= quiet {
                return true;
            }
        }
        false
    }

    /// Lets the first screen settle, types `keys` orbit keys `gap` apart, lets the editor go
    /// quiet again, and gives the frames drawn since the first screen.
    pub fn orbit_burst(&mut self, keys: usize, gap: Duration) -> Vec<Frame> {
        let (quiet, limit) = (Duration::from_millis(800), Duration::from_secs(60));
        assert!(self.run_until_quiet(quiet, limit), "no first screen");
        let before = self.frames.len();
        for _ in 0..keys {
            self.keys(b"]");
            self.run_for(gap);
        }
        assert!(self.run_until_quiet(quiet, limit), "no quiet after keys");
        self.frames[before..].to_vec()
    }

    /// Bytes that reached the terminal so far.
    pub fn shown(&self) -> usize {
        self.frames.iter().map(|f| f.bytes.len()).sum::<usize>() + self.partial.len()
    }

    /// One tick: read what the editor wrote, move what the rate allows through the link, answer
    /// the queries that arrived.
    fn step(&mut self) {
        let mut fds = [PollFd::new(&self.master, PollFlags::IN)];
        let timeout = rustix::event::Timespec {
            tv_sec: 0,
            tv_nsec: 1_000_000,
        };
        if poll(&mut fds, Some(&timeout)).unwrap_or(0) > 0 {
            let mut buf = [0u8; 65536];
            while let Ok(n @ 1..) = rustix::io::read(&self.master, &mut buf) {
                let fresh = &buf[..n];
                if self.unanswered > 0 {
                    // Only a query's own bytes may follow an unanswered query.
                    self.written_in_flight += fresh.len() - count(fresh, QUERY) * QUERY.len();
                }
                self.unanswered += count(fresh, QUERY);
                self.queue.extend(fresh);
                self.last_write = Instant::now();
            }
        }
        let now = Instant::now();
        if self.queue.is_empty() {
            // An idle link saves no credit.
            self.credit = now;
            return;
        }
        let allowed = (now.duration_since(self.credit).as_secs_f64() * self.rate) as usize;
        let n = allowed.min(self.queue.len());
        if n == 0 {
            return;
        }
        self.credit += Duration::from_secs_f64(n as f64 / self.rate);
        for byte in self.queue.drain(..n) {
            self.partial.push(byte);
            if self.partial.ends_with(QUERY) {
                self.frames.push(Frame {
                    shown_at: now,
                    bytes: std::mem::take(&mut self.partial),
                });
                self.unanswered = self.unanswered.saturating_sub(1);
                rustix::io::write(&self.master, ANSWER).expect("answer the query");
            }
        }
    }

    /// Types `q` and waits for the editor to exit; its exit code.
    pub fn quit(mut self) -> Option<i32> {
        self.keys(b"q");
        let end = Instant::now() + Duration::from_secs(30);
        while Instant::now() < end {
            self.step();
            if let Some(status) = self.child.try_wait().expect("wait for the editor") {
                return status.code();
            }
        }
        None
    }
}

impl Drop for SlowLink {
    fn drop(&mut self) {
        if self.child.try_wait().ok().flatten().is_none() {
            let _ = self.child.kill();
            let _ = self.child.wait();
        }
    }
}

fn count(haystack: &[u8], needle: &[u8]) -> usize {
    haystack
        .windows(needle.len())
        .filter(|w| *w == needle)
        .count()
}
