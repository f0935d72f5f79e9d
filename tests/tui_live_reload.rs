//! Live reload: the editor takes in a scene file (or a model, or a file a model pulls in, such as
//! its texture) rewritten by another program, keeps the view, the selection and the undo
//! history, and keeps the last good scene when the file no longer parses. Driven through
//! actions, without a terminal.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant, SystemTime};

use glam::Vec3;
use rastray::scene::{Scene, default_scene, to_toml_string};
use rastray::tui::input::action::Action;
use rastray::tui::state::app::App;
use rastray::tui::state::selection::Item;
use rastray::tui::update::apply;
use rastray::tui::worker::{Job, RenderReply, Slot, Wanted, Worker};

/// A bound on waiting for the editor to notice a write (it looks every 0.4 s).
const PATIENCE: Duration = Duration::from_secs(10);

/// Writes `text` to `path`, dated one second after the file's last write so that a file system
/// with coarse timestamps sees the change.
fn write(path: &Path, text: &str) {
    let before = std::fs::metadata(path).and_then(|m| m.modified()).ok();
    std::fs::write(path, text).unwrap();
    let after = before.map_or_else(SystemTime::now, |t| t + Duration::from_secs(1));
    let file = std::fs::File::options().write(true).open(path).unwrap();
    file.set_modified(after).unwrap();
}

/// An editor on the default scene saved at `dir/scene.toml`.
fn editor(dir: &Path) -> (App, PathBuf) {
    let path = dir.join("scene.toml");
    write(&path, &to_toml_string(&default_scene()));
    let scene = rastray::scene::load(&path).unwrap();
    (App::new(scene, Some(path.clone()), dir.to_path_buf()), path)
}

/// Ticks the editor until its status line starts with `expected`.
fn tick_until(app: &mut App, expected: &str) {
    let started = Instant::now();
    loop {
        apply(app, Action::Tick);
        if let Some(status) = app.status()
            && status.text.starts_with(expected)
        {
            return;
        }
        assert!(
            started.elapsed() < PATIENCE,
            "the status line never said {expected:?}: {:?}",
            app.status()
        );
        std::thread::sleep(Duration::from_millis(20));
    }
}

/// Moves the selection down the scene list to the first object.
fn select_first_object(app: &mut App) {
    while !matches!(app.item(), Item::Object(_)) {
        apply(app, Action::Down);
    }
}

/// The default scene with its first object's colour changed, as another editor would write it.
fn recoloured() -> Scene {
    let mut scene = default_scene();
    scene.objects[0].material.color = Vec3::new(0.1, 0.9, 0.2);
    scene
}

#[test]
fn a_rewritten_scene_is_taken_in_with_view_selection_and_history_kept() {
    let dir = tempfile::tempdir().unwrap();
    let (mut app, path) = editor(dir.path());
    apply(
        &mut app,
        Action::Orbit {
            yaw: 30.0,
            pitch: 10.0,
        },
    );
    select_first_object(&mut app);
    let (view, item) = (app.view().camera(), app.item());
    assert!(matches!(item, Item::Object(_)), "{item:?}");
    let generation = app.document().generation();

    write(&path, &to_toml_string(&recoloured()));
    tick_until(&mut app, "reloaded");
    assert_eq!(*app.document().scene(), recoloured());
    assert!(!app.document().is_dirty(), "the editor matches its file");
    assert!(
        app.document().generation() > generation,
        "the preview renders again"
    );
    assert_eq!(app.view().camera(), view, "the view stays where it was");
    assert_eq!(app.item(), item, "the selection stays");
    // The reload is one step of the history: undo brings back the scene from before it.
    apply(&mut app, Action::Undo);
    assert_eq!(*app.document().scene(), default_scene());
    assert!(app.document().is_dirty());
}

#[test]
fn a_file_that_no_longer_parses_keeps_the_last_good_scene_and_says_why() {
    let dir = tempfile::tempdir().unwrap();
    let (mut app, path) = editor(dir.path());
    let good = to_toml_string(&recoloured());
    assert!(good.contains("[[object]]"));
    let text = good.replacen("[[object]]", "[[object]\n", 1);
    write(&path, &text);
    tick_until(&mut app, "not reloaded");
    let status = app.status().unwrap().text.clone();
    let at = status.find("scene.toml:").expect("names the file");
    let line = &status[at + "scene.toml:".len()..];
    assert!(
        line.starts_with(|c: char| c.is_ascii_digit()),
        "and the line: {status}"
    );
    assert_eq!(*app.document().scene(), default_scene());
    // Mended, it is taken in.
    write(&path, &to_toml_string(&recoloured()));
    tick_until(&mut app, "reloaded");
    assert_eq!(*app.document().scene(), recoloured());
}

#[test]
fn unsaved_edits_are_not_replaced_by_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let (mut app, path) = editor(dir.path());
    // Step the first object's second property (its centre's x) here.
    select_first_object(&mut app);
    apply(&mut app, Action::FocusNext);
    apply(&mut app, Action::Down);
    apply(&mut app, Action::Step(1));
    assert!(app.document().is_dirty(), "an edit was made");
    let edited = app.document().scene().clone();
    write(&path, &to_toml_string(&recoloured()));
    tick_until(&mut app, "not reloaded over unsaved edits: ");
    assert_eq!(*app.document().scene(), edited);
}

#[test]
fn the_editors_own_save_is_not_taken_for_a_change() {
    let dir = tempfile::tempdir().unwrap();
    let (mut app, _path) = editor(dir.path());
    apply(
        &mut app,
        Action::Orbit {
            yaw: 10.0,
            pitch: 0.0,
        },
    );
    apply(&mut app, Action::SceneCameraFromView);
    apply(&mut app, Action::Save);
    let history = app.document().undo_steps();
    for _ in 0..30 {
        apply(&mut app, Action::Tick);
        std::thread::sleep(Duration::from_millis(20));
    }
    assert!(app.status().unwrap().text.starts_with("saved"));
    assert_eq!(app.document().undo_steps(), history);
}

#[test]
fn a_rewritten_model_is_read_again() {
    let dir = tempfile::tempdir().unwrap();
    let obj = dir.path().join("part.obj");
    write(&obj, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    let (scene, path) = part_scene(dir.path());
    let mut app = App::new(scene, Some(path), dir.path().to_path_buf());
    let generation = app.document().generation();
    write(&obj, "v 0 0 0\nv 2 0 0\nv 0 2 0\nf 1 2 3\n");
    tick_until(&mut app, "a model file changed on disk");
    assert!(
        app.document().generation() > generation,
        "the world is built again"
    );
    assert!(
        !app.document().is_dirty(),
        "the scene itself did not change"
    );
}

/// A folder holding `part.obj`, a textured triangle whose MTL names `wood.png` (a 2×2 image of
/// `color`), and the scene of it: the scene's path.
fn textured_obj(dir: &Path, color: [u8; 3]) -> PathBuf {
    write(
        &dir.join("part.obj"),
        "mtllib part.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n\
         usemtl wood\nf 1/1 2/2 3/3\n",
    );
    write(
        &dir.join("part.mtl"),
        "newmtl wood\nKd 1 1 1\nmap_Kd wood.png\n",
    );
    write_texture(&dir.join("wood.png"), color);
    part_scene(dir).1
}

/// The scene of one mesh object, `part.obj`, saved as `dir/scene.toml`: (scene, its path).
fn part_scene(dir: &Path) -> (Scene, PathBuf) {
    let mut scene = default_scene();
    scene.objects.truncate(1);
    scene.objects[0].shape = rastray::scene::Shape::new(
        rastray::scene::ShapeKind::Mesh,
        Vec3::ZERO,
        PathBuf::from("part.obj"),
    );
    let path = dir.join("scene.toml");
    write(&path, &to_toml_string(&scene));
    (scene, path)
}

/// Writes a 2×2 PNG of `color` to `path`, dated as [`write`] dates files.
fn write_texture(path: &Path, color: [u8; 3]) {
    let before = std::fs::metadata(path).and_then(|m| m.modified()).ok();
    image::RgbImage::from_pixel(2, 2, image::Rgb(color))
        .save(path)
        .unwrap();
    let after = before.map_or_else(SystemTime::now, |t| t + Duration::from_secs(1));
    let file = std::fs::File::options().write(true).open(path).unwrap();
    file.set_modified(after).unwrap();
}

#[test]
fn the_worker_names_the_files_a_model_pulls_in() {
    let dir = tempfile::tempdir().unwrap();
    let path = textured_obj(dir.path(), [200, 100, 50]);
    let scene = rastray::scene::load(&path).unwrap();
    let (tx, rx) = std::sync::mpsc::channel();
    let mut worker = Worker::spawn(move |reply| {
        let _ = tx.send(reply);
    });
    let wanted = Wanted {
        generation: 0,
        camera: scene.camera,
        jobs: vec![Job {
            slot: Slot::Main,
            algorithm: rastray::render::Algorithm::Gouraud,
            width: 16,
            height: 16,
        }],
        display: Default::default(),
    };
    worker.request(wanted, std::sync::Arc::new(scene), dir.path().to_path_buf());
    let files = loop {
        match rx.recv_timeout(PATIENCE).expect("the worker answers") {
            RenderReply::ModelFiles { files, .. } => break files,
            RenderReply::Shot { .. } => panic!("the files come before the first image"),
            _ => {}
        }
    };
    let names: Vec<_> = files.iter().filter_map(|f| f.file_name()).collect();
    assert_eq!(names, ["part.obj", "part.mtl", "wood.png"], "{files:?}");
}

#[test]
fn a_rewritten_texture_is_read_again_and_redrawn() {
    let dir = tempfile::tempdir().unwrap();
    let path = textured_obj(dir.path(), [200, 100, 50]);
    let scene = rastray::scene::load(&path).unwrap();
    // The texture's colour in the world built through one cache, as the worker keeps it.
    let mut cache = rastray::world::MeshFileCache::default();
    let texel = |cache: &mut rastray::world::MeshFileCache| {
        let report = rastray::World::build_report(&scene, dir.path(), cache).unwrap();
        let binding = report.world.objects[0].appearance.base_color.clone();
        (
            binding.expect("textured").texture.levels[0].texel(0, 0),
            report.inputs,
        )
    };
    let (before, inputs) = texel(&mut cache);
    let mut app = App::new(scene.clone(), Some(path), dir.path().to_path_buf());
    // What the worker says after building the world.
    apply(
        &mut app,
        Action::Rendered(Box::new(RenderReply::ModelFiles {
            id: 1,
            files: inputs,
        })),
    );
    let generation = app.document().generation();
    write_texture(&dir.path().join("wood.png"), [20, 180, 90]);
    tick_until(&mut app, "a model file changed on disk");
    assert!(
        app.document().generation() > generation,
        "the world is built again"
    );
    let (after, _) = texel(&mut cache);
    assert!(
        before[1] < 0.2 && after[1] > 0.4,
        "{before:?} then {after:?}"
    );
    // The MTL file is watched too (the status line already says a model changed: the
    // generation tells this change from that one).
    let generation = app.document().generation();
    write(
        &dir.path().join("part.mtl"),
        "newmtl wood\nKd 0.5 1 1\nmap_Kd wood.png\n",
    );
    let started = Instant::now();
    while app.document().generation() == generation {
        assert!(
            started.elapsed() < PATIENCE,
            "the MTL's change is never seen"
        );
        apply(&mut app, Action::Tick);
        std::thread::sleep(Duration::from_millis(20));
    }
}
