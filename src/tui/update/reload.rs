//! Live reload: what other programs wrote to the scene file or its models, taken into the
//! editor on its ticks. The view camera, the selection and the undo history stay; a file that
//! no longer parses leaves the last good scene on screen with the error on the status line.

use std::path::Path;
use std::time::Instant;

use super::field_keys;
use crate::tui::persistence::disk_watch::DiskChange;
use crate::tui::state::app::App;

/// Looks at the watched files (at most every [`crate::tui::persistence::disk_watch::POLL_EVERY`]) and takes
/// in what changed.
pub(super) fn poll_disk(app: &mut App, now: Instant) {
    match app.disk.poll(&app.doc, now) {
        DiskChange::None => return,
        DiskChange::Models => {
            app.doc.models_changed();
            app.info("a model file changed on disk: reloaded");
        }
        DiskChange::Scene => reload_scene(app),
    }
    app.ticked_change = true;
}

/// Takes in the scene file as another program left it.
fn reload_scene(app: &mut App) {
    let Some(path) = app.doc.path().map(Path::to_path_buf) else {
        return;
    };
    // Models written together with the scene are read again with it.
    app.doc.models_changed();
    let shown = crate::tui::text::clean(&path.display().to_string());
    match crate::scene::load(&path) {
        Err(e) => app.error(format!(
            "not reloaded, the last good scene stays: {}",
            crate::tui::text::clean(&e.to_string())
        )),
        // The editor's own save read back, or a write that changed nothing.
        Ok(scene) if scene == *app.doc.scene() => {}
        Ok(_) if app.doc.is_dirty() => app.error(format!(
            "not reloaded over unsaved edits: {shown} changed on disk (s saves the edits over it)"
        )),
        Ok(scene) => {
            app.doc.reload(scene);
            app.selection.clamp_item(app.items().len());
            app.selection.clamp_field(field_keys(app).len());
            app.info(format!("reloaded {shown} (u undoes)"));
        }
    }
}
