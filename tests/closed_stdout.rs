//! Standard output that goes away or fills up: a reader that leaves ends the command quietly, as
//! it ends `cat` (killed by SIGPIPE, no message, no panic); a full device is an `error:` line and
//! exit code 2.

use std::os::unix::process::ExitStatusExt;
use std::path::Path;
use std::process::{Command, Stdio};

fn rastray() -> Command {
    let mut command = Command::new(env!("CARGO_BIN_EXE_rastray"));
    command.current_dir(Path::new(env!("CARGO_MANIFEST_DIR")));
    command
}

/// Runs `args` with standard output a pipe whose reader is closed before anything is written.
fn with_reader_gone(args: &[&str]) -> std::process::Output {
    let mut child = rastray()
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("spawn");
    drop(child.stdout.take());
    child.wait_with_output().expect("output")
}

#[test]
fn info_into_a_closed_pipe_ends_quietly() {
    let o = with_reader_gone(&["info", "scenes/default.toml"]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(stderr.is_empty(), "quiet: {stderr}");
    assert_eq!(
        o.status.signal(),
        Some(13),
        "killed by SIGPIPE: {:?}",
        o.status
    );
}

#[test]
fn render_into_a_closed_pipe_writes_its_image_and_ends_quietly() {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("out.png");
    let o = with_reader_gone(&[
        "render",
        "scenes/default.toml",
        "-s",
        "32x18",
        "-o",
        out.to_str().expect("UTF-8"),
    ]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert_eq!(o.status.signal(), Some(13), "{:?}: {stderr}", o.status);
    assert!(out.exists(), "the image was written before the summary");
}

#[test]
fn info_onto_a_full_device_is_an_error_with_exit_code_2() {
    if !Path::new("/dev/full").exists() {
        return; // Linux only; nothing to test elsewhere.
    }
    let full = std::fs::OpenOptions::new()
        .write(true)
        .open("/dev/full")
        .expect("/dev/full");
    let o = rastray()
        .args(["info", "scenes/default.toml"])
        .stdout(full)
        .output()
        .expect("runs");
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.starts_with("error: cannot write to standard output"),
        "{stderr}"
    );
    assert!(!stderr.contains("panicked"), "{stderr}");
}

#[test]
fn view_into_a_closed_pipe_ends_quietly() {
    let o = with_reader_gone(&["view", "scenes/default.toml", "--width", "20"]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(stderr.is_empty(), "quiet: {stderr}");
    assert_eq!(o.status.signal(), Some(13), "{:?}", o.status);
}
