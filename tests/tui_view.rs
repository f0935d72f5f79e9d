//! Screens drawn with ratatui's TestBackend: insta snapshots of the layout and overlays at several
//! terminal sizes, and the cell colours checked through the buffer (snapshots hold no colours).

use std::path::PathBuf;
use std::sync::Arc;

use glam::Vec3;
use rastray::World;
use rastray::render::{Algorithm, Frame, Progress, RenderOptions, Renderer};
use rastray::scene::default_scene;
use rastray::terminal_image::preview::{ColorMode, PreviewImage, halves_match, nearest_256};
use rastray::terminal_image::{CellSize, Protocol};
use rastray::tui::input::action::Action;
use rastray::tui::input::keys::KEYS;
use rastray::tui::input::map_too_small;
use rastray::tui::state::app::App;
use rastray::tui::state::selection::{Focus, Item};
use rastray::tui::terminal::graphics::Graphics;
use rastray::tui::update::apply;
use rastray::tui::view::{Picture, layout};
use rastray::tui::worker::{RenderReply, Slot};
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use ratatui::buffer::Buffer;
use ratatui::crossterm::event::{Event, KeyCode, KeyEvent, KeyModifiers};
use ratatui::layout::Rect;
use ratatui::style::Color;
use ratatui::widgets::Widget;

/// A synthetic picture: left half bright, right half dark, so snapshots do not depend on the
/// renderers; its upper and lower pixels differ on odd rows to exercise both cell kinds.
fn stripes(width: u32, height: u32) -> PreviewImage {
    let pixels = (0..height)
        .flat_map(|y| (0..width).map(move |x| (x, y)))
        .map(|(x, y)| match (x < width / 2, y % 2 == 0) {
            (true, _) => [200, 60, 40],
            (false, true) => [20, 30, 40],
            (false, false) => [90, 90, 90],
        })
        .collect();
    PreviewImage {
        width,
        height,
        pixels,
    }
}

fn app() -> App {
    App::new(default_scene(), None, PathBuf::from(".")).with_timings(false)
}

fn draw(app: &App, width: u16, height: u16) -> Terminal<TestBackend> {
    let mut terminal = Terminal::new(TestBackend::new(width, height)).unwrap();
    terminal.draw(|f| f.render_widget(app, f.area())).unwrap();
    terminal
}

/// Every cell's symbol, row after row.
fn screen_text(terminal: &Terminal<TestBackend>) -> String {
    terminal
        .backend()
        .buffer()
        .content()
        .iter()
        .map(|c| c.symbol())
        .collect()
}

/// A frame of a 112-triangle world from the render worker, for `slot`.
fn frame(slot: Slot, cells: Rect) -> Action {
    Action::Rendered(Box::new(RenderReply::Shot {
        id: 1,
        slot,
        image: stripes(cells.width as u32, 2 * cells.height as u32),
        millis: 1.0,
        triangles: 112,
        last: true,
    }))
}

/// Gives the app previews of the sizes its layout asks for.
fn fill_previews(app: &mut App, width: u16, height: u16) {
    let areas = layout(Rect::new(0, 0, width, height), app).unwrap();
    let p = areas.picture;
    apply(app, frame(Slot::Main, p));
    for (i, (_, _, image)) in rastray::tui::view::compare_panes(p).into_iter().enumerate() {
        apply(app, frame(Slot::Compare(i), image));
    }
}

/// Presses Tab until `focus` has the keys.
fn focus(app: &mut App, focus: Focus) {
    while app.focus() != focus {
        apply(app, Action::FocusNext);
    }
}

#[test]
fn main_layout() {
    let mut app = app();
    fill_previews(&mut app, 100, 30);
    insta::assert_snapshot!(draw(&app, 100, 30).backend());
}

#[test]
fn properties_of_an_object_while_typing_a_bad_value() {
    let mut app = app();
    fill_previews(&mut app, 100, 30);
    while app.item() != Item::Object(1) {
        apply(&mut app, Action::Down);
    }
    focus(&mut app, Focus::Properties);
    for _ in 0..4 {
        apply(&mut app, Action::Down); // to the radius
    }
    for a in [
        Action::Edit,
        Action::ClearInput,
        Action::Input('-'),
        Action::Input('2'),
        Action::Submit,
    ] {
        apply(&mut app, a);
    }
    insta::assert_snapshot!(draw(&app, 100, 30).backend());
}

#[test]
fn help_overlay() {
    let mut app = app();
    fill_previews(&mut app, 110, 36);
    apply(&mut app, Action::Help);
    insta::assert_snapshot!(draw(&app, 110, 36).backend());
}

#[test]
fn add_menu() {
    let mut app = app();
    fill_previews(&mut app, 100, 30);
    apply(&mut app, Action::AddMenu);
    apply(&mut app, Action::Down);
    insta::assert_snapshot!(draw(&app, 100, 30).backend());
}

#[test]
fn compare_view() {
    let mut app = app();
    apply(&mut app, Action::ToggleCompare);
    fill_previews(&mut app, 100, 30);
    focus(&mut app, Focus::Preview);
    insta::assert_snapshot!(draw(&app, 100, 30).backend());
}

#[test]
fn export_dialog() {
    let mut app = app();
    fill_previews(&mut app, 100, 30);
    apply(&mut app, Action::Export);
    apply(&mut app, Action::Down);
    insta::assert_snapshot!(draw(&app, 100, 30).backend());
}

#[test]
fn a_tiny_terminal_says_so_without_panicking() {
    let app = app();
    draw(&app, 1, 1);
    draw(&app, 0, 0);
    for (w, h) in [(10, 5), (19, 8), (20, 7)] {
        let text = screen_text(&draw(&app, w, h));
        assert!(
            text.contains("terminal") && text.contains("small"),
            "{w}x{h}: {text:?}"
        );
    }
    let text = screen_text(&draw(&app, 20, 8));
    assert!(!text.contains("too small"));
}

#[test]
fn control_characters_in_names_are_not_drawn() {
    let mut scene = default_scene();
    scene.objects[0].name = Some("evil\x1b[2Jname\x07".into());
    let app = App::new(scene, None, PathBuf::from("."));
    let text = screen_text(&draw(&app, 100, 30));
    assert!(text.contains("evil[2Jname"));
    assert!(!text.contains('\x1b') && !text.contains('\x07'));
}

/// Draws `image` into a buffer the size of its cells.
fn cells(image: &PreviewImage, mode: ColorMode) -> Buffer {
    cells_coarse(image, mode, &None)
}

/// Draws `image` with the pixels flagged in `coarse` in the 256-colour palette.
fn cells_coarse(image: &PreviewImage, mode: ColorMode, coarse: &Option<Vec<bool>>) -> Buffer {
    let area = Rect::new(0, 0, image.width as u16, image.height.div_ceil(2) as u16);
    let mut buf = Buffer::empty(area);
    Picture {
        image,
        mode,
        coarse,
        set: rastray::terminal_image::GlyphSet::HalfBlock,
    }
    .render(area, &mut buf);
    buf
}

#[test]
fn a_motion_frame_draws_only_the_flagged_pixels_in_the_palette() {
    // Two cells: the left one's upper pixel is flagged, the right one is not.
    let image = PreviewImage {
        width: 2,
        height: 2,
        pixels: vec![[200, 40, 40], [12, 13, 20], [10, 200, 30], [240, 240, 10]],
    };
    let coarse = Some(vec![true, false, false, false]);
    let buf = cells_coarse(&image, ColorMode::Truecolor, &coarse);
    let left = &buf[(0, 0)];
    assert_eq!(left.symbol(), "▀");
    assert_eq!(left.fg, Color::Indexed(nearest_256([200, 40, 40])));
    assert_eq!(left.bg, Color::Rgb(10, 200, 30));
    let right = &buf[(1, 0)];
    assert_eq!(
        (right.fg, right.bg),
        (Color::Rgb(12, 13, 20), Color::Rgb(240, 240, 10))
    );
}

#[test]
fn upper_and_lower_halves_carry_their_pixels() {
    // A real render of the default scene, so the check covers the path the editor uses.
    let scene = default_scene();
    let world = Arc::new(World::build(&scene, std::path::Path::new(".")).unwrap());
    let mut frame = Frame::default();
    Renderer::new(RenderOptions::new(Algorithm::Phong, 48, 32))
        .render(&world, &scene.camera, &Progress::new(), &mut frame)
        .unwrap();
    let image = PreviewImage::from_frame(&frame);
    let buf = cells(&image, ColorMode::Truecolor);
    // Each colour is its pixel's, or the pen's within the tolerance (see `tui::view::pen`).
    let near =
        |c: Color, p: [u8; 3]| matches!(c, Color::Rgb(r, g, b) if halves_match([r, g, b], p));
    let (mut halves, mut spaces) = (0, 0);
    for row in 0..16u32 {
        for col in 0..48u32 {
            let cell = &buf[(col as u16, row as u16)];
            let upper = frame.srgb8_at(col, 2 * row);
            let lower = frame.srgb8_at(col, 2 * row + 1);
            if cell.symbol() == " " {
                spaces += 1;
                assert!(near(cell.bg, upper), "cell {col},{row}: {:?}", cell.bg);
                assert!(near(cell.bg, lower), "cell {col},{row}: {:?}", cell.bg);
            } else {
                halves += 1;
                assert!(
                    !halves_match(upper, lower),
                    "cell {col},{row} is one colour"
                );
                assert_eq!(cell.symbol(), "▀");
                assert!(near(cell.fg, upper), "upper pixel of cell {col},{row}");
                assert!(near(cell.bg, lower), "lower pixel of cell {col},{row}");
            }
        }
    }
    assert!(
        halves > 0 && spaces > 0,
        "both kinds of cell appear ({halves}, {spaces})"
    );
}

#[test]
fn odd_heights_and_the_256_palette() {
    let mut frame = Frame::filled(2, 3, Vec3::ZERO);
    frame.pixels[0] = Vec3::ONE; // top-left white
    frame.pixels[4] = Vec3::new(1.0, 0.0, 0.0); // bottom-left red, alone in the last row
    let image = PreviewImage::from_frame(&frame);
    let buf = cells(&image, ColorMode::Ansi256);
    assert_eq!(buf[(0, 0)].symbol(), "▀");
    assert_eq!(buf[(0, 0)].fg, Color::Indexed(231)); // white in the cube
    assert_eq!(buf[(0, 0)].bg, Color::Indexed(16)); // black in the cube
    assert_eq!(buf[(0, 1)].symbol(), "▀");
    assert_eq!(buf[(0, 1)].fg, Color::Indexed(196)); // pure red
    assert_eq!(buf[(0, 1)].bg, Color::Reset);
}

#[test]
fn nearly_equal_halves_share_one_colour() {
    let image = PreviewImage {
        width: 2,
        height: 2,
        pixels: vec![
            [100, 100, 100],
            [100, 100, 100],
            [104, 96, 100],
            [105, 100, 100],
        ],
    };
    let buf = cells(&image, ColorMode::Truecolor);
    assert_eq!(buf[(0, 0)].symbol(), " ");
    assert_eq!(buf[(0, 0)].bg, Color::Rgb(100, 100, 100));
    assert_eq!(
        buf[(1, 0)].symbol(),
        "▀",
        "5 levels apart is drawn as two halves"
    );
    assert_eq!(buf[(1, 0)].bg, Color::Rgb(105, 100, 100));
}

#[test]
fn palette_picks_greys_for_greys() {
    assert_eq!(nearest_256([128, 128, 128]), 244); // grey ramp: 8 + 10·12 = 128
    assert_eq!(nearest_256([0, 0, 255]), 21);
    assert_eq!(nearest_256([95, 135, 175]), 16 + 36 + 12 + 3);
}

#[test]
fn the_help_shows_every_row_of_the_key_table_whole() {
    let mut app = app();
    fill_previews(&mut app, 110, 36);
    apply(&mut app, Action::Help);
    let mut screens = String::new();
    for _ in 0..rastray::tui::input::keys::KEYS.len() {
        let terminal = draw(&app, 110, 36);
        let buffer = terminal.backend().buffer();
        for y in 0..36 {
            let line: String = (0..110).map(|x| buffer[(x, y)].symbol()).collect();
            screens.push_str(&line);
            screens.push('\n');
        }
        apply(&mut app, Action::Down);
    }
    for row in rastray::tui::input::keys::KEYS {
        let line = format!("{} ", row.keys());
        assert!(
            screens
                .lines()
                .any(|l| l.contains(&line) && l.contains(row.what)),
            "`{}` | {} is not shown whole",
            row.keys(),
            row.what
        );
    }
}

#[test]
fn the_preview_says_when_the_view_left_the_scene_camera() {
    let mut app = app();
    fill_previews(&mut app, 100, 30);
    let title = |app: &App| screen_text(&draw(app, 100, 30));
    assert!(!title(&app).contains("view moved"));
    apply(
        &mut app,
        Action::Orbit {
            yaw: 5.0,
            pitch: 0.0,
        },
    );
    assert!(title(&app).contains("Preview · Phong · view moved, C keeps it"));
    apply(&mut app, Action::SceneCameraFromView);
    assert!(!title(&app).contains("view moved"));
    assert!(title(&app).contains("● modified"));
}

// Small terminals: whole screens at 80×24, 60×20 and 10×5, with the colours of chosen cells
// checked through the buffer, values shown whole where labels give way, and keys on the
// "too small" screen changing nothing.

/// The app with a preview of the size its layout at `width`×`height` asks for (none when the
/// terminal is too small for the editor).
fn small_app(width: u16, height: u16) -> App {
    let mut app = app();
    if layout(Rect::new(0, 0, width, height), &app).is_some() {
        fill_previews(&mut app, width, height);
    }
    app
}

/// The screen at `width`×`height`.
fn buffer(app: &App, width: u16, height: u16) -> Buffer {
    draw(app, width, height).backend().buffer().clone()
}

/// Row `y` of `buf` as text.
fn row(buf: &Buffer, y: u16) -> String {
    (0..buf.area.width).map(|x| buf[(x, y)].symbol()).collect()
}

fn snapshot(buf: &Buffer) -> String {
    (0..buf.area.height)
        .map(|y| row(buf, y))
        .collect::<Vec<_>>()
        .join("\n")
}

/// The preview's first cell shows the red left half in truecolor, and the bottom line hints in
/// the dim colour, ending with help and quit.
fn check_colours(buf: &Buffer, app: &App) {
    let areas = layout(buf.area, app).unwrap();
    let cell = &buf[(areas.picture.x, areas.picture.y)];
    assert_eq!(cell.bg, Color::Rgb(200, 60, 40), "preview colour");
    let right = &buf[(areas.picture.right() - 1, areas.picture.y)];
    assert_eq!(
        (right.symbol(), right.fg, right.bg),
        ("▀", Color::Rgb(20, 30, 40), Color::Rgb(90, 90, 90)),
        "both halves of a cell"
    );
    let hints_y = buf.area.height - 1;
    let hints = row(buf, hints_y);
    assert!(hints.trim_end().ends_with("? help · q quit"), "{hints}");
    assert_eq!(buf[(2, hints_y)].fg, Color::DarkGray, "hints are dim");
    let status = row(buf, hints_y - 1);
    assert_eq!(buf[(1, hints_y - 1)].fg, Color::Cyan, "{status}");
}

#[test]
fn at_80_by_24() {
    let app = small_app(80, 24);
    let buf = buffer(&app, 80, 24);
    check_colours(&buf, &app);
    insta::assert_snapshot!(snapshot(&buf));
}

#[test]
fn at_60_by_20_values_show_whole_and_labels_give_way() {
    let mut app = small_app(60, 20);
    while app.item() != Item::Object(1) {
        apply(&mut app, Action::Down);
    }
    apply(&mut app, Action::FocusNext);
    assert_eq!(app.focus(), Focus::Properties);
    let buf = buffer(&app, 60, 20);
    check_colours(&buf, &app);
    let text = snapshot(&buf);
    let shows_whole = |text: &str, label: &str, value: &str| {
        text.lines()
            .filter(|l| l.contains(label))
            .any(|l| l.contains(&format!(" {value} ")) || l.contains(&format!(" {value}┃")))
    };
    // The gem's centre and radius, each value whole.
    for (label, value) in [("center.x", "-2.2"), ("radius", "1.2")] {
        assert!(
            shows_whole(&text, label, value),
            "{label} {value} is cut:\n{text}"
        );
    }
    // Further down the list: its colour and material, whole too.
    let mut below = small_app(60, 20);
    while below.item() != Item::Object(1) {
        apply(&mut below, Action::Down);
    }
    apply(&mut below, Action::FocusNext);
    for _ in 0..15 {
        apply(&mut below, Action::Down);
    }
    let lower = snapshot(&buffer(&below, 60, 20));
    for (label, value) in [
        ("color.g", "0.12"),
        ("specular", "0.7"),
        ("reflection", "0.2"),
    ] {
        let cut = &label[..label.len().min(8)];
        assert!(
            shows_whole(&lower, cut, value),
            "{label} {value} is cut:\n{lower}"
        );
    }
    // The selected property is highlighted.
    let areas = layout(buf.area, &app).unwrap();
    let selected = &buf[(areas.properties.x + 2, areas.properties.y + 1)];
    assert_eq!(selected.bg, Color::Yellow);
    insta::assert_snapshot!(text);
}

#[test]
fn at_10_by_5_the_screen_says_it_is_too_small() {
    let app = small_app(10, 5);
    let buf = buffer(&app, 10, 5);
    let text = snapshot(&buf);
    assert!(
        text.contains("terminal") && text.contains("small"),
        "{text}"
    );
    // Nothing of the picture is drawn: every cell keeps the terminal's colours.
    assert!(
        buf.content
            .iter()
            .all(|c| c.fg == Color::Reset && c.bg == Color::Reset)
    );
    insta::assert_snapshot!(text);
}

fn key_event(code: KeyCode) -> Event {
    let modifiers = match code {
        KeyCode::Char(c) if c.is_ascii_uppercase() => KeyModifiers::SHIFT,
        _ => KeyModifiers::NONE,
    };
    Event::Key(KeyEvent::new(code, modifiers))
}

#[test]
fn keys_on_the_too_small_screen_change_nothing_but_quit_and_help_act() {
    let mut app = app();
    let before = format!("{:?}", app.document().scene());
    let view_before = app.view().clone();
    // Every key the table names, plus the ones a user types by habit.
    let mut codes: Vec<KeyCode> =
        "abcdefghijklmnoprstuvwxyzABCDEFGHIJKLMNOPRSTUVWXYZ0123456789[]+-=<>,./ "
            .chars()
            .map(KeyCode::Char)
            .collect();
    codes.extend([
        KeyCode::Up,
        KeyCode::Down,
        KeyCode::Left,
        KeyCode::Right,
        KeyCode::Enter,
        KeyCode::Tab,
        KeyCode::BackTab,
        KeyCode::Esc,
        KeyCode::Delete,
        KeyCode::Backspace,
    ]);
    assert!(!KEYS.is_empty());
    // On a screen of normal size these keys do act.
    let acting =
        |c: char| rastray::tui::input::map(&app, &key_event(KeyCode::Char(c)), Rect::default());
    assert!(acting('a').is_some() && acting('x').is_some() && acting(']').is_some());
    for code in codes {
        if let Some(action) = map_too_small(&app, &key_event(code)) {
            assert!(
                matches!(
                    action,
                    Action::Quit | Action::QuitNow | Action::SaveAndQuit | Action::Help
                ),
                "{code:?} acts unseen: {action:?}"
            );
        }
    }
    assert_eq!(format!("{:?}", app.document().scene()), before);
    assert_eq!(app.view(), &view_before);
    assert!(matches!(
        map_too_small(&app, &key_event(KeyCode::Char('?'))),
        Some(Action::Help)
    ));
    assert!(matches!(
        map_too_small(&app, &key_event(KeyCode::Char('q'))),
        Some(Action::Quit | Action::QuitNow)
    ));
    // Inside the help, its own keys work (it can be seen).
    apply(&mut app, Action::Help);
    assert!(map_too_small(&app, &key_event(KeyCode::Esc)).is_some());
}

/// The app drawing its preview in sixel on 10×20-pixel cells, with a frame of the size rendered
/// for real pixels at `width`×`height`.
fn sixel_app(width: u16, height: u16) -> App {
    let graphics = Graphics {
        protocol: Some(Protocol::Sixel),
        cells: rastray::terminal_image::GlyphSet::HalfBlock,
        cell: CellSize {
            width: 10,
            height: 20,
        },
        ..Graphics::default()
    };
    let mut app = app().with_graphics(graphics.clone());
    let p = layout(Rect::new(0, 0, width, height), &app)
        .unwrap()
        .picture;
    let (w, h) = graphics.pixel_size(p.width, p.height).unwrap();
    apply(
        &mut app,
        Action::Rendered(Box::new(RenderReply::Shot {
            id: 1,
            slot: Slot::Main,
            image: stripes(w, h),
            millis: 1.0,
            triangles: 112,
            last: true,
        })),
    );
    app
}

#[test]
fn a_picture_in_pixels_lies_over_blank_cells_that_a_dialog_rewrites() {
    let mut app = sixel_app(100, 30);
    let picture = layout(Rect::new(0, 0, 100, 30), &app).unwrap().picture;
    let placed = rastray::tui::view::placements(&app, picture);
    assert_eq!(placed.len(), 1);
    assert_eq!(placed[0].area, picture);
    let under = buffer(&app, 100, 30);
    assert!(picture.positions().all(|p| under[p].symbol() == " "));
    assert!(row(&under, 28).contains("│ sixel │"), "{}", row(&under, 28));
    // The help opens over the preview: no picture, and every cell that lay under it is written
    // again (a sixel picture is wiped only where cells are written).
    apply(&mut app, Action::Help);
    assert!(rastray::tui::view::placements(&app, picture).is_empty());
    let over = buffer(&app, 100, 30);
    let changed: std::collections::HashSet<(u16, u16)> = under
        .diff(&over)
        .into_iter()
        .map(|(x, y, _)| (x, y))
        .collect();
    assert!(
        picture.positions().all(|p| changed.contains(&(p.x, p.y))),
        "cells under the picture are left as they were"
    );
}

/// A frame rendered for `graphics`' glyph set over the preview of a `width`×`height` screen:
/// a red disc on dark blue, in square pixels of the size the set asks for.
fn cells_app(graphics: Graphics, width: u16, height: u16) -> (App, Rect) {
    let mut app = app().with_graphics(graphics.clone());
    let p = layout(Rect::new(0, 0, width, height), &app)
        .unwrap()
        .picture;
    let (w, h) = graphics.cells_size(p.width, p.height);
    let (cx, cy, r) = (w as f32 / 2.0, h as f32 / 2.0, h as f32 / 3.0);
    let pixels = (0..h)
        .flat_map(|y| (0..w).map(move |x| (x, y)))
        .map(|(x, y)| {
            let (dx, dy) = (x as f32 + 0.5 - cx, y as f32 + 0.5 - cy);
            if dx * dx + dy * dy < r * r {
                [220, 40, 30]
            } else {
                [10, 20, 70]
            }
        })
        .collect();
    apply(
        &mut app,
        Action::Rendered(Box::new(RenderReply::Shot {
            id: 1,
            slot: Slot::Main,
            image: PreviewImage {
                width: w,
                height: h,
                pixels,
            },
            millis: 1.0,
            triangles: 112,
            last: true,
        })),
    );
    (app, p)
}

#[test]
fn each_glyph_set_draws_the_preview_and_the_status_line_names_it() {
    use rastray::terminal_image::GlyphSet;
    let cell = CellSize {
        width: 8,
        height: 19,
    };
    for (set, name, glyphs) in [
        (GlyphSet::HalfBlock, "half blocks", "▀▄"),
        (GlyphSet::Quadrant, "quadrants", "▘▝▖▗▚▞▙▛▜▟"),
        (
            GlyphSet::Sextant,
            "sextants",
            "\u{1FB00}\u{1FB01}\u{1FB02}\u{1FB03}\u{1FB07}\u{1FB0B}\u{1FB0F}\u{1FB13}\u{1FB17}\u{1FB1B}\u{1FB1E}\u{1FB20}\u{1FB22}\u{1FB26}\u{1FB28}\u{1FB2A}\u{1FB2D}\u{1FB30}\u{1FB32}\u{1FB34}\u{1FB36}\u{1FB38}\u{1FB3A}\u{1FB3B}",
        ),
        (GlyphSet::Braille, "braille", ""),
    ] {
        let (app, picture) = cells_app(Graphics::in_cells(set, cell, None), 100, 30);
        let buf = buffer(&app, 100, 30);
        assert!(
            row(&buf, 28).contains(&format!("│ {name} │")),
            "{}",
            row(&buf, 28)
        );
        let drawn: String = picture
            .positions()
            .map(|p| buf[p].symbol().to_string())
            .collect();
        let finer = match set {
            GlyphSet::Braille => drawn
                .chars()
                .any(|c| ('\u{2801}'..='\u{28FF}').contains(&c)),
            _ => drawn.chars().any(|c| glyphs.contains(c)),
        };
        assert!(finer, "{name}: {drawn}");
        // The disc is round on 8×19 cells: as many pixels of it across as down, counted in
        // cells of its colour (a cell whose background or foreground is the disc's).
        let red = |p: (u16, u16)| {
            let c = &buf[p];
            let is = |color: ratatui::style::Color| matches!(color, ratatui::style::Color::Rgb(r, _, _) if r > 150);
            is(c.bg) || (c.symbol() != " " && is(c.fg))
        };
        let middle_row = picture.y + picture.height / 2;
        let middle_col = picture.x + picture.width / 2;
        let across = (picture.x..picture.right())
            .filter(|&x| red((x, middle_row)))
            .count();
        let down = (picture.y..picture.bottom())
            .filter(|&y| red((middle_col, y)))
            .count();
        let ratio = (across as f32 * 8.0) / (down as f32 * 19.0);
        assert!(
            (ratio - 1.0).abs() < 0.2,
            "{name}: {across} across, {down} down"
        );
    }
}

#[test]
fn at_60_by_20_the_camera_target_labels_stay_apart() {
    let mut app = small_app(60, 20);
    while app.item() != Item::Settings {
        apply(&mut app, Action::Up);
    }
    apply(&mut app, Action::FocusNext);
    // Down to the target's coordinates, so that they are in view.
    for _ in 0..4 {
        apply(&mut app, Action::Down);
    }
    let text = snapshot(&buffer(&app, 60, 20));
    let labels: Vec<&str> = ["x", "y", "z"]
        .iter()
        .map(|axis| {
            let suffix = format!(".target.{axis} ");
            let found = text.lines().find(|l| l.contains(&suffix));
            assert!(found.is_some(), "no .target.{axis}:\n{text}");
            found.unwrap()
        })
        .collect();
    assert!(labels[0] != labels[1] && labels[1] != labels[2]);
    insta::assert_snapshot!(text);
}
