//! The recovery file and the autosave that keeps it: what is written where, what is removed
//! when, and that an earlier session's file is never overwritten nor removed.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use rastray::scene::{default_scene, to_toml_string};
use rastray::tui::input::action::Action;
use rastray::tui::persistence::autosave::Autosave;
use rastray::tui::persistence::recovery::{self, RecoveryFile};
use rastray::tui::state::app::App;
use rastray::tui::state::mode::AddKind;
use rastray::tui::update::apply;

/// Longest wait for the background thread (slow CI machines included).
const TIMEOUT: Duration = Duration::from_secs(60);

/// An editor on `scene.toml` (the built-in scene, saved) in a fresh folder.
fn editor() -> (tempfile::TempDir, App, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("scene.toml");
    rastray::scene::save(&default_scene(), &path).unwrap();
    let app = App::new(
        default_scene(),
        Some(path.clone()),
        dir.path().to_path_buf(),
    );
    let recovery = recovery::path_for(Some(&path));
    (dir, app, recovery)
}

fn wait_until(what: &str, done: impl Fn() -> bool) {
    let start = Instant::now();
    while !done() {
        assert!(start.elapsed() < TIMEOUT, "{what} within {TIMEOUT:?}");
        std::thread::sleep(Duration::from_millis(20));
    }
}

/// The first failure the autosave reports for the status line.
fn first_problem(autosave: &mut Autosave, app: &App) -> String {
    let start = Instant::now();
    loop {
        if let Some(problem) = autosave.note(app) {
            return problem;
        }
        assert!(start.elapsed() < TIMEOUT, "no failure reported");
        std::thread::sleep(Duration::from_millis(20));
    }
}

fn holds(path: &Path, app: &App) -> bool {
    std::fs::read_to_string(path).is_ok_and(|t| t == to_toml_string(app.document().scene()))
}

#[test]
fn recovery_file_sits_next_to_the_scene() {
    assert_eq!(
        recovery::path_for(Some(Path::new("dir/room.toml"))),
        Path::new("dir/room.recovered.toml")
    );
    assert_eq!(
        recovery::path_for(None),
        Path::new("rastray-recovered.toml")
    );
}

#[test]
fn an_earlier_recovery_file_is_moved_aside_not_overwritten() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("scene.recovered.toml");
    std::fs::write(&path, "earlier").unwrap();
    let mut scene = default_scene();
    let mut file = RecoveryFile::default();
    file.write(&scene, &path).unwrap();
    let aside = dir.path().join("scene.recovered-1.toml");
    assert_eq!(std::fs::read_to_string(&aside).unwrap(), "earlier");
    assert_eq!(
        std::fs::read_to_string(&path).unwrap(),
        to_toml_string(&scene)
    );
    // Its own file it overwrites in place.
    scene.ambient = 0.5;
    file.write(&scene, &path).unwrap();
    assert_eq!(
        std::fs::read_to_string(&path).unwrap(),
        to_toml_string(&scene)
    );
    assert_eq!(recovery::moved_aside(&path), vec![aside.clone()]);
    let scene_path = dir.path().join("scene.toml");
    let notice = recovery::notice(Some(&scene_path)).unwrap();
    assert!(
        notice.contains("scene.recovered.toml (o opens it)"),
        "{notice}"
    );
    assert!(notice.contains("scene.recovered-1.toml"), "{notice}");
    // Removing takes its own file only.
    file.remove().unwrap();
    assert!(!path.exists());
    assert_eq!(std::fs::read_to_string(&aside).unwrap(), "earlier");
    let notice = recovery::notice(Some(&scene_path)).unwrap();
    assert!(notice.contains("scene.recovered-1.toml"), "{notice}");
}

#[test]
fn a_file_replaced_by_someone_else_is_not_removed() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("scene.recovered.toml");
    let mut file = RecoveryFile::default();
    file.write(&default_scene(), &path).unwrap();
    std::fs::write(&path, "another editor's").unwrap();
    file.remove().unwrap();
    assert_eq!(std::fs::read_to_string(&path).unwrap(), "another editor's");
}

#[test]
fn no_notice_without_a_recovery_file() {
    let dir = tempfile::tempdir().unwrap();
    assert_eq!(recovery::notice(Some(&dir.path().join("scene.toml"))), None);
}

#[test]
fn autosave_writes_unsaved_edits_and_saving_removes_them() {
    let (_dir, mut app, recovery) = editor();
    let mut autosave = Autosave::start().unwrap();
    assert_eq!(autosave.note(&app), None);
    apply(&mut app, Action::Add(AddKind::Box));
    assert!(app.document().is_dirty());
    autosave.note(&app);
    wait_until("the recovery file holds the edit", || {
        holds(&recovery, &app)
    });
    apply(&mut app, Action::Add(AddKind::Light));
    autosave.note(&app);
    wait_until("the recovery file holds the second edit", || {
        holds(&recovery, &app)
    });
    apply(&mut app, Action::Save);
    assert!(!app.document().is_dirty());
    autosave.note(&app);
    wait_until("saving removes the recovery file", || !recovery.exists());
    autosave.quit().unwrap();
}

#[test]
fn quitting_removes_the_recovery_file_even_before_it_was_due() {
    let (_dir, mut app, recovery) = editor();
    let mut autosave = Autosave::start().unwrap();
    apply(&mut app, Action::Add(AddKind::Box));
    autosave.note(&app);
    wait_until("the recovery file holds the edit", || {
        holds(&recovery, &app)
    });
    apply(&mut app, Action::Add(AddKind::Box));
    autosave.note(&app);
    // Quit and discard: the pending write is dropped with the file.
    autosave.quit().unwrap();
    assert!(!recovery.exists());
}

#[test]
fn flush_writes_at_once() {
    let (_dir, mut app, recovery) = editor();
    let mut autosave = Autosave::start().unwrap();
    apply(&mut app, Action::Add(AddKind::Box));
    autosave.note(&app);
    let written = autosave.flush(&app).expect("unsaved edits").unwrap();
    assert_eq!(written, recovery);
    assert!(holds(&recovery, &app));
}

#[test]
fn flush_without_edits_writes_nothing() {
    let (_dir, app, recovery) = editor();
    let autosave = Autosave::start().unwrap();
    assert!(autosave.flush(&app).is_none());
    assert!(!recovery.exists());
}

#[test]
fn edits_left_for_another_scene_stay_recoverable() {
    let (dir, mut app, recovery) = editor();
    let other = dir.path().join("other.toml");
    rastray::scene::save(&default_scene(), &other).unwrap();
    let mut autosave = Autosave::start().unwrap();
    apply(&mut app, Action::Add(AddKind::Box));
    autosave.note(&app);
    let edited = app.document().scene().clone();
    // Opening another scene drops the edits from the editor, not from the disk.
    rastray::tui::update::open(&mut app, &other).unwrap();
    autosave.note(&app);
    autosave.quit().unwrap();
    let kept = std::fs::read_to_string(&recovery).unwrap();
    assert_eq!(kept, to_toml_string(&edited));
}

#[test]
fn a_dropped_autosave_writes_what_it_was_given() {
    let (_dir, mut app, recovery) = editor();
    let mut autosave = Autosave::start().unwrap();
    apply(&mut app, Action::Add(AddKind::Box));
    autosave.note(&app);
    // As when a panic unwinds through the event loop.
    drop(autosave);
    assert!(holds(&recovery, &app));
}

#[test]
fn a_failed_write_is_reported_once() {
    let dir = tempfile::tempdir().unwrap();
    // The scene's folder does not exist: the recovery file cannot be written next to it.
    let path = dir.path().join("missing").join("scene.toml");
    let mut app = App::new(default_scene(), Some(path), dir.path().to_path_buf());
    let mut autosave = Autosave::start().unwrap();
    apply(&mut app, Action::Add(AddKind::Box));
    autosave.note(&app);
    let problem = first_problem(&mut autosave, &app);
    assert!(problem.contains("scene.recovered.toml"), "{problem}");
    assert_eq!(autosave.note(&app), None);
}

#[test]
fn a_link_planted_in_the_recovery_files_place_is_refused_and_reported() {
    let (dir, mut app, recovery) = editor();
    // A dangling link: following it would create the file it names.
    let victim = dir.path().join("victim.txt");
    std::os::unix::fs::symlink(&victim, &recovery).unwrap();
    let mut autosave = Autosave::start().unwrap();
    apply(&mut app, Action::Add(AddKind::Box));
    autosave.note(&app);
    let problem = first_problem(&mut autosave, &app);
    assert!(problem.contains("symlink"), "{problem}");
    assert!(!victim.exists(), "the link's target was not created");
    assert!(
        std::fs::symlink_metadata(&recovery)
            .unwrap()
            .file_type()
            .is_symlink(),
        "the link is left as it was"
    );
    // A link to an existing file is neither followed nor moved aside either.
    std::fs::write(&victim, "theirs").unwrap();
    let mut file = RecoveryFile::default();
    assert!(file.write(app.document().scene(), &recovery).is_err());
    assert_eq!(std::fs::read_to_string(&victim).unwrap(), "theirs");
}
