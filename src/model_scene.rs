//! A scene made for a model file opened on its own (`rastray model.glb`, `rastray render
//! bunny.obj -o bunny.png`): the model, scaled to fit a sphere of radius 1 about the origin,
//! seen whole from the front, a little above and to the right, under a key light and a fill
//! light. Saved, it is an ordinary scene file.

use std::path::{Path, PathBuf};

use glam::Vec3;

use crate::mesh::{MeshFile, MeshFileError, ModelFormat};
use crate::scene::{Camera, Light, Object, Scene, Shape, ShapeKind, UpAxis};
use crate::world::MeshFileCache;

/// Radius of the sphere the model is scaled to fit, world units.
pub const FIT_RADIUS: f32 = 1.0;

/// Vertical field of view of the camera, degrees.
const FOV: f32 = 40.0;

// A model is shown with the built-in default scene's ambient light, background and reflection
// depth, written out below rather than taken from a parsed `scenes/default.toml`: parsing it
// took 0.4–0.8 ms of the 3.8–4.0 ms that `rastray info` took on a one-triangle OBJ. A test
// keeps them equal to the file's.

/// Ambient intensity, as the default scene's.
const AMBIENT: f32 = 0.08;
/// Background, linear RGB, as the default scene's.
const BACKGROUND: Vec3 = Vec3::new(0.04, 0.05, 0.08);
/// Reflection depth of the ray tracer, as the default scene's.
const MAX_DEPTH: u32 = 4;

/// Whether `path` names a model file (`.obj`, `.stl`, `.ply`, `.gltf`, `.glb`, any case) by
/// its extension.
pub fn is_model_path(path: &Path) -> bool {
    ModelFormat::of_extension(path).is_some()
}

/// Whether the file at `path` is a model rather than a scene: by its extension, or, when the
/// extension is not `.toml`, by its content (see [`ModelFormat::sniff`]). A file that cannot
/// be read is no model here: reading it as a scene says why.
pub fn is_model_file(path: &Path) -> bool {
    let toml = path
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("toml"));
    is_model_path(path) || (!toml && matches!(ModelFormat::of_file(path), Ok(Some(_))))
}

/// A model file that cannot be shown.
#[derive(Debug, thiserror::Error)]
pub enum ModelSceneError {
    /// The file could not be read as a model.
    #[error("{}", load_message(path, error))]
    Load { path: PathBuf, error: MeshFileError },
    /// The file holds nothing to draw.
    #[error("{}: the model has no triangles to show", path.display())]
    Empty { path: PathBuf },
}

/// The message of a model that could not be loaded, naming the file once (an OBJ error already
/// names it, with the line).
fn load_message(path: &Path, error: &MeshFileError) -> String {
    match error {
        MeshFileError::Gltf(_) => format!("{}: {error}", path.display()),
        _ => error.to_string(),
    }
}

/// The scene showing the model at `path`, turned so that its `up` axis is +Y, with its mesh
/// path written as the file's name: the scene's folder is the model's folder. An STL model is
/// drawn flat (its faces are usually a CAD model's facets), any other smooth.
pub fn scene_for_model(path: &Path, up: UpAxis) -> Result<Scene, ModelSceneError> {
    let model = MeshFile::load(path).map_err(|error| ModelSceneError::Load {
        path: path.to_path_buf(),
        error,
    })?;
    scene_for_loaded_model(path, &model, up)
}

/// As [`scene_for_model`], reading the model through `cache` under the path its scene names it
/// by (the file's name in its folder, `path`'s parent): a world then built from the scene with
/// the same cache, its models relative to that folder, reads the file no more. Returns the scene
/// and that folder.
pub fn scene_for_model_cached(
    path: &Path,
    up: UpAxis,
    cache: &mut MeshFileCache,
) -> Result<(Scene, PathBuf), ModelSceneError> {
    let folder = path.parent().map(Path::to_path_buf).unwrap_or_default();
    let key = folder.join(path.file_name().unwrap_or_default());
    let model = cache.get(&key).map_err(|error| ModelSceneError::Load {
        path: path.to_path_buf(),
        error,
    })?;
    Ok((scene_for_loaded_model(path, &model, up)?, folder))
}

/// As [`scene_for_model`], for `model`, the file at `path` already loaded (the editor keeps it
/// for its first world, rather than reading the file twice).
pub fn scene_for_loaded_model(
    path: &Path,
    model: &MeshFile,
    up: UpAxis,
) -> Result<Scene, ModelSceneError> {
    let (lo, hi) = model.bounds();
    let radius = (hi - lo).length() / 2.0;
    if model.triangle_count() == 0 || !radius.is_finite() || radius <= 0.0 {
        return Err(ModelSceneError::Empty {
            path: path.to_path_buf(),
        });
    }
    let name = path.file_name().map(PathBuf::from).unwrap_or_default();
    let mut object = Object::new(Shape::new(ShapeKind::Mesh, Vec3::ZERO, name.clone()));
    if let Shape::Mesh {
        scale, up: axis, ..
    } = &mut object.shape
    {
        *scale = FIT_RADIUS / radius;
        *axis = up;
    }
    object.smooth = !model.flat_by_default();
    object.name = path.file_stem().map(|s| s.to_string_lossy().into_owned());
    Ok(Scene {
        camera: framing_camera(),
        lights: vec![
            light("key", Vec3::new(-3.0, 4.0, 4.0), 0.85),
            light("fill", Vec3::new(4.0, 1.5, 2.5), 0.35),
        ],
        objects: vec![object],
        ambient: AMBIENT,
        background: BACKGROUND,
        max_depth: MAX_DEPTH,
        falloff: None,
    })
}

/// A camera that sees the whole sphere of radius [`FIT_RADIUS`] about the origin, with a
/// little room, whatever the image's aspect (the vertical field of view is the narrower one
/// for every landscape image).
fn framing_camera() -> Camera {
    let half = (FOV / 2.0).to_radians();
    let distance = FIT_RADIUS / half.sin() * 1.1;
    Camera {
        position: Vec3::new(0.45, 0.35, 1.0).normalize() * distance,
        target: Vec3::ZERO,
        up: Vec3::Y,
        fov: FOV,
        ..Camera::default()
    }
}

fn light(name: &str, position: Vec3, intensity: f32) -> Light {
    Light {
        name: Some(name.into()),
        position,
        intensity,
        color: Vec3::ONE,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn model_files_are_told_from_scenes_by_their_extension() {
        for model in ["a.obj", "b.GLB", "dir/c.gltf", "d.STL", "e.ply"] {
            assert!(is_model_path(Path::new(model)), "{model}");
        }
        for scene in ["a.toml", "obj", "a.obj.toml", "a"] {
            assert!(!is_model_path(Path::new(scene)), "{scene}");
        }
    }

    #[test]
    fn a_model_is_shown_with_the_default_scenes_ambient_background_and_depth() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a.obj");
        std::fs::write(&path, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
        let scene = scene_for_model(&path, UpAxis::default()).expect("a scene");
        let default = crate::scene::default_scene();
        assert_eq!(scene.ambient, default.ambient);
        assert_eq!(scene.background, default.background);
        assert_eq!(scene.max_depth, default.max_depth);
        assert_eq!(scene.falloff, default.falloff);
    }

    #[test]
    fn the_camera_sees_the_whole_fitted_sphere() {
        let camera = framing_camera();
        let to_centre = (camera.target - camera.position).length();
        // The sphere's angular radius from the eye is inside half the field of view.
        let seen = (FIT_RADIUS / to_centre).asin().to_degrees();
        assert!(seen < camera.fov / 2.0, "{seen} ≥ {}", camera.fov / 2.0);
        assert!(
            seen > camera.fov / 2.0 * 0.8,
            "the model fills the view: {seen}"
        );
    }
}
