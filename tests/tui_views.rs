//! The editor's view keys: preset views, fit all, perspective/orthographic and auto-spin move
//! the view alone and never mark the scene modified.

use std::path::PathBuf;
use std::time::Duration;

use glam::Vec3;
use rastray::preset_view::PresetView;
use rastray::scene::{Projection, default_scene};
use rastray::tui::input::action::Action;
use rastray::tui::input::map;
use rastray::tui::state::app::App;
use rastray::tui::state::selection::Focus;
use rastray::tui::update::apply;
use rastray::tui::worker::RenderReply;
use ratatui::crossterm::event::{Event, KeyCode, KeyEvent, KeyModifiers};
use ratatui::layout::Rect;

/// The default scene's bounds as the worker reports them: a floor 14 × 0.5 × 10 under shapes.
const BOUNDS: (Vec3, Vec3) = (Vec3::new(-7.0, -0.5, -5.0), Vec3::new(7.0, 2.0, 5.0));

fn app() -> App {
    let mut app = App::new(default_scene(), None, PathBuf::from("."));
    apply(
        &mut app,
        Action::Rendered(Box::new(RenderReply::Bounds {
            id: 0,
            bounds: Some(BOUNDS),
        })),
    );
    app
}

fn forward(app: &App) -> Vec3 {
    let camera = app.view().camera();
    (camera.target - camera.position).normalize()
}

fn unchanged_scene(app: &App) {
    assert!(!app.document().is_dirty());
    assert_eq!(app.document().undo_steps(), 0);
    assert_eq!(app.document().scene().camera, default_scene().camera);
}

#[test]
fn the_view_keys_are_v_shift_v_f_p_and_t_in_every_pane() {
    let mut app = app();
    for focus in [Focus::List, Focus::Properties, Focus::Preview] {
        while app.focus() != focus {
            apply(&mut app, Action::FocusNext);
        }
        let preview = Rect::new(40, 0, 80, 38);
        let key = |c: char| {
            let event = Event::Key(KeyEvent::new(KeyCode::Char(c), KeyModifiers::NONE));
            map(&app, &event, preview)
        };
        assert_eq!(key('v'), Some(Action::StepPresetView(1)), "{focus:?}");
        assert_eq!(key('V'), Some(Action::StepPresetView(-1)), "{focus:?}");
        assert_eq!(key('f'), Some(Action::FitAll), "{focus:?}");
        assert_eq!(key('p'), Some(Action::ToggleProjection), "{focus:?}");
        assert_eq!(key('t'), Some(Action::ToggleSpin), "{focus:?}");
    }
}

#[test]
fn presets_step_through_the_sides_and_look_at_the_bounds_centre() {
    let mut app = app();
    apply(&mut app, Action::StepPresetView(1));
    assert_eq!(app.view().preset(), Some(PresetView::Front));
    assert!(forward(&app).distance(Vec3::NEG_Z) < 1e-5);
    assert!(
        app.view()
            .camera()
            .target
            .distance(Vec3::new(0.0, 0.75, 0.0))
            < 1e-5
    );
    apply(&mut app, Action::StepPresetView(1));
    assert_eq!(app.view().preset(), Some(PresetView::Right));
    assert!(forward(&app).distance(Vec3::NEG_X) < 1e-5);
    apply(&mut app, Action::StepPresetView(-1));
    apply(&mut app, Action::StepPresetView(-1));
    assert_eq!(app.view().preset(), Some(PresetView::Iso));
    assert!(forward(&app).distance(-Vec3::ONE.normalize()) < 1e-5);
    // Orbiting leaves the preset.
    apply(
        &mut app,
        Action::Orbit {
            yaw: 10.0,
            pitch: 0.0,
        },
    );
    assert_eq!(app.view().preset(), None);
    unchanged_scene(&app);
}

#[test]
fn fit_all_keeps_the_direction_and_frames_the_bounds() {
    let mut app = app();
    apply(&mut app, Action::Zoom(5.0));
    let before = forward(&app);
    let far = app
        .view()
        .camera()
        .position
        .distance(app.view().camera().target);
    apply(&mut app, Action::FitAll);
    assert!(forward(&app).distance(before) < 1e-2);
    let near = app
        .view()
        .camera()
        .position
        .distance(app.view().camera().target);
    assert!(near < far, "fit moved from {far} to {near}");
    unchanged_scene(&app);
}

#[test]
fn p_switches_to_orthographic_keeping_the_framing_and_back() {
    let mut app = app();
    let home = app.view().camera();
    apply(&mut app, Action::ToggleProjection);
    let ortho = app.view().camera();
    assert_eq!(ortho.projection, Projection::Orthographic);
    let distance = home.position.distance(home.target);
    let expected = 2.0 * distance * (home.fov.to_radians() / 2.0).tan();
    assert!((ortho.height.unwrap() - expected).abs() < 1e-4);
    // Zooming an orthographic view scales its height.
    apply(&mut app, Action::Zoom(0.5));
    assert!((app.view().camera().height.unwrap() - expected * 0.5).abs() < 1e-4);
    apply(&mut app, Action::Zoom(2.0));
    apply(&mut app, Action::ToggleProjection);
    let back = app.view().camera();
    assert_eq!(back.projection, Projection::Perspective);
    assert!(back.position.distance(home.position) < 1e-3);
    unchanged_scene(&app);
}

#[test]
fn auto_spin_turns_the_view_on_ticks_until_t_again() {
    let mut app = app();
    let home = app.view().camera();
    apply(&mut app, Action::ToggleSpin);
    assert!(app.view().spinning());
    std::thread::sleep(Duration::from_millis(60));
    apply(&mut app, Action::Tick);
    let turned = app.view().camera();
    assert_ne!(turned.position, home.position);
    // About the target, at the same distance and height.
    assert!(
        (turned.position.distance(home.target) - home.position.distance(home.target)).abs() < 1e-3
    );
    assert!((turned.position.y - home.position.y).abs() < 1e-3);
    apply(&mut app, Action::ToggleSpin);
    std::thread::sleep(Duration::from_millis(20));
    apply(&mut app, Action::Tick);
    assert_eq!(app.view().camera(), turned);
    unchanged_scene(&app);
}

/// The editor drawn on a 120×30 test terminal, as text.
fn screen(app: &App) -> String {
    use ratatui::Terminal;
    use ratatui::backend::TestBackend;
    let mut terminal = Terminal::new(TestBackend::new(120, 30)).unwrap();
    terminal.draw(|f| f.render_widget(app, f.area())).unwrap();
    let buffer = terminal.backend().buffer();
    (0..30)
        .map(|y| {
            (0..120)
                .map(|x| buffer[(x, y)].symbol())
                .collect::<String>()
                + "\n"
        })
        .collect()
}

#[test]
fn the_preview_title_names_the_projection_the_preset_and_the_spin() {
    let mut app = app();
    assert!(!screen(&app).contains("ortho"));
    apply(&mut app, Action::StepPresetView(-1));
    apply(&mut app, Action::ToggleProjection);
    apply(&mut app, Action::ToggleSpin);
    let text = screen(&app);
    assert!(
        text.contains("Preview · Phong · ortho · iso · spinning"),
        "{text}"
    );
    // A turn of the spin leaves the preset: the title stops naming it.
    std::thread::sleep(Duration::from_millis(20));
    apply(&mut app, Action::Tick);
    assert!(screen(&app).contains("Preview · Phong · ortho · spinning"));
}
