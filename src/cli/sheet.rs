//! `rastray render IN... --sheet sheet.png`: every input rendered as a thumbnail by the one
//! renderer, titled with its file's stem, laid out in one image. A file that fails is reported
//! on its own line and left out; the summary ends the run, exit code 1 when anything failed.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use rastray::export::{Destination, SheetLayout, Thumbnail, compose_sheet, save_sheet};
use rastray::render::{Frame, Progress, RenderOptions, Renderer, Size};
use rastray::text_escape::Escaped;

use super::batch_run::{Settings, load};

/// What the sheet looks like.
#[derive(Debug, Clone, Copy)]
pub struct SheetRequest<'a> {
    pub path: &'a Path,
    pub columns: Option<u32>,
    /// Each thumbnail's size, pixels.
    pub cell: Size,
}

/// Renders `inputs` (sorted here) into the sheet `request` describes.
pub fn run(
    inputs: &[PathBuf],
    settings: &Settings,
    request: SheetRequest,
) -> anyhow::Result<ExitCode> {
    let mut inputs: Vec<PathBuf> = inputs.to_vec();
    inputs.sort();
    inputs.dedup();
    if inputs.is_empty() {
        anyhow::bail!(
            "--sheet lays out the thumbnails of its inputs: name the files, as `rastray render models/* --sheet sheet.png`"
        );
    }
    let layout = SheetLayout::new(
        inputs.len(),
        request.columns,
        (request.cell.width, request.cell.height),
    );
    layout
        .check(inputs.len())
        .map_err(|e| anyhow::anyhow!("{}: {e}", shown(request.path)))?;
    let destination = Destination::for_path(request.path)?;
    destination.refuse_inputs(&inputs)?;
    let options = RenderOptions {
        width: request.cell.width,
        height: request.cell.height,
        alpha: false,
        ..settings.options
    };
    options.check()?;
    let mut renderer = Renderer::new(options);
    let mut frame = Frame::default();
    let progress = Progress::new();
    let mut thumbnails = Vec::with_capacity(inputs.len());
    let mut failed = Vec::new();
    for input in &inputs {
        let name = shown(input);
        let rendered = load(Some(input), settings, &inputs).and_then(|loaded| {
            destination.refuse_inputs(&loaded.files)?;
            // The first --view (and --ortho) places each thumbnail's camera.
            let aspect = request.cell.width as f32 / request.cell.height as f32;
            let camera = settings.camera.camera_for(
                settings.camera.view.first().copied(),
                &loaded.scene.camera,
                &loaded.world,
                aspect,
            );
            renderer.render(&loaded.world, &camera, &progress, &mut frame)?;
            Ok(frame.to_srgb8())
        });
        match rendered {
            Ok(pixels) => thumbnails.push(Thumbnail {
                title: input
                    .file_stem()
                    .map(|s| s.to_string_lossy().into_owned())
                    .unwrap_or_default(),
                pixels,
            }),
            Err(error) => {
                let message = Escaped(&format!("{error:#}")).to_string();
                let line = if message.starts_with(&name) {
                    format!("error: {message}")
                } else {
                    format!("error: {name}: {message}")
                };
                let _ = writeln!(std::io::stderr(), "{line}");
                failed.push(name);
            }
        }
    }
    let sheet = compose_sheet(&thumbnails, layout)
        .map_err(|e| anyhow::anyhow!("{}: {e}", shown(request.path)))?;
    save_sheet(&sheet, &destination, &progress)?;
    super::stdout::line(format_args!(
        "{} {} thumbnails of {} in {} columns: wrote {} ({}x{})",
        options.algorithm,
        thumbnails.len(),
        request.cell,
        layout.columns,
        shown(request.path),
        sheet.width,
        sheet.height
    ));
    if failed.is_empty() {
        return Ok(ExitCode::SUCCESS);
    }
    let _ = writeln!(
        std::io::stderr(),
        "rendered {} of {} inputs; failed: {}",
        thumbnails.len(),
        inputs.len(),
        failed.join(", ")
    );
    Ok(ExitCode::from(1))
}

fn shown(path: &Path) -> String {
    Escaped(&path.display().to_string()).to_string()
}
