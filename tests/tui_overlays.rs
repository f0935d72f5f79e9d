//! The editor's display modes and overlays, from the keys to the screen: keys become actions,
//! the view asks the real render worker for its previews, and the screen is drawn with ratatui's
//! TestBackend. Snapshots hold the text (the status bar names the mode, the grid's spacing and
//! the box's size); the overlays' colours are checked cell by cell in the buffer.

use std::path::PathBuf;
use std::sync::Arc;
use std::sync::mpsc::channel;
use std::time::Duration;

use glam::Vec3;
use rastray::render::{encode_srgb, overlay_colors};
use rastray::scene::default_scene;
use rastray::tui::input::action::Action;
use rastray::tui::state::app::App;
use rastray::tui::state::selection::Item;
use rastray::tui::update::apply;
use rastray::tui::view::layout;
use rastray::tui::worker::{RenderReply, Worker};
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use ratatui::buffer::Buffer;
use ratatui::crossterm::event::{Event, KeyCode, KeyEvent, KeyModifiers};
use ratatui::layout::Rect;
use ratatui::style::Color;

const PATIENCE: Duration = Duration::from_secs(120);
const SIZE: (u16, u16) = (100, 30);

fn key_event(c: char) -> Event {
    let modifiers = if c.is_ascii_uppercase() {
        KeyModifiers::SHIFT
    } else {
        KeyModifiers::NONE
    };
    Event::Key(KeyEvent::new(KeyCode::Char(c), modifiers))
}

/// The editor on the default scene after `keys` (typed with the scene list focused, on the
/// entry `item`), with the previews the render worker draws for it, as a screen.
fn screen_after(item: Item, keys: &str) -> (App, Buffer) {
    let mut app = App::new(default_scene(), None, PathBuf::from(".")).with_timings(false);
    while app.item() != item {
        apply(&mut app, Action::Down);
    }
    let area = Rect::new(0, 0, SIZE.0, SIZE.1);
    for c in keys.chars() {
        let action = rastray::tui::input::map(&app, &key_event(c), area).expect("a bound key");
        apply(&mut app, action);
    }
    let picture = layout(area, &app).expect("room for the editor").picture;
    let wanted = rastray::tui::wanted(&app, picture, false).expect("a preview");
    let (tx, rx) = channel();
    let mut worker = Worker::spawn(move |reply| {
        let _ = tx.send(reply);
    });
    worker.request(wanted, Arc::new(default_scene()), PathBuf::from("."));
    loop {
        let reply = rx.recv_timeout(PATIENCE).expect("the worker answers");
        let last = matches!(reply, RenderReply::Shot { last: true, .. });
        assert!(!matches!(reply, RenderReply::Failed { .. }), "{reply:?}");
        apply(&mut app, Action::Rendered(Box::new(reply)));
        if last {
            break;
        }
    }
    let mut terminal = Terminal::new(TestBackend::new(SIZE.0, SIZE.1)).unwrap();
    terminal.draw(|f| f.render_widget(&app, f.area())).unwrap();
    let buffer = terminal.backend().buffer().clone();
    (app, buffer)
}

fn snapshot(buf: &Buffer) -> String {
    (0..buf.area.height)
        .map(|y| {
            (0..buf.area.width)
                .map(|x| buf[(x, y)].symbol())
                .collect::<String>()
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// The truecolor cell colour of linear `color`.
fn cell_color(color: Vec3) -> Color {
    let [r, g, b] = color.to_array().map(encode_srgb);
    Color::Rgb(r, g, b)
}

/// How many half-cell pixels of the preview show `color`.
fn pixels_of(buf: &Buffer, app: &App, color: Vec3) -> usize {
    let picture = layout(buf.area, app).unwrap().picture;
    let wanted = cell_color(color);
    let mut count = 0;
    for y in picture.top()..picture.bottom() {
        for x in picture.left()..picture.right() {
            let cell = &buf[(x, y)];
            count += (cell.fg == wanted) as usize + (cell.bg == wanted) as usize;
        }
    }
    count
}

/// The status bar's line.
fn status(buf: &Buffer) -> String {
    let y = buf.area.height - 2;
    (0..buf.area.width).map(|x| buf[(x, y)].symbol()).collect()
}

#[test]
fn no_overlay_draws_none_of_their_colours() {
    let (app, buf) = screen_after(Item::Settings, "");
    for color in [
        overlay_colors::GRID,
        overlay_colors::BOUNDS,
        overlay_colors::OUTLINE,
    ]
    .into_iter()
    .chain(overlay_colors::AXES)
    {
        assert_eq!(pixels_of(&buf, &app, color), 0, "{color}");
    }
}

#[test]
fn g_draws_the_ground_grid_and_the_status_bar_gives_its_spacing() {
    let (app, buf) = screen_after(Item::Settings, "g");
    assert!(pixels_of(&buf, &app, overlay_colors::GRID) > 20);
    assert!(status(&buf).contains("grid 5"), "{}", status(&buf));
    insta::assert_snapshot!(snapshot(&buf));
}

#[test]
#[allow(non_snake_case)]
fn G_draws_the_axis_gizmo_in_red_green_and_blue() {
    let (app, buf) = screen_after(Item::Settings, "G");
    for axis in overlay_colors::AXES {
        assert!(pixels_of(&buf, &app, axis) >= 2, "{axis}");
    }
    insta::assert_snapshot!(snapshot(&buf));
}

#[test]
fn b_draws_the_selected_objects_box_and_the_status_bar_gives_its_size() {
    // Object 1 of the default scene is the gem: the status bar gives the size of its bounds
    // (four significant digits), as the world has them.
    let (app, buf) = screen_after(Item::Object(1), "b");
    assert!(pixels_of(&buf, &app, overlay_colors::BOUNDS) > 20);
    let world = rastray::World::build(&default_scene(), std::path::Path::new(".")).unwrap();
    let (lo, hi) = world.objects[1].extent.expect("a mesh");
    let line = status(&buf);
    let shown = line
        .split("box ")
        .nth(1)
        .expect("the box's size")
        .split_whitespace();
    let shown: Vec<f32> = shown
        .take(1)
        .flat_map(|s| {
            s.split('×')
                .map(|v| v.parse::<f32>().expect("a number"))
                .collect::<Vec<_>>()
        })
        .collect();
    let size = (hi - lo).to_array();
    assert_eq!(shown.len(), 3, "{line}");
    for (s, e) in shown.iter().zip(size) {
        assert!(
            (s - e).abs() <= 0.001 * e.abs().max(1.0),
            "{line}: {size:?}"
        );
    }
    insta::assert_snapshot!(snapshot(&buf));
}

#[test]
#[allow(non_snake_case)]
fn O_outlines_the_selected_object() {
    let (app, buf) = screen_after(Item::Object(1), "O");
    assert!(pixels_of(&buf, &app, overlay_colors::OUTLINE) > 20);
    insta::assert_snapshot!(snapshot(&buf));
}

#[test]
fn m_cycles_the_display_modes_and_the_status_bar_names_them() {
    let (_, buf) = screen_after(Item::Settings, "mm");
    assert!(status(&buf).contains("hidden-line"), "{}", status(&buf));
    let (_, buf) = screen_after(Item::Settings, "M");
    assert!(status(&buf).contains("uv"), "{}", status(&buf));
    assert!(
        status(&buf).contains("4 objects without UVs"),
        "{}",
        status(&buf)
    );
    let (app, buf) = screen_after(Item::Settings, "mmm");
    assert!(status(&buf).contains("normals"), "{}", status(&buf));
    // The floor's top faces +Y: (0.5, 1, 0.5) as bytes, (128, 255, 128) within 2, the most
    // common colour of the preview's lower rows.
    let picture = layout(buf.area, &app).unwrap().picture;
    let cell = &buf[(picture.x + picture.width / 2, picture.bottom() - 1)];
    let Color::Rgb(r, g, b) = cell.bg else {
        panic!("truecolor cells: {cell:?}")
    };
    assert!(
        r.abs_diff(128) <= 2 && g >= 253 && b.abs_diff(128) <= 2,
        "{r} {g} {b}"
    );
}

#[test]
fn the_selected_objects_measurements_show_under_its_properties() {
    // The default scene's cube is 1.6 on a side: closed, volume 1.6³ = 4.096, area 6 × 2.56,
    // and its properties pane lists that over the editable values.
    let (_, buf) = screen_after(Item::Object(2), "");
    let text = snapshot(&buf);
    assert!(text.contains("closed · volume 4.096"), "{text}");
    assert!(text.contains("area 15.360"), "{text}");
    assert!(text.contains("non-manifold 0 · degenerate 0"), "{text}");
    // The floor, 14 × 0.5 × 10: 70 cubic units.
    let (_, buf) = screen_after(Item::Object(0), "");
    assert!(
        snapshot(&buf).contains("volume 70.000"),
        "{}",
        snapshot(&buf)
    );
}
