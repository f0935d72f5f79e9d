//! Applies an [`Action`] to the [`App`]: the one place the editor's state changes.

use std::path::{Path, PathBuf};

use glam::Vec3;

use super::action::Action;
use super::app::{
    AddKind, App, ExportField, ExportForm, Focus, Item, LineEdit, Mode, PromptPurpose, Shot,
    UNDO_LIMIT,
};
use super::export_job::ExportJob;
use super::fields::{self, Part};
use super::orbit;
use super::worker::{RenderReply, Slot};
use crate::render::{Algorithm, RenderOptions, Size};
use crate::scene::{Light, Object, Scene, Shape, ShapeKind};

/// Degrees turned per mouse column dragged.
const DRAG_YAW: f32 = 2.0;
/// Degrees turned per mouse row dragged (rows are about twice as tall as columns).
const DRAG_PITCH: f32 = 4.0;

/// Carries out `action`.
pub fn apply(app: &mut App, action: Action) {
    match action {
        Action::Rendered(reply) => return rendered(app, *reply),
        Action::Tick => return poll_export(app),
        _ => {}
    }
    match std::mem::take(&mut app.mode) {
        Mode::Normal => normal(app, action),
        Mode::Edit(line) => app.mode = edit(app, line, action),
        Mode::AddMenu(index) => app.mode = add_menu(app, index, action),
        Mode::Help(scroll) => match action {
            Action::Up => app.mode = Mode::Help(scroll.saturating_sub(1)),
            Action::Down => {
                app.mode = Mode::Help((scroll + 1).min(super::keys::KEYS.len().saturating_sub(1)))
            }
            _ => {}
        },
        Mode::Prompt(purpose, line) => app.mode = prompt(app, purpose, line, action),
        Mode::Export(form) => app.mode = export_form(app, form, action),
        Mode::ConfirmQuit => match action {
            Action::QuitNow => app.quit = true,
            Action::SaveAndQuit => {
                save(app);
                app.quit = !app.dirty;
            }
            Action::Cancel => {}
            _ => app.mode = Mode::ConfirmQuit,
        },
    }
}

fn normal(app: &mut App, action: Action) {
    match action {
        Action::Quit if app.dirty => app.mode = Mode::ConfirmQuit,
        Action::Quit | Action::QuitNow => app.quit = true,
        Action::FocusNext => app.focus = app.focus.next(),
        Action::FocusPrev => app.focus = app.focus.prev(),
        Action::Up | Action::Down => {
            let down = action == Action::Down;
            match app.focus {
                Focus::Properties => {
                    let n = field_keys(app).len();
                    app.field = move_index(app.field, n, down);
                }
                _ => {
                    let n = app.items().len();
                    app.selected = move_index(app.selected, n, down);
                    app.field = 0;
                }
            }
        }
        Action::Step(times) => step_field(app, times),
        Action::Edit => match app.focus {
            Focus::List => app.focus = Focus::Properties,
            _ => begin_edit(app),
        },
        Action::Help => app.mode = Mode::Help(0),
        Action::AddMenu => app.mode = Mode::AddMenu(0),
        Action::Add(kind) => add(app, kind),
        Action::Duplicate => duplicate(app),
        Action::Remove => remove(app),
        Action::Undo => undo(app),
        Action::Redo => redo(app),
        Action::Save => save(app),
        Action::SaveAs => {
            app.mode = Mode::Prompt(PromptPurpose::SaveAs, LineEdit::new(path_text(app)))
        }
        Action::Open => {
            // Offer the recovery file when there is one: the status line pointed at it.
            let recovered = super::recovery::path_for(app.path.as_deref());
            let text = if recovered.is_file() {
                recovered.display().to_string()
            } else {
                String::new()
            };
            app.mode = Mode::Prompt(PromptPurpose::Open, LineEdit::new(text));
        }
        Action::Export => open_export(app),
        Action::Algorithm(a) => {
            app.algorithm = a;
            app.compare = false;
        }
        Action::ToggleCompare => app.compare = !app.compare,
        Action::Orbit { yaw, pitch } => {
            move_camera(app, orbit::orbit(&app.scene.camera, yaw, pitch))
        }
        Action::Pan { right, up } => move_camera(app, orbit::pan(&app.scene.camera, right, up)),
        Action::Zoom(f) => move_camera(app, orbit::zoom(&app.scene.camera, f)),
        Action::ResetView => move_camera(app, app.home),
        Action::DragStart { column, row } => app.drag = Some((column, row)),
        Action::DragTo { column, row } => {
            if let Some((c0, r0)) = app.drag.replace((column, row)) {
                let yaw = -(column as f32 - c0 as f32) * DRAG_YAW;
                let pitch = (row as f32 - r0 as f32) * DRAG_PITCH;
                if yaw != 0.0 || pitch != 0.0 {
                    move_camera(app, orbit::orbit(&app.scene.camera, yaw, pitch));
                }
            }
        }
        Action::DragEnd => app.drag = None,
        Action::Cancel => cancel_export(app),
        _ => {}
    }
}

/// `i` moved one place up or down in a list of `n`, wrapping around.
fn move_index(i: usize, n: usize, down: bool) -> usize {
    match (n, down) {
        (0, _) => 0,
        (_, true) => (i + 1) % n,
        (_, false) => (i + n - 1) % n,
    }
}

/// The properties of the selected item.
pub fn field_keys(app: &App) -> Vec<fields::Key> {
    Part::of(&app.scene, app.item())
        .map(|p| p.keys())
        .unwrap_or_default()
}

fn chosen_key(app: &App) -> Option<fields::Key> {
    field_keys(app).get(app.field).copied()
}

/// Replaces the scene with `new` as one undoable edit.
fn commit(app: &mut App, new: Scene) {
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

fn move_camera(app: &mut App, camera: crate::scene::Camera) {
    let mut new = app.scene.clone();
    new.camera = camera;
    if crate::scene::validate(&new).is_ok() {
        commit(app, new);
    }
}

fn step_field(app: &mut App, times: i32) {
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

fn begin_edit(app: &mut App) {
    let Some(key) = chosen_key(app) else { return };
    let value = Part::of(&app.scene, app.item()).and_then(|p| p.value(key));
    let text = value.map(|v| v.to_string()).unwrap_or_default();
    app.focus = Focus::Properties;
    app.mode = Mode::Edit(LineEdit::new(text));
}

/// Applies typing keys to `line`; returns whether the action was one of them.
fn type_line(line: &mut LineEdit, action: &Action) -> bool {
    if matches!(action, Action::Input(_)) && line.pristine {
        line.text.clear();
    }
    let typed = type_into(&mut line.text, action);
    if typed {
        line.pristine = false;
        line.error = None;
    }
    typed
}

/// Applies typing keys to `text`; returns whether the action was one of them.
fn type_into(text: &mut String, action: &Action) -> bool {
    match action {
        Action::Input(c) if !c.is_control() => text.push(*c),
        Action::Backspace => {
            text.pop();
        }
        Action::ClearInput => text.clear(),
        _ => return false,
    }
    true
}

fn edit(app: &mut App, mut line: LineEdit, action: Action) -> Mode {
    if type_line(&mut line, &action) {
        return Mode::Edit(line);
    }
    match action {
        Action::Cancel => Mode::Normal,
        Action::Submit => {
            let Some(key) = chosen_key(app) else {
                return Mode::Normal;
            };
            match fields::typed(&app.scene, app.item(), key, &line.text) {
                Ok(new) => {
                    commit(app, new);
                    app.camera_streak = false;
                    Mode::Normal
                }
                Err(message) => {
                    line.error = Some(message);
                    Mode::Edit(line)
                }
            }
        }
        _ => Mode::Edit(line),
    }
}

fn add_menu(app: &mut App, index: usize, action: Action) -> Mode {
    let n = AddKind::ALL.len();
    match action {
        Action::Up | Action::Down => Mode::AddMenu(move_index(index, n, action == Action::Down)),
        Action::Submit => {
            add(app, AddKind::ALL[index.min(n - 1)]);
            std::mem::take(&mut app.mode)
        }
        Action::Add(kind) => {
            add(app, kind);
            std::mem::take(&mut app.mode)
        }
        Action::Cancel => Mode::Normal,
        _ => Mode::AddMenu(index),
    }
}

fn add(app: &mut App, kind: AddKind) {
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

fn add_object(app: &mut App, mut object: Object) {
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

fn select(app: &mut App, item: Item) {
    app.selected = app.index_of(item);
    app.field = 0;
}

fn duplicate(app: &mut App) {
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

fn remove(app: &mut App) {
    let mut new = app.scene.clone();
    let label = match app.item() {
        Item::Settings => return app.error("the camera and scene settings cannot be removed"),
        Item::Light(i) => new.lights.remove(i).name.unwrap_or_else(|| "light".into()),
        Item::Object(i) => new.objects.remove(i).label().to_string(),
    };
    commit(app, new);
    app.selected = app.selected.min(app.items().len() - 1);
    app.field = 0;
    app.info(format!("removed {}", super::text::clean(&label)));
}

fn restore(app: &mut App, scene: Scene) {
    app.scene = scene;
    app.generation += 1;
    app.dirty = true;
    app.camera_streak = false;
    app.selected = app.selected.min(app.items().len() - 1);
    app.field = app.field.min(field_keys(app).len().saturating_sub(1));
}

fn undo(app: &mut App) {
    match app.undo.pop() {
        Some(scene) => {
            let now = std::mem::replace(&mut app.scene, scene.clone());
            app.redo.push(now);
            restore(app, scene);
            app.info("undone");
        }
        None => app.error("nothing to undo"),
    }
}

fn redo(app: &mut App) {
    match app.redo.pop() {
        Some(scene) => {
            let now = std::mem::replace(&mut app.scene, scene.clone());
            app.undo.push(now);
            restore(app, scene);
            app.info("redone");
        }
        None => app.error("nothing to redo"),
    }
}

fn path_text(app: &App) -> String {
    app.path
        .as_ref()
        .map(|p| p.display().to_string())
        .unwrap_or_else(|| "scene.toml".into())
}

fn save(app: &mut App) {
    match app.path.clone() {
        Some(path) => save_to(app, &path).unwrap_or_else(|e| app.error(e)),
        None => app.mode = Mode::Prompt(PromptPurpose::SaveAs, LineEdit::new(path_text(app))),
    }
}

fn save_to(app: &mut App, path: &Path) -> Result<(), String> {
    crate::scene::save(&app.scene, path).map_err(|e| e.to_string())?;
    app.dirty = false;
    if app.path.as_deref() != Some(path) {
        app.base_dir = base_of(path);
        app.path = Some(path.to_path_buf());
        app.generation += 1;
    }
    app.info(format!("saved {}", path.display()));
    Ok(())
}

fn base_of(path: &Path) -> PathBuf {
    path.parent().map(Path::to_path_buf).unwrap_or_default()
}

fn prompt(app: &mut App, purpose: PromptPurpose, mut line: LineEdit, action: Action) -> Mode {
    if type_line(&mut line, &action) {
        return Mode::Prompt(purpose, line);
    }
    match action {
        Action::Cancel => return Mode::Normal,
        Action::Submit => {}
        _ => return Mode::Prompt(purpose, line),
    }
    let text = line.text.trim().to_string();
    if text.is_empty() {
        line.error = Some("type a path".into());
        return Mode::Prompt(purpose, line);
    }
    let path = PathBuf::from(&text);
    let result = match purpose {
        PromptPurpose::SaveAs => save_to(app, &path),
        PromptPurpose::Open => open(app, &path),
        PromptPurpose::ObjPath => {
            if app.base_dir.join(&path).is_file() {
                add_object(
                    app,
                    Object::new(Shape::new(ShapeKind::Mesh, app.scene.camera.target, path)),
                );
                Ok(())
            } else {
                Err(format!(
                    "{} is not a file",
                    app.base_dir.join(&path).display()
                ))
            }
        }
    };
    match result {
        Ok(()) => Mode::Normal,
        Err(message) => {
            line.error = Some(message);
            Mode::Prompt(purpose, line)
        }
    }
}

/// Replaces the scene with the one at `path`.
pub fn open(app: &mut App, path: &Path) -> Result<(), String> {
    let scene = crate::scene::load(path).map_err(|e| e.to_string())?;
    let mut fresh = App::new(scene, Some(path.to_path_buf()), base_of(path));
    fresh.algorithm = app.algorithm;
    fresh.compare = app.compare;
    fresh.color = app.color;
    fresh.show_timings = app.show_timings;
    fresh.generation = app.generation + 1;
    fresh.export = app.export.take();
    fresh.info(format!("opened {}", path.display()));
    *app = fresh;
    Ok(())
}

fn open_export(app: &mut App) {
    if app.export.is_some() {
        return app.error("an export is already running (Esc cancels it)");
    }
    let stem = app
        .path
        .as_ref()
        .and_then(|p| p.file_stem())
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "render".into());
    app.mode = Mode::Export(ExportForm {
        path: format!("{stem}.png"),
        size: "1920x1080".into(),
        algorithm: app.algorithm,
        samples: "1".into(),
        field: ExportField::Path,
        pristine: true,
        error: None,
    });
}

fn export_form(app: &mut App, mut form: ExportForm, action: Action) -> Mode {
    let fields = ExportField::ALL;
    let at = fields.iter().position(|&f| f == form.field).unwrap_or(0);
    let text = match form.field {
        ExportField::Path => Some(&mut form.path),
        ExportField::Size => Some(&mut form.size),
        ExportField::Samples => Some(&mut form.samples),
        ExportField::Algorithm => None,
    };
    if let Some(text) = text {
        // As in a spreadsheet: the first character typed into a field replaces its value.
        if form.pristine && matches!(action, Action::Input(_)) {
            text.clear();
        }
        if type_into(text, &action) {
            form.pristine = false;
            form.error = None;
            return Mode::Export(form);
        }
    }
    form.pristine = true;
    match action {
        Action::Cancel => return Mode::Normal,
        Action::Up | Action::FocusPrev => form.field = fields[move_index(at, fields.len(), false)],
        Action::Down | Action::FocusNext => form.field = fields[move_index(at, fields.len(), true)],
        Action::Step(n) if form.field == ExportField::Algorithm => {
            let i = Algorithm::ALL
                .iter()
                .position(|&a| a == form.algorithm)
                .unwrap_or(0);
            form.algorithm = Algorithm::ALL[(i as i32 + n.signum()).rem_euclid(3) as usize];
        }
        Action::Input(c @ '1'..='3') if form.field == ExportField::Algorithm => {
            form.algorithm = Algorithm::ALL[c as usize - '1' as usize];
        }
        Action::Submit => match start_export(app, &form) {
            Ok(()) => return Mode::Normal,
            Err(message) => form.error = Some(message),
        },
        _ => {}
    }
    Mode::Export(form)
}

fn start_export(app: &mut App, form: &ExportForm) -> Result<(), String> {
    let size: Size = form
        .size
        .parse()
        .map_err(|e: crate::render::SizeError| e.to_string())?;
    let samples: u32 = form
        .samples
        .trim()
        .parse()
        .map_err(|_| format!("`{}` is not a sample count", form.samples.trim()))?;
    let options = RenderOptions {
        samples,
        ..RenderOptions::new(form.algorithm, size.width, size.height)
    };
    options.check().map_err(|e| e.to_string())?;
    let path = PathBuf::from(form.path.trim());
    if path.as_os_str().is_empty() {
        return Err("type the PNG's path".into());
    }
    app.export = Some(ExportJob::start(
        app.scene.clone(),
        &app.base_dir,
        options,
        path.clone(),
    ));
    app.info(format!(
        "exporting {} ({} {size})…",
        path.display(),
        form.algorithm
    ));
    Ok(())
}

fn cancel_export(app: &mut App) {
    if let Some(job) = &app.export {
        job.progress.cancel();
        app.info("cancelling the export…");
    }
}

fn poll_export(app: &mut App) {
    if !app.export.as_ref().is_some_and(|j| j.is_finished()) {
        return;
    }
    let Some(job) = app.export.take() else { return };
    let path = job.path.clone();
    match job.finish() {
        Ok(ms) => app.info(format!("exported {} in {:.0} ms", path.display(), ms)),
        Err(message) => app.error(format!("export: {message}")),
    }
}

fn rendered(app: &mut App, reply: RenderReply) {
    match reply {
        RenderReply::Shot {
            slot,
            image,
            millis,
            triangles,
            ..
        } => {
            app.triangles = Some(triangles);
            let shot = Some(Shot { image, millis });
            match slot {
                Slot::Main => app.shot = shot,
                Slot::Compare(i) => {
                    if let Some(s) = app.compare_shots.get_mut(i) {
                        *s = shot;
                    }
                }
            }
        }
        RenderReply::Failed { message, .. } => app.error(message),
    }
}
