//! The model file of a `mesh` object, read by the loader of its format: the one its extension
//! names, or else the one its content shows.

use std::path::{Path, PathBuf};

use glam::Vec3;

use super::geometry::ModelGeometry;
use super::gltf::{GltfError, GltfModel, ImportWarning, load_gltf};
use super::model_format::{EXPECTED_MODEL, ModelFormat};
use super::obj::load_obj;
use super::obj_error::ObjError;
use super::ply::{PlyError, PlyModel, load_ply};
use super::stl::{StlError, StlModel, load_stl};

/// A loaded model file: OBJ, STL or PLY (one geometry each) or glTF (one part per primitive
/// instance).
#[derive(Debug, Clone, PartialEq)]
pub enum MeshFile {
    Obj(ModelGeometry),
    Gltf(GltfModel),
    Stl(StlModel),
    Ply(PlyModel),
}

/// Why a model file could not be loaded. Every variant's message names the file but glTF's,
/// whose caller names it.
#[derive(Debug, thiserror::Error)]
pub enum MeshFileError {
    /// A malformed or unreadable OBJ file.
    #[error(transparent)]
    Obj(#[from] ObjError),
    /// A malformed or unreadable glTF file.
    #[error(transparent)]
    Gltf(#[from] GltfError),
    /// A malformed or unreadable STL file.
    #[error(transparent)]
    Stl(#[from] StlError),
    /// A malformed or unreadable PLY file.
    #[error(transparent)]
    Ply(#[from] PlyError),
    /// The file could not be opened to learn its format.
    #[error("{}: {error}", path.display())]
    Io {
        path: PathBuf,
        error: std::io::Error,
    },
    /// Neither the extension nor the content names a model format.
    #[error("{}: not {EXPECTED_MODEL}", path.display())]
    Unrecognized { path: PathBuf },
}

impl MeshFile {
    /// Reads the model at `path` with the loader of its format: by extension, else by content.
    pub fn load(path: &Path) -> Result<MeshFile, MeshFileError> {
        let format = ModelFormat::of_file(path).map_err(|error| MeshFileError::Io {
            path: path.to_path_buf(),
            error,
        })?;
        Ok(match format {
            Some(ModelFormat::Obj) => MeshFile::Obj(load_obj(path)?),
            Some(ModelFormat::Gltf | ModelFormat::Glb) => MeshFile::Gltf(load_gltf(path)?),
            Some(ModelFormat::Stl) => MeshFile::Stl(load_stl(path)?),
            Some(ModelFormat::Ply) => MeshFile::Ply(load_ply(path)?),
            None => {
                return Err(MeshFileError::Unrecognized {
                    path: path.to_path_buf(),
                });
            }
        })
    }

    /// The one geometry of an OBJ, STL or PLY file; `None` for glTF (see its parts).
    pub fn geometry(&self) -> Option<&ModelGeometry> {
        match self {
            MeshFile::Obj(geometry) => Some(geometry),
            MeshFile::Stl(model) => Some(&model.geometry),
            MeshFile::Ply(model) => Some(&model.geometry),
            MeshFile::Gltf(_) => None,
        }
    }

    /// Every geometry of the file: one, or one per glTF part.
    pub fn geometries(&self) -> Vec<&ModelGeometry> {
        match self {
            MeshFile::Gltf(model) => model.parts.iter().map(|p| &p.geometry).collect(),
            _ => self.geometry().into_iter().collect(),
        }
    }

    /// The file's format and how it is written: `OBJ`, `glTF`, `GLB`, `STL binary`,
    /// `STL ASCII`, `PLY binary_little_endian`.
    pub fn format(&self) -> String {
        match self {
            MeshFile::Obj(_) => "OBJ".into(),
            MeshFile::Gltf(model) if model.binary => "GLB".into(),
            MeshFile::Gltf(_) => "glTF".into(),
            MeshFile::Stl(model) => format!("STL {}", model.encoding),
            MeshFile::Ply(model) => format!("PLY {}", model.encoding),
        }
    }

    /// Whether the model is drawn flat when the scene does not say: STL files, whose faces are
    /// usually a CAD model's flat facets. Every other format is smooth by default.
    pub fn flat_by_default(&self) -> bool {
        matches!(self, MeshFile::Stl(_))
    }

    /// Triangles over the whole file.
    pub fn triangle_count(&self) -> usize {
        self.geometries().iter().map(|g| g.triangles.len()).sum()
    }

    /// Axis-aligned bounds (min, max) of the whole file, in its own space.
    pub fn bounds(&self) -> (Vec3, Vec3) {
        match self {
            MeshFile::Gltf(model) => model.bounds(),
            _ => self
                .geometry()
                .map_or((Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)), |g| {
                    g.bounds()
                }),
        }
    }

    /// What the loader skipped; glTF files and PLY textures report anything.
    pub fn warnings(&self) -> &[ImportWarning] {
        match self {
            MeshFile::Gltf(model) => &model.warnings,
            MeshFile::Ply(model) => &model.warnings,
            _ => &[],
        }
    }
}
