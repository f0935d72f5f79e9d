//! The real editor on a pseudo-terminal, held as a terminal emulator or sshd holds it: keys are
//! typed into the master side, the screen is read back through a terminal emulator (vt100), and
//! hanging up closes the master. The editor leads its own session with the pty as its
//! controlling terminal (util-linux `setsid --ctty`), so a hang-up sends it SIGHUP.

#![allow(dead_code)]

use std::num::NonZeroU16;
use std::os::fd::OwnedFd;
use std::path::Path;
use std::process::{Child, Command, ExitStatus, Stdio};
use std::time::{Duration, Instant};

use rustix::event::{PollFd, PollFlags, poll};
use rustix::fs::{Mode, OFlags};
use rustix::process::{Pid, Signal, kill_process};
use rustix::pty::{OpenptFlags, grantpt, openpt, ptsname, unlockpt};
use rustix::termios::{Winsize, tcsetwinsize};

/// How long any one expected screen, file or exit may take (slow CI machines included).
pub const TIMEOUT: Duration = Duration::from_secs(60);

const ROWS: NonZeroU16 = NonZeroU16::new(40).unwrap();
const COLUMNS: NonZeroU16 = NonZeroU16::new(120).unwrap();

/// The editor running on a pty of 120×40 cells.
pub struct Editor {
    child: Child,
    /// The terminal's side; `None` once hung up.
    master: Option<OwnedFd>,
    screen: vt100::Parser,
    /// Every byte the editor wrote.
    pub output: Vec<u8>,
}

impl Editor {
    /// Starts `rastray ARGS` in `dir`.
    pub fn start(dir: &Path, args: &[&str]) -> Editor {
        let size = Winsize {
            ws_row: ROWS.get(),
            ws_col: COLUMNS.get(),
            ws_xpixel: 0,
            ws_ypixel: 0,
        };
        Editor::start_sized(dir, args, size)
    }

    /// Starts `rastray ARGS` in `dir` on a pty of `size` (cells, and pixels when not 0).
    pub fn start_sized(dir: &Path, args: &[&str], size: Winsize) -> Editor {
        Editor::start_env(dir, args, size, &[])
    }

    /// Starts `rastray ARGS` in `dir` on a pty of `size`, with the environment variables `env`
    /// set beside `TERM=xterm-256color` (a `TERM` among them wins).
    pub fn start_env(dir: &Path, args: &[&str], size: Winsize, env: &[(&str, &str)]) -> Editor {
        let master = openpt(OpenptFlags::RDWR | OpenptFlags::NOCTTY | OpenptFlags::CLOEXEC)
            .expect("open a pty");
        grantpt(&master).expect("grantpt");
        unlockpt(&master).expect("unlockpt");
        let name = ptsname(&master, Vec::new()).expect("ptsname");
        let slave = rustix::fs::open(
            name.as_c_str(),
            OFlags::RDWR | OFlags::NOCTTY | OFlags::CLOEXEC,
            Mode::empty(),
        )
        .expect("open the pty's terminal side");
        tcsetwinsize(&slave, size).expect("set the pty's size");
        // Descriptors are close-on-exec: a hang-up must close the last copy of the master.
        rustix::fs::fcntl_setfl(&master, OFlags::NONBLOCK).expect("non-blocking master");
        let child = Command::new("setsid")
            .arg("--ctty")
            .arg(env!("CARGO_BIN_EXE_rastray"))
            .args(args)
            .current_dir(dir)
            // The terminal is the test's: nothing of the one the tests run in.
            .env_remove("TMUX")
            .env_remove("KITTY_WINDOW_ID")
            .env_remove("COLORTERM")
            .env_remove("TERM_PROGRAM")
            .env("TERM", "xterm-256color")
            .envs(env.iter().copied())
            .stdin(Stdio::from(slave.try_clone().expect("dup")))
            .stdout(Stdio::from(slave.try_clone().expect("dup")))
            .stderr(Stdio::from(slave))
            .spawn()
            .expect("setsid (util-linux) starts the editor");
        Editor {
            child,
            master: Some(master),
            screen: vt100::Parser::new(
                NonZeroU16::new(size.ws_row).unwrap_or(ROWS),
                NonZeroU16::new(size.ws_col).unwrap_or(COLUMNS),
                0,
            ),
            output: Vec::new(),
        }
    }

    /// Reads what the editor wrote within `wait`; false once the terminal side is closed.
    fn pump(&mut self, wait: Duration) -> bool {
        let Some(master) = &self.master else {
            std::thread::sleep(wait);
            return false;
        };
        let timeout = rustix::event::Timespec {
            tv_sec: 0,
            tv_nsec: wait.subsec_nanos().into(),
        };
        let mut fds = [PollFd::new(master, PollFlags::IN)];
        if poll(&mut fds, Some(&timeout)).unwrap_or(0) == 0 {
            return true;
        }
        let mut buf = [0u8; 65536];
        loop {
            match rustix::io::read(master, &mut buf) {
                Ok(0) => return false,
                Ok(n) => {
                    self.screen.process(&buf[..n]);
                    self.output.extend_from_slice(&buf[..n]);
                }
                Err(rustix::io::Errno::AGAIN) => return true,
                // EIO: every terminal-side descriptor is closed (the editor exited).
                Err(_) => return false,
            }
        }
    }

    /// The screen's text.
    pub fn text(&self) -> String {
        self.screen.screen().contents()
    }

    /// The emulated terminal's state (modes, cursor).
    pub fn screen(&self) -> &vt100::Screen {
        self.screen.screen()
    }

    /// Reads until the screen shows `needle`; panics with the screen on timeout.
    pub fn wait_for(&mut self, needle: &str) -> String {
        let start = Instant::now();
        loop {
            self.pump(Duration::from_millis(50));
            let text = self.text();
            if text.contains(needle) {
                return text;
            }
            assert!(
                start.elapsed() < TIMEOUT,
                "`{needle}` did not appear within {TIMEOUT:?}; the screen was:\n{text}"
            );
        }
    }

    /// Reads until everything the editor wrote satisfies `done`; panics on timeout.
    pub fn read_until(&mut self, done: impl Fn(&[u8]) -> bool) {
        let start = Instant::now();
        while !done(&self.output) {
            self.pump(Duration::from_millis(50));
            assert!(
                start.elapsed() < TIMEOUT,
                "the editor's output did not arrive within {TIMEOUT:?}"
            );
        }
    }

    /// Reads whatever arrives within `wait`.
    pub fn settle(&mut self, wait: Duration) {
        let start = Instant::now();
        while start.elapsed() < wait && self.pump(Duration::from_millis(20)) {}
    }

    /// Types `bytes` as keys.
    pub fn keys(&mut self, bytes: &[u8]) {
        let master = self.master.as_ref().expect("the terminal is open");
        let mut rest = bytes;
        while !rest.is_empty() {
            match rustix::io::write(master, rest) {
                Ok(n) => rest = &rest[n..],
                Err(rustix::io::Errno::AGAIN) => std::thread::sleep(Duration::from_millis(5)),
                Err(e) => panic!("typing into the pty: {e}"),
            }
        }
    }

    /// Adds a box through the add menu (`a`, `b`) and waits for the status line to confirm it.
    pub fn add_box(&mut self, name: &str) {
        self.keys(b"ab");
        self.wait_for(&format!("added {name}"));
    }

    /// Closes the terminal, as a dropped SSH connection or a closed window does.
    pub fn hang_up(&mut self) {
        self.master = None;
    }

    /// Sends `signal` to the editor.
    pub fn signal(&self, signal: Signal) {
        kill_process(Pid::from_child(&self.child), signal).expect("signal the editor");
    }

    /// Kills the editor with SIGKILL, which it cannot catch.
    pub fn kill_9(&mut self) {
        self.child.kill().expect("kill -9");
    }

    /// Waits for the editor to exit, reading its output meanwhile.
    pub fn wait(&mut self) -> ExitStatus {
        let start = Instant::now();
        loop {
            if let Some(status) = self.child.try_wait().expect("wait for the editor") {
                while self.pump(Duration::from_millis(10)) {}
                return status;
            }
            assert!(
                start.elapsed() < TIMEOUT,
                "the editor did not exit within {TIMEOUT:?}; the screen was:\n{}",
                self.text()
            );
            self.pump(Duration::from_millis(20));
        }
    }
}

impl Drop for Editor {
    fn drop(&mut self) {
        if self.child.try_wait().ok().flatten().is_none() {
            let _ = self.child.kill();
            let _ = self.child.wait();
        }
    }
}

/// Polls until `path` holds text containing `needle`; returns the text.
pub fn wait_for_file(path: &Path, needle: &str) -> String {
    let start = Instant::now();
    loop {
        if let Ok(text) = std::fs::read_to_string(path)
            && text.contains(needle)
        {
            return text;
        }
        assert!(
            start.elapsed() < TIMEOUT,
            "{} did not come to hold `{needle}` within {TIMEOUT:?}",
            path.display()
        );
        std::thread::sleep(Duration::from_millis(50));
    }
}

/// Polls until `path` is gone.
pub fn wait_until_gone(path: &Path) {
    let start = Instant::now();
    while path.exists() {
        assert!(
            start.elapsed() < TIMEOUT,
            "{} was still there after {TIMEOUT:?}",
            path.display()
        );
        std::thread::sleep(Duration::from_millis(50));
    }
}
