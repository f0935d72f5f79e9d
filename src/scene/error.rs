//! Errors met while reading, checking or writing a scene. Each names the file, and the line and
//! key where they are known.

use std::path::PathBuf;

use super::validate::Invalid;
use crate::mesh::ObjError;

/// A scene that could not be read, checked or written.
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    /// The file could not be read or written.
    #[error("{}: {error}", path.display())]
    Io {
        path: PathBuf,
        /// Shown in the message itself (not chained as a source, which would print it twice).
        error: std::io::Error,
    },
    /// TOML syntax error, unknown key or wrong type.
    #[error("{}{}: {}{}", path.display(), at_line(*line), error.message().trim(), quoted(source_line))]
    Parse {
        path: PathBuf,
        /// 1-based line of the error, when the parser knows it.
        line: Option<usize>,
        /// That line's text, trimmed, when it has any.
        source_line: Option<String>,
        error: Box<toml::de::Error>,
    },
    /// A value out of range (NaN, negative size, coefficient above 1 …).
    #[error("{}{}: {error}", path.display(), at_line(*line))]
    Invalid {
        path: PathBuf,
        /// 1-based line of the value, or of the nearest enclosing table the file spells out.
        line: Option<usize>,
        error: Invalid,
    },
    /// The scene would tessellate into more triangles than the renderers accept.
    #[error("the scene has {triangles} triangles; the limit is {limit}")]
    TooManyTriangles { triangles: u64, limit: u64 },
    /// The world would take more memory than the bound allows.
    #[error("{0}")]
    OverBudget(crate::memory_budget::OverBudget),
    /// An OBJ model referenced by the scene could not be loaded.
    #[error("{}: cannot load the OBJ model of object[{index}]: {}", error.location(), error.problem)]
    Obj { index: usize, error: ObjError },
    /// A glTF model referenced by the scene could not be loaded.
    #[error("{path}: cannot load the glTF model of object[{index}]: {error}")]
    Gltf {
        index: usize,
        path: PathBuf,
        error: crate::mesh::gltf::GltfError,
    },
    /// An STL or PLY model referenced by the scene could not be loaded, or its file is no
    /// model.
    #[error("{}", model_message(*index, error))]
    Model {
        index: usize,
        error: crate::mesh::MeshFileError,
    },
}

/// The message of a model file of object `index` that could not be loaded: the file and
/// place first, as for OBJ.
fn model_message(index: usize, error: &crate::mesh::MeshFileError) -> String {
    use crate::mesh::MeshFileError;
    let (path, place, format, problem) = match error {
        MeshFileError::Stl(e) => (&e.path, e.place, "STL", e.problem.to_string()),
        MeshFileError::Ply(e) => (&e.path, e.place, "PLY", e.problem.to_string()),
        other => return format!("cannot load the model of object[{index}]: {other}"),
    };
    format!(
        "{}{place}: cannot load the {format} model of object[{index}]: {problem}",
        path.display()
    )
}

/// `:12` for line 12, nothing when the line is unknown.
fn at_line(line: Option<usize>) -> String {
    line.map(|l| format!(":{l}")).unwrap_or_default()
}

/// ` (in `text`)`, or nothing.
fn quoted(source_line: &Option<String>) -> String {
    source_line
        .as_ref()
        .map(|text| format!(" (in `{text}`)"))
        .unwrap_or_default()
}
