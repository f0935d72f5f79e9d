//! The editor driven by Actions alone, checked against the scene each sequence should produce.

use std::path::PathBuf;

use glam::Vec3;
use rastray::render::Algorithm;
use rastray::scene::{Shape, ShapeKind, default_scene};
use rastray::tui::action::Action;
use rastray::tui::app::{AddKind, App, Focus, Item, Mode};
use rastray::tui::fields::Key;
use rastray::tui::update::{apply, field_keys};

fn app() -> App {
    App::new(default_scene(), None, PathBuf::from("."))
}

fn run(app: &mut App, actions: impl IntoIterator<Item = Action>) {
    for a in actions {
        apply(app, a);
    }
}

/// Moves the properties cursor to `key` of the selected item.
fn choose(app: &mut App, key: Key) {
    app.focus = Focus::Properties;
    app.field = field_keys(app)
        .iter()
        .position(|&k| k == key)
        .expect("the selected item has this property");
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
    let before = app.scene.objects.len();
    run(&mut app, [Action::AddMenu, Action::Down, Action::Submit]);
    assert_eq!(app.scene.objects.len(), before + 1);
    let added = app.scene.objects.last().unwrap();
    assert_eq!(added.shape.kind(), ShapeKind::Box);
    assert_eq!(added.shape.center(), app.scene.camera.target);
    assert_eq!(app.item(), Item::Object(before));
    assert!(app.dirty);

    choose(&mut app, Key::Color(rastray::tui::fields::Axis::X));
    run(&mut app, typed("0.1"));
    assert_eq!(app.mode, Mode::Normal);
    assert_eq!(app.scene.objects[before].material.color.x, 0.1);
    // Stepping up by ten steps of 0.05 adds 0.5.
    run(&mut app, [Action::Step(10)]);
    assert!((app.scene.objects[before].material.color.x - 0.6).abs() < 1e-6);
}

#[test]
fn undo_and_redo_walk_the_history() {
    let mut app = app();
    let original = app.scene.clone();
    run(&mut app, [Action::Add(AddKind::Prism)]);
    let with_prism = app.scene.clone();
    run(&mut app, [Action::Add(AddKind::Light)]);
    let with_light = app.scene.clone();
    assert_eq!(with_light.lights.len(), original.lights.len() + 1);

    run(&mut app, [Action::Undo]);
    assert_eq!(app.scene, with_prism);
    run(&mut app, [Action::Undo]);
    assert_eq!(app.scene, original);
    run(&mut app, [Action::Undo]);
    assert_eq!(app.scene, original, "undo past the start changes nothing");
    run(&mut app, [Action::Redo, Action::Redo]);
    assert_eq!(app.scene, with_light);
    run(&mut app, [Action::Undo, Action::Add(AddKind::Box)]);
    run(&mut app, [Action::Redo]);
    assert!(
        app.scene.lights.len() == original.lights.len(),
        "a new edit clears redo"
    );
}

#[test]
fn delete_and_duplicate() {
    let mut app = app();
    let n = app.scene.objects.len();
    let first = app.index_of(Item::Object(0));
    app.selected = first;
    let floor = app.scene.objects[0].clone();
    run(&mut app, [Action::Duplicate]);
    assert_eq!(app.scene.objects.len(), n + 1);
    let copy = &app.scene.objects[1];
    assert_eq!(copy.shape.kind(), floor.shape.kind());
    assert_eq!(copy.material, floor.material);
    assert_eq!(
        copy.shape.center(),
        floor.shape.center() + Vec3::new(0.5, 0.0, 0.5)
    );
    assert_eq!(app.item(), Item::Object(1));

    run(&mut app, [Action::Remove]);
    assert_eq!(app.scene.objects.len(), n);
    app.selected = first;
    run(&mut app, [Action::Remove]);
    assert_eq!(app.scene.objects.len(), n - 1);
    assert!(app.scene.objects.iter().all(|o| o.name != floor.name));

    // The settings entry is not removable.
    app.selected = 0;
    let before = app.scene.clone();
    run(&mut app, [Action::Remove, Action::Duplicate]);
    assert_eq!(app.scene, before);
}

#[test]
fn invalid_typed_value_leaves_the_scene_unchanged() {
    let mut app = app();
    app.selected = app.index_of(Item::Object(1));
    let before = app.scene.clone();
    for (key, text) in [
        (Key::Diffuse, "1.5"),
        (Key::Radius, "-1"),
        (Key::Radius, "abc"),
        (Key::Subdivisions, "99"),
        (Key::Shininess, "nan"),
    ] {
        choose(&mut app, key);
        run(&mut app, typed(text));
        match &app.mode {
            Mode::Edit(line) => assert!(line.error.is_some(), "{text} shows an error"),
            other => panic!("{text}: expected to stay in edit mode, got {other:?}"),
        }
        assert_eq!(app.scene, before, "{text} changed the scene");
        run(&mut app, [Action::Cancel]);
    }
    assert!(!app.dirty);
    assert!(app.undo.is_empty());
}

#[test]
fn stepping_keeps_to_the_range() {
    let mut app = app();
    app.selected = app.index_of(Item::Object(1));
    choose(&mut app, Key::Specular);
    run(
        &mut app,
        [Action::Step(10), Action::Step(10), Action::Step(10)],
    );
    assert_eq!(app.scene.objects[1].material.specular, 1.0);
    choose(&mut app, Key::Smooth);
    let smooth = app.scene.objects[1].smooth;
    run(&mut app, [Action::Step(1)]);
    assert_eq!(app.scene.objects[1].smooth, !smooth);
}

#[test]
fn vector_components_are_edited_one_at_a_time() {
    let mut app = app();
    app.selected = app.index_of(Item::Object(2));
    let Shape::Box { size, .. } = app.scene.objects[2].shape else {
        panic!("a box")
    };
    choose(&mut app, Key::Size(rastray::tui::fields::Axis::Y));
    run(&mut app, typed("3"));
    let Shape::Box { size: new, .. } = app.scene.objects[2].shape else {
        panic!("a box")
    };
    assert_eq!(new, Vec3::new(size.x, 3.0, size.z));
}

#[test]
fn camera_moves_share_one_undo_step_and_reset() {
    let mut app = app();
    let home = app.scene.camera;
    run(
        &mut app,
        [
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
        ],
    );
    assert_ne!(app.scene.camera, home);
    assert_eq!(app.generation, 0, "camera moves reuse the world");
    let moved = app.scene.camera;
    let distance = (moved.position - moved.target).length();
    let home_distance = (home.position - home.target).length();
    assert!((distance - home_distance * 0.5).abs() < 1e-3);
    assert_eq!(app.undo.len(), 1);
    run(&mut app, [Action::ResetView]);
    assert_eq!(app.scene.camera, home);
    run(&mut app, [Action::Undo]);
    assert_eq!(
        app.scene.camera, home,
        "one undo step undid the whole camera move"
    );
}

#[test]
fn quitting_with_unsaved_edits_asks() {
    let mut app = app();
    run(&mut app, [Action::Quit]);
    assert!(app.quit, "nothing to lose: quits at once");

    let mut app = self::app();
    run(&mut app, [Action::Add(AddKind::Icosahedron), Action::Quit]);
    assert_eq!(app.mode, Mode::ConfirmQuit);
    assert!(!app.quit);
    run(&mut app, [Action::Cancel]);
    assert_eq!(app.mode, Mode::Normal);
    run(&mut app, [Action::Quit, Action::QuitNow]);
    assert!(app.quit);
}

#[test]
fn save_asks_for_a_path_then_writes_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("mine.toml");
    let mut app = app();
    run(&mut app, [Action::Add(AddKind::Box), Action::Save]);
    assert!(matches!(app.mode, Mode::Prompt(..)));
    run(&mut app, [Action::ClearInput]);
    run(
        &mut app,
        path.display().to_string().chars().map(Action::Input),
    );
    run(&mut app, [Action::Submit]);
    assert_eq!(app.mode, Mode::Normal);
    assert!(!app.dirty);
    assert_eq!(app.path.as_deref(), Some(path.as_path()));
    let saved = rastray::scene::load(&path).unwrap();
    assert_eq!(saved, app.scene);

    // Opening it again gives the same scene.
    let mut other = self::app();
    rastray::tui::update::open(&mut other, &path).unwrap();
    assert_eq!(other.scene, saved);
}

#[test]
fn keys_switch_algorithm_and_compare() {
    let mut app = app();
    run(&mut app, [Action::Algorithm(Algorithm::Ray)]);
    assert_eq!(app.algorithm, Algorithm::Ray);
    run(&mut app, [Action::ToggleCompare]);
    assert!(app.compare);
    run(&mut app, [Action::Algorithm(Algorithm::Gouraud)]);
    assert!(!app.compare);
    assert_eq!(app.algorithm, Algorithm::Gouraud);
}

#[test]
fn adding_a_missing_obj_is_refused() {
    let mut app = app();
    let before = app.scene.clone();
    run(&mut app, [Action::Add(AddKind::Mesh)]);
    run(&mut app, "no/such/model.obj".chars().map(Action::Input));
    run(&mut app, [Action::Submit]);
    match &app.mode {
        Mode::Prompt(_, line) => assert!(line.error.is_some()),
        other => panic!("expected the prompt to stay open, got {other:?}"),
    }
    assert_eq!(app.scene, before);
}

#[test]
fn typing_replaces_the_shown_value_and_backspace_edits_it() {
    let mut app = app();
    app.selected = app.index_of(Item::Object(1));
    choose(&mut app, Key::Radius);
    run(&mut app, [Action::Edit, Action::Input('2'), Action::Submit]);
    let Shape::Icosahedron { radius, .. } = app.scene.objects[1].shape else {
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
    let Shape::Icosahedron { radius, .. } = app.scene.objects[1].shape else {
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
        app.mode,
        Mode::Normal,
        "the model is found relative to the scene's folder"
    );
    let mesh_path = |app: &App| match &app.scene.objects.last().unwrap().shape {
        Shape::Mesh { path, .. } => path.clone(),
        other => panic!("expected a mesh, got {other:?}"),
    };
    assert_eq!(mesh_path(&app), PathBuf::from("models/quad.obj"));

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
    assert_eq!(app.mode, Mode::Normal);
    let saved = rastray::scene::load(&elsewhere).unwrap();
    rastray::World::build(&saved, elsewhere.parent().unwrap()).expect("the mesh still loads");
    assert_eq!(mesh_path(&app), PathBuf::from("../models/quad.obj"));
}
