//! Why an export failed.

use std::path::PathBuf;

use super::format::FormatError;
use super::turntable::TurntableError;
use crate::render::RenderError;

/// Why an image or turntable could not be rendered or written.
#[derive(Debug, thiserror::Error)]
pub enum ExportError {
    #[error(transparent)]
    Render(#[from] RenderError),
    #[error(transparent)]
    Format(#[from] FormatError),
    #[error(transparent)]
    Turntable(#[from] TurntableError),
    #[error("{}: cannot encode {format}: {message}", path.display())]
    Encode {
        path: PathBuf,
        /// The format being written, as a user names it.
        format: String,
        message: String,
    },
    /// The output is the scene file or one of the files it loads.
    #[error(
        "{}: this is {}, an input of the scene; refusing to write over it",
        path.display(),
        input.display()
    )]
    OutputIsInput { path: PathBuf, input: PathBuf },
    /// A frame given to a join that cannot be one of its frames.
    #[error("{}: {message}", path.display())]
    Join { path: PathBuf, message: String },
    #[error("{}: {error}", path.display())]
    Io {
        path: PathBuf,
        /// Shown in the message itself (not chained as a source, which would print it twice).
        error: std::io::Error,
    },
}

impl ExportError {
    /// An encoder's failure to write `format` to `path`.
    pub(super) fn encode(
        path: &std::path::Path,
        format: impl ToString,
        error: impl ToString,
    ) -> ExportError {
        ExportError::Encode {
            path: path.to_path_buf(),
            format: format.to_string(),
            message: error.to_string(),
        }
    }

    /// A failure to write `path`.
    pub(super) fn io(path: &std::path::Path, error: std::io::Error) -> ExportError {
        ExportError::Io {
            path: path.to_path_buf(),
            error,
        }
    }
}
