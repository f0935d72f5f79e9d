//! Text from files never reaches the terminal raw: names, paths and error messages that quote
//! a scene print their control characters escaped (`\u{1b}`, `\u{7}`, `\n`), so a name such as
//! `"\u001b]0;pwned\u0007"` cannot retitle the window or write the clipboard. The editor drops
//! them instead (tests/tui_view.rs).

use std::path::Path;
use std::process::{Command, Output};

fn rastray(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_rastray"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("runs")
}

/// Writes `scene` as `s.toml` in a fresh folder and runs `rastray info` on it.
fn info(scene: &str) -> (Output, tempfile::TempDir) {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("s.toml"), scene).unwrap();
    (rastray(dir.path(), &["info", "s.toml"]), dir)
}

/// No control character but the line feeds that end lines.
fn assert_no_controls(text: &[u8]) {
    let text = String::from_utf8_lossy(text);
    let raw: Vec<char> = text
        .chars()
        .filter(|&c| c.is_control() && c != '\n')
        .collect();
    assert!(raw.is_empty(), "raw controls {raw:?} in:\n{text}");
}

const PWNED: &str = r#"\u001b]0;pwned\u0007"#;

#[test]
fn info_escapes_object_and_light_names() {
    let (o, _dir) = info(&format!(
        "[[light]]\nname = \"{PWNED}\"\nposition = [1.0, 2.0, 3.0]\n\
         [[object]]\ntype = \"box\"\nname = \"{PWNED}\\r\\nfake line\"\nsize = [1.0, 1.0, 1.0]\n"
    ));
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_no_controls(&o.stdout);
    assert_no_controls(&o.stderr);
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(out.contains(r"\u{1b}]0;pwned\u{7}\r\nfake line"), "{out}");
    assert_eq!(out.matches(r"\u{1b}]0;pwned\u{7}").count(), 2, "{out}");
}

#[test]
fn info_escapes_the_scene_path() {
    let dir = tempfile::tempdir().unwrap();
    let name = "a\u{1b}[2Jb.toml";
    std::fs::write(dir.path().join(name), "").unwrap();
    let o = rastray(dir.path(), &["info", name]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_no_controls(&o.stdout);
    assert!(String::from_utf8_lossy(&o.stdout).contains(r"a\u{1b}[2Jb.toml"));
}

/// Runs `info` on `scene`, which must be refused, and returns the message.
fn refused(scene: &str) -> String {
    let (o, _dir) = info(scene);
    assert_eq!(o.status.code(), Some(2), "refused");
    assert_no_controls(&o.stderr);
    String::from_utf8_lossy(&o.stderr).into_owned()
}

#[test]
fn error_messages_escape_what_they_quote() {
    // An unknown type.
    let m = refused(&format!("[[object]]\ntype = \"{PWNED}\"\n"));
    assert!(m.contains(r"\u{1b}]0;pwned\u{7}"), "{m}");
    // An unknown key.
    let m = refused(&format!(
        "[[object]]\ntype = \"box\"\nsize = [1.0, 1.0, 1.0]\n\"{PWNED}\" = 1\n"
    ));
    assert!(m.contains(r"\u{1b}]0;pwned\u{7}"), "{m}");
    // A mesh path that does not exist.
    let m = refused(&format!(
        "[[object]]\ntype = \"mesh\"\npath = \"{PWNED}.obj\"\n"
    ));
    assert!(m.contains(r"\u{1b}]0;pwned\u{7}.obj"), "{m}");
    // A raw escape in the file: a TOML error, whose message quotes the line.
    let m = refused("[camera]\nfov = 45 # \u{1b}]0;pwned\u{7}\n");
    assert!(m.contains("s.toml:2"), "{m}");
    assert!(m.contains(r"\u{1b}]0;pwned\u{7}"), "{m}");
    // A warning names the object.
    let (o, _dir) = info(&format!(
        "[[object]]\ntype = \"box\"\nname = \"{PWNED}\"\nsize = [1.0, 1.0, 1.0]\n"
    ));
    assert!(o.status.success());
    assert_no_controls(&o.stderr);
}

#[test]
fn an_obj_error_escapes_its_path() {
    let dir = tempfile::tempdir().unwrap();
    let model = "m\u{1b}]0;x\u{7}.obj";
    std::fs::write(dir.path().join(model), "v 0 0 0\nf 1 2 3\n").unwrap();
    std::fs::write(
        dir.path().join("s.toml"),
        r#"[[object]]
type = "mesh"
path = "m\u001b]0;x\u0007.obj"
"#,
    )
    .unwrap();
    let o = rastray(dir.path(), &["info", "s.toml"]);
    assert_eq!(o.status.code(), Some(2));
    assert_no_controls(&o.stderr);
    let m = String::from_utf8_lossy(&o.stderr);
    assert!(m.contains(r"m\u{1b}]0;x\u{7}.obj:2"), "{m}");
}
