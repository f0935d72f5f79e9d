//! Errors met while reading, checking or writing a scene. Each names the file, and the line and
//! key where they are known.

use std::path::PathBuf;

use super::validate::Invalid;

/// A scene that could not be read, checked or written.
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    /// The file could not be read or written.
    #[error("{path}: {error}")]
    Io {
        path: PathBuf,
        /// Shown in the message itself (not chained as a source, which would print it twice).
        error: std::io::Error,
    },
    /// TOML syntax error, unknown key or wrong type.
    #[error("{path}{}: {message}", line.map(|l| format!(":{l}")).unwrap_or_default())]
    Parse {
        path: PathBuf,
        line: Option<usize>,
        message: String,
    },
    /// A value out of range (NaN, negative size, coefficient above 1 …).
    #[error("{path}{}: {error}", line.map(|l| format!(":{l}")).unwrap_or_default())]
    Invalid {
        path: PathBuf,
        /// 1-based line of the value, or of the nearest enclosing table the file spells out.
        line: Option<usize>,
        error: Invalid,
    },
    /// The scene would tessellate into more triangles than the renderers accept.
    #[error("the scene has {triangles} triangles; the limit is {limit}")]
    TooManyTriangles { triangles: u64, limit: u64 },
    /// An OBJ model referenced by the scene could not be loaded.
    #[error("{obj}: cannot load the OBJ model of object[{index}]: {message}")]
    Obj {
        index: usize,
        obj: PathBuf,
        message: String,
    },
}
