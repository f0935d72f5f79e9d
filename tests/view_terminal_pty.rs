//! `rastray view` asks the terminal it prints to: scripted replies on a pseudo-terminal give it
//! the cell size (the picture's rows follow the cells' shape), the text area (a sixel picture
//! never exceeds it) and truecolor; a silent terminal gets 256 colours, and `TERM=dumb` the
//! plain ramp with no escapes.

mod pty;

use std::path::Path;

use pty::Editor;
use rustix::termios::Winsize;

fn contains(haystack: &[u8], needle: &[u8]) -> bool {
    haystack.windows(needle.len()).any(|w| w == needle)
}

/// `rastray view` of the default scene on a 100×30 pty, answering its questions with `reply`
/// (nothing when `None`); returns everything it wrote after its questions.
fn view(dir: &Path, args: &[&str], reply: Option<&[u8]>, env: &[(&str, &str)]) -> Vec<u8> {
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/default.toml");
    let mut all = vec!["view", scene.to_str().unwrap()];
    all.extend(args);
    let size = Winsize {
        ws_row: 30,
        ws_col: 100,
        ws_xpixel: 0,
        ws_ypixel: 0,
    };
    let mut view = Editor::start_env(dir, &all, size, env);
    if let Some(reply) = reply {
        view.read_until(|out| contains(out, b"\x1b[c"));
        view.keys(reply);
    }
    assert!(view.wait().success(), "{}", view.text());
    let output = &view.output;
    let start = output
        .windows(3)
        .position(|w| w == b"\x1b[c")
        .map_or(0, |i| i + 3);
    output[start..].to_vec()
}

/// Lines of text cells: rows of the picture.
fn cell_rows(output: &[u8]) -> usize {
    String::from_utf8_lossy(output)
        .split("\r\n")
        .filter(|line| line.contains("\x1b[0m"))
        .count()
}

const NO_COLORTERM: &[(&str, &str)] = &[("COLORTERM", "")];

#[test]
fn the_cell_size_answered_gives_the_picture_its_aspect() {
    let dir = tempfile::tempdir().unwrap();
    // 40 columns of 16:9: 8×19-pixel cells give 320×180 pixels, 9.5 rows → 9 (10×20: 11).
    let answer = b"\x1b[6;19;8t\x1b[4;570;800t\x1b[?62;22c";
    let out = view(
        dir.path(),
        &["--width", "40", "--graphics", "sextant"],
        Some(answer),
        NO_COLORTERM,
    );
    assert_eq!(cell_rows(&out), 9, "{}", String::from_utf8_lossy(&out));
    let silent = view(
        dir.path(),
        &["--width", "40", "--graphics", "sextant"],
        Some(b"\x1b[?62;22c"),
        NO_COLORTERM,
    );
    assert_eq!(cell_rows(&silent), 11);
}

#[test]
fn truecolor_where_the_terminal_answers_for_it_else_256_colours() {
    let dir = tempfile::tempdir().unwrap();
    let args = ["--width", "30", "--graphics", "halfblock"];
    let truecolor = view(
        dir.path(),
        &args,
        Some(b"\x1bP1+r524742=382F382F38\x1b\\\x1b[?62;22c"),
        NO_COLORTERM,
    );
    assert!(contains(&truecolor, b"48;2;"), "truecolor escapes");
    let refused = view(
        dir.path(),
        &args,
        Some(b"\x1bP0+r524742\x1b\\\x1b[?62;22c"),
        NO_COLORTERM,
    );
    assert!(contains(&refused, b"48;5;") && !contains(&refused, b"48;2;"));
}

#[test]
fn auto_picks_kitty_on_its_answer_and_sextants_by_xtversion() {
    let dir = tempfile::tempdir().unwrap();
    let kitty = view(
        dir.path(),
        &["--width", "30"],
        Some(b"\x1b_Gi=31;OK\x1b\\\x1bP>|kitty(0.26.5)\x1b\\\x1b[6;19;8t\x1b[?62;c"),
        NO_COLORTERM,
    );
    assert!(contains(&kitty, b"\x1b_Ga=T,f=100"), "a kitty picture");
    // A terminal named foot without sixel: the sharpest cells it draws, sextants.
    let foot = view(
        dir.path(),
        &["--width", "30"],
        Some(b"\x1bP>|foot(1.16.2)\x1b\\\x1b[?62;22c"),
        NO_COLORTERM,
    );
    let text = String::from_utf8_lossy(&foot);
    assert!(
        text.chars()
            .any(|c| ('\u{1FB00}'..='\u{1FB3B}').contains(&c)),
        "{text}"
    );
}

#[test]
fn a_sixel_picture_never_exceeds_the_window() {
    let dir = tempfile::tempdir().unwrap();
    // 8-pixel cells: 60 columns would be 480 pixels, but the text area is 320 wide.
    let answer = b"\x1b[6;19;8t\x1b[4;570;320t\x1b[?63;1;2;4;6c";
    let out = view(
        dir.path(),
        &["--width", "60", "--graphics", "sixel"],
        Some(answer),
        NO_COLORTERM,
    );
    let text = String::from_utf8_lossy(&out);
    let raster = text
        .split("\"1;1;")
        .nth(1)
        .expect("sixel raster attributes");
    let mut size = raster.split(|c: char| !c.is_ascii_digit());
    let width: u32 = size.next().unwrap().parse().unwrap();
    let height: u32 = size.next().unwrap().parse().unwrap();
    assert_eq!(width, 320);
    assert!(
        (width as f32 / height as f32 - 16.0 / 9.0).abs() < 0.05,
        "{width}x{height}"
    );
}

#[test]
fn term_dumb_prints_the_plain_ramp_without_asking() {
    let dir = tempfile::tempdir().unwrap();
    let out = view(
        dir.path(),
        &["--width", "30"],
        None,
        &[("TERM", "dumb"), ("COLORTERM", "")],
    );
    assert!(!out.contains(&0x1b), "{}", String::from_utf8_lossy(&out));
    assert!(out.len() > 30 * 5);
}
