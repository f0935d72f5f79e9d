//! Still images: a frame to a file in one format, and a world rendered straight to one.

use std::io::Write;
use std::path::Path;
use std::sync::Arc;

use super::destination::Destination;
use super::error::ExportError;
use super::exr::encode_exr;
use super::format::ImageFormat;
use super::png::encode_png;
use crate::render::{Frame, Progress, RenderError, RenderOptions, RenderStats, Renderer};
use crate::scene::Camera;
use crate::world::World;

/// The frame as the bytes of a file in `format`.
pub fn encode_image(frame: &Frame, format: ImageFormat) -> Result<Vec<u8>, image::ImageError> {
    match format {
        ImageFormat::Png(depth) => encode_png(frame, depth),
        ImageFormat::Exr => encode_exr(frame),
    }
}

/// Writes `frame` to `path` in `format`: a regular file atomically, a FIFO or character
/// device as a stream ([`Destination`]). A frame with alpha is written with alpha.
pub fn save_image(frame: &Frame, format: ImageFormat, path: &Path) -> Result<(), ExportError> {
    save_image_to(
        frame,
        format,
        &Destination::for_path(path)?,
        &Progress::new(),
    )
}

/// Writes `frame` to `destination` in `format`. Once `progress` is cancelled nothing more is
/// written, and a file is not committed: its temporary file is removed.
pub fn save_image_to(
    frame: &Frame,
    format: ImageFormat,
    destination: &Destination,
    progress: &Progress,
) -> Result<(), ExportError> {
    let path = destination.path();
    let bytes = encode_image(frame, format).map_err(|e| ExportError::encode(path, format, e))?;
    progress.check().map_err(RenderError::from)?;
    let mut sink = destination.open(progress)?;
    sink.write_all(&bytes)
        .map_err(|error| ExportError::io(path, error))?;
    sink.commit(progress).map_err(|error| error.at(path))
}

/// Renders `world` seen by `camera` with `options` and writes the image to `destination` in
/// `format`. `progress` follows the render and cancels it; a file is written only when the
/// render finished and was not cancelled.
pub fn render_image(
    world: &Arc<World>,
    camera: &Camera,
    options: &RenderOptions,
    format: ImageFormat,
    destination: &Destination,
    progress: &Progress,
) -> Result<RenderStats, ExportError> {
    let mut frame = Frame::default();
    let stats = Renderer::new(*options).render(world, camera, progress, &mut frame)?;
    save_image_to(&frame, format, destination, progress)?;
    Ok(stats)
}
