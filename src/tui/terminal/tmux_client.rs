//! Writing to the terminal outside tmux directly. tmux passes nothing on from a pane whose window
//! is not shown, so a kitty picture left on the screen by such a pane can only be deleted by
//! writing to the client's terminal (`#{client_tty}`, the kitty window tmux runs in) ourselves.

use std::io::{self, Write};
use std::process::Command;

/// Writes `bytes` in one write to the terminal of the tmux client that shows this pane's
/// session (asked of tmux each time: clients come and go).
pub fn write(bytes: &[u8]) -> io::Result<()> {
    let out = Command::new("tmux")
        .args(["display", "-p", "#{client_tty}"])
        .output()?;
    let path = String::from_utf8_lossy(&out.stdout).trim().to_string();
    if !out.status.success() || path.is_empty() {
        return Err(io::Error::other("tmux named no client terminal"));
    }
    std::fs::OpenOptions::new()
        .append(true)
        .open(&path)?
        .write_all(bytes)
}
