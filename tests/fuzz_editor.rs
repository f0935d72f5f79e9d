//! Fuzzing the editor: random sequences of the Actions keys and the mouse produce, applied to the
//! editor state without a terminal, and random screen sizes to draw at. After every step the
//! state keeps its invariants: the scene is valid, the selection names an item that exists, the
//! property cursor is on a field, the view camera is finite and looks somewhere. At the end,
//! undoing every edit gives back the scene it started from, and the scene writes to TOML that
//! reads back the same.
//!
//! Actions that write files (save, save as, export) or read a scene (open) are left out; adding
//! a mesh reads a small OBJ from a temporary folder. CI runs proptest's default 256 cases;
//! `PROPTEST_CASES=250000` runs a long session (see the README, "Fuzzing").

use std::path::{Path, PathBuf};

use proptest::prelude::*;
use rastray::render::Algorithm;
use rastray::scene::{from_toml_str, to_toml_string, validate};
use rastray::tui::input::action::Action;
use rastray::tui::state::app::App;
use rastray::tui::state::mode::{AddKind, Mode};
use rastray::tui::state::selection::Focus;
use rastray::tui::update::{apply, field_keys};
use ratatui::Terminal;
use ratatui::backend::TestBackend;

/// One step of a session: an Action, a path typed into a prompt, or a redraw at a size.
#[derive(Debug, Clone)]
enum Step {
    Act(Action),
    /// Types the name of the OBJ file in the session's folder.
    TypeModelPath,
    Draw(u16, u16),
}

fn action() -> impl Strategy<Value = Action> {
    let simple = prop::sample::select(vec![
        Action::Quit,
        Action::QuitNow,
        Action::FocusNext,
        Action::FocusPrev,
        Action::Up,
        Action::Down,
        Action::Edit,
        Action::Backspace,
        Action::ClearInput,
        Action::Submit,
        Action::Cancel,
        Action::Help,
        Action::AddMenu,
        Action::Duplicate,
        Action::Remove,
        Action::Undo,
        Action::Redo,
        Action::ToggleCompare,
        Action::ResetView,
        Action::SceneCameraFromView,
        Action::DragEnd,
    ]);
    prop_oneof![
        12 => simple,
        4 => prop::sample::select(vec![-10, -1, 1, 10]).prop_map(Action::Step),
        4 => prop::sample::select("0123456789.-e+ xnaif".chars().collect::<Vec<_>>())
            .prop_map(Action::Input),
        2 => prop::sample::select(AddKind::ALL.to_vec()).prop_map(Action::Add),
        1 => prop::sample::select(Algorithm::ALL.to_vec()).prop_map(Action::Algorithm),
        2 => prop::sample::select(vec![(5.0, 0.0), (-5.0, 0.0), (0.0, 5.0), (0.0, -5.0)])
            .prop_map(|(yaw, pitch)| Action::Orbit { yaw, pitch }),
        1 => prop::sample::select(vec![(0.05, 0.0), (-0.05, 0.0), (0.0, 0.05), (0.0, -0.05)])
            .prop_map(|(right, up)| Action::Pan { right, up }),
        1 => prop::sample::select(vec![0.9, 1.0 / 0.9]).prop_map(Action::Zoom),
        1 => (0u16..200, 0u16..60).prop_map(|(column, row)| Action::DragStart { column, row }),
        2 => (0u16..200, 0u16..60).prop_map(|(column, row)| Action::DragTo { column, row }),
    ]
}

fn step() -> impl Strategy<Value = Step> {
    prop_oneof![
        20 => action().prop_map(Step::Act),
        1 => Just(Step::TypeModelPath),
        1 => (1u16..140, 1u16..50).prop_map(|(w, h)| Step::Draw(w, h)),
    ]
}

/// The folder adding a mesh reads from, with one small OBJ file, made once.
fn folder() -> &'static Path {
    static DIR: std::sync::OnceLock<tempfile::TempDir> = std::sync::OnceLock::new();
    DIR.get_or_init(|| {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(
            dir.path().join("m.obj"),
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n",
        )
        .unwrap();
        dir
    })
    .path()
}

fn check(app: &App) -> Result<(), TestCaseError> {
    let scene = app.document().scene();
    prop_assert!(validate(scene).is_ok(), "{:?}", validate(scene));
    prop_assert!(app.items().contains(&app.item()), "{:?}", app.item());
    if app.focus() == Focus::Properties {
        let keys = field_keys(app);
        prop_assert!(
            keys.is_empty() || app.field() < keys.len(),
            "field {}",
            app.field()
        );
    }
    let camera = app.view().camera();
    prop_assert!(camera.position.is_finite() && camera.target.is_finite());
    prop_assert!(camera.position != camera.target, "{camera:?}");
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::default())]

    #[test]
    fn editor_sessions_keep_the_state_valid(steps in prop::collection::vec(step(), 1..60)) {
        let start = rastray::scene::default_scene();
        let mut app = App::new(start.clone(), None, PathBuf::from(folder()));
        for step in steps {
            match step {
                Step::Act(action) => apply(&mut app, action),
                Step::TypeModelPath => {
                    for c in "m.obj".chars() {
                        apply(&mut app, Action::Input(c));
                    }
                }
                Step::Draw(width, height) => {
                    let mut terminal = Terminal::new(TestBackend::new(width, height)).unwrap();
                    terminal.draw(|f| f.render_widget(&app, f.area())).unwrap();
                }
            }
            check(&app)?;
            if app.should_quit() {
                break;
            }
        }
        for _ in 0..4 {
            if *app.mode() == Mode::Normal {
                break;
            }
            apply(&mut app, Action::Cancel);
        }
        let scene = app.document().scene().clone();
        let again = from_toml_str(&to_toml_string(&scene), Path::new("written.toml"));
        prop_assert_eq!(again.ok(), Some(scene));
        if *app.mode() == Mode::Normal {
            while app.document().undo_steps() > 0 {
                apply(&mut app, Action::Undo);
                check(&app)?;
            }
            prop_assert_eq!(app.document().scene(), &start);
        }
    }
}
