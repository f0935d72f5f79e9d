//! The box (rectangular parallelepiped).

use glam::Vec3;

use super::patch::FaceList;

/// A box of `size` = [width, height, depth] centred on the origin, each face split into
/// `segments`² quads: 12·segments² triangles, wound counter-clockwise seen from outside.
///
/// Every vertex is a point of one lattice, each coordinate worked out once per lattice index,
/// so faces meeting along an edge share its vertices bit for bit and the surface is closed.
pub fn cuboid(size: Vec3, segments: u32) -> FaceList {
    let n = segments.max(1);
    let step = |len: f32, i: u32| -0.5 * len + len * (i as f32 / n as f32);
    let at = |x: u32, y: u32, z: u32| Vec3::new(step(size.x, x), step(size.y, y), step(size.z, z));
    let mut faces = FaceList::default();
    faces.grid(n, |col, row| at(n, row, n - col)); // +X
    faces.grid(n, |col, row| at(0, row, col)); // −X
    faces.grid(n, |col, row| at(col, n, n - row)); // +Y
    faces.grid(n, |col, row| at(col, 0, row)); // −Y
    faces.grid(n, |col, row| at(col, row, n)); // +Z
    faces.grid(n, |col, row| at(n - col, row, 0)); // −Z
    faces
}
