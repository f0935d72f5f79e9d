//! Real pixels in the editor's preview: the protocol and colour depth chosen from scripted
//! terminal replies, and the kitty picture the editor sends, decoded and compared pixel for
//! pixel with the renderer's image at the size it states.

mod pty;

use std::path::PathBuf;
use std::sync::Arc;

use base64::Engine;
use base64::engine::general_purpose::STANDARD;
use rastray::World;
use rastray::render::{Algorithm, Frame, Progress, RenderOptions, Renderer};
use rastray::scene::default_scene;
use rastray::terminal_image::ColorMode;
use rastray::terminal_image::preview::PreviewImage;
use rastray::terminal_image::{CellSize, GlyphSet, Protocol, kitty};
use rastray::tui::state::app::App;
use rastray::tui::terminal::color_probe::{decide, query};
use rastray::tui::terminal::graphics::{Facts, Graphics, GraphicsRequest, choose};
use rastray::tui::terminal::term_input::{Decoder, Reply, TermInput};
use ratatui::layout::Rect;
use rustix::termios::Winsize;

/// The replies a terminal sends as `bytes`.
fn replies(bytes: &[u8]) -> Vec<Reply> {
    let mut decoder = Decoder::new();
    let mut out = Vec::new();
    decoder.feed(bytes, &mut out);
    decoder.flush(&mut out);
    out.into_iter()
        .filter_map(|i| match i {
            TermInput::Reply(r) => Some(r),
            TermInput::Event(_) => None,
        })
        .collect()
}

/// What a terminal that answered `bytes` gets, with the environment of `facts`.
fn chosen(bytes: &[u8], facts: Facts) -> (Graphics, ColorMode) {
    let facts = Facts {
        replies: replies(bytes),
        ..facts
    };
    (
        choose(GraphicsRequest::Auto, &facts),
        decide(&facts.replies),
    )
}

fn cell(width: u32, height: u32) -> CellSize {
    CellSize { width, height }
}

fn xterm_env() -> Facts {
    Facts {
        term: "xterm-256color".into(),
        winsize: Some((160, 48, 0, 0)),
        ..Facts::default()
    }
}

#[test]
fn kitty_answers_ok_and_gets_kitty_in_truecolor_at_its_cell_size() {
    // kitty 0.26: XTGETTCAP RGB, the graphics query, the cell size, then DA1.
    let answer = b"\x1bP1+r524742=382F382F38\x1b\\\x1b_Gi=31;OK\x1b\\\x1bP>|kitty(0.26.5)\x1b\\\
                   \x1b[6;20;10t\x1b[4;960;1600t\x1b[?62;c";
    let (graphics, color) = chosen(answer, xterm_env());
    assert_eq!(graphics.protocol, Some(Protocol::Kitty));
    assert_eq!(graphics.cell, cell(10, 20));
    assert_eq!(graphics.tmux_pane, None);
    assert_eq!(graphics.label(), "kitty");
    assert_eq!(color, ColorMode::Truecolor);
}

#[test]
fn a_sixel_xterm_gets_sixel_with_the_cell_size_from_its_text_area() {
    // xterm -ti vt340: sixel (4) among the attributes; no CSI 16 t answer, but CSI 14 t.
    let answer = b"\x1bP0+r524742;5463\x1b\\\x1bP1$r0m\x1b\\\x1bP>|XTerm(379)\x1b\\\
                   \x1b[4;960;1440t\x1b[?63;1;2;4;6;9;15;16;22;28c";
    let (graphics, color) = chosen(answer, xterm_env());
    assert_eq!(graphics.protocol, Some(Protocol::Sixel));
    // 1440×960 pixels over 160×48 cells.
    assert_eq!(graphics.cell, cell(9, 20));
    assert_eq!(color, ColorMode::Ansi256);
    let (w, h) = graphics.pixel_size(100, 30).unwrap();
    assert_eq!(h % 6, 0, "whole sixel bands");
    assert!(u64::from(w) * u64::from(h) <= rastray::tui::terminal::graphics::PIXEL_BUDGET);
}

#[test]
fn a_terminal_that_answers_nothing_gets_half_blocks_in_256_colours() {
    let (graphics, color) = chosen(b"", xterm_env());
    assert_eq!(graphics.protocol, None);
    assert_eq!(graphics.why, None);
    assert_eq!(graphics.label(), "half blocks");
    assert_eq!(color, ColorMode::Ansi256);
    // A hint alone does not decide: the query does, and the reason is given.
    let hinted = Facts {
        kitty_window: true,
        ..xterm_env()
    };
    let (graphics, _) = chosen(b"", hinted);
    assert_eq!(graphics.protocol, None);
    assert!(graphics.why.unwrap().contains("did not answer"));
}

#[test]
fn tmux_without_passthrough_gets_half_blocks_and_says_why() {
    // tmux answers DA1 itself; the kitty query never reached the terminal outside.
    let tmux = Facts {
        in_tmux: true,
        tmux_passthrough: Some(false),
        term: "tmux-256color".into(),
        ..xterm_env()
    };
    let (graphics, color) = chosen(b"\x1bP1+r5463\x1b\\\x1b[?1;2c", tmux.clone());
    assert_eq!(graphics.protocol, None);
    assert!(
        graphics
            .why
            .as_deref()
            .unwrap()
            .contains("allow-passthrough"),
        "{:?}",
        graphics.why
    );
    assert_eq!(color, ColorMode::Truecolor, "tmux's Tc capability");
    // Forcing kitty does not help: nothing would reach the terminal.
    let forced = choose(GraphicsRequest::Kitty, &tmux);
    assert_eq!(forced.protocol, None);
    // With passthrough on, the kitty answer through it decides, placed at the pane's offset.
    let allowed = Facts {
        tmux_passthrough: Some(true),
        tmux_pane: (81, 0),
        replies: replies(b"\x1b_Gi=31;OK\x1b\\\x1b[?1;2c"),
        ..tmux
    };
    let graphics = choose(GraphicsRequest::Auto, &allowed);
    assert_eq!(graphics.protocol, Some(Protocol::Kitty));
    assert_eq!(graphics.tmux_pane, Some((81, 0)));
    // The kitty query travels through passthrough there.
    let asked = query(true, true);
    let wrapped = b"\x1bPtmux;\x1b\x1b_Gi=31,";
    assert!(
        asked.windows(wrapped.len()).any(|w| w == wrapped),
        "{asked:?}"
    );
}

#[test]
fn truecolor_answered_by_xtgettcap_alone() {
    let (graphics, color) = chosen(b"\x1bP1+r524742\x1b\\\x1b[?62;22c", xterm_env());
    assert_eq!(color, ColorMode::Truecolor);
    assert_eq!(graphics.protocol, None);
}

#[test]
fn iterm2_names_itself_and_forced_choices_are_kept() {
    let (graphics, _) = chosen(b"\x1bP>|iTerm2 3.5.0\x1b\\\x1b[?62;4c", xterm_env());
    assert_eq!(graphics.protocol, Some(Protocol::Iterm2), "before sixel");
    let silent = xterm_env();
    assert_eq!(
        choose(GraphicsRequest::Sixel, &silent).protocol,
        Some(Protocol::Sixel)
    );
    assert_eq!(
        choose(GraphicsRequest::Cells(GlyphSet::HalfBlock), &silent).protocol,
        None
    );
    // The kernel's pixel fields give the cell size when the terminal does not.
    let kernel = Facts {
        winsize: Some((100, 30, 1000, 600)),
        ..Facts::default()
    };
    assert_eq!(choose(GraphicsRequest::Kitty, &kernel).cell, cell(10, 20));
}

/// Every kitty picture in `output`: its control keys and its decoded PNG.
fn kitty_pictures(output: &[u8]) -> Vec<(String, image::RgbImage)> {
    let text = String::from_utf8_lossy(output);
    let mut pictures = Vec::new();
    let mut current: Option<(String, String)> = None;
    for sequence in text.split("\x1b_G").skip(1) {
        let Some(end) = sequence.find("\x1b\\") else {
            break;
        };
        let body = &sequence[..end];
        let (keys, payload) = body.split_once(';').unwrap_or((body, ""));
        if keys.contains("a=T") {
            current = Some((keys.to_string(), String::new()));
        }
        if let Some((_, data)) = &mut current {
            data.push_str(payload);
        }
        if keys.contains("m=0")
            && let Some((keys, data)) = current.take()
        {
            let png = STANDARD.decode(data).expect("base64");
            let image = image::load_from_memory(&png).expect("a PNG").to_rgb8();
            pictures.push((keys, image));
        }
    }
    pictures
}

/// The value of `key` in kitty control keys such as `a=T,i=1,c=80`.
fn control(keys: &str, key: &str) -> Option<u32> {
    keys.split(',')
        .find_map(|kv| kv.strip_prefix(key)?.strip_prefix('=')?.parse().ok())
}

/// The built-in scene rendered by Phong at `width`×`height` from `camera`, as the editor would.
fn rendered(width: u32, height: u32) -> image::RgbImage {
    let scene = default_scene();
    let world = Arc::new(World::build(&scene, std::path::Path::new(".")).unwrap());
    let mut frame = Frame::default();
    Renderer::new(RenderOptions::new(Algorithm::Phong, width, height))
        .render(&world, &scene.camera, &Progress::new(), &mut frame)
        .unwrap();
    let image = PreviewImage::from_frame(&frame);
    image::RgbImage::from_raw(width, height, image.pixels.as_flattened().to_vec()).unwrap()
}

#[test]
fn the_editor_sends_the_rendered_image_over_kitty_and_deletes_it_on_quit() {
    let dir = tempfile::tempdir().unwrap();
    // 100×30 cells of 10×20 pixels, said by the kernel: no terminal answers here.
    let size = Winsize {
        ws_row: 30,
        ws_col: 100,
        ws_xpixel: 1000,
        ws_ypixel: 600,
    };
    let mut editor = pty::Editor::start_sized(dir.path(), &["--graphics", "kitty"], size);
    editor.read_until(|out| !kitty_pictures(&unwrapped(out)).is_empty());
    editor.wait_for("kitty");
    let (keys, shown) = kitty_pictures(&editor.output).remove(0);
    // The picture fills the preview's cells, at their pixels.
    let app = App::new(default_scene(), None, PathBuf::from("."));
    let picture = rastray::tui::view::layout(Rect::new(0, 0, 100, 30), &app)
        .unwrap()
        .picture;
    assert_eq!(
        control(&keys, "c"),
        Some(u32::from(picture.width)),
        "{keys}"
    );
    assert_eq!(
        control(&keys, "r"),
        Some(u32::from(picture.height)),
        "{keys}"
    );
    // At the pane's pixels (10 × 20 per cell), scaled down with their aspect to the budget.
    let (w, h) = shown.dimensions();
    let graphics = Graphics {
        protocol: Some(Protocol::Kitty),
        cells: GlyphSet::HalfBlock,
        cell: cell(10, 20),
        ..Graphics::default()
    };
    assert_eq!(
        Some((w, h)),
        graphics.pixel_size(picture.width, picture.height)
    );
    let pane_aspect = (10.0 * f32::from(picture.width)) / (20.0 * f32::from(picture.height));
    assert!(
        (w as f32 / h as f32 / pane_aspect - 1.0).abs() < 0.01,
        "{w}x{h}"
    );
    assert!(u64::from(w) * u64::from(h) <= rastray::tui::terminal::graphics::PIXEL_BUDGET);
    if let Ok(out) = std::env::var("RASTRAY_EDITOR_KITTY_PNG") {
        shown.save(out).unwrap();
    }
    assert!(shown == rendered(w, h), "the picture is not the render");
    let id = control(&keys, "i").expect("an image id");

    // Orbit: half blocks while the keys arrive (the picture is deleted), a new picture after.
    editor.keys(b"]]]");
    let before = editor.output.len();
    editor.read_until(|out| kitty_pictures(&out[before..]).len() == 1);
    let after = &editor.output[before..];
    let deleted = kitty::delete(id);
    assert!(
        after.windows(deleted.len()).any(|w| w == deleted),
        "the first picture was not deleted"
    );
    let (_, moved) = kitty_pictures(after).remove(0);
    assert_eq!(moved.dimensions(), (w, h));
    assert!(moved != shown, "the orbit did not change the picture");

    // Quit: every picture is deleted before the alternate screen is left.
    editor.keys(b"q");
    assert!(editor.wait().success());
    let text = String::from_utf8_lossy(&editor.output);
    let cleanup = text
        .rfind("\x1b_Ga=d,d=A,q=2\x1b\\")
        .expect("pictures deleted on quit");
    let leave = text.rfind("\x1b[?1049l").expect("alternate screen left");
    assert!(cleanup < leave);
}

/// The editor on a pty as if inside tmux (`TMUX` set, and a `tmux` on the PATH that reports
/// `allow-passthrough` as `passthrough` and the pane at the top-left), started in `dir`.
fn editor_in_tmux(dir: &std::path::Path, passthrough: &str) -> pty::Editor {
    editor_in_fake_tmux(
        dir,
        &format!("  *allow-passthrough*) echo {passthrough};;\n  *pane_left*) echo 0,0;;\n"),
    )
}

/// The editor on a pty as if inside tmux, with a `tmux` on the PATH that answers as the shell
/// `case` branches `cases` say (matched against its arguments), started in `dir`.
fn editor_in_fake_tmux(dir: &std::path::Path, cases: &str) -> pty::Editor {
    use std::os::unix::fs::PermissionsExt;
    let bin = dir.join("bin");
    std::fs::create_dir_all(&bin).unwrap();
    let fake = bin.join("tmux");
    std::fs::write(&fake, format!("#!/bin/sh\ncase \"$*\" in\n{cases}esac\n")).unwrap();
    std::fs::set_permissions(&fake, std::fs::Permissions::from_mode(0o755)).unwrap();
    let path = format!(
        "{}:{}",
        bin.display(),
        std::env::var("PATH").unwrap_or_default()
    );
    let size = Winsize {
        ws_row: 30,
        ws_col: 100,
        ws_xpixel: 0,
        ws_ypixel: 0,
    };
    pty::Editor::start_env(
        dir,
        &[],
        size,
        &[
            ("TMUX", "/tmp/tmux-0/default,1,0"),
            ("TERM", "tmux-256color"),
            ("PATH", &path),
        ],
    )
}

/// `bytes` with tmux passthrough's doubled escapes made single again.
fn unwrapped(bytes: &[u8]) -> Vec<u8> {
    let mut out = Vec::with_capacity(bytes.len());
    for (i, &b) in bytes.iter().enumerate() {
        if !(b == 0x1b && i > 0 && bytes[i - 1] == 0x1b && out.last() == Some(&0x1b)) {
            out.push(b);
        }
    }
    out
}

fn position(haystack: &[u8], needle: &[u8]) -> Option<usize> {
    haystack.windows(needle.len()).position(|w| w == needle)
}

#[test]
fn in_tmux_with_passthrough_kitty_answering_after_tmux_s_da1_still_gets_pixels() {
    let dir = tempfile::tempdir().unwrap();
    let mut editor = editor_in_tmux(dir.path(), "on");
    editor.read_until(|out| position(out, b"\x1b[c").is_some());
    // The kitty query went through passthrough, never raw (tmux would make it the title).
    let asked = editor.output.clone();
    let raw = b"\x1b_Gi=31";
    let at = position(&asked, raw).expect("the kitty query");
    assert!(
        at > 0 && asked[at - 1] == 0x1b,
        "raw kitty query: {asked:?}"
    );
    // tmux answers at once; kitty's answers come through a moment later.
    editor.keys(b"\x1bP>|tmux 3.3a\x1b\\\x1b[?1;2c");
    std::thread::sleep(std::time::Duration::from_millis(150));
    editor.keys(b"\x1b_Gi=31;OK\x1b\\\x1b[6;19;8t\x1b[4;570;800t");
    editor.read_until(|out| !kitty_pictures(&unwrapped(out)).is_empty());
    editor.wait_for("kitty");
    // The cursor move and the picture travel in one passthrough sequence.
    let out = editor.output.clone();
    let moved = position(&out, b"\x1bPtmux;\x1b\x1b7\x1b\x1b[").expect("a placed picture");
    let rest = &out[moved + 8..];
    let picture = position(rest, b"\x1b\x1b_Ga=T").expect("the picture");
    let next = position(rest, b"\x1bPtmux;").unwrap_or(usize::MAX);
    assert!(picture < next, "the picture left the cursor's passthrough");
    // At the cells' shape: 8×19 pixels.
    let (keys, shown) = kitty_pictures(&unwrapped(&out)).remove(0);
    let (c, r) = (control(&keys, "c").unwrap(), control(&keys, "r").unwrap());
    let aspect = (8.0 * c as f32) / (19.0 * r as f32);
    let (w, h) = shown.dimensions();
    assert!((w as f32 / h as f32 / aspect - 1.0).abs() < 0.02, "{w}x{h}");
    editor.keys(b"q");
    assert!(editor.wait().success());
}

#[test]
fn in_tmux_without_passthrough_nothing_reaches_the_pane_title() {
    let dir = tempfile::tempdir().unwrap();
    let mut editor = editor_in_tmux(dir.path(), "off");
    editor.read_until(|out| position(out, b"\x1b[c").is_some());
    editor.keys(b"\x1bP>|tmux 3.3a\x1b\\\x1b[?1;2c");
    editor.wait_for("allow-passthrough");
    editor.wait_for("half blocks");
    editor.keys(b"q");
    assert!(editor.wait().success());
    // No kitty sequence at all, wrapped or raw: tmux takes a raw one for the title.
    assert_eq!(position(&editor.output, b"_G"), None);
    assert_eq!(position(&editor.output, b"\x1bPtmux;"), None);
}

#[test]
fn without_pixels_auto_draws_sextants_where_xtversion_names_a_terminal_known_to_draw_them() {
    let facts = |version: &[u8]| Facts {
        replies: replies(&[version, b"\x1b[6;19;8t\x1b[?62;22c"].concat()),
        ..xterm_env()
    };
    for name in [
        "kitty(0.26.5)",
        "foot(1.16.2)",
        "WezTerm 20240203",
        "ghostty 1.0",
    ] {
        let version = format!("\x1bP>|{name}\x1b\\");
        let graphics = choose(GraphicsRequest::Cells(GlyphSet::Sextant), &facts(b""));
        assert_eq!(graphics.label(), "sextants");
        let auto = choose(GraphicsRequest::Auto, &facts(version.as_bytes()));
        if auto.protocol.is_none() {
            assert_eq!(auto.cells, GlyphSet::Sextant, "{name}");
            assert_eq!(auto.label(), "sextants");
        }
    }
    let xterm = choose(GraphicsRequest::Auto, &facts(b"\x1bP>|XTerm(379)\x1b\\"));
    assert_eq!(xterm.label(), "half blocks");
    assert_eq!(xterm.cell, cell(8, 19));
    // Cells rendered with square pixels in the cells' shape: 8×19 → 2 across, 4.75 down a cell.
    assert_eq!(xterm.cells_size(40, 20), (40, 48));
    let quadrants = choose(GraphicsRequest::Cells(GlyphSet::Quadrant), &facts(b""));
    assert_eq!(quadrants.cells_size(40, 20), (80, 95));
    assert_eq!(quadrants.label(), "quadrants");
    // Without an answer, 1:2.
    let silent = choose(GraphicsRequest::Cells(GlyphSet::Braille), &xterm_env());
    assert_eq!(silent.cells_size(40, 20), (80, 80));
}

/// tmux (3.3a, passthrough on) answers at once; the kitty outside, named `version` by
/// XTVERSION, answers what passed through a moment later, with cells of 8×19 pixels.
fn answer_as_kitty_in_tmux(editor: &mut pty::Editor, version: &str) {
    editor.read_until(|out| position(out, b"\x1b[c").is_some());
    editor.keys(b"\x1bP>|tmux 3.3a\x1b\\\x1b[?1;2c");
    std::thread::sleep(std::time::Duration::from_millis(150));
    let kitty = format!("\x1b_Gi=31;OK\x1b\\\x1bP>|{version}\x1b\\\x1b[6;19;8t\x1b[4;570;800t");
    editor.keys(kitty.as_bytes());
}

#[test]
fn in_tmux_kitty_0_28_gets_a_virtual_placement_and_unicode_placeholder_cells() {
    use rastray::terminal_image::kitty_placeholder::{self, PLACEHOLDER};
    let dir = tempfile::tempdir().unwrap();
    let mut editor = editor_in_tmux(dir.path(), "on");
    // XTVERSION passes through tmux with the kitty query.
    editor.read_until(|out| position(&unwrapped(out), b"\x1b_Gi=31").is_some());
    let asked = unwrapped(&editor.output);
    let query = position(&asked, b"\x1b_Gi=31").unwrap();
    assert!(
        position(&asked[query..], b"\x1b[>0q").is_some(),
        "XTVERSION in the passthrough"
    );
    answer_as_kitty_in_tmux(&mut editor, "kitty(0.35.2)");
    editor.read_until(|out| !kitty_pictures(&unwrapped(out)).is_empty());
    editor.wait_for("kitty");
    editor.settle(std::time::Duration::from_millis(300));
    let out = unwrapped(&editor.output);
    let (keys, _) = kitty_pictures(&out).remove(0);
    // Sent with a virtual placement only: no cursor move, no placement at the cursor.
    assert!(keys.starts_with("a=T,U=1,f=100,q=2,i="), "{keys}");
    assert_eq!(
        position(&out, b"\x1b7"),
        None,
        "no cursor saved for a placement"
    );
    assert_eq!(position(&out, b"C=1"), None, "no direct placement");
    let id = control(&keys, "i").unwrap();
    let (cols, rows) = (control(&keys, "c").unwrap(), control(&keys, "r").unwrap());
    assert_eq!(id & 0xff, 1, "slot 0's id ends in colour 1");
    let high = (id >> 24) as u8;
    assert!(high >= 1, "the high byte tells editors apart");
    // The preview's cells hold the placeholders: find the top-left one.
    let screen = editor.screen();
    let (w, h) = (100, 30);
    let top_left = (0..h)
        .flat_map(|r| (0..w).map(move |c| (r, c)))
        .find(|&(r, c)| {
            let cell = screen.cell(r, c).unwrap();
            cell.contents().starts_with(PLACEHOLDER)
        })
        .expect("placeholder cells on the screen");
    let (r0, c0) = top_left;
    for (r, c) in [(0, 0), (0, 1), (1, 0), (rows - 1, cols - 1)] {
        let cell = screen.cell(r0 + r as u16, c0 + c as u16).unwrap();
        let expected = kitty_placeholder::cell(r as u16, c as u16, high).unwrap();
        assert_eq!(cell.contents(), expected, "cell ({r}, {c})");
        assert_eq!(cell.fgcolor(), vt100::Color::Idx(1), "cell ({r}, {c})");
    }
    // Row 0, column 1: U+0305 (0) then U+030D (1), as in kitty's documentation.
    let second = screen.cell(r0, c0 + 1).unwrap().contents();
    assert!(second.starts_with("\u{10EEEE}\u{305}\u{30D}"), "{second:?}");
    // The area ends where the placeholders end.
    let after = screen.cell(r0, c0 + cols as u16).unwrap().contents();
    assert!(!after.starts_with(PLACEHOLDER), "{after:?}");
    editor.keys(b"q");
    assert!(editor.wait().success());
    // On quit the image is deleted by id (deleting all leaves virtual placements).
    let out = unwrapped(&editor.output);
    let delete = format!("\x1b_Ga=d,d=I,i={id},q=2\x1b\\");
    assert!(position(&out, delete.as_bytes()).is_some());
}

#[test]
fn in_tmux_older_kitty_draws_cells_while_unfocused_and_deletes_the_picture_on_the_client() {
    let dir = tempfile::tempdir().unwrap();
    let client = dir.path().join("client-tty");
    std::fs::write(&client, b"").unwrap();
    let mut editor = editor_in_fake_tmux(
        dir.path(),
        &format!(
            "  *allow-passthrough*) echo on;;\n  *client_tty*) echo {};;\n  *pane_left*) echo 0,0,1,;;\n",
            client.display()
        ),
    );
    answer_as_kitty_in_tmux(&mut editor, "kitty(0.26.5)");
    editor.read_until(|out| !kitty_pictures(&unwrapped(out)).is_empty());
    editor.wait_for("kitty");
    assert!(
        position(&editor.output, b"\x1b[?1004h").is_some(),
        "focus reports asked for"
    );
    let (keys, _) = kitty_pictures(&unwrapped(&editor.output)).remove(0);
    assert!(keys.contains("C=1"), "placed at the cursor: {keys}");
    let id = control(&keys, "i").unwrap();
    // tmux reports the focus lost (a window switch): the delete goes to the client terminal.
    let before = editor.output.len();
    editor.keys(b"\x1b[O");
    let delete = format!("\x1b_Ga=d,d=I,i={id},q=2\x1b\\");
    let start = std::time::Instant::now();
    while std::fs::read(&client).unwrap() != delete.as_bytes() {
        assert!(
            start.elapsed() < pty::TIMEOUT,
            "no delete on the client terminal"
        );
        editor.settle(std::time::Duration::from_millis(50));
    }
    // The preview is drawn in half blocks meanwhile, and no picture is sent.
    editor.read_until(|out| position(&out[before..], "▀".as_bytes()).is_some());
    editor.settle(std::time::Duration::from_millis(500));
    assert!(kitty_pictures(&unwrapped(&editor.output[before..])).is_empty());
    // The focus back: the picture is placed again through passthrough.
    let before = editor.output.len();
    editor.keys(b"\x1b[I");
    editor.read_until(|out| !kitty_pictures(&unwrapped(&out[before..])).is_empty());
    editor.keys(b"q");
    assert!(editor.wait().success());
    assert!(
        position(&editor.output, b"\x1b[?1004l").is_some(),
        "focus reports off"
    );
}
