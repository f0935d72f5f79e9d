//! Still images: a frame to a file in one format, and a world rendered straight to one.

use std::path::Path;
use std::sync::Arc;

use super::error::ExportError;
use super::exr::encode_exr;
use super::format::ImageFormat;
use super::png::encode_png;
use crate::atomic_file::write_atomically;
use crate::render::{Frame, Progress, RenderOptions, RenderStats, Renderer};
use crate::scene::Camera;
use crate::world::World;

/// The frame as the bytes of a file in `format`.
pub fn encode_image(frame: &Frame, format: ImageFormat) -> Result<Vec<u8>, image::ImageError> {
    match format {
        ImageFormat::Png(depth) => encode_png(frame, depth),
        ImageFormat::Exr => encode_exr(frame),
    }
}

/// Writes `frame` to `path` in `format`, atomically. A frame with alpha is written with alpha.
pub fn save_image(frame: &Frame, format: ImageFormat, path: &Path) -> Result<(), ExportError> {
    let bytes = encode_image(frame, format).map_err(|e| ExportError::encode(path, format, e))?;
    write_atomically(path, &bytes).map_err(|error| ExportError::io(path, error))
}

/// Renders `world` seen by `camera` with `options` and writes the image to `path` in `format`,
/// atomically. `progress` follows the render and cancels it; the file is written only when the
/// render finished.
pub fn render_image(
    world: &Arc<World>,
    camera: &Camera,
    options: &RenderOptions,
    format: ImageFormat,
    path: &Path,
    progress: &Progress,
) -> Result<RenderStats, ExportError> {
    let mut frame = Frame::default();
    let stats = Renderer::new(*options).render(world, camera, progress, &mut frame)?;
    save_image(&frame, format, path)?;
    Ok(stats)
}
