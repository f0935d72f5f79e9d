//! PNG export: 8-bit sRGB, written atomically.

use std::path::Path;

use crate::atomic_file::write_atomically;
use crate::render::Frame;

/// Why a PNG could not be written.
#[derive(Debug, thiserror::Error)]
pub enum ExportError {
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
