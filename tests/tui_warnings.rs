//! The editor shows scene warnings on its status line: when a scene opens with one, and when an
//! edit creates one; a warning already shown is not repeated by later edits.

use std::path::PathBuf;
use std::sync::Arc;
use std::sync::mpsc::channel;
use std::time::Duration;

use rastray::render::Algorithm;
use rastray::scene::{Scene, default_scene};
use rastray::tui::input::action::Action;
use rastray::tui::state::app::{App, Tone};
use rastray::tui::update::apply;
use rastray::tui::worker::{Job, RenderReply, Slot, Wanted, Worker};
use rastray::warnings::Warning;

/// A bound on waiting for the worker, so a broken one fails the test instead of hanging it.
const PATIENCE: Duration = Duration::from_secs(120);

fn unlit() -> Scene {
    let mut scene = default_scene();
    scene.lights.clear();
    scene
}

fn warned(warnings: Vec<Warning>) -> Action {
    Action::Rendered(Box::new(RenderReply::Warned { id: 1, warnings }))
}

fn status(app: &App) -> (String, Tone) {
    let s = app.status().expect("a status message");
    (s.text.clone(), s.tone)
}

#[test]
fn new_warnings_reach_the_status_line_once() {
    let mut app = App::new(unlit(), None, PathBuf::from("."));
    apply(&mut app, warned(vec![Warning::NoLights]));
    assert_eq!(
        status(&app),
        (
            "warning: the scene has no lights; only ambient light will show".into(),
            Tone::Error
        )
    );
    // A later world with the same warning does not cover the edit's own message.
    app.info("added box 2");
    apply(&mut app, warned(vec![Warning::NoLights]));
    assert_eq!(status(&app).0, "added box 2");
    // Fixed, then broken again: shown again.
    apply(&mut app, warned(vec![]));
    apply(&mut app, warned(vec![Warning::NoLights]));
    assert!(status(&app).0.contains("no lights"), "{:?}", status(&app));
}

#[test]
fn several_new_warnings_show_the_first_and_a_count() {
    let mut app = App::new(unlit(), None, PathBuf::from("."));
    let behind = |index| {
        Warning::BehindCamera(rastray::warnings::ObjectName {
            index,
            label: "box".into(),
        })
    };
    apply(
        &mut app,
        warned(vec![Warning::NoLights, behind(1), behind(2)]),
    );
    assert_eq!(
        status(&app).0,
        "warning: the scene has no lights; only ambient light will show (and 2 more)"
    );
}

fn request(worker: &mut Worker, scene: Scene, generation: u64) -> u64 {
    let wanted = Wanted {
        generation,
        camera: scene.camera,
        jobs: vec![Job {
            slot: Slot::Main,
            algorithm: Algorithm::Gouraud,
            width: 16,
            height: 12,
        }],
        display: Default::default(),
    };
    worker.request(wanted, Arc::new(scene), PathBuf::from("."))
}

/// Every reply to request `id`, up to and including its image.
fn replies(rx: &std::sync::mpsc::Receiver<RenderReply>, id: u64) -> Vec<RenderReply> {
    let mut got = Vec::new();
    loop {
        let reply = rx.recv_timeout(PATIENCE).expect("the worker answers");
        assert_eq!(reply.id(), id, "{reply:?}");
        let last = matches!(reply, RenderReply::Shot { last: true, .. });
        got.push(reply);
        if last {
            return got;
        }
    }
}

fn warnings_in(replies: &[RenderReply]) -> Option<Vec<Warning>> {
    replies.iter().find_map(|r| match r {
        RenderReply::Warned { warnings, .. } => Some(warnings.clone()),
        _ => None,
    })
}

#[test]
fn the_worker_reports_the_warnings_of_each_world_it_builds() {
    let (tx, rx) = channel();
    let mut worker = Worker::spawn(move |reply| {
        let _ = tx.send(reply);
    });
    // A scene without warnings gets images only.
    let id = request(&mut worker, default_scene(), 0);
    assert_eq!(warnings_in(&replies(&rx, id)), None);
    // An edit removes the lights: the new world's warning comes before its image.
    let id = request(&mut worker, unlit(), 1);
    let got = replies(&rx, id);
    assert!(matches!(got[0], RenderReply::Warned { .. }), "{got:?}");
    assert_eq!(warnings_in(&got), Some(vec![Warning::NoLights]));
    // A camera move reuses the world: nothing new to say.
    let id = request(&mut worker, unlit(), 1);
    assert_eq!(warnings_in(&replies(&rx, id)), None);
    // Lit again: an empty list says the warning is gone.
    let id = request(&mut worker, default_scene(), 2);
    assert_eq!(warnings_in(&replies(&rx, id)), Some(vec![]));
}
