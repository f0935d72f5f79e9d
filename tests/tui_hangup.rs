//! The editor losing its terminal or its process: a hang-up (SSH drop, closed window, tmux
//! kill-session), SIGTERM, SIGINT and `kill -9`, each with unsaved edits. The real binary runs on
//! a pseudo-terminal; the recovery file must hold the edits, the exit status must say what
//! happened, and the next start must offer the file.

mod pty;

use std::os::unix::process::ExitStatusExt;
use std::path::{Path, PathBuf};

use pty::{Editor, wait_for_file, wait_until_gone};
use rustix::process::Signal;

/// A folder holding `scene.toml` (the shipped default scene).
fn scene_dir() -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let shipped = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/default.toml");
    std::fs::copy(shipped, dir.path().join("scene.toml")).unwrap();
    let recovery = dir.path().join("scene.recovered.toml");
    (dir, recovery)
}

/// The editor on `scene.toml` in `dir`, its first frame drawn.
fn open_scene(dir: &Path) -> Editor {
    let mut editor = Editor::start(dir, &["scene.toml"]);
    editor.wait_for("camera & scene");
    editor
}

#[test]
fn a_hang_up_writes_the_recovery_file_and_exits_129() {
    let (dir, recovery) = scene_dir();
    let mut editor = open_scene(dir.path());
    editor.add_box("box 3");
    // The autosave has the first edit; the second is newer than its delay when the line drops,
    // so only the hang-up itself can write it.
    wait_for_file(&recovery, "box 3");
    editor.add_box("box 4");
    editor.hang_up();
    let status = editor.wait();
    assert_eq!(status.code(), Some(129), "{status:?} (101 is a panic)");
    let recovered = rastray::scene::load(&recovery).expect("the recovery file is a scene");
    // The scene file itself is untouched.
    let saved = rastray::scene::load(&dir.path().join("scene.toml")).unwrap();
    assert_eq!(recovered.objects.len(), saved.objects.len() + 2);
    assert_eq!(
        recovered.objects.last().unwrap().name.as_deref(),
        Some("box 4")
    );
}

#[test]
fn signals_write_the_recovery_file_restore_the_terminal_and_exit_128_plus_n() {
    for (signal, code) in [(Signal::TERM, 143), (Signal::HUP, 129), (Signal::INT, 130)] {
        let (dir, recovery) = scene_dir();
        let mut editor = open_scene(dir.path());
        editor.add_box("box 3");
        editor.signal(signal);
        let status = editor.wait();
        assert_eq!(status.code(), Some(code), "{signal:?}: {status:?}");
        let recovered = std::fs::read_to_string(&recovery).unwrap();
        assert!(recovered.contains("box 3"), "{signal:?}: {recovered}");
        // The shell gets its screen back, and is told where the edits went.
        let screen = editor.screen();
        assert!(!screen.alternate_screen(), "{signal:?}");
        assert!(!screen.hide_cursor(), "{signal:?}");
        assert_eq!(
            screen.mouse_protocol_mode(),
            vt100::MouseProtocolMode::None,
            "{signal:?}"
        );
        let text = editor.text();
        assert!(
            text.contains("unsaved edits written to scene.recovered.toml"),
            "{signal:?}: {text}"
        );
    }
}

#[test]
fn autosave_outlives_kill_9_and_the_next_start_offers_it() {
    let (dir, recovery) = scene_dir();
    let mut editor = open_scene(dir.path());
    editor.add_box("box 3");
    wait_for_file(&recovery, "box 3");
    editor.kill_9();
    assert_eq!(editor.wait().signal(), Some(9));
    drop(editor);
    let recovered = rastray::scene::load(&recovery).expect("the recovery file is a scene");
    let saved = rastray::scene::load(&dir.path().join("scene.toml")).unwrap();
    assert_eq!(recovered.objects.len(), saved.objects.len() + 1);

    let mut again = open_scene(dir.path());
    again.wait_for("earlier unsaved edits are in scene.recovered.toml (o opens it)");
    again.keys(b"o");
    again.wait_for("scene.recovered.toml");
    again.keys(b"\r");
    again.wait_for("opened scene.recovered.toml");
    again.wait_for("box 3");
    again.keys(b"q");
    assert_eq!(again.wait().code(), Some(0));
    // Quitting without edits leaves the earlier session's file alone.
    assert!(recovery.is_file());
}

#[test]
fn saving_removes_the_recovery_file() {
    let (dir, recovery) = scene_dir();
    let mut editor = open_scene(dir.path());
    editor.add_box("box 3");
    wait_for_file(&recovery, "box 3");
    editor.keys(b"s");
    editor.wait_for("saved scene.toml");
    wait_until_gone(&recovery);
    editor.keys(b"q");
    assert_eq!(editor.wait().code(), Some(0));
    assert!(!recovery.exists());
}

#[test]
fn quitting_and_discarding_removes_the_recovery_file() {
    let (dir, recovery) = scene_dir();
    let mut editor = open_scene(dir.path());
    editor.add_box("box 3");
    wait_for_file(&recovery, "box 3");
    editor.keys(b"q");
    editor.wait_for("unsaved");
    editor.keys(b"y");
    assert_eq!(editor.wait().code(), Some(0));
    assert!(!recovery.exists());
}

#[test]
fn mouse_reports_drags_not_every_motion_and_is_switched_off_on_quit() {
    let dir = tempfile::tempdir().unwrap();
    let mut editor = Editor::start(dir.path(), &[]);
    editor.wait_for("camera & scene");
    let enter = String::from_utf8_lossy(&editor.output).into_owned();
    assert!(enter.contains("\x1b[?1002h"), "{enter:?}");
    assert!(enter.contains("\x1b[?1006h"), "{enter:?}");
    assert!(!enter.contains("\x1b[?1003h"), "{enter:?}");
    assert_eq!(
        editor.screen().mouse_protocol_mode(),
        vt100::MouseProtocolMode::ButtonMotion
    );
    assert_eq!(
        editor.screen().mouse_protocol_encoding(),
        vt100::MouseProtocolEncoding::Sgr
    );
    let entered = editor.output.len();
    editor.keys(b"q");
    assert_eq!(editor.wait().code(), Some(0));
    let leave = String::from_utf8_lossy(&editor.output[entered..]).into_owned();
    for reset in ["\x1b[?1006l", "\x1b[?1002l", "\x1b[?1000l", "\x1b[?1049l"] {
        assert!(leave.contains(reset), "{reset:?} missing from {leave:?}");
    }
    let screen = editor.screen();
    assert_eq!(screen.mouse_protocol_mode(), vt100::MouseProtocolMode::None);
    assert_eq!(
        screen.mouse_protocol_encoding(),
        vt100::MouseProtocolEncoding::Default
    );
    assert!(!screen.alternate_screen());
}
