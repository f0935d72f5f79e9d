//! A model part placed in the world as a bare shape: where its triangles are, with no normals
//! and no texture coordinates. `rastray info` reads nothing more of a world, and building the
//! normals took a fifth of its time on the 1.31M-triangle icosphere.

use glam::Vec3;
use rayon::prelude::*;

use super::face_list::Mesh;
use super::geometry::ModelGeometry;
use super::tessellate::placed_positions;
use super::used_vertices::drop_unused;
use crate::scene::Object;

/// The world positions of the vertices `geometry`'s triangles use, placed as
/// [`super::tessellate_part`] places them (bit for bit: the same values, each once), its
/// triangles on them, and its vertex colours. The normals are empty. The mesh holds the same
/// points as `tessellate_part`'s, so its bounds, bounding sphere and zero-area triangles are the
/// same; a vertex no triangle uses is left out, as there.
///
/// # Panics
/// If `object` is not a mesh object (a caller bug).
pub fn placed_shape(object: &Object, geometry: &ModelGeometry, centre: Vec3) -> Mesh {
    bare_shape(placed_positions(object, geometry, centre), geometry)
}

/// `geometry`'s used vertices where the file puts them, its triangles on them and its vertex
/// colours, with no normals: the shape of a part shared by several instances, each of which
/// places it ([`super::instance_transform`]). Its points are those of
/// [`super::tessellate_shared`]'s mesh, so each instance's bounds are the same.
pub fn shared_shape(geometry: &ModelGeometry) -> Mesh {
    bare_shape(geometry.positions.clone(), geometry)
}

/// The used ones of `positions` (one per vertex of `geometry`), `geometry`'s triangles on them
/// and its vertex colours.
fn bare_shape(positions: Vec<Vec3>, geometry: &ModelGeometry) -> Mesh {
    // Copied on every core: 16 MB for the 1.31M-triangle icosphere.
    let mut triangles: Vec<[u32; 3]> =
        crate::huge_pages::collected(geometry.triangles.par_iter().copied());
    match drop_unused(&mut triangles, geometry.positions.len()) {
        None => Mesh {
            positions,
            triangles,
            colors: geometry.colors.clone(),
            ..Mesh::default()
        },
        // Keep the used vertices, in order.
        Some(kept) => Mesh {
            positions: kept.iter().map(|&k| positions[k as usize]).collect(),
            triangles,
            colors: (geometry.colors.as_ref())
                .map(|colors| kept.iter().map(|&k| colors[k as usize]).collect()),
            ..Mesh::default()
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::{cuboid, tessellate_part};
    use crate::scene::{Shape, ShapeKind};

    #[test]
    fn the_shape_holds_the_points_of_the_tessellated_part_bit_for_bit() {
        let cube = cuboid(Vec3::new(1.0, 2.0, 3.0), 2);
        // One vertex no triangle uses, far away: neither mesh has it.
        let mut positions = cube.positions.clone();
        positions.insert(0, Vec3::splat(100.0));
        let geometry = ModelGeometry {
            positions,
            triangles: cube.triangles.iter().map(|t| t.map(|i| i + 1)).collect(),
            ..ModelGeometry::default()
        };
        for smooth in [false, true] {
            let mut object = Object::new(Shape::new(
                ShapeKind::Mesh,
                Vec3::new(1.0, -2.0, 0.5),
                "m".into(),
            ));
            object.rotation = Vec3::new(10.0, 20.0, 30.0);
            object.smooth = smooth;
            if let Shape::Mesh { scale, .. } = &mut object.shape {
                *scale = 0.37;
            }
            let centre = Vec3::new(0.1, 0.2, 0.3);
            let shape = placed_shape(&object, &geometry, centre);
            let full = tessellate_part(&object, &geometry, centre);
            let bits = |m: &Mesh| {
                let mut points: Vec<[u32; 3]> = m
                    .positions
                    .iter()
                    .map(|p| p.to_array().map(f32::to_bits))
                    .collect();
                points.sort_unstable();
                points.dedup();
                points
            };
            assert_eq!(bits(&shape), bits(&full));
            assert_eq!(shape.bounds(), full.bounds());
            assert_eq!(shape.triangles.len(), full.triangles.len());
            for (a, b) in shape.triangles.iter().zip(&full.triangles) {
                let corners = |m: &Mesh, t: &[u32; 3]| t.map(|i| m.positions[i as usize]);
                assert_eq!(corners(&shape, a), corners(&full, b));
            }
            assert_eq!(shape.zero_area_triangles(), full.zero_area_triangles());
        }
    }
}
