//! An OBJ file with its materials: the faces of each `usemtl` material become one part, drawn
//! with that material (as each glTF primitive is), from the MTL libraries the file names with
//! `mtllib`. Libraries and textures are read from the model's folder or below it, through
//! [`ModelFolder`]; one that is missing, unreadable or outside gives a warning, never a failure.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use super::geometry::ModelGeometry;
use super::gltf::ImportWarning;
use super::mtl::{MtlMaterial, parse_mtl};
use super::mtl_phong::phong_from_mtl;
use super::obj::{ObjRead, read_obj};
use super::obj_error::{ObjError, ObjProblem};
use super::texture::{Texture, load_texture};
use crate::memory_budget::Estimate;
use crate::model_folder::{ModelFolder, ReferenceKind};
use crate::scene::Material;

/// Largest MTL file read, in bytes: far beyond any real library.
pub const MAX_MTL_BYTES: u64 = 64 << 20;

/// One material's faces of an OBJ file.
#[derive(Debug, Clone, PartialEq)]
pub struct ObjPart {
    /// `material "Wood"`, or `no material` for faces before any `usemtl`; `None` when the file
    /// never says `usemtl` (its one part is the whole file).
    pub label: Option<String>,
    /// The faces, with the positions they use.
    pub geometry: ModelGeometry,
    /// The material's name as `usemtl` gives it.
    pub material_name: Option<String>,
    /// The MTL material mapped to Phong; `None` when the faces have none (or it is undefined).
    pub material: Option<Material>,
    /// The material's `map_Kd` texture as the MTL names it, and decoded; `None` when it has none
    /// or it could not be read.
    pub texture: Option<(String, Arc<Texture>)>,
}

/// An OBJ file as rastray draws it.
#[derive(Debug, Clone, PartialEq)]
pub struct ObjModel {
    /// One part per material, in the order `usemtl` first names them; never empty.
    pub parts: Vec<ObjPart>,
    /// What was skipped: libraries, lines of them, textures.
    pub warnings: Vec<ImportWarning>,
    /// The MTL files read, then the `map_Kd` textures named (read or not, to be watched),
    /// resolved, in the order the file names them.
    pub material_files: Vec<PathBuf>,
}

impl ObjModel {
    /// Every part's faces in one geometry is what [`super::load_obj`] gives; this is the
    /// triangle count over the parts.
    pub fn triangle_count(&self) -> usize {
        self.parts.iter().map(|p| p.geometry.triangles.len()).sum()
    }
}

/// Reads the OBJ at `path` and the materials its `mtllib` libraries define.
pub fn load_obj_model(path: &Path) -> Result<ObjModel, ObjError> {
    let read = read_obj(path)?;
    let folder = ModelFolder::of(path).map_err(|e| ObjError {
        path: path.to_path_buf(),
        line: None,
        problem: ObjProblem::Io(e),
    })?;
    let mut warnings = Vec::new();
    let mut material_files = Vec::new();
    let library = read_libraries(&read, &folder, &mut warnings, &mut material_files);
    let ObjRead {
        geometry,
        material_names,
        material_runs,
        ..
    } = read;
    let groups = triangles_by_material(&material_runs, geometry.triangles.len());
    let whole = groups.len() == 1;
    folder.textures().count_model(Estimate {
        triangles: geometry.triangles.len() as u64,
        objects: groups.len() as u64,
        ..Estimate::default()
    });
    let mut parts = Vec::with_capacity(groups.len());
    let mut geometry = Some(geometry);
    let mut textures = HashMap::new();
    for (slot, triangles) in groups {
        let name = slot.map(|m| material_names[m as usize].clone());
        let mtl = name.as_ref().and_then(|n| library.get(n.as_str()));
        if let (Some(name), None) = (&name, mtl) {
            warnings.push(ImportWarning::UnknownMaterial { name: name.clone() });
        }
        let texture = mtl.and_then(|m| {
            texture_of(
                m,
                &folder,
                &mut textures,
                &mut warnings,
                &mut material_files,
            )
        });
        if let Some(over) = folder.textures().refusal() {
            return Err(ObjError {
                path: path.to_path_buf(),
                line: None,
                problem: ObjProblem::OverBudget(over.figures()),
            });
        }
        let part_geometry = match (&geometry, whole) {
            (Some(_), true) => geometry.take().unwrap_or_default(),
            (Some(all), false) => all.subset(&triangles),
            (None, _) => ModelGeometry::default(),
        };
        parts.push(ObjPart {
            label: (!material_runs.is_empty()).then(|| match &name {
                Some(name) => format!("material \"{name}\""),
                None => "no material".to_string(),
            }),
            geometry: part_geometry,
            material_name: name,
            material: mtl.map(phong_from_mtl),
            texture,
        });
    }
    Ok(ObjModel {
        parts,
        warnings,
        material_files,
    })
}

/// The materials of every library `read` names, by name (a later definition wins), read inside
/// `folder`; what could not be read becomes a warning.
fn read_libraries(
    read: &ObjRead,
    folder: &ModelFolder,
    warnings: &mut Vec<ImportWarning>,
    files: &mut Vec<PathBuf>,
) -> HashMap<String, MtlMaterial> {
    let mut library = HashMap::new();
    for (line, text) in &read.libraries {
        for reference in library_names(text, folder) {
            let bytes = folder
                .read(reference, ReferenceKind::Path, MAX_MTL_BYTES, "an MTL file")
                .and_then(|bytes| Ok((folder.resolve(reference, ReferenceKind::Path)?, bytes)));
            let (resolved, bytes) = match bytes {
                Ok(found) => found,
                Err(error) => {
                    warnings.push(ImportWarning::MaterialLibraryNotRead {
                        reference: reference.to_string(),
                        line: *line,
                        reason: error.to_string(),
                    });
                    continue;
                }
            };
            files.push(resolved);
            let (materials, notes) = parse_mtl(&bytes);
            if let Some(first) = notes.first() {
                warnings.push(ImportWarning::MaterialLinesSkipped {
                    library: reference.to_string(),
                    line: first.line,
                    problem: first.problem,
                    count: notes.len(),
                });
            }
            for material in materials {
                library.insert(material.name.clone(), material);
            }
        }
    }
    library
}

/// The library files one `mtllib` statement names: the whole text when a file of that name
/// exists (names may hold spaces), else each word (the statement may list several).
fn library_names<'a>(text: &'a str, folder: &ModelFolder) -> Vec<&'a str> {
    let words: Vec<&str> = text.split_whitespace().collect();
    if words.len() > 1 && folder.resolve(text, ReferenceKind::Path).is_err() {
        words
    } else {
        vec![text]
    }
}

/// The `map_Kd` of `material`, read inside `folder` once per name (`loaded` keeps what was
/// read), or `None` with a warning when it cannot be read. The file it resolves to is added
/// to `files` once.
fn texture_of(
    material: &MtlMaterial,
    folder: &ModelFolder,
    loaded: &mut HashMap<String, Option<Arc<Texture>>>,
    warnings: &mut Vec<ImportWarning>,
    files: &mut Vec<PathBuf>,
) -> Option<(String, Arc<Texture>)> {
    let reference = material.diffuse_map.as_ref()?;
    let texture = loaded.entry(reference.clone()).or_insert_with(|| {
        files.extend(folder.resolve(reference, ReferenceKind::Path).ok());
        load_texture(folder, reference, ReferenceKind::Path)
            .map_err(|error| {
                warnings.push(ImportWarning::TextureNotRead {
                    material: material.name.clone(),
                    reference: reference.clone(),
                    reason: error.to_string(),
                })
            })
            .ok()
    });
    Some((reference.clone(), texture.clone()?))
}

/// The triangles of each material, in the order materials are first used: one group of all
/// `count` triangles when the file has no runs.
fn triangles_by_material(
    runs: &[(u32, Option<u32>)],
    count: usize,
) -> Vec<(Option<u32>, Vec<u32>)> {
    if runs.is_empty() {
        return vec![(None, Vec::new())];
    }
    let mut groups: Vec<(Option<u32>, Vec<u32>)> = Vec::new();
    let mut at: HashMap<Option<u32>, usize> = HashMap::new();
    for (k, &(start, material)) in runs.iter().enumerate() {
        let end = runs.get(k + 1).map_or(count as u32, |next| next.0);
        if start == end {
            continue;
        }
        let slot = *at.entry(material).or_insert_with(|| {
            groups.push((material, Vec::new()));
            groups.len() - 1
        });
        groups[slot].1.extend(start..end);
    }
    groups
}
