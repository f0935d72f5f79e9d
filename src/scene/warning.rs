//! Warnings met while building a scene: parts of its model files that rastray does not draw.

use std::path::PathBuf;

use crate::mesh::gltf::ImportWarning;

/// Something a model file of object `index` holds that rastray skipped; the rest still draws.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{path}: object[{index}]: {warning}")]
pub struct SceneWarning {
    pub index: usize,
    /// The model file, as the scene's folder and the object's path make it.
    pub path: PathBuf,
    pub warning: ImportWarning,
}
