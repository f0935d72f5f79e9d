//! The editor driven by Actions alone, checked against the scene each sequence should produce.

use std::path::PathBuf;

use glam::Vec3;
use rastray::render::Algorithm;
use rastray::scene::{Shape, ShapeKind, default_scene};
use rastray::tui::input::action::Action;
use rastray::tui::state::app::App;
use rastray::tui::state::fields::Key;
use rastray::tui::state::mode::{AddKind, Mode};
use rastray::tui::state::selection::{Focus, Item};
use rastray::tui::update::{apply, field_keys};

fn app() -> App {
    App::new(default_scene(), None, PathBuf::from("."))
}

fn run(app: &mut App, actions: impl IntoIterator<Item = Action>) {
    for a in actions {
        apply(app, a);
    }
}

/// Gives the keys to `focus`, pressing Tab.
fn focus(app: &mut App, focus: Focus) {
    for _ in 0..3 {
        if app.focus() == focus {
            return;
        }
        apply(app, Action::FocusNext);
    }
    panic!("Tab never reached {focus:?}");
}

/// Selects `item` in the scene list, pressing Down.
fn select(app: &mut App, item: Item) {
    focus(app, Focus::List);
    for _ in 0..app.items().len() {
        if app.item() == item {
            return;
        }
        apply(app, Action::Down);
    }
    panic!("{item:?} is not in the scene list");
}

/// Moves the properties cursor to `key` of the selected item, pressing Down.
fn choose(app: &mut App, key: Key) {
    focus(app, Focus::Properties);
    let keys = field_keys(app);
    assert!(keys.contains(&key), "the selected item has {key:?}");
    while keys[app.field()] != key {
        apply(app, Action::Down);
    }
}

fn typed(text: &str) -> Vec<Action> {
    let mut v = vec![Action::Edit, Action::ClearInput];
    v.extend(text.chars().map(Action::Input));
    v.push(Action::Submit);
    v
}

#[test]
fn add_box_and_colour_it() {
    let mut app = app();
    let before = app.document().scene().objects.len();
    run(&mut app, [Action::AddMenu, Action::Down, Action::Submit]);
    assert_eq!(app.document().scene().objects.len(), before + 1);
    let added = app.document().scene().objects.last().unwrap();
    assert_eq!(added.shape.kind(), ShapeKind::Box);
    assert_eq!(added.shape.center(), app.view().camera().target);
    assert_eq!(app.item(), Item::Object(before));
    assert!(app.document().is_dirty());

    choose(&mut app, Key::Color(rastray::tui::state::fields::Axis::X));
    run(&mut app, typed("0.1"));
    assert_eq!(*app.mode(), Mode::Normal);
    assert_eq!(app.document().scene().objects[before].material.color.x, 0.1);
    // Stepping up by ten steps of 0.05 adds 0.5.
    run(&mut app, [Action::Step(10)]);
    assert!((app.document().scene().objects[before].material.color.x - 0.6).abs() < 1e-6);
}

#[test]
fn undo_and_redo_walk_the_history() {
    let mut app = app();
    let original = app.document().scene().clone();
    run(&mut app, [Action::Add(AddKind::Prism)]);
    let with_prism = app.document().scene().clone();
    run(&mut app, [Action::Add(AddKind::Light)]);
    let with_light = app.document().scene().clone();
    assert_eq!(with_light.lights.len(), original.lights.len() + 1);

    run(&mut app, [Action::Undo]);
    assert_eq!(*app.document().scene(), with_prism);
    run(&mut app, [Action::Undo]);
    assert_eq!(*app.document().scene(), original);
    run(&mut app, [Action::Undo]);
    assert_eq!(
        *app.document().scene(),
        original,
        "undo past the start changes nothing"
    );
    run(&mut app, [Action::Redo, Action::Redo]);
    assert_eq!(*app.document().scene(), with_light);
    run(&mut app, [Action::Undo, Action::Add(AddKind::Box)]);
    run(&mut app, [Action::Redo]);
    assert!(
        app.document().scene().lights.len() == original.lights.len(),
        "a new edit clears redo"
    );
}

#[test]
fn delete_and_duplicate() {
    let mut app = app();
    let n = app.document().scene().objects.len();
    select(&mut app, Item::Object(0));
    let floor = app.document().scene().objects[0].clone();
    run(&mut app, [Action::Duplicate]);
    assert_eq!(app.document().scene().objects.len(), n + 1);
    let copy = &app.document().scene().objects[1];
    assert_eq!(copy.shape.kind(), floor.shape.kind());
    assert_eq!(copy.material, floor.material);
    assert_eq!(
        copy.shape.center(),
        floor.shape.center() + Vec3::new(0.5, 0.0, 0.5)
    );
    assert_eq!(app.item(), Item::Object(1));

    run(&mut app, [Action::Remove]);
    assert_eq!(app.document().scene().objects.len(), n);
    select(&mut app, Item::Object(0));
    run(&mut app, [Action::Remove]);
    assert_eq!(app.document().scene().objects.len(), n - 1);
    assert!(
        app.document()
            .scene()
            .objects
            .iter()
            .all(|o| o.name != floor.name)
    );

    // The settings entry is not removable.
    select(&mut app, Item::Settings);
    let before = app.document().scene().clone();
    run(&mut app, [Action::Remove, Action::Duplicate]);
    assert_eq!(*app.document().scene(), before);
}

#[test]
fn invalid_typed_value_leaves_the_scene_unchanged() {
    let mut app = app();
    select(&mut app, Item::Object(1));
    let before = app.document().scene().clone();
    for (key, text) in [
        (Key::Diffuse, "1.5"),
        (Key::Radius, "-1"),
        (Key::Radius, "abc"),
        (Key::Subdivisions, "99"),
        (Key::Shininess, "nan"),
    ] {
        choose(&mut app, key);
        run(&mut app, typed(text));
        match app.mode() {
            Mode::Edit(line) => assert!(line.error.is_some(), "{text} shows an error"),
            other => panic!("{text}: expected to stay in edit mode, got {other:?}"),
        }
        assert_eq!(*app.document().scene(), before, "{text} changed the scene");
        run(&mut app, [Action::Cancel]);
    }
    assert!(!app.document().is_dirty());
    assert_eq!(app.document().undo_steps(), 0);
}

#[test]
fn stepping_keeps_to_the_range() {
    let mut app = app();
    select(&mut app, Item::Object(1));
    choose(&mut app, Key::Specular);
    run(
        &mut app,
        [Action::Step(10), Action::Step(10), Action::Step(10)],
    );
    assert_eq!(app.document().scene().objects[1].material.specular, 1.0);
    choose(&mut app, Key::Smooth);
    let smooth = app.document().scene().objects[1].smooth;
    run(&mut app, [Action::Step(1)]);
    assert_eq!(app.document().scene().objects[1].smooth, !smooth);
}

#[test]
fn vector_components_are_edited_one_at_a_time() {
    let mut app = app();
    select(&mut app, Item::Object(2));
    let Shape::Box { size, .. } = app.document().scene().objects[2].shape else {
        panic!("a box")
    };
    choose(&mut app, Key::Size(rastray::tui::state::fields::Axis::Y));
    run(&mut app, typed("3"));
    let Shape::Box { size: new, .. } = app.document().scene().objects[2].shape else {
        panic!("a box")
    };
    assert_eq!(new, Vec3::new(size.x, 3.0, size.z));
}

/// Orbit, pan and zoom, as the preview's keys and mouse send them.
fn look_around() -> Vec<Action> {
    vec![
        Action::Orbit {
            yaw: 10.0,
            pitch: 0.0,
        },
        Action::Orbit {
            yaw: 10.0,
            pitch: 5.0,
        },
        Action::Zoom(0.5),
        Action::Pan {
            right: 0.1,
            up: 0.0,
        },
        Action::DragStart { column: 50, row: 9 },
        Action::DragTo { column: 53, row: 9 },
        Action::DragEnd,
    ]
}

#[test]
fn looking_around_moves_the_view_and_leaves_the_document_clean() {
    let mut app = app();
    let home = app.document().scene().camera;
    assert_eq!(
        app.view().camera(),
        home,
        "the view starts at the scene's camera"
    );
    run(&mut app, look_around());
    let view = app.view().camera();
    assert_ne!(view, home, "the view moved");
    let distance = (view.position - view.target).length();
    let home_distance = (home.position - home.target).length();
    assert!((distance - home_distance * 0.5).abs() < 1e-3);
    assert_eq!(
        app.document().scene().camera,
        home,
        "the scene's camera stays"
    );
    assert!(!app.document().is_dirty());
    assert_eq!(
        app.document().generation(),
        0,
        "looking around reuses the world"
    );
    assert_eq!(app.document().undo_steps(), 0);
    run(&mut app, [Action::ResetView]);
    assert_eq!(app.view().camera(), home);
    assert!(!app.document().is_dirty());
}

#[test]
fn the_preview_looks_through_the_view() {
    let mut app = app();
    run(&mut app, look_around());
    let picture = ratatui::layout::Rect::new(0, 0, 40, 12);
    let wanted = rastray::tui::wanted(&app, picture, true).expect("a preview is wanted");
    assert_eq!(wanted.camera, app.view().camera());
    assert_ne!(wanted.camera, app.document().scene().camera);
    assert_eq!(wanted.generation, app.document().generation());
}

#[test]
fn copying_the_view_into_the_scene_is_an_undoable_edit() {
    let mut app = app();
    let home = app.document().scene().camera;
    run(&mut app, look_around());
    let view = app.view().camera();
    run(&mut app, [Action::SceneCameraFromView]);
    assert_eq!(app.document().scene().camera, view);
    assert!(app.document().is_dirty());
    assert_eq!(app.document().undo_steps(), 1);
    assert_eq!(app.document().generation(), 1);

    run(&mut app, [Action::Undo]);
    assert_eq!(
        app.document().scene().camera,
        home,
        "undo restores the old camera"
    );
    assert_eq!(app.view().camera(), home, "and the view shows it");
    run(&mut app, [Action::Redo]);
    assert_eq!(app.document().scene().camera, view);
    assert_eq!(app.view().camera(), view);

    // Once the scene's camera is the view, copying again changes nothing.
    run(&mut app, [Action::SceneCameraFromView]);
    assert_eq!(app.document().undo_steps(), 1);
}

#[test]
fn typing_a_camera_property_edits_the_scene_and_moves_the_view_there() {
    let mut app = app();
    run(&mut app, look_around());
    select(&mut app, Item::Settings);
    choose(
        &mut app,
        Key::CameraPosition(rastray::tui::state::fields::Axis::X),
    );
    run(&mut app, typed("1.5"));
    let camera = app.document().scene().camera;
    assert_eq!(camera.position.x, 1.5);
    assert_eq!(app.view().camera(), camera);
    assert!(app.document().is_dirty());
}

#[test]
fn the_generation_changes_exactly_when_the_document_does() {
    let dir = tempfile::tempdir().unwrap();
    let saved = dir.path().join("sub").join("g.toml");
    std::fs::create_dir(saved.parent().unwrap()).unwrap();
    let mut app = app();
    let mut steps: Vec<Vec<Action>> = look_around().into_iter().map(|a| vec![a]).collect();
    steps.extend([
        vec![Action::ResetView],
        vec![Action::Algorithm(Algorithm::Ray)],
        vec![Action::ToggleCompare],
        vec![Action::Help, Action::Cancel],
        vec![Action::Down],
        vec![Action::FocusNext],
        vec![Action::Down],
        vec![Action::Step(1)],
        vec![Action::Step(-1)],
        vec![
            Action::Edit,
            Action::Input('x'),
            Action::Submit,
            Action::Cancel,
        ],
        vec![Action::Add(AddKind::Box)],
        vec![Action::Duplicate],
        vec![Action::Remove],
        vec![Action::Undo],
        vec![Action::Redo],
        vec![Action::Redo],
        vec![Action::Orbit {
            yaw: 30.0,
            pitch: 0.0,
        }],
        vec![Action::SceneCameraFromView],
        vec![Action::SceneCameraFromView],
        vec![Action::SaveAs, Action::ClearInput],
        saved
            .display()
            .to_string()
            .chars()
            .map(Action::Input)
            .collect(),
        vec![Action::Submit],
        vec![Action::Save],
        vec![Action::Quit],
    ]);
    let mut changes = 0;
    for step in steps {
        let before = (
            app.document().scene().clone(),
            app.document().base_dir().to_path_buf(),
            app.document().generation(),
        );
        run(&mut app, step.clone());
        let changed = *app.document().scene() != before.0 || app.document().base_dir() != before.1;
        let bumps = app.document().generation() - before.2;
        assert_eq!(bumps, changed as u64, "{step:?}");
        changes += bumps;
    }
    // Two steps, add, duplicate, remove, undo, redo, the camera and the new folder; the refused
    // value, the redo with nothing to redo and the second copy of the view change nothing.
    assert_eq!(changes, 9, "the sequence changes the document nine times");
    assert!(app.should_quit(), "saved, so quitting does not ask");
}

#[test]
fn quitting_after_only_looking_around_does_not_ask() {
    let mut app = app();
    run(&mut app, look_around());
    run(&mut app, [Action::ResetView, Action::Quit]);
    assert!(app.should_quit());
    assert_eq!(*app.mode(), Mode::Normal);

    let mut app = self::app();
    run(&mut app, look_around());
    run(&mut app, [Action::SceneCameraFromView, Action::Quit]);
    assert_eq!(
        *app.mode(),
        Mode::ConfirmQuit,
        "a new scene camera is an edit"
    );
    assert!(!app.should_quit());
}

#[test]
fn saving_writes_the_scene_camera_and_opening_resets_the_view() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("cam.toml");
    let mut app = App::new(
        default_scene(),
        Some(path.clone()),
        dir.path().to_path_buf(),
    );
    let home = app.document().scene().camera;
    run(&mut app, [Action::Add(AddKind::Light)]);
    run(&mut app, look_around());
    run(&mut app, [Action::Save]);
    assert!(!app.document().is_dirty());
    let saved = rastray::scene::load(&path).unwrap();
    assert_eq!(saved.camera, home, "the view is not saved");
    assert_ne!(app.view().camera(), home);

    rastray::tui::update::open(&mut app, &path).unwrap();
    assert_eq!(
        app.view().camera(),
        home,
        "the view starts at the opened scene's camera"
    );
    assert!(!app.document().is_dirty());
}

#[test]
fn quitting_with_unsaved_edits_asks() {
    let mut app = app();
    run(&mut app, [Action::Quit]);
    assert!(app.should_quit(), "nothing to lose: quits at once");

    let mut app = self::app();
    run(&mut app, [Action::Add(AddKind::Icosahedron), Action::Quit]);
    assert_eq!(*app.mode(), Mode::ConfirmQuit);
    assert!(!app.should_quit());
    run(&mut app, [Action::Cancel]);
    assert_eq!(*app.mode(), Mode::Normal);
    run(&mut app, [Action::Quit, Action::QuitNow]);
    assert!(app.should_quit());
}

#[test]
fn save_asks_for_a_path_then_writes_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("mine.toml");
    let mut app = app();
    run(&mut app, [Action::Add(AddKind::Box), Action::Save]);
    assert!(matches!(app.mode(), Mode::Prompt(..)));
    run(&mut app, [Action::ClearInput]);
    run(
        &mut app,
        path.display().to_string().chars().map(Action::Input),
    );
    run(&mut app, [Action::Submit]);
    assert_eq!(*app.mode(), Mode::Normal);
    assert!(!app.document().is_dirty());
    assert_eq!(app.document().path(), Some(path.as_path()));
    let saved = rastray::scene::load(&path).unwrap();
    assert_eq!(saved, *app.document().scene());

    // Opening it again gives the same scene.
    let mut other = self::app();
    rastray::tui::update::open(&mut other, &path).unwrap();
    assert_eq!(*other.document().scene(), saved);
}

#[test]
fn keys_switch_algorithm_and_compare() {
    let mut app = app();
    run(&mut app, [Action::Algorithm(Algorithm::Ray)]);
    assert_eq!(app.view().algorithm(), Algorithm::Ray);
    run(&mut app, [Action::ToggleCompare]);
    assert!(app.view().compare());
    run(&mut app, [Action::Algorithm(Algorithm::Gouraud)]);
    assert!(!app.view().compare());
    assert_eq!(app.view().algorithm(), Algorithm::Gouraud);
}

#[test]
fn adding_a_missing_obj_is_refused() {
    let mut app = app();
    let before = app.document().scene().clone();
    run(&mut app, [Action::Add(AddKind::Mesh)]);
    run(&mut app, "no/such/model.obj".chars().map(Action::Input));
    run(&mut app, [Action::Submit]);
    match app.mode() {
        Mode::Prompt(_, line) => assert!(line.error.is_some()),
        other => panic!("expected the prompt to stay open, got {other:?}"),
    }
    assert_eq!(*app.document().scene(), before);
}

#[test]
fn typing_replaces_the_shown_value_and_backspace_edits_it() {
    let mut app = app();
    select(&mut app, Item::Object(1));
    choose(&mut app, Key::Radius);
    run(&mut app, [Action::Edit, Action::Input('2'), Action::Submit]);
    let Shape::Icosahedron { radius, .. } = app.document().scene().objects[1].shape else {
        panic!()
    };
    assert_eq!(radius, 2.0);
    // "2" → Backspace → "" → "15" … then Backspace keeps editing: "1".
    run(
        &mut app,
        [
            Action::Edit,
            Action::Backspace,
            Action::Input('1'),
            Action::Input('5'),
            Action::Backspace,
            Action::Submit,
        ],
    );
    let Shape::Icosahedron { radius, .. } = app.document().scene().objects[1].shape else {
        panic!()
    };
    assert_eq!(radius, 1.0);
}

#[test]
fn saving_into_another_folder_keeps_mesh_paths_pointing_at_their_models() {
    let dir = tempfile::tempdir().unwrap();
    let models = dir.path().join("models");
    std::fs::create_dir(&models).unwrap();
    std::fs::write(
        models.join("quad.obj"),
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\n",
    )
    .unwrap();
    let mut app = App::new(default_scene(), None, dir.path().to_path_buf());
    run(&mut app, [Action::Add(AddKind::Mesh)]);
    run(&mut app, "models/quad.obj".chars().map(Action::Input));
    run(&mut app, [Action::Submit]);
    assert_eq!(
        *app.mode(),
        Mode::Normal,
        "the model is found relative to the scene's folder"
    );
    let mesh_path = |app: &App| match &app.document().scene().objects.last().unwrap().shape {
        Shape::Mesh { path, .. } => path.clone(),
        other => panic!("expected a mesh, got {other:?}"),
    };
    assert_eq!(mesh_path(&app), PathBuf::from("models/quad.obj"));
    run(&mut app, [Action::Add(AddKind::Light)]);

    // Save into a sub-folder: the saved scene must still find the model.
    let elsewhere = dir.path().join("scenes").join("copy.toml");
    std::fs::create_dir(elsewhere.parent().unwrap()).unwrap();
    run(&mut app, [Action::SaveAs]);
    run(&mut app, [Action::ClearInput]);
    run(
        &mut app,
        elsewhere.display().to_string().chars().map(Action::Input),
    );
    run(&mut app, [Action::Submit]);
    assert_eq!(*app.mode(), Mode::Normal);
    let saved = rastray::scene::load(&elsewhere).unwrap();
    rastray::World::build(&saved, elsewhere.parent().unwrap()).expect("the mesh still loads");
    assert_eq!(mesh_path(&app), PathBuf::from("../models/quad.obj"));
    // The history moved with the file: the scene before the light still finds the model.
    run(&mut app, [Action::Undo]);
    assert_eq!(mesh_path(&app), PathBuf::from("../models/quad.obj"));
}
