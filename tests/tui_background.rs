//! The background threads: the preview worker (newest request wins) and the cancellable export.

use std::path::PathBuf;
use std::sync::Arc;
use std::sync::mpsc::channel;
use std::time::Duration;

use rastray::render::Algorithm;
use rastray::scene::default_scene;
use rastray::tui::input::action::Action;
use rastray::tui::state::app::{App, Tone};
use rastray::tui::state::mode::Mode;
use rastray::tui::update::apply;
use rastray::tui::worker::{Job, RenderReply, Slot, Wanted, Worker};

/// A bound on waiting for a thread, so a broken worker fails the test instead of hanging it.
const PATIENCE: Duration = Duration::from_secs(120);

fn wanted(algorithm: Algorithm, width: u32, height: u32, generation: u64) -> Wanted {
    Wanted {
        generation,
        camera: default_scene().camera,
        jobs: vec![Job {
            slot: Slot::Main,
            algorithm,
            width,
            height,
        }],
        display: Default::default(),
    }
}

#[test]
fn the_newest_request_wins() {
    let (tx, rx) = channel();
    let mut worker = Worker::spawn(move |reply| {
        let _ = tx.send(reply);
    });
    let scene = Arc::new(default_scene());
    let base = PathBuf::from(".");
    // A big render, then at once two small ones: the first two are superseded.
    let big = worker.request(
        wanted(Algorithm::Phong, 4000, 4000, 0),
        scene.clone(),
        base.clone(),
    );
    let middle = worker.request(
        wanted(Algorithm::Gouraud, 64, 48, 0),
        scene.clone(),
        base.clone(),
    );
    let last = worker.request(wanted(Algorithm::Gouraud, 32, 24, 0), scene, base);
    let mut seen = Vec::new();
    loop {
        let reply = rx.recv_timeout(PATIENCE).expect("the worker answers");
        // A world's bounds come with its first build, before any frame: not a frame.
        if let RenderReply::Bounds { .. } = reply {
            continue;
        }
        let RenderReply::Shot { id, image, .. } = reply else {
            panic!("unexpected failure: {reply:?}")
        };
        seen.push(id);
        if id == last {
            assert_eq!((image.width, image.height), (32, 24));
            break;
        }
    }
    assert!(
        seen.windows(2).all(|w| w[0] < w[1]),
        "replies arrive in request order: {seen:?}"
    );
    assert!(
        !seen.contains(&big),
        "the superseded big render was cancelled or skipped"
    );
    assert!(seen.iter().all(|&id| id == middle || id == last));
    std::thread::sleep(Duration::from_millis(50));
    assert!(
        rx.try_recv().is_err(),
        "nothing arrives after the newest request's frame"
    );
}

#[test]
fn a_failed_world_is_reported() {
    let (tx, rx) = channel();
    let mut worker = Worker::spawn(move |reply| {
        let _ = tx.send(reply);
    });
    let mut scene = default_scene();
    scene
        .objects
        .push(rastray::scene::Object::new(rastray::scene::Shape::new(
            rastray::scene::ShapeKind::Mesh,
            glam::Vec3::ZERO,
            PathBuf::from("missing.obj"),
        )));
    let id = worker.request(
        wanted(Algorithm::Phong, 16, 16, 1),
        Arc::new(scene),
        PathBuf::from("."),
    );
    match rx.recv_timeout(PATIENCE).expect("the worker answers") {
        RenderReply::Failed { id: got, message } => {
            assert_eq!(got, id);
            assert!(message.contains("missing.obj"), "{message}");
        }
        other => panic!("expected a failure, got {other:?}"),
    }
}

fn type_text(app: &mut App, text: &str) {
    apply(app, Action::ClearInput);
    for c in text.chars() {
        apply(app, Action::Input(c));
    }
}

/// Fills the export dialog and starts it.
fn export(app: &mut App, path: &str, size: &str, samples: &str) {
    apply(app, Action::Export);
    type_text(app, path);
    apply(app, Action::Down);
    type_text(app, size);
    apply(app, Action::Down);
    apply(app, Action::Down);
    type_text(app, samples);
    apply(app, Action::Submit);
}

fn wait_for_export(app: &mut App) {
    let start = std::time::Instant::now();
    while app.is_exporting() {
        assert!(start.elapsed() < PATIENCE, "the export thread ends");
        std::thread::sleep(Duration::from_millis(5));
        apply(app, Action::Tick);
    }
}

#[test]
fn export_writes_a_png_and_esc_cancels_one() {
    let dir = tempfile::tempdir().unwrap();
    let mut app = App::new(default_scene(), None, PathBuf::from("."));

    let small = dir.path().join("small.png");
    export(&mut app, small.to_str().unwrap(), "64x48", "2");
    assert_eq!(*app.mode(), Mode::Normal);
    wait_for_export(&mut app);
    let image = image::open(&small).expect("a PNG");
    assert_eq!((image.width(), image.height()), (64, 48));
    assert_eq!(app.status().unwrap().tone, Tone::Info);

    let big = dir.path().join("big.png");
    export(&mut app, big.to_str().unwrap(), "1024x1024", "8");
    assert!(app.is_exporting());
    apply(&mut app, Action::Cancel);
    wait_for_export(&mut app);
    let status = app.status().cloned().unwrap();
    assert_eq!(status.tone, Tone::Error, "{status:?}");
    assert!(status.text.contains("cancelled"), "{status:?}");
    assert!(!big.exists());
}

#[test]
fn a_bad_export_size_is_refused_in_the_dialog() {
    let mut app = App::new(default_scene(), None, PathBuf::from("."));
    export(&mut app, "x.png", "100000x5", "1");
    match app.mode() {
        Mode::Export(form) => assert!(form.error.is_some()),
        other => panic!("the dialog stays open, got {other:?}"),
    }
    assert!(!app.is_exporting());
}

#[test]
fn typing_in_an_export_field_replaces_its_value() {
    let mut app = App::new(default_scene(), None, PathBuf::from("."));
    apply(&mut app, Action::Export);
    for c in "a.png".chars() {
        apply(&mut app, Action::Input(c));
    }
    apply(&mut app, Action::Down);
    apply(&mut app, Action::Backspace);
    match app.mode() {
        Mode::Export(form) => {
            assert_eq!(form.path, "a.png");
            assert_eq!(form.size, "1920x108", "Backspace edits the shown value");
        }
        other => panic!("the dialog is open, got {other:?}"),
    }
}

#[test]
fn the_export_looks_through_the_view() {
    let dir = tempfile::tempdir().unwrap();
    let mut app = App::new(default_scene(), None, PathBuf::from("."));
    apply(
        &mut app,
        Action::Orbit {
            yaw: 40.0,
            pitch: 10.0,
        },
    );
    let png = dir.path().join("view.png");
    export(&mut app, png.to_str().unwrap(), "48x32", "1");
    wait_for_export(&mut app);
    let exported = image::open(&png).expect("a PNG").to_rgb8().into_raw();

    // The same render as the preview's core call, from the view and from the scene's camera.
    let scene = default_scene();
    let world = Arc::new(rastray::World::build(&scene, std::path::Path::new(".")).unwrap());
    let options = rastray::RenderOptions::new(app.view().algorithm(), 48, 32);
    let from = |camera| {
        let mut frame = rastray::render::Frame::default();
        rastray::render::Renderer::new(options)
            .render(
                &world,
                &camera,
                &rastray::render::Progress::new(),
                &mut frame,
            )
            .unwrap();
        frame.to_srgb8()
    };
    assert_eq!(exported, from(app.view().camera()), "the view is exported");
    assert_ne!(exported, from(scene.camera), "not the scene's camera");
    assert!(!app.document().is_dirty());
}

#[test]
fn a_preview_past_the_memory_bound_is_refused_before_it_renders() {
    // 16384×16384 pixels of frame: 11.3 GB at 42 bytes a pixel, past the 6 GB bound.
    let (tx, rx) = channel();
    let mut worker = Worker::spawn(move |reply| {
        let _ = tx.send(reply);
    });
    let id = worker.request(
        wanted(Algorithm::Phong, 16384, 16384, 0),
        Arc::new(default_scene()),
        PathBuf::from("."),
    );
    loop {
        match rx.recv_timeout(PATIENCE).expect("the worker answers") {
            RenderReply::Bounds { .. } => continue,
            RenderReply::Failed { id: got, message } => {
                assert_eq!(got, id);
                assert!(
                    message.starts_with("the preview: ") && message.contains("the memory bound is"),
                    "{message}"
                );
                break;
            }
            other => panic!("expected a refusal, got {other:?}"),
        }
    }
}
