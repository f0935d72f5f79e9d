//! The right triangular prism.

use glam::{Vec2, Vec3};

use super::patch::FaceList;

/// A right prism whose cross-section is an isosceles triangle of base `size.x` (along X) and height
/// `size.y` (along Y), extruded `size.z` along Z, centred on its bounding box. Each face is split
/// into `segments`² pieces: 8·segments² triangles, wound counter-clockwise seen from outside.
///
/// Every vertex is a point of one lattice (a cross-section point by its steps toward the right
/// corner and the apex, and a depth step), each worked out once per lattice index, so faces
/// meeting along an edge share its vertices bit for bit and the surface is closed.
pub fn prism(size: Vec3, segments: u32) -> FaceList {
    let n = segments.max(1);
    let h = size * 0.5;
    let (left, right, apex) = (
        Vec2::new(-h.x, -h.y),
        Vec2::new(h.x, -h.y),
        Vec2::new(0.0, h.y),
    );
    let fraction = |i: u32| i as f32 / n as f32;
    // `to_right` steps from the left corner toward the right one, `up` toward the apex.
    let at = |to_right: u32, up: u32, z: u32| {
        let p = left + (right - left) * fraction(to_right) + (apex - left) * fraction(up);
        p.extend(-h.z + size.z * fraction(z))
    };
    let mut faces = FaceList::default();
    faces.triangle_grid(n, |k, r| at(k, r, n)); // +Z cap: left, right, apex
    faces.triangle_grid(n, |k, r| at(n - k - r, r, 0)); // −Z cap: right, left, apex
    faces.grid(n, |col, row| at(col, 0, row)); // base, facing −Y
    faces.grid(n, |col, row| at(n - row, row, n - col)); // right slope
    faces.grid(n, |col, row| at(0, n - row, n - col)); // left slope
    faces
}
