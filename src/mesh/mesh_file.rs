//! The model file of a `mesh` object, read by the loader its extension names.

use std::path::Path;

use glam::Vec3;

use super::geometry::ModelGeometry;
use super::gltf::{GltfError, GltfModel, ImportWarning, load_gltf};
use super::obj::load_obj;
use super::obj_error::ObjError;

/// A loaded model file: OBJ (one geometry) or glTF (one part per primitive instance).
#[derive(Debug, Clone, PartialEq)]
pub enum MeshFile {
    Obj(ModelGeometry),
    Gltf(GltfModel),
}

/// Why a model file could not be loaded; the caller names the file.
#[derive(Debug, thiserror::Error)]
pub enum MeshFileError {
    /// A malformed or unreadable OBJ file.
    #[error(transparent)]
    Obj(#[from] ObjError),
    /// A malformed or unreadable glTF file.
    #[error(transparent)]
    Gltf(#[from] GltfError),
}

impl MeshFile {
    /// Whether `path` names a glTF file (`.gltf` or `.glb`, any case); every other file is read
    /// as OBJ.
    pub fn is_gltf(path: &Path) -> bool {
        path.extension()
            .and_then(|e| e.to_str())
            .is_some_and(|e| e.eq_ignore_ascii_case("gltf") || e.eq_ignore_ascii_case("glb"))
    }

    /// Reads the model at `path` with the loader its extension names.
    pub fn load(path: &Path) -> Result<MeshFile, MeshFileError> {
        if MeshFile::is_gltf(path) {
            Ok(MeshFile::Gltf(load_gltf(path)?))
        } else {
            load_obj(path)
                .map(MeshFile::Obj)
                .map_err(MeshFileError::Obj)
        }
    }

    /// Triangles over the whole file.
    pub fn triangle_count(&self) -> usize {
        match self {
            MeshFile::Obj(geometry) => geometry.triangles.len(),
            MeshFile::Gltf(model) => model.triangle_count(),
        }
    }

    /// Axis-aligned bounds (min, max) of the whole file, in its own space.
    pub fn bounds(&self) -> (Vec3, Vec3) {
        match self {
            MeshFile::Obj(geometry) => geometry.bounds(),
            MeshFile::Gltf(model) => model.bounds(),
        }
    }

    /// What the loader skipped; OBJ files report nothing.
    pub fn warnings(&self) -> &[ImportWarning] {
        match self {
            MeshFile::Obj(_) => &[],
            MeshFile::Gltf(model) => &model.warnings,
        }
    }
}
