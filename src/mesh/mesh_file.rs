//! The model file of a `mesh` object, read by the loader of its format: the one its extension
//! names, or else the one its content shows.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use glam::Vec3;

use super::texture::{Appearance, Texture};
use crate::scene::Material;

use super::geometry::ModelGeometry;
use super::gltf::{GltfError, GltfInstance, GltfModel, ImportWarning, load_gltf, placed_bounds};
use super::model_format::{EXPECTED_MODEL, ModelFormat};
use super::obj_error::ObjError;
use super::obj_model::{ObjModel, load_obj_model};
use super::ply::{PlyError, PlyModel, load_ply};
use super::stl::{StlError, StlModel, load_stl};

/// A loaded model file: STL or PLY (one geometry each), OBJ (one part per material) or glTF
/// (one part per primitive instance).
#[derive(Debug, Clone, PartialEq)]
pub enum MeshFile {
    Obj(ObjModel),
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
            Some(ModelFormat::Obj) => MeshFile::Obj(load_obj_model(path)?),
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

    /// The parts the file is drawn as: one for STL and PLY, one per material for OBJ, one per
    /// primitive instance for glTF; never empty.
    pub fn parts(&self) -> Vec<ModelPart<'_>> {
        match self {
            MeshFile::Obj(model) => model
                .parts
                .iter()
                .map(|p| ModelPart {
                    label: p.label.as_deref(),
                    geometry: &p.geometry,
                    material: p.material,
                    texture: p.texture.as_ref().map(|(name, t)| (name.as_str(), t)),
                    appearance: Appearance::textured_by(p.texture.as_ref().map(|(_, t)| t)),
                    instances: &[],
                })
                .collect(),
            MeshFile::Gltf(model) => model
                .parts
                .iter()
                .map(|p| ModelPart {
                    label: Some(&p.label),
                    geometry: &p.geometry,
                    material: p.material,
                    texture: p
                        .appearance
                        .base_color
                        .as_ref()
                        .map(|b| (b.texture.name.as_str(), &b.texture)),
                    appearance: p.appearance.clone(),
                    instances: &p.instances,
                })
                .collect(),
            MeshFile::Stl(StlModel { geometry, .. }) => vec![ModelPart {
                label: None,
                geometry,
                material: None,
                texture: None,
                appearance: Appearance::plain(),
                instances: &[],
            }],
            MeshFile::Ply(PlyModel {
                geometry,
                appearance,
                ..
            }) => vec![ModelPart {
                label: None,
                geometry,
                material: None,
                texture: None,
                appearance: appearance.clone(),
                instances: &[],
            }],
        }
    }

    /// Every geometry of the file, one per part.
    pub fn geometries(&self) -> Vec<&ModelGeometry> {
        self.parts().into_iter().map(|p| p.geometry).collect()
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

    /// Triangles over the whole file, a shared part's counted once per instance: the
    /// triangles placed in the world.
    pub fn triangle_count(&self) -> usize {
        self.parts().iter().map(ModelPart::placed_triangles).sum()
    }

    /// Triangles the file stores: a shared part's counted once.
    pub fn stored_triangle_count(&self) -> usize {
        self.geometries().iter().map(|g| g.triangles.len()).sum()
    }

    /// Axis-aligned bounds (min, max) of the whole file, in its own space, every instance of a
    /// shared part placed; inverted (MAX, MIN) when empty.
    pub fn bounds(&self) -> (Vec3, Vec3) {
        placed_bounds(self.parts().into_iter().map(|p| (p.geometry, p.instances)))
    }

    /// What the loader skipped; glTF and OBJ files and PLY textures report it.
    pub fn warnings(&self) -> &[ImportWarning] {
        match self {
            MeshFile::Gltf(model) => &model.warnings,
            MeshFile::Obj(model) => &model.warnings,
            MeshFile::Ply(model) => &model.warnings,
            _ => &[],
        }
    }

    /// The files the model pulls in (glTF buffers and images, MTL libraries and their
    /// textures, a PLY's texture), in the order named.
    pub fn companion_files(&self) -> &[PathBuf] {
        match self {
            MeshFile::Gltf(model) => &model.buffer_files,
            MeshFile::Obj(model) => &model.material_files,
            MeshFile::Ply(model) => &model.texture_files,
            MeshFile::Stl(_) => &[],
        }
    }
}

/// One part of a model file as the world draws it.
#[derive(Debug, Clone)]
pub struct ModelPart<'a> {
    /// Which part, as `material "Wood"` or a glTF primitive's label; `None` for a file drawn
    /// whole.
    pub label: Option<&'a str>,
    pub geometry: &'a ModelGeometry,
    /// The file's material for the part, mapped to Phong; `None` when it gives none.
    pub material: Option<Material>,
    /// The part's colour texture: its name as the file gives it, and the decoded image.
    pub texture: Option<(&'a str, &'a Arc<Texture>)>,
    /// How the file draws the part: its colour texture and sampler, and its alpha mode.
    pub appearance: Appearance,
    /// Where a part shared by several glTF nodes is drawn (its geometry then in its mesh's
    /// space); empty for a part drawn once, in the model's space.
    pub instances: &'a [GltfInstance],
}

impl ModelPart<'_> {
    /// The triangles the part places in the world: its own, once per instance.
    pub fn placed_triangles(&self) -> usize {
        self.geometry.triangles.len() * self.instances.len().max(1)
    }

    /// The world objects it becomes: one per instance, or one.
    pub fn objects(&self) -> usize {
        self.instances.len().max(1)
    }
}
