//! glTF models in the editor: the add-mesh prompt takes `.glb` and `.gltf` paths, and a broken
//! model is reported by the preview worker, never a crash.

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::mpsc::channel;
use std::time::Duration;

use rastray::render::Algorithm;
use rastray::scene::{Shape, default_scene};
use rastray::tui::input::action::Action;
use rastray::tui::state::app::App;
use rastray::tui::state::mode::{AddKind, Mode};
use rastray::tui::update::apply;
use rastray::tui::worker::{Job, RenderReply, Slot, Wanted, Worker};

/// A bound on waiting for the worker, so a broken one fails the test instead of hanging it.
const PATIENCE: Duration = Duration::from_secs(120);

fn add_mesh(app: &mut App, typed: &str) {
    apply(app, Action::Add(AddKind::Mesh));
    for c in typed.chars() {
        apply(app, Action::Input(c));
    }
    apply(app, Action::Submit);
}

#[test]
fn the_add_mesh_prompt_takes_glb_and_gltf_files() {
    let base = Path::new(env!("CARGO_MANIFEST_DIR")).to_path_buf();
    let mut app = App::new(default_scene(), None, base.clone());
    let before = app.document().scene().objects.len();
    for typed in ["tests/data/gltf/box.glb", "tests/data/gltf/scene.gltf"] {
        add_mesh(&mut app, typed);
        assert_eq!(*app.mode(), Mode::Normal, "{typed} is accepted");
        match &app.document().scene().objects.last().expect("added").shape {
            Shape::Mesh { path, .. } => assert_eq!(path, &PathBuf::from(typed)),
            other => panic!("expected a mesh, got {other:?}"),
        }
    }
    assert_eq!(app.document().scene().objects.len(), before + 2);
    let world = rastray::World::build(app.document().scene(), &base).expect("the models load");
    // The default scene's objects, the box, and the five drawn primitives of scene.gltf.
    assert_eq!(world.objects.len(), before + 1 + 5);
}

#[test]
fn a_broken_glb_is_reported_by_the_preview_worker() {
    let dir = tempfile::tempdir().expect("tempdir");
    let glb = std::fs::read(Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/gltf/box.glb"))
        .expect("box.glb");
    std::fs::write(dir.path().join("cut.glb"), &glb[..glb.len() / 3]).expect("write");
    let mut app = App::new(default_scene(), None, dir.path().to_path_buf());
    add_mesh(&mut app, "cut.glb");
    assert_eq!(
        *app.mode(),
        Mode::Normal,
        "the file exists: the prompt takes it"
    );

    let (tx, rx) = channel();
    let mut worker = Worker::spawn(move |reply| {
        let _ = tx.send(reply);
    });
    let wanted = Wanted {
        generation: 1,
        camera: app.document().scene().camera,
        jobs: vec![Job {
            slot: Slot::Main,
            algorithm: Algorithm::Phong,
            width: 16,
            height: 16,
        }],
        display: Default::default(),
    };
    let id = worker.request(
        wanted,
        Arc::new(app.document().scene().clone()),
        dir.path().to_path_buf(),
    );
    match rx.recv_timeout(PATIENCE).expect("the worker answers") {
        RenderReply::Failed { id: got, message } => {
            assert_eq!(got, id);
            assert!(
                message.contains("cut.glb") && message.contains("truncated"),
                "{message}"
            );
        }
        other => panic!("expected a failure, got {other:?}"),
    }
}
