//! Files: saving, opening, typed paths, and the PNG export started from its dialog.

use std::path::{Path, PathBuf};

use super::edits::add_object;
use super::{type_into, type_line};
use crate::export::ImageFormat;
use crate::render::{Algorithm, RenderOptions, Size};
use crate::scene::{Object, Shape, ShapeKind};
use crate::tui::input::action::Action;
use crate::tui::persistence::export_job::{ExportJob, export_output};
use crate::tui::state::app::{App, Previews};
use crate::tui::state::mode::{ExportField, ExportForm, LineEdit, Mode, PromptPurpose};
use crate::tui::state::selection::{Selection, wrap_step};

pub(super) fn path_text(app: &App) -> String {
    app.doc
        .path()
        .map(|p| p.display().to_string())
        .unwrap_or_else(|| "scene.toml".into())
}

pub(super) fn save(app: &mut App) {
    match app.doc.path().map(Path::to_path_buf) {
        Some(path) => save_to(app, &path).unwrap_or_else(|e| app.error(e)),
        None => app.mode = Mode::Prompt(PromptPurpose::SaveAs, LineEdit::new(path_text(app))),
    }
}

pub(super) fn save_to(app: &mut App, path: &Path) -> Result<(), String> {
    app.doc.save_to(path).map_err(|e| e.to_string())?;
    app.disk.sync(&app.doc);
    app.info(format!("saved {}", path.display()));
    Ok(())
}

/// Where a typed OBJ path points: relative to the working directory, as in a shell, or else to
/// the scene's folder. `None` when neither is a file.
fn find_obj(typed: &Path, base_dir: &Path) -> Option<PathBuf> {
    [typed.to_path_buf(), base_dir.join(typed)]
        .into_iter()
        .find(|p| p.is_file())
}

pub(super) fn prompt(
    app: &mut App,
    purpose: PromptPurpose,
    mut line: LineEdit,
    action: Action,
) -> Mode {
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
        PromptPurpose::ObjPath => match find_obj(&path, app.doc.base_dir()) {
            Some(found) => {
                let stored = app.doc.stored_path(&found);
                let center = app.view.camera().target;
                add_object(
                    app,
                    Object::new(Shape::new(ShapeKind::Mesh, center, stored)),
                );
                Ok(())
            }
            None => Err(format!("{} is not a file", path.display())),
        },
    };
    match result {
        Ok(()) => Mode::Normal,
        Err(message) => {
            line.error = Some(message);
            Mode::Prompt(purpose, line)
        }
    }
}

/// Replaces the scene with the one at `path`; the view starts from its camera, and keeps its
/// algorithm and colours.
pub fn open(app: &mut App, path: &Path) -> Result<(), String> {
    app.doc.open(path).map_err(|e| e.to_string())?;
    app.disk.sync(&app.doc);
    app.view.look_from(app.doc.scene().camera);
    app.selection = Selection::default();
    app.previews = Previews::default();
    app.drag = None;
    app.info(format!("opened {}", path.display()));
    Ok(())
}

pub(super) fn open_export(app: &mut App) {
    if app.export.is_some() {
        return app.error("an export is already running (Esc cancels it)");
    }
    let stem = app
        .doc
        .path()
        .and_then(|p| p.file_stem())
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "render".into());
    app.mode = Mode::Export(ExportForm {
        path: format!("{stem}.png"),
        format: None,
        size: "1920x1080".into(),
        algorithm: app.view.algorithm(),
        transparent: false,
        samples: "1".into(),
        turntable: "0".into(),
        field: ExportField::Path,
        pristine: true,
        error: None,
    });
}

pub(super) fn export_form(app: &mut App, mut form: ExportForm, action: Action) -> Mode {
    let fields = ExportField::ALL;
    let at = fields.iter().position(|&f| f == form.field).unwrap_or(0);
    let text = match form.field {
        ExportField::Path => Some(&mut form.path),
        ExportField::Size => Some(&mut form.size),
        ExportField::Samples => Some(&mut form.samples),
        ExportField::Turntable => Some(&mut form.turntable),
        ExportField::Format | ExportField::Algorithm | ExportField::Background => None,
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
        Action::Up | Action::FocusPrev => form.field = fields[wrap_step(at, fields.len(), false)],
        Action::Down | Action::FocusNext => form.field = fields[wrap_step(at, fields.len(), true)],
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
        Action::Step(n) if form.field == ExportField::Format => step_format(&mut form, n),
        Action::Step(_) | Action::Input(' ') if form.field == ExportField::Background => {
            form.transparent = !form.transparent;
        }
        Action::Submit => match start_export(app, &form) {
            Ok(()) => return Mode::Normal,
            Err(message) => form.error = Some(message),
        },
        _ => {}
    }
    Mode::Export(form)
}

/// Moves the format choice one step through "by the name", then each format in `--format`
/// order; a named format also gives the file its extension, so name and bytes agree.
fn step_format(form: &mut ExportForm, n: i32) {
    let choices: Vec<Option<ImageFormat>> = std::iter::once(None)
        .chain(ImageFormat::ALL.map(Some))
        .collect();
    let at = choices.iter().position(|&c| c == form.format).unwrap_or(0);
    form.format = choices[(at as i32 + n.signum()).rem_euclid(choices.len() as i32) as usize];
    if let Some(format) = form.format {
        let path = Path::new(form.path.trim());
        if path.file_stem().is_some() {
            form.path = path
                .with_extension(format.extension())
                .to_string_lossy()
                .into_owned();
        }
    }
}

pub(super) fn start_export(app: &mut App, form: &ExportForm) -> Result<(), String> {
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
        alpha: form.transparent,
        // In the preview's display mode; overlays are the preview's and `--overlay`'s.
        mode: app.view.mode(),
        ..RenderOptions::new(form.algorithm, size.width, size.height)
    };
    options.check().map_err(|e| e.to_string())?;
    let path = PathBuf::from(form.path.trim());
    if path.as_os_str().is_empty() {
        return Err("type the file's path".into());
    }
    // The export shows what the preview shows: the scene as edited, seen from the view.
    let mut scene = app.doc.scene().clone();
    scene.camera = app.view.camera();
    let output = export_output(&path, form.format, &form.turntable)?;
    app.export = Some(ExportJob::start(
        scene,
        app.doc.base_dir(),
        options,
        output,
        path.clone(),
    ));
    app.info(format!(
        "exporting {} ({} {size})…",
        path.display(),
        form.algorithm
    ));
    Ok(())
}

pub(super) fn cancel_export(app: &mut App) {
    if let Some(job) = &app.export {
        job.progress.cancel();
        app.info("cancelling the export…");
    }
}

pub(super) fn poll_export(app: &mut App) {
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
