//! Texture coordinates put on a mesh's vertices: a vertex whose corners carry different
//! coordinates (a UV seam) is split, one vertex per distinct coordinate.

use std::collections::HashMap;

use glam::Vec2;

use super::face_list::Mesh;

/// `mesh` with `corner_uvs` (one entry per triangle, in the mesh's triangle order) as its
/// vertices' texture coordinates. Corners of one vertex with bit-identical coordinates share
/// it; the others get copies of the vertex (its position, normal and colour).
///
/// # Panics
/// If `corner_uvs` does not have one entry per triangle (a caller bug).
pub fn with_corner_uvs(mesh: Mesh, corner_uvs: &[[Vec2; 3]]) -> Mesh {
    assert_eq!(mesh.triangles.len(), corner_uvs.len());
    let mut out = Mesh {
        positions: Vec::with_capacity(mesh.positions.len()),
        normals: Vec::with_capacity(mesh.positions.len()),
        triangles: Vec::with_capacity(mesh.triangles.len()),
        colors: mesh.colors.as_ref().map(|_| Vec::new()),
        uvs: Some(Vec::with_capacity(mesh.positions.len())),
        flat: mesh.flat,
    };
    let mut made: HashMap<(u32, [u32; 2]), u32> = HashMap::with_capacity(mesh.positions.len());
    for (triangle, uvs) in mesh.triangles.iter().zip(corner_uvs) {
        let corners = std::array::from_fn(|k| {
            let (v, uv) = (triangle[k], uvs[k]);
            *made
                .entry((v, uv.to_array().map(f32::to_bits)))
                .or_insert_with(|| {
                    out.positions.push(mesh.positions[v as usize]);
                    out.normals.push(mesh.normals[v as usize]);
                    if let (Some(colors), Some(from)) = (&mut out.colors, &mesh.colors) {
                        colors.push(from[v as usize]);
                    }
                    out.uvs.as_mut().expect("set above").push(uv);
                    out.positions.len() as u32 - 1
                })
        });
        out.triangles.push(corners);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    #[test]
    fn a_seam_splits_a_vertex_and_shared_coordinates_do_not() {
        let mesh = Mesh {
            positions: vec![Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::ONE],
            normals: vec![Vec3::Z; 4],
            triangles: vec![[0, 1, 2], [1, 3, 2]],
            ..Mesh::default()
        };
        let (a, b, c, d) = (Vec2::ZERO, Vec2::X, Vec2::Y, Vec2::ONE);
        // Vertex 2 carries (0, 1) in the first triangle and (1, 1) in the second: a seam.
        let out = with_corner_uvs(mesh, &[[a, b, c], [b, d, d]]);
        assert_eq!(out.positions.len(), 5);
        assert_eq!(out.triangles, [[0, 1, 2], [1, 3, 4]]);
        assert_eq!(out.uvs.unwrap(), [a, b, c, d, d]);
        assert_eq!(out.positions[4], Vec3::Y);
    }
}
