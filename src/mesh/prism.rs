//! The right triangular prism.

use glam::Vec3;

use super::patch::FaceList;

/// A right prism whose cross-section is an isosceles triangle of base `size.x` (along X) and height
/// `size.y` (along Y), extruded `size.z` along Z, centred on its bounding box. Each face is split
/// into `segments`² pieces: 8·segments² triangles, wound counter-clockwise seen from outside.
pub fn prism(size: Vec3, segments: u32) -> FaceList {
    let h = size * 0.5;
    let left = Vec3::new(-h.x, -h.y, 0.0);
    let right = Vec3::new(h.x, -h.y, 0.0);
    let apex = Vec3::new(0.0, h.y, 0.0);
    let front = Vec3::Z * h.z;
    let depth = Vec3::Z * size.z;
    let mut faces = FaceList::default();
    faces.triangle(left + front, right + front, apex + front, segments); // +Z cap
    faces.triangle(right - front, left - front, apex - front, segments); // −Z cap
    faces.quad(left - front, right - left, depth, segments); // base, facing −Y
    faces.quad(right + front, -depth, apex - right, segments); // right slope
    faces.quad(apex + front, -depth, left - apex, segments); // left slope
    faces
}
