//! Edits of the scene: stepping and typing values, adding, duplicating and removing items,
//! camera moves, undo and redo. Every change goes through [`commit`] as one undoable step.

use std::path::PathBuf;

use glam::Vec3;

use super::{chosen_key, field_keys};
use crate::scene::{Light, Object, Scene, Shape, ShapeKind};
use crate::tui::app::{AddKind, App, Focus, Item, LineEdit, Mode, PromptPurpose, UNDO_LIMIT};
use crate::tui::fields::{self, Part};

/// Replaces the scene with `new` as one undoable edit.
pub(super) fn commit(app: &mut App, new: Scene) {
    if new == app.scene {
        return;
    }
    let old = std::mem::replace(&mut app.scene, new);
    let camera_only = {
        let mut probe = app.scene.clone();
        probe.camera = old.camera;
        probe == old
    };
    if !(camera_only && app.camera_streak) {
        app.undo.push(old);
        if app.undo.len() > UNDO_LIMIT {
            app.undo.remove(0);
        }
    }
    app.camera_streak = camera_only;
    if !camera_only {
        app.generation += 1;
    }
    app.redo.clear();
    app.dirty = true;
}

pub(super) fn move_camera(app: &mut App, camera: crate::scene::Camera) {
    let mut new = app.scene.clone();
    new.camera = camera;
    if crate::scene::validate(&new).is_ok() {
        commit(app, new);
    }
}

pub(super) fn step_field(app: &mut App, times: i32) {
    if app.focus != Focus::Properties {
        return;
    }
    let Some(key) = chosen_key(app) else { return };
    match fields::stepped(&app.scene, app.item(), key, times) {
        Ok(new) => {
            commit(app, new);
            app.camera_streak = false;
        }
        Err(message) => {
            let label = Part::of(&app.scene, app.item()).map(|p| key.label(&p));
            app.error(format!("{}: {message}", label.unwrap_or_default()));
        }
    }
}

pub(super) fn begin_edit(app: &mut App) {
    let Some(key) = chosen_key(app) else { return };
    let value = Part::of(&app.scene, app.item()).and_then(|p| p.value(key));
    let text = value.map(|v| v.to_string()).unwrap_or_default();
    app.focus = Focus::Properties;
    app.mode = Mode::Edit(LineEdit::new(text));
}

pub(super) fn add(app: &mut App, kind: AddKind) {
    let center = app.scene.camera.target;
    let shape = match kind {
        AddKind::Icosahedron => ShapeKind::Icosahedron,
        AddKind::Box => ShapeKind::Box,
        AddKind::Prism => ShapeKind::Prism,
        AddKind::Mesh => {
            app.mode = Mode::Prompt(PromptPurpose::ObjPath, LineEdit::default());
            return;
        }
        AddKind::Light => {
            let n = app.scene.lights.len() + 1;
            let mut new = app.scene.clone();
            new.lights.push(Light {
                name: Some(format!("light {n}")),
                ..Light::default()
            });
            commit(app, new);
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
        .scene
        .objects
        .iter()
        .filter(|o| o.shape.kind() == kind)
        .count();
    object.name = Some(format!("{} {n}", kind.name()));
    let mut new = app.scene.clone();
    new.objects.push(object);
    let index = new.objects.len() - 1;
    commit(app, new);
    select(app, Item::Object(index));
    app.info(format!("added {} {n}", kind.name()));
}

pub(super) fn select(app: &mut App, item: Item) {
    app.selected = app.index_of(item);
    app.field = 0;
}

pub(super) fn duplicate(app: &mut App) {
    let mut new = app.scene.clone();
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
    commit(app, new);
    select(app, item);
    app.info("duplicated");
}

pub(super) fn remove(app: &mut App) {
    let mut new = app.scene.clone();
    let label = match app.item() {
        Item::Settings => return app.error("the camera and scene settings cannot be removed"),
        Item::Light(i) => new.lights.remove(i).name.unwrap_or_else(|| "light".into()),
        Item::Object(i) => new.objects.remove(i).label().to_string(),
    };
    commit(app, new);
    app.selected = app.selected.min(app.items().len() - 1);
    app.field = 0;
    app.info(format!("removed {}", crate::tui::text::clean(&label)));
}

pub(super) fn restore(app: &mut App, scene: Scene) {
    app.scene = scene;
    app.generation += 1;
    app.dirty = true;
    app.camera_streak = false;
    app.selected = app.selected.min(app.items().len() - 1);
    app.field = app.field.min(field_keys(app).len().saturating_sub(1));
}

pub(super) fn undo(app: &mut App) {
    travel(app, true);
}

pub(super) fn redo(app: &mut App) {
    travel(app, false);
}

/// Moves one step back (`back`) or forward through the history.
fn travel(app: &mut App, back: bool) {
    let (from, to) = if back {
        (&mut app.undo, &mut app.redo)
    } else {
        (&mut app.redo, &mut app.undo)
    };
    match from.pop() {
        Some(scene) => {
            to.push(std::mem::replace(&mut app.scene, scene.clone()));
            restore(app, scene);
            app.info(if back { "undone" } else { "redone" });
        }
        None => app.error(if back {
            "nothing to undo"
        } else {
            "nothing to redo"
        }),
    }
}
