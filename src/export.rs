//! PNG export: 8-bit sRGB, written atomically; and the one function that renders a world
//! straight to a PNG file.

use std::path::Path;
use std::sync::Arc;

use crate::atomic_file::write_atomically;
use crate::render::{Frame, Progress, RenderError, RenderOptions, RenderStats, Renderer};
use crate::scene::Camera;
use crate::world::World;

/// Why a PNG could not be rendered or written.
#[derive(Debug, thiserror::Error)]
pub enum ExportError {
    #[error(transparent)]
    Render(#[from] RenderError),
    #[error("{path}: cannot encode PNG: {message}")]
    Encode {
        path: std::path::PathBuf,
        message: String,
    },
    #[error("{path}: {error}")]
    Io {
        path: std::path::PathBuf,
        /// Shown in the message itself (not chained as a source, which would print it twice).
        error: std::io::Error,
    },
}

/// The frame as PNG bytes (8-bit sRGB, no alpha).
pub fn encode_png(frame: &Frame) -> Result<Vec<u8>, image::ImageError> {
    let mut bytes = Vec::new();
    let encoder = image::codecs::png::PngEncoder::new(&mut bytes);
    image::ImageEncoder::write_image(
        encoder,
        &frame.to_srgb8(),
        frame.width,
        frame.height,
        image::ExtendedColorType::Rgb8,
    )?;
    Ok(bytes)
}

/// Writes `frame` to `path` as a PNG, atomically.
pub fn save_png(frame: &Frame, path: &Path) -> Result<(), ExportError> {
    let bytes = encode_png(frame).map_err(|e| ExportError::Encode {
        path: path.to_path_buf(),
        message: e.to_string(),
    })?;
    write_atomically(path, &bytes).map_err(|error| ExportError::Io {
        path: path.to_path_buf(),
        error,
    })
}

/// Renders `world` seen by `camera` with `options` and writes the image to `path` as a PNG,
/// atomically: `rastray render` and the editor's export both come here. `progress` follows the
/// render and cancels it; the PNG is written only when the render finished.
pub fn render_to_png(
    world: &Arc<World>,
    camera: &Camera,
    options: &RenderOptions,
    path: &Path,
    progress: &Progress,
) -> Result<RenderStats, ExportError> {
    let mut frame = Frame::default();
    let stats = Renderer::new(*options).render(world, camera, progress, &mut frame)?;
    save_png(&frame, path)?;
    Ok(stats)
}
