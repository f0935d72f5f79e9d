//! Why a benchmark run stopped, whichever of its stages failed.

use crate::render::RenderError;
use crate::scene::SceneError;

/// Why a benchmark run stopped: building or rendering a scene, or writing the report or plots.
#[derive(Debug, thiserror::Error)]
pub enum BenchError {
    #[error("building the benchmark scene: {0}")]
    Scene(#[from] SceneError),
    #[error("rendering the benchmark scene: {0}")]
    Render(#[from] RenderError),
    #[error("writing {path}: {source}")]
    Write {
        path: std::path::PathBuf,
        source: std::io::Error,
    },
    #[error("drawing {path}: {message}")]
    Plot {
        path: std::path::PathBuf,
        message: String,
    },
}
