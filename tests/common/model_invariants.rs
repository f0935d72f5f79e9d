//! The invariants every loaded model keeps (`ModelGeometry`'s doc), checked by the fuzz
//! targets, and the world-space mesh it makes.

use std::path::Path;

use rastray::mesh::{ModelGeometry, tessellate};
use rastray::scene::limits::COORDINATE;
use rastray::scene::{Object, Shape};

/// Why `g` breaks an invariant, if it does.
pub fn broken(g: &ModelGeometry) -> Option<String> {
    if g.triangles.is_empty() {
        return Some("no triangles".into());
    }
    if let Some(i) = g
        .triangles
        .iter()
        .flatten()
        .find(|&&i| i as usize >= g.positions.len())
    {
        return Some(format!("index {i} of {} positions", g.positions.len()));
    }
    if let Some(p) = g
        .positions
        .iter()
        .find(|p| !p.to_array().iter().all(|&x| COORDINATE.accepts(x)))
    {
        return Some(format!("position {p} beyond the limits"));
    }
    if let Some(normals) = &g.corner_normals {
        if normals.len() != g.triangles.len() {
            return Some("a normal triple per triangle".into());
        }
        if let Some(n) = normals
            .iter()
            .flatten()
            .find(|n| !n.is_finite() || (n.length() - 1.0).abs() > 1e-4)
        {
            return Some(format!("normal {n} not a unit vector"));
        }
    }
    if let Some(uvs) = &g.corner_uvs
        && (uvs.len() != g.triangles.len() || !uvs.iter().flatten().all(|uv| uv.is_finite()))
    {
        return Some("a finite UV triple per triangle".into());
    }
    if let Some(colors) = &g.colors {
        if colors.len() != g.positions.len() {
            return Some("a colour per position".into());
        }
        if let Some(c) = colors
            .iter()
            .find(|c| !c.to_array().iter().all(|x| (0.0..=1.0).contains(x)))
        {
            return Some(format!("colour {c} outside 0..=1"));
        }
    }
    let object = Object::new(Shape::Mesh {
        path: Path::new("fuzz").to_path_buf(),
        position: glam::Vec3::ZERO,
        scale: 1.0,
        up: rastray::scene::UpAxis::Z,
        materials: rastray::scene::MaterialSource::File,
    });
    let mesh = tessellate(&object, Some(g));
    if mesh.triangle_count() != g.triangles.len()
        || !mesh.positions.iter().all(|p| p.is_finite())
        || !mesh.normals.iter().all(|n| n.is_finite())
        || !mesh.surface_area().is_finite()
    {
        return Some("the world-space mesh is not finite".into());
    }
    None
}

/// What is wrong with the outcome of loading the model at `path`, if anything: a refusal must
/// name the file, a model must keep its invariants.
pub fn wrong_outcome<E: std::fmt::Display>(
    path: &Path,
    loaded: Result<&ModelGeometry, E>,
) -> Option<String> {
    match loaded {
        Err(error) => {
            let message = error.to_string();
            (!message.starts_with(&path.display().to_string()))
                .then(|| format!("the refusal does not name the file: {message}"))
        }
        Ok(geometry) => broken(geometry),
    }
}
