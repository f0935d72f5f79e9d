//! The render-ready world: every object tessellated into a world-space mesh, with the lights and
//! scene settings the renderers need. Built once per scene edit, shared by all three algorithms.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::SystemTime;

use rayon::prelude::*;

use crate::mesh::{Mesh, ObjError, ObjModel, Sphere, load_obj, tessellate};
use crate::scene::{Falloff, Light, Material, Scene, SceneError, Shape};

/// Most triangles a world may hold (about 2 GB of vertex data).
pub const MAX_TRIANGLES: u64 = 20_000_000;

/// One tessellated object.
#[derive(Debug, Clone)]
pub struct WorldObject {
    /// World-space triangles and normals.
    pub mesh: Mesh,
    /// Surface material.
    pub material: Material,
    /// Sphere enclosing the mesh: the first cull of the ray tracer.
    pub bounds: Sphere,
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

/// Loaded OBJ models keyed by absolute path, reloaded when the file changes on disk.
#[derive(Debug, Default)]
pub struct ObjCache {
    models: HashMap<PathBuf, (Option<SystemTime>, Arc<ObjModel>)>,
}

impl ObjCache {
    /// The model at `path`, from the cache when the file is unchanged.
    pub fn get(&mut self, path: &Path) -> Result<Arc<ObjModel>, ObjError> {
        let modified = std::fs::metadata(path).and_then(|m| m.modified()).ok();
        if let Some((when, model)) = self.models.get(path)
            && *when == modified
            && modified.is_some()
        {
            return Ok(model.clone());
        }
        let model = Arc::new(load_obj(path)?);
        self.models
            .insert(path.to_path_buf(), (modified, model.clone()));
        Ok(model)
    }
}

impl World {
    /// Tessellates `scene`; OBJ paths are relative to `base_dir` (the scene file's directory).
    pub fn build(scene: &Scene, base_dir: &Path) -> Result<World, SceneError> {
        World::build_cached(scene, base_dir, &mut ObjCache::default())
    }

    /// As [`World::build`], reusing models already in `cache`.
    pub fn build_cached(
        scene: &Scene,
        base_dir: &Path,
        cache: &mut ObjCache,
    ) -> Result<World, SceneError> {
        let mut models = Vec::with_capacity(scene.objects.len());
        for (index, object) in scene.objects.iter().enumerate() {
            models.push(match &object.shape {
                Shape::Mesh { path, .. } => {
                    let full = base_dir.join(path);
                    let model = cache
                        .get(&full)
                        .map_err(|error| SceneError::Obj { index, error })?;
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
                (Shape::Mesh { .. }, Some(model)) => model.triangles.len() as u64,
                (Shape::Mesh { .. }, None) => 0,
            })
            .sum();
        if triangles > MAX_TRIANGLES {
            return Err(SceneError::TooManyTriangles {
                triangles,
                limit: MAX_TRIANGLES,
            });
        }
        let objects = scene
            .objects
            .par_iter()
            .zip(models.par_iter())
            .map(|(object, model)| {
                let mesh = tessellate(object, model.as_deref());
                let bounds = mesh.bounding_sphere();
                WorldObject {
                    mesh,
                    material: object.material,
                    bounds,
                }
            })
            .collect();
        Ok(World {
            objects,
            lights: scene.lights.clone(),
            ambient: scene.ambient,
            background: scene.background,
            max_depth: scene.max_depth,
            falloff: scene.falloff,
        })
    }

    /// Total triangles over all objects.
    pub fn triangle_count(&self) -> usize {
        self.objects.iter().map(|o| o.mesh.triangle_count()).sum()
    }

    /// Axis-aligned bounds (min, max) of every object; `None` for an empty world.
    pub fn bounds(&self) -> Option<(glam::Vec3, glam::Vec3)> {
        self.objects
            .iter()
            .filter_map(|o| o.mesh.bounds())
            .reduce(|(a, b), (c, d)| (a.min(c), b.max(d)))
    }
}
