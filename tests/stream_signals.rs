//! An export that waits on its reader can always be stopped: `-o` naming a FIFO that no process
//! reads, and `-o -` into a pipe whose reader stopped reading, both end on SIGTERM or SIGINT with
//! 128 + the signal's number and a message, within a second.

use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use rustix::process::{Pid, Signal, kill_process};

fn rastray(args: &[&str], stdout: Stdio) -> Child {
    Command::new(env!("CARGO_BIN_EXE_rastray"))
        .args(args)
        .current_dir(Path::new(env!("CARGO_MANIFEST_DIR")))
        .stdout(stdout)
        .stderr(Stdio::piped())
        .spawn()
        .expect("spawn")
}

/// Sends `signal` to `child` once it has had `after` to get stuck, and returns its exit code, its
/// stderr and how long it took to end after the signal.
fn stop(mut child: Child, after: Duration, signal: Signal) -> (Option<i32>, String, Duration) {
    std::thread::sleep(after);
    assert!(child.try_wait().expect("wait").is_none(), "still waiting");
    let pid = Pid::from_child(&child);
    kill_process(pid, signal).expect("kill");
    let sent = Instant::now();
    while child.try_wait().expect("wait").is_none() {
        if sent.elapsed() > Duration::from_secs(10) {
            child.kill().ok();
            panic!("did not end on {signal:?}");
        }
        std::thread::sleep(Duration::from_millis(5));
    }
    let took = sent.elapsed();
    let output = child.wait_with_output().expect("output");
    (
        output.status.code(),
        String::from_utf8_lossy(&output.stderr).into_owned(),
        took,
    )
}

#[test]
fn a_fifo_with_no_reader_ends_on_sigterm() {
    let dir = tempfile::tempdir().expect("tempdir");
    let fifo = dir.path().join("out.png");
    rustix::fs::mkfifoat(
        rustix::fs::CWD,
        &fifo,
        rustix::fs::Mode::from_raw_mode(0o600),
    )
    .expect("fifo");
    let child = rastray(
        &[
            "render",
            "scenes/default.toml",
            "-s",
            "32x18",
            "-o",
            fifo.to_str().unwrap(),
        ],
        Stdio::null(),
    );
    let (code, stderr, took) = stop(child, Duration::from_millis(700), Signal::TERM);
    assert_eq!(code, Some(143), "{stderr}");
    assert!(stderr.contains("stopped by SIGTERM"), "{stderr}");
    assert!(took < Duration::from_secs(1), "took {took:?}");
}

#[test]
fn a_pipe_whose_reader_stopped_reading_ends_on_sigint() {
    // The pipe holds 64 KiB; a 1280×720 PNG of the default scene is larger, so the write waits.
    let child = rastray(
        &["render", "scenes/default.toml", "-s", "1280x720", "-o", "-"],
        Stdio::piped(),
    );
    let (code, stderr, took) = stop(child, Duration::from_millis(2500), Signal::INT);
    assert_eq!(code, Some(130), "{stderr}");
    assert!(stderr.contains("stopped by SIGINT"), "{stderr}");
    assert!(took < Duration::from_secs(1), "took {took:?}");
}
