//! The render-ready world: every object tessellated into a world-space mesh, with the lights and
//! scene settings the renderers need. Built once per scene edit, shared by all three algorithms.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::{Arc, OnceLock};
use std::time::SystemTime;

use rayon::prelude::*;

use glam::Vec3;

use crate::instance::{Instance, SharedMesh};
use crate::memory_budget::{Estimate, distinct_texture_bytes};
use crate::mesh::texture::Appearance;
use crate::mesh::{
    Mesh, MeshFile, MeshFileError, ModelPart, Sphere, UniquePositions, instance_transform,
    placed_shape, shared_shape, tessellate, tessellate_part, tessellate_shared, with_corner_uvs,
};
use crate::scene::{
    Falloff, Light, Material, MaterialSource, Object, Scene, SceneError, SceneWarning, Shape,
};

/// Most triangles a world may hold: what the memory bound leaves for them
/// ([`crate::memory_budget`]).
pub use crate::memory_budget::MAX_TRIANGLES;

/// One tessellated object.
#[derive(Debug, Clone)]
pub struct WorldObject {
    /// World-space triangles and normals.
    pub mesh: Mesh,
    /// Surface material.
    pub material: Material,
    /// Texture and alpha cut-out beside the material (plain for primitives and untextured
    /// parts). A texture is drawn only where the mesh has texture coordinates.
    pub appearance: Appearance,
    /// Sphere enclosing the mesh: the first cull of the ray tracer.
    pub bounds: Sphere,
    /// The mesh's axis-aligned bounds (min, max), world units; `None` for an empty mesh. Kept
    /// so that the scene's bounds need no pass over every vertex (the 1.31M-triangle icosphere
    /// has 3.9M vertices: 8–12 ms on one thread).
    pub extent: Option<(glam::Vec3, glam::Vec3)>,
    /// The mesh's distinct positions, which the Z-buffer projects once each per frame: built on
    /// the Z-buffer's first use ([`WorldObject::unique`]), so a ray-traced render never holds
    /// them; `Some(None)` when the mesh's own positions are all distinct (a smooth mesh of a
    /// welded file), which then serve as they are.
    unique: OnceLock<Option<UniquePositions>>,
    /// The model file's texture coordinates at each corner of each triangle (index-aligned with
    /// `mesh.triangles`), when the file gives them; read by the `uv` display mode.
    pub corner_uvs: Option<Vec<[glam::Vec2; 3]>>,
    /// For an instance of a shared mesh: the mesh and its placement. Then `mesh`, `unique`
    /// and `corner_uvs` are empty, and the triangles are the shared mesh's, in its own space
    /// ([`WorldObject::local_mesh`]); `bounds` and `extent` are the placed mesh's, in the world.
    pub instance: Option<Instance>,
}

impl WorldObject {
    /// An object of `mesh` and `material`, with its bounds and distinct positions.
    pub fn new(mesh: Mesh, material: Material) -> WorldObject {
        WorldObject::with_appearance(mesh, material, Appearance::plain())
    }

    /// An object of `mesh`, `material` and `appearance`, with its bounds and distinct
    /// positions.
    pub fn with_appearance(mesh: Mesh, material: Material, appearance: Appearance) -> WorldObject {
        let extent = mesh.bounds();
        WorldObject {
            appearance,
            bounds: mesh.bounding_sphere(extent),
            extent,
            unique: OnceLock::new(),
            mesh,
            material,
            corner_uvs: None,
            instance: None,
        }
    }

    /// An object drawing `instance` with `material` and `appearance`: bounds of the placed
    /// mesh, nothing else of its own.
    pub fn instance_of(instance: Instance, material: Material, appearance: Appearance) -> Self {
        let extent = instance.extent();
        let bounds = match extent {
            Some((lo, hi)) => {
                let center = (lo + hi) * 0.5;
                Sphere {
                    center,
                    radius: instance.radius_about(center),
                }
            }
            None => Mesh::default().bounding_sphere(None),
        };
        WorldObject {
            mesh: Mesh::default(),
            material,
            appearance,
            bounds,
            extent,
            unique: OnceLock::from(None),
            corner_uvs: None,
            instance: Some(instance),
        }
    }

    /// The distinct positions of `mesh` and its triangles on them, for the Z-buffer: found on
    /// first use (a pass over every vertex), or `mesh`'s own when its positions are distinct.
    /// Empty for an instance (the Z-buffer draws [`WorldObject::placed`] copies).
    pub fn unique(&self) -> DistinctPositions<'_> {
        match self.unique.get_or_init(|| distinct_unless_all(&self.mesh)) {
            Some(unique) => DistinctPositions {
                positions: &unique.positions,
                triangles: &unique.triangles,
            },
            None => DistinctPositions {
                positions: &self.mesh.positions,
                triangles: &self.mesh.triangles,
            },
        }
    }

    /// This object, told that its mesh's positions are all distinct (so [`WorldObject::unique`]
    /// needs no pass to find them); any two equal ones are projected twice, with the same bits.
    fn with_distinct_positions(self) -> WorldObject {
        let _ = self.unique.set(None);
        self
    }

    /// The mesh the object's triangle indices refer to: its own (world space), or for an
    /// instance the shared one (in the mesh's own space).
    #[inline]
    pub fn local_mesh(&self) -> &Mesh {
        match &self.instance {
            Some(instance) => &instance.shared.mesh,
            None => &self.mesh,
        }
    }

    /// The corner texture coordinates of [`WorldObject::local_mesh`]'s triangles, when the
    /// file has them.
    pub fn local_corner_uvs(&self) -> Option<&[[glam::Vec2; 3]]> {
        match &self.instance {
            Some(instance) => instance.shared.corner_uvs.as_deref(),
            None => self.corner_uvs.as_deref(),
        }
    }

    /// The world positions and unit normals at the corners of triangle `triangle` of
    /// [`WorldObject::local_mesh`].
    #[inline]
    pub fn world_corners(&self, triangle: u32) -> ([Vec3; 3], [Vec3; 3]) {
        let mesh = self.local_mesh();
        let abc = mesh.triangles[triangle as usize];
        match &self.instance {
            Some(instance) => instance.corners(abc),
            None => (
                abc.map(|k| mesh.positions[k as usize]),
                abc.map(|k| mesh.normals[k as usize]),
            ),
        }
    }

    /// This object placed in the world: an instance becomes an object of its own with the
    /// shared mesh moved into world space; any other object is cloned.
    pub fn placed(&self) -> WorldObject {
        let Some(instance) = &self.instance else {
            return self.clone();
        };
        // A mirrored placement swaps its triangles' last two corners; per-corner values follow.
        let appearance = match instance.mirrors() {
            true => self.appearance.with_corners_swapped(),
            false => self.appearance.clone(),
        };
        let mut placed =
            WorldObject::with_appearance(instance.placed_mesh(), self.material, appearance);
        placed.corner_uvs = instance.placed_corner_uvs();
        placed
    }

    /// This object with the texture coordinates of `geometry`, the file it was tessellated
    /// from, when the file has them for each of the mesh's triangles.
    fn with_uvs_of(mut self, geometry: &crate::mesh::ModelGeometry) -> WorldObject {
        self.corner_uvs = corner_uvs_for(geometry, &self.mesh);
        self
    }

    /// Whether the object is drawn with a texture (it has one and texture coordinates).
    pub fn is_textured(&self) -> bool {
        self.appearance.base_color.is_some() && self.local_mesh().uvs.is_some()
    }
}

/// `geometry`'s corner texture coordinates, when it has one set a triangle of `mesh` (a mesh
/// tessellated from it, its triangles in the file's order).
fn corner_uvs_for(
    geometry: &crate::mesh::ModelGeometry,
    mesh: &Mesh,
) -> Option<Vec<[glam::Vec2; 3]>> {
    (geometry.corner_uvs.as_ref())
        .filter(|uvs| uvs.len() == mesh.triangles.len())
        .cloned()
}

/// A mesh's distinct positions and its triangles' corners as indices into them
/// ([`UniquePositions`], or the mesh's own positions and triangles when they are distinct).
#[derive(Debug, Clone, Copy)]
pub struct DistinctPositions<'a> {
    /// Positions, world units.
    pub positions: &'a [Vec3],
    /// Indices into `positions` of each mesh triangle's corners, in the mesh's order.
    pub triangles: &'a [[u32; 3]],
}

/// `mesh`'s distinct positions, or `None` when there are as many as it has positions.
fn distinct_unless_all(mesh: &Mesh) -> Option<UniquePositions> {
    let unique = UniquePositions::of(mesh);
    (unique.positions.len() < mesh.positions.len()).then_some(unique)
}

/// Everything the renderers read, in world space.
#[derive(Debug, Clone)]
pub struct World {
    /// Objects in scene order.
    pub objects: Vec<WorldObject>,
    /// Point lights.
    pub lights: Vec<Light>,
    /// Ambient intensity Ia in [0, 1].
    pub ambient: f32,
    /// Linear RGB of the background.
    pub background: glam::Vec3,
    /// Deepest reflection recursion.
    pub max_depth: u32,
    /// Distance attenuation of the lights; `None` means att(d) = 1.
    pub falloff: Option<Falloff>,
}

/// Loaded model files (OBJ, STL, PLY or glTF) keyed by path, reloaded when the file or a file it
/// pulls in (an MTL library, a texture, a glTF buffer or image) changes on disk.
#[derive(Debug, Default)]
pub struct MeshFileCache {
    models: HashMap<PathBuf, CachedModel>,
}

/// A model as read, with the modification times of its file and of its companion files (in
/// [`MeshFile::companion_files`] order) then.
#[derive(Debug)]
struct CachedModel {
    modified: Option<SystemTime>,
    companions: Vec<Option<SystemTime>>,
    model: Arc<MeshFile>,
}

/// The modification time of the file at `path`, `None` when it cannot be had.
fn modified(path: &Path) -> Option<SystemTime> {
    std::fs::metadata(path).and_then(|m| m.modified()).ok()
}

impl MeshFileCache {
    /// The model at `path`, from the cache when neither it nor its companion files changed.
    pub fn get(&mut self, path: &Path) -> Result<Arc<MeshFile>, MeshFileError> {
        let when = modified(path);
        if let Some(CachedModel {
            modified: seen,
            companions,
            model,
        }) = self.models.get(path)
            && *seen == when
            && when.is_some()
            && model
                .companion_files()
                .iter()
                .zip(companions)
                .all(|(file, seen)| modified(file) == *seen)
        {
            return Ok(model.clone());
        }
        let model = Arc::new(MeshFile::load(path)?);
        let companions = model
            .companion_files()
            .iter()
            .map(|f| modified(f))
            .collect();
        let cached = CachedModel {
            modified: when,
            companions,
            model: model.clone(),
        };
        self.models.insert(path.to_path_buf(), cached);
        Ok(model)
    }
}

/// How much of each object a world is built with.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Detail {
    /// Everything the renderers read: normals, texture coordinates, textures.
    Render,
    /// Where the triangles are and nothing more, for `rastray info`: a model part's mesh is its
    /// placed positions, triangles and vertex colours ([`placed_shape`]), without normals and
    /// drawn plain. Counts, bounds, materials and the scene's warnings are as [`Detail::Render`]
    /// gives them. A part shared by several instances is one bare shape ([`shared_shape`]) that
    /// each instance places.
    Shape,
}

/// Where a world object came from.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct WorldObjectSource {
    /// Index of the scene object.
    pub object: usize,
    /// For one part of a multi-part model file (a glTF primitive), its label.
    pub part: Option<String>,
}

/// A built world, with where each of its objects came from and what the model files held that
/// rastray does not draw.
#[derive(Debug, Clone)]
pub struct WorldReport {
    pub world: World,
    /// One entry per world object, in the same order.
    pub sources: Vec<WorldObjectSource>,
    /// Skipped parts of model files, in scene order.
    pub warnings: Vec<SceneWarning>,
    /// Every model file read, and the files beside them it read (glTF buffers, MTL libraries),
    /// in scene order.
    pub inputs: Vec<PathBuf>,
}

/// The material one part of a mesh object is drawn with: with `materials = "file"`, the file's
/// material for the part (or the object's, for a part that has none); with `"object"`, the
/// object's own.
fn part_material(object: &Object, from_file: Option<Material>) -> Material {
    match object.shape {
        Shape::Mesh {
            materials: MaterialSource::File,
            ..
        } => from_file.unwrap_or(object.material),
        _ => object.material,
    }
}

/// The mesh and appearance one part of a mesh object is drawn with: the file's texture (its
/// corner UVs put on the mesh's vertices) and alpha mode when the object uses the file's
/// materials; plain otherwise. A part without texture coordinates everywhere is drawn
/// untextured.
fn part_appearance(object: &Object, part: &ModelPart<'_>, mesh: Mesh) -> (Mesh, Appearance) {
    let from_file = matches!(
        object.shape,
        Shape::Mesh {
            materials: MaterialSource::File,
            ..
        }
    );
    if !from_file {
        return (mesh, Appearance::plain());
    }
    match (&part.geometry.corner_uvs, &part.appearance.base_color) {
        (Some(uvs), Some(_)) => (with_corner_uvs(mesh, uvs), part.appearance.clone()),
        _ => (
            mesh,
            Appearance {
                base_color: None,
                ..part.appearance.clone()
            },
        ),
    }
}

/// The world objects of `part`, a part shared by several instances, of scene object `object`
/// (the `index`-th) whose model is centred on `centre`: its mesh tessellated once, in its own
/// space, and one object per instance holding it. An instance whose placement cannot be inverted
/// in f32 gets a placed mesh of its own. At [`Detail::Shape`] the meshes are bare shapes, drawn
/// plain.
fn instances_of(
    object: &Object,
    index: usize,
    part: &ModelPart<'_>,
    centre: Vec3,
    detail: Detail,
) -> Vec<(WorldObject, WorldObjectSource)> {
    let (mesh, corner_uvs, appearance) = match detail {
        Detail::Render => {
            let (mesh, appearance) =
                part_appearance(object, part, tessellate_shared(object, part.geometry));
            let corner_uvs = corner_uvs_for(part.geometry, &mesh);
            (mesh, corner_uvs, appearance)
        }
        Detail::Shape => (shared_shape(part.geometry), None, Appearance::plain()),
    };
    let shared = Arc::new(SharedMesh {
        unique: UniquePositions::of(&mesh),
        corner_uvs,
        mesh,
    });
    let material = part_material(object, part.material);
    part.instances
        .iter()
        .map(|placement| {
            let to_world = instance_transform(object, centre, placement.transform);
            let source = WorldObjectSource {
                object: index,
                part: Some(placement.label.clone()),
            };
            let instance = Instance::new(shared.clone(), to_world);
            let built = match instance {
                Some(instance) => WorldObject::instance_of(instance, material, appearance.clone()),
                None => {
                    let mut geometry = part.geometry.clone();
                    for p in &mut geometry.positions {
                        *p = placement.transform.transform_point3(*p);
                    }
                    geometry.corner_normals = None;
                    if detail == Detail::Shape {
                        let mesh = placed_shape(object, &geometry, centre);
                        return (WorldObject::new(mesh, material), source);
                    }
                    let mesh = tessellate_part(object, &geometry, centre);
                    let (mesh, appearance) = part_appearance(object, part, mesh);
                    WorldObject::with_appearance(mesh, material, appearance)
                        .with_uvs_of(part.geometry)
                }
            };
            (built, source)
        })
        .collect()
}

/// Checks the world `scene` would build from its loaded `models` (one per object, `None` for
/// primitives) and `triangles` against the memory bound, before any object is tessellated: its
/// triangles, its objects (a model's parts each become one) and its textures. The error names
/// the model with the most triangles; its file is empty when the scene has no model (the
/// caller knows the scene's own file).
fn check_budget(
    scene: &Scene,
    base_dir: &Path,
    models: &[Option<Arc<MeshFile>>],
    triangles: u64,
) -> Result<(), SceneError> {
    // Each shared part is stored once per scene object that draws its model, and placed once
    // per instance.
    let (mut objects, mut instances, mut placed, mut shared) = (0, 0, 0, 0);
    for model in models {
        let Some(model) = model else {
            objects += 1;
            continue;
        };
        for part in model.parts() {
            if part.instances.is_empty() {
                objects += 1;
            } else {
                instances += part.instances.len() as u64;
                placed += part.placed_triangles() as u64;
                shared += part.geometry.triangles.len() as u64;
            }
        }
    }
    let estimate = Estimate {
        triangles: triangles - placed + shared,
        objects,
        instances,
        placed_triangles: placed,
        texture_bytes: distinct_texture_bytes(
            models
                .iter()
                .flatten()
                .flat_map(|model| model.parts())
                .filter_map(|part| part.appearance.base_color.map(|binding| binding.texture)),
        ),
        frame_bytes: 0,
    };
    let largest = scene
        .objects
        .iter()
        .zip(models)
        .filter_map(|(object, model)| match (&object.shape, model) {
            (Shape::Mesh { path, .. }, Some(model)) => Some((model.triangle_count(), path)),
            _ => None,
        })
        .max_by_key(|&(count, _)| count)
        .map_or_else(PathBuf::new, |(_, path)| base_dir.join(path));
    estimate.check(&largest).map_err(SceneError::OverBudget)
}

impl World {
    /// Tessellates `scene`; model paths are relative to `base_dir` (the scene file's directory).
    pub fn build(scene: &Scene, base_dir: &Path) -> Result<World, SceneError> {
        World::build_cached(scene, base_dir, &mut MeshFileCache::default())
    }

    /// As [`World::build`], reusing models already in `cache`.
    pub fn build_cached(
        scene: &Scene,
        base_dir: &Path,
        cache: &mut MeshFileCache,
    ) -> Result<World, SceneError> {
        World::build_report(scene, base_dir, cache).map(|report| report.world)
    }

    /// As [`World::build_cached`], also telling where each world object came from (a glTF model
    /// becomes one world object per primitive, each with its own material) and what the model
    /// files held that rastray skipped.
    pub fn build_report(
        scene: &Scene,
        base_dir: &Path,
        cache: &mut MeshFileCache,
    ) -> Result<WorldReport, SceneError> {
        World::build_report_with(scene, base_dir, cache, Detail::Render)
    }

    /// As [`World::build_report`], with the objects built in `detail`.
    pub fn build_report_with(
        scene: &Scene,
        base_dir: &Path,
        cache: &mut MeshFileCache,
        detail: Detail,
    ) -> Result<WorldReport, SceneError> {
        let mut models = Vec::with_capacity(scene.objects.len());
        let mut warnings = Vec::new();
        let mut inputs = Vec::new();
        for (index, object) in scene.objects.iter().enumerate() {
            models.push(match &object.shape {
                Shape::Mesh { path, .. } => {
                    let full = base_dir.join(path);
                    let model = cache.get(&full).map_err(|error| match error {
                        MeshFileError::Obj(error) => SceneError::Obj { index, error },
                        MeshFileError::Gltf(error) => SceneError::Gltf {
                            index,
                            path: full.clone(),
                            error,
                        },
                        error => SceneError::Model { index, error },
                    })?;
                    inputs.push(full.clone());
                    inputs.extend(model.companion_files().iter().cloned());
                    warnings.extend(model.warnings().iter().map(|warning| SceneWarning {
                        index,
                        path: full.clone(),
                        warning: warning.clone(),
                    }));
                    Some(model)
                }
                _ => None,
            });
        }
        let triangles: u64 = scene
            .objects
            .iter()
            .zip(&models)
            .map(|(object, model)| match (&object.shape, model) {
                (Shape::Icosahedron { subdivisions, .. }, _) => 20 * 4u64.pow(*subdivisions),
                (Shape::Box { segments, .. }, _) => 12 * (*segments as u64).pow(2),
                (Shape::Prism { segments, .. }, _) => 8 * (*segments as u64).pow(2),
                (Shape::Mesh { .. }, Some(model)) => model.triangle_count() as u64,
                (Shape::Mesh { .. }, None) => 0,
            })
            .sum();
        // The bound in force decides by bytes (`check_budget`); past the renderers' own limit,
        // whatever the bound, by count.
        let limit = crate::memory_budget::TRIANGLE_INDEX_LIMIT;
        if triangles > limit {
            return Err(SceneError::TooManyTriangles { triangles, limit });
        }
        check_budget(scene, base_dir, &models, triangles)?;
        let built: Vec<Vec<(WorldObject, WorldObjectSource)>> = scene
            .objects
            .par_iter()
            .zip(models.par_iter())
            .enumerate()
            .map(|(index, (object, model))| match model.as_deref() {
                Some(model) => {
                    let (lo, hi) = model.bounds();
                    let centre = (lo + hi) * 0.5;
                    model
                        .parts()
                        .par_iter()
                        .flat_map_iter(|part| {
                            if !part.instances.is_empty() {
                                return instances_of(object, index, part, centre, detail);
                            }
                            let source = WorldObjectSource {
                                object: index,
                                part: part.label.map(str::to_string),
                            };
                            let material = part_material(object, part.material);
                            if detail == Detail::Shape {
                                let mesh = placed_shape(object, part.geometry, centre);
                                return vec![(WorldObject::new(mesh, material), source)];
                            }
                            let mesh = tessellate_part(object, part.geometry, centre);
                            let (mesh, appearance) = part_appearance(object, part, mesh);
                            // The file's positions are welded: a mesh with one vertex per
                            // position (smooth, no creases or seams split) has them distinct.
                            let welded = mesh.positions.len() == part.geometry.positions.len();
                            let built = WorldObject::with_appearance(mesh, material, appearance)
                                .with_uvs_of(part.geometry);
                            vec![(
                                if welded {
                                    built.with_distinct_positions()
                                } else {
                                    built
                                },
                                source,
                            )]
                        })
                        .collect()
                }
                None => vec![(
                    WorldObject::new(tessellate(object, None), object.material),
                    WorldObjectSource {
                        object: index,
                        part: None,
                    },
                )],
            })
            .collect();
        let (objects, sources) = built.into_iter().flatten().unzip();
        Ok(WorldReport {
            world: World {
                objects,
                lights: scene.lights.clone(),
                ambient: scene.ambient,
                background: scene.background,
                max_depth: scene.max_depth,
                falloff: scene.falloff,
            },
            sources,
            warnings,
            inputs,
        })
    }

    /// Total triangles over all objects, each instance counting its shared mesh's: the
    /// triangles placed in the world.
    pub fn triangle_count(&self) -> usize {
        self.objects
            .iter()
            .map(|o| o.local_mesh().triangle_count())
            .sum()
    }

    /// Triangles stored once: every object's own, and each shared mesh's once however many
    /// instances draw it.
    pub fn stored_triangle_count(&self) -> usize {
        let mut seen = std::collections::HashSet::new();
        self.objects
            .iter()
            .map(|o| match &o.instance {
                Some(i) if !seen.insert(Arc::as_ptr(&i.shared)) => 0,
                _ => o.local_mesh().triangle_count(),
            })
            .sum()
    }

    /// Whether some object is an instance of a shared mesh.
    pub fn has_instances(&self) -> bool {
        self.objects.iter().any(|o| o.instance.is_some())
    }

    /// This world with every instance placed into a world-space mesh of its own
    /// ([`WorldObject::placed`]), as the Z-buffer draws it; `None` when it has no instance.
    pub fn placed(&self) -> Option<World> {
        if !self.has_instances() {
            return None;
        }
        Some(World {
            objects: self.objects.par_iter().map(WorldObject::placed).collect(),
            ..self.clone_settings()
        })
    }

    /// The lights and settings of this world, with no objects.
    fn clone_settings(&self) -> World {
        World {
            objects: Vec::new(),
            lights: self.lights.clone(),
            ambient: self.ambient,
            background: self.background,
            max_depth: self.max_depth,
            falloff: self.falloff,
        }
    }

    /// Axis-aligned bounds (min, max) of every object; `None` for an empty world.
    pub fn bounds(&self) -> Option<(glam::Vec3, glam::Vec3)> {
        self.objects
            .iter()
            .filter_map(|o| o.extent)
            .reduce(|(a, b), (c, d)| (a.min(c), b.max(d)))
    }
}
