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
use rastray::terminal_image::{CellSize, Protocol, kitty};
use rastray::tui::ColorMode;
use rastray::tui::app::App;
use rastray::tui::color_probe::{decide, query};
use rastray::tui::graphics::{Facts, Graphics, GraphicsRequest, choose};
use rastray::tui::preview::PreviewImage;
use rastray::tui::term_input::{Decoder, Reply, TermInput};
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
    assert!(u64::from(w) * u64::from(h) <= rastray::tui::graphics::PIXEL_BUDGET);
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
    let asked = query(true);
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
    assert_eq!(choose(GraphicsRequest::HalfBlock, &silent).protocol, None);
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
    editor.read_until(|out| !kitty_pictures(out).is_empty());
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
        cell: cell(10, 20),
        tmux_pane: None,
        why: None,
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
    assert!(u64::from(w) * u64::from(h) <= rastray::tui::graphics::PIXEL_BUDGET);
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
