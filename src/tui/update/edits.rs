//! Edits of the scene: stepping and typing values, adding, duplicating and removing items,
//! setting the camera from the view, undo and redo. Every change is one undoable
//! [`crate::tui::state::document::Document::edit`].

use std::path::PathBuf;

use glam::Vec3;

use super::{chosen_key, field_keys};
use crate::scene::{Light, Object, Shape, ShapeKind};
use crate::tui::state::app::App;
use crate::tui::state::fields::{self, Part};
use crate::tui::state::mode::{AddKind, LineEdit, Mode, PromptPurpose};
use crate::tui::state::selection::{Focus, Item};

/// Makes the view the scene's camera, as one undoable edit.
pub(super) fn camera_from_view(app: &mut App) {
    let mut new = app.doc.scene().clone();
    new.camera = app.view.camera();
    if app.doc.edit(new) {
        app.info("the scene's camera is now the view (u undoes)");
    } else {
        app.info("the scene's camera already is the view");
    }
}

pub(super) fn step_field(app: &mut App, times: i32) {
    if app.focus() != Focus::Properties {
        return;
    }
    let Some(key) = chosen_key(app) else { return };
    match fields::stepped(app.doc.scene(), app.item(), key, times) {
        Ok(new) => {
            app.doc.edit(new);
        }
        Err(message) => {
            let label = Part::of(app.doc.scene(), app.item()).map(|p| key.label(&p));
            app.error(format!("{}: {message}", label.unwrap_or_default()));
        }
    }
}

pub(super) fn begin_edit(app: &mut App) {
    let Some(key) = chosen_key(app) else { return };
    let value = Part::of(app.doc.scene(), app.item()).and_then(|p| p.value(key));
    let text = value.map(|v| v.to_string()).unwrap_or_default();
    app.selection.focus_on(Focus::Properties);
    app.mode = Mode::Edit(LineEdit::new(text));
}

/// Adds an item of `kind` where the view looks.
pub(super) fn add(app: &mut App, kind: AddKind) {
    let center = app.view.camera().target;
    let shape = match kind {
        AddKind::Icosahedron => ShapeKind::Icosahedron,
        AddKind::Box => ShapeKind::Box,
        AddKind::Prism => ShapeKind::Prism,
        AddKind::Mesh => {
            app.mode = Mode::Prompt(PromptPurpose::ObjPath, LineEdit::default());
            return;
        }
        AddKind::Light => {
            let n = app.doc.scene().lights.len() + 1;
            let mut new = app.doc.scene().clone();
            new.lights.push(Light {
                name: Some(format!("light {n}")),
                ..Light::default()
            });
            app.doc.edit(new);
            select(app, Item::Light(n - 1));
            app.info("added a point light");
            return;
        }
    };
    add_object(app, Object::new(Shape::new(shape, center, PathBuf::new())));
}

pub(super) fn add_object(app: &mut App, mut object: Object) {
    let kind = object.shape.kind();
    let n = 1 + app
        .doc
        .scene()
        .objects
        .iter()
        .filter(|o| o.shape.kind() == kind)
        .count();
    object.name = Some(format!("{} {n}", kind.name()));
    let mut new = app.doc.scene().clone();
    new.objects.push(object);
    let index = new.objects.len() - 1;
    app.doc.edit(new);
    select(app, Item::Object(index));
    app.info(format!("added {} {n}", kind.name()));
}

pub(super) fn select(app: &mut App, item: Item) {
    app.selection.choose_item(app.index_of(item));
}

pub(super) fn duplicate(app: &mut App) {
    let mut new = app.doc.scene().clone();
    let item = match app.item() {
        Item::Settings => return app.error("the camera cannot be duplicated"),
        Item::Light(i) => {
            let mut light = new.lights[i].clone();
            light.name = light.name.map(|n| format!("{n} copy"));
            light.position += Vec3::new(0.5, 0.0, 0.5);
            new.lights.insert(i + 1, light);
            Item::Light(i + 1)
        }
        Item::Object(i) => {
            let mut object = new.objects[i].clone();
            object.name = Some(format!("{} copy", object.label()));
            let c = object.shape.center();
            object.shape.set_center(c + Vec3::new(0.5, 0.0, 0.5));
            new.objects.insert(i + 1, object);
            Item::Object(i + 1)
        }
    };
    app.doc.edit(new);
    select(app, item);
    app.info("duplicated");
}

pub(super) fn remove(app: &mut App) {
    let mut new = app.doc.scene().clone();
    let label = match app.item() {
        Item::Settings => return app.error("the camera and scene settings cannot be removed"),
        Item::Light(i) => new.lights.remove(i).name.unwrap_or_else(|| "light".into()),
        Item::Object(i) => new.objects.remove(i).label().to_string(),
    };
    app.doc.edit(new);
    app.selection.clamp_item(app.items().len());
    app.selection.choose_item(app.selection.item());
    app.info(format!("removed {}", crate::tui::text::clean(&label)));
}

pub(super) fn undo(app: &mut App) {
    travel(app, true);
}

pub(super) fn redo(app: &mut App) {
    travel(app, false);
}

/// Moves one step back (`back`) or forward through the history, keeping the selection on
/// existing entries.
fn travel(app: &mut App, back: bool) {
    let moved = if back { app.doc.undo() } else { app.doc.redo() };
    match (moved, back) {
        (true, _) => {
            app.selection.clamp_item(app.items().len());
            app.selection.clamp_field(field_keys(app).len());
            app.info(if back { "undone" } else { "redone" });
        }
        (false, true) => app.error("nothing to undo"),
        (false, false) => app.error("nothing to redo"),
    }
}
