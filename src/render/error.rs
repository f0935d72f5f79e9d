//! Why a render produced no image.

use super::options::SizeError;
use super::progress::Cancelled;

/// Why a render produced no image.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum RenderError {
    /// The options ask for a size or sample count beyond the limits.
    #[error(transparent)]
    Size(#[from] SizeError),
    /// [`crate::render::Progress::cancel`] was called.
    #[error(transparent)]
    Cancelled(#[from] Cancelled),
    /// The pool of render threads the options ask for could not be started.
    #[error("cannot start {threads} render threads: {message}")]
    Threads { threads: usize, message: String },
}
