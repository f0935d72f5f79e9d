//! `rastray view --spin` on a real terminal (a pseudo-terminal): frames drawn in place until a
//! key or Ctrl-C, and the terminal left as it was (cursor shown, keyboard cooked).

mod pty;

use std::path::Path;

use pty::Editor;
use rustix::process::Signal;

/// Bytes that bring the cursor back to the picture's corner before each frame.
const BACK_TO_CORNER: &[u8] = b"\x1b8";

fn count(haystack: &[u8], needle: &[u8]) -> usize {
    haystack
        .windows(needle.len())
        .filter(|w| *w == needle)
        .count()
}

fn spin(dir: &Path, extra: &[&str]) -> Editor {
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/default.toml");
    let mut args = vec![
        "view",
        scene.to_str().unwrap(),
        "--spin",
        "--frames",
        "8",
        "--graphics",
        "halfblock",
        "--width",
        "30",
    ];
    args.extend(extra);
    Editor::start(dir, &args)
}

/// The terminal after the run: the cursor shown again after it was hidden.
fn left_clean(editor: &Editor) {
    let output = &editor.output;
    let hidden = output.windows(6).rposition(|w| w == b"\x1b[?25l");
    let shown = output.windows(6).rposition(|w| w == b"\x1b[?25h");
    assert!(hidden.is_some(), "the cursor was never hidden");
    assert!(shown > hidden, "the cursor is left hidden");
    assert!(!editor.screen().hide_cursor());
}

#[test]
fn a_key_stops_the_turntable_and_the_terminal_is_restored() {
    let dir = tempfile::tempdir().unwrap();
    // A key ends it with success; Ctrl-C (a key on the raw terminal) as SIGINT would: 130.
    for (key, code) in [(&b"x"[..], 0), (b"\x03", 130)] {
        let mut editor = spin(dir.path(), &[]);
        // Several frames drawn in place, over the first.
        editor.read_until(|out| count(out, BACK_TO_CORNER) >= 3);
        editor.keys(key);
        let status = editor.wait();
        assert_eq!(status.code(), Some(code), "{status:?} after {key:?}");
        left_clean(&editor);
    }
}

#[test]
fn a_signal_stops_the_turntable_with_its_exit_code_and_the_terminal_is_restored() {
    let dir = tempfile::tempdir().unwrap();
    for (signal, code) in [(Signal::TERM, 143), (Signal::INT, 130)] {
        let mut editor = spin(dir.path(), &[]);
        editor.read_until(|out| count(out, BACK_TO_CORNER) >= 3);
        editor.signal(signal);
        let status = editor.wait();
        assert_eq!(status.code(), Some(code), "{status:?} after {signal:?}");
        left_clean(&editor);
    }
}

#[test]
fn loops_end_the_turntable_on_their_own() {
    let dir = tempfile::tempdir().unwrap();
    let mut editor = spin(dir.path(), &["--loops", "2"]);
    let status = editor.wait();
    assert!(status.success(), "{status:?}");
    // Sixteen frames, each drawn from the picture's corner, and once more on the way out to
    // leave the cursor below the picture.
    assert_eq!(count(&editor.output, BACK_TO_CORNER), 16 + 1);
    left_clean(&editor);
}

#[test]
fn on_a_kitty_terminal_each_frame_replaces_the_last_as_one_image() {
    let dir = tempfile::tempdir().unwrap();
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/default.toml");
    let mut args = vec!["view", scene.to_str().unwrap()];
    args.extend("--spin --frames 4 --loops 1 --graphics kitty --width 20".split(' '));
    let mut editor = Editor::start(dir.path(), &args);
    assert!(editor.wait().success());
    // Four pictures, all transmitted as the same image id (each replaces the last).
    let text = String::from_utf8_lossy(&editor.output).into_owned();
    assert_eq!(text.matches("a=T").count(), 4);
    let ids: std::collections::BTreeSet<&str> = text
        .split("a=T,")
        .skip(1)
        .map(|s| s.split(',').find(|f| f.starts_with("i=")).expect("an id"))
        .collect();
    assert_eq!(ids.len(), 1, "{ids:?}");
    left_clean(&editor);
}
