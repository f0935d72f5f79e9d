//! How the editor meets terminals that cannot host it.

use std::process::Command;

#[test]
fn a_dumb_terminal_gets_a_message_and_exit_code_2_instead_of_the_editor() {
    let out = Command::new(env!("CARGO_BIN_EXE_rastray"))
        .env("TERM", "dumb")
        .output()
        .expect("runs");
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("move the cursor"), "{stderr}");
    assert!(stderr.contains("rastray render"), "{stderr}");
    // Nothing full-screen was started: no alternate screen, no queries on stdout.
    assert!(out.stdout.is_empty(), "{:?}", out.stdout);
}
