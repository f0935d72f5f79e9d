//! OBJ import through tobj: polygons triangulated, every group merged into one face list.

use std::io::BufReader;
use std::path::Path;

use glam::Vec3;

use super::geometry::ModelGeometry;

/// An OBJ file's geometry: every group of the file merged into one face list.
pub type ObjModel = ModelGeometry;

/// Reads the OBJ file at `path`. Errors are one-line messages (the caller names the file).
pub fn load_obj(path: &Path) -> Result<ObjModel, String> {
    let file = std::fs::File::open(path).map_err(|e| e.to_string())?;
    let options = tobj::LoadOptions {
        triangulate: true,
        single_index: false,
        ignore_points: true,
        ignore_lines: true,
    };
    let (models, _materials) = tobj::load_obj_buf(&mut BufReader::new(file), &options, |_| {
        Err(tobj::LoadError::MaterialParseError)
    })
    .map_err(|e| format!("malformed OBJ: {e}"))?;

    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    let mut corner_normals = Some(Vec::new());
    for model in &models {
        let m = &model.mesh;
        let base = positions.len() as u32;
        let count = m.positions.len() / 3;
        for p in m.positions.chunks_exact(3) {
            let v = Vec3::new(p[0], p[1], p[2]);
            if !v.is_finite() {
                return Err(format!(
                    "a vertex of object `{}` is not a finite number",
                    model.name
                ));
            }
            positions.push(v);
        }
        if m.indices.iter().any(|&i| i as usize >= count) {
            return Err(format!(
                "a face of object `{}` names a vertex that does not exist",
                model.name
            ));
        }
        triangles.extend(
            m.indices
                .chunks_exact(3)
                .map(|t| [t[0] + base, t[1] + base, t[2] + base]),
        );
        let has_normals = m.normal_indices.len() == m.indices.len() && !m.normals.is_empty();
        match (&mut corner_normals, has_normals) {
            (Some(list), true) => {
                let normal = |i: u32| -> Vec3 {
                    let i = i as usize * 3;
                    m.normals
                        .get(i..i + 3)
                        .map(|n| Vec3::new(n[0], n[1], n[2]).normalize_or_zero())
                        .unwrap_or(Vec3::ZERO)
                };
                list.extend(
                    m.normal_indices
                        .chunks_exact(3)
                        .map(|t| [normal(t[0]), normal(t[1]), normal(t[2])]),
                );
            }
            _ => corner_normals = None,
        }
    }
    if triangles.is_empty() {
        return Err("the file holds no faces".to_string());
    }
    let corner_normals = corner_normals.filter(|list| {
        list.iter()
            .flatten()
            .all(|n| n.is_finite() && *n != Vec3::ZERO)
    });
    Ok(ObjModel {
        positions,
        triangles,
        corner_normals,
    })
}
