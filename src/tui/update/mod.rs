//! Applies an [`Action`] to the [`App`]: the one place the editor's state changes. The document
//! changes through [`crate::tui::state::document::Document`]'s methods and the view through
//! [`crate::tui::state::view_state::ViewState`]'s.

mod edits;
mod files;
mod reload;

pub use files::open;

use edits::{add, begin_edit, camera_from_view, duplicate, redo, remove, step_field, undo};
use files::{cancel_export, export_form, open_export, path_text, poll_export, prompt, save};

use super::worker::{RenderReply, Slot};
use crate::tui::input::action::Action;
use crate::tui::state::app::{App, Shot};
use crate::tui::state::fields::{self, Part};
use crate::tui::state::mode::{AddKind, LineEdit, Mode, PromptPurpose};
use crate::tui::state::selection::{Focus, wrap_step};

/// Degrees turned per mouse column dragged.
const DRAG_YAW: f32 = 2.0;
/// Degrees turned per mouse row dragged (rows are about twice as tall as columns).
const DRAG_PITCH: f32 = 4.0;

/// Carries out `action`.
pub fn apply(app: &mut App, action: Action) {
    match action {
        Action::Rendered(reply) => return rendered(app, *reply),
        Action::Tick => {
            poll_export(app);
            app.ticked_change |= app.view.spin(std::time::Instant::now());
            return reload::poll_disk(app, std::time::Instant::now());
        }
        Action::TerminalFocus(focused) => return app.view.set_terminal_focused(focused),
        _ => {}
    }
    let scene_camera = app.doc.scene().camera;
    match std::mem::take(&mut app.mode) {
        Mode::Normal => normal(app, action),
        Mode::Edit(line) => app.mode = edit(app, line, action),
        Mode::AddMenu(index) => app.mode = add_menu(app, index, action),
        Mode::Help(scroll) => match action {
            Action::Up => app.mode = Mode::Help(scroll.saturating_sub(1)),
            Action::Down => {
                app.mode = Mode::Help(
                    (scroll + 1).min(crate::tui::input::keys::KEYS.len().saturating_sub(1)),
                )
            }
            _ => {}
        },
        Mode::Prompt(purpose, line) => app.mode = prompt(app, purpose, line, action),
        Mode::Export(form) => app.mode = export_form(app, form, action),
        Mode::ConfirmQuit => match action {
            Action::QuitNow => app.quit = true,
            Action::SaveAndQuit => {
                save(app);
                app.quit = !app.doc.is_dirty();
            }
            Action::Cancel => {}
            _ => app.mode = Mode::ConfirmQuit,
        },
    }
    // The scene's camera changed (typed, undone, redone): the view goes there to show it.
    let camera = app.doc.scene().camera;
    if camera != scene_camera {
        app.view.look_from(camera);
    }
}

fn normal(app: &mut App, action: Action) {
    match action {
        Action::Quit if app.doc.is_dirty() => app.mode = Mode::ConfirmQuit,
        Action::Quit | Action::QuitNow => app.quit = true,
        Action::FocusNext => app.selection.focus_on(app.focus().next()),
        Action::FocusPrev => app.selection.focus_on(app.focus().prev()),
        Action::Up | Action::Down => {
            let down = action == Action::Down;
            match app.focus() {
                Focus::Properties => {
                    let n = field_keys(app).len();
                    app.selection.step_field(n, down);
                }
                _ => {
                    let n = app.items().len();
                    app.selection.step_item(n, down);
                }
            }
        }
        Action::Step(times) => step_field(app, times),
        Action::Edit => match app.focus() {
            Focus::List => app.selection.focus_on(Focus::Properties),
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
            let recovered = crate::tui::persistence::recovery::path_for(app.doc.path());
            let text = if recovered.is_file() {
                recovered.display().to_string()
            } else {
                String::new()
            };
            app.mode = Mode::Prompt(PromptPurpose::Open, LineEdit::new(text));
        }
        Action::Export => open_export(app),
        Action::Algorithm(a) => app.view.show_algorithm(a),
        Action::ToggleCompare => app.view.toggle_compare(),
        Action::CycleMode(steps) => app.view.cycle_mode(steps),
        Action::ToggleOverlay(kind) => app.view.toggle_overlay(kind),
        Action::Orbit { yaw, pitch } => app.view.orbit(yaw, pitch),
        Action::Pan { right, up } => app.view.pan(right, up),
        Action::Zoom(f) => app.view.zoom(f),
        Action::ResetView => app.view.look_from(app.doc.scene().camera),
        Action::StepPresetView(step) => app.view.step_preset(step, preview_aspect(app)),
        Action::FitAll => app.view.fit_all(preview_aspect(app)),
        Action::ToggleProjection => app.view.toggle_projection(),
        Action::ToggleSpin => app.view.toggle_spin(std::time::Instant::now()),
        Action::SceneCameraFromView => camera_from_view(app),
        Action::DragStart { column, row } => app.drag = Some((column, row)),
        Action::DragTo { column, row } => {
            if let Some((c0, r0)) = app.drag.replace((column, row)) {
                let yaw = -(column as f32 - c0 as f32) * DRAG_YAW;
                let pitch = (row as f32 - r0 as f32) * DRAG_PITCH;
                if yaw != 0.0 || pitch != 0.0 {
                    app.view.orbit(yaw, pitch);
                }
            }
        }
        Action::DragEnd => app.drag = None,
        Action::Cancel => cancel_export(app),
        _ => {}
    }
}

/// The properties of the selected item.
pub fn field_keys(app: &App) -> Vec<fields::Key> {
    Part::of(app.doc.scene(), app.item())
        .map(|p| p.keys())
        .unwrap_or_default()
}

fn chosen_key(app: &App) -> Option<fields::Key> {
    field_keys(app).get(app.field()).copied()
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
            match fields::typed(app.doc.scene(), app.item(), key, &line.text) {
                Ok(new) => {
                    app.doc.edit(new);
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
        Action::Up | Action::Down => Mode::AddMenu(wrap_step(index, n, action == Action::Down)),
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

fn rendered(app: &mut App, reply: RenderReply) {
    match reply {
        RenderReply::Shot {
            slot,
            image,
            millis,
            triangles,
            ..
        } => {
            app.previews.triangles = Some(triangles);
            let shot = Some(Shot {
                image,
                millis,
                coarse: None,
            });
            match slot {
                Slot::Main => app.previews.shot = shot,
                Slot::Compare(i) => {
                    if let Some(s) = app.previews.compare.get_mut(i) {
                        *s = shot;
                    }
                }
            }
        }
        RenderReply::Failed { message, .. } => app.error(message),
        RenderReply::Measured { measures, .. } => app.previews.measures = Some(measures),
        RenderReply::Shape {
            object,
            measurements,
            ..
        } => app.previews.shape = Some((object, measurements)),
        RenderReply::Warned { warnings, .. } => {
            let new: Vec<_> = warnings
                .iter()
                .filter(|w| !app.warnings.contains(w))
                .collect();
            if let Some(first) = new.first() {
                let more = match new.len() - 1 {
                    0 => String::new(),
                    n => format!(" (and {n} more)"),
                };
                app.error(format!("warning: {first}{more}"));
            }
            app.warnings = warnings;
        }
        RenderReply::Bounds { bounds, .. } => app.view.set_bounds(bounds),
        RenderReply::ModelFiles { files, .. } => app.disk.watch_model_files(files),
    }
}

/// Width / height of the preview last drawn (16:9 before the first): what a fit fills.
fn preview_aspect(app: &App) -> f32 {
    app.previews.shot.as_ref().map_or(16.0 / 9.0, |s| {
        s.image.width as f32 / s.image.height.max(1) as f32
    })
}
