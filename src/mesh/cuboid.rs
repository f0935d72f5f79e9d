//! The box (rectangular parallelepiped).

use glam::Vec3;

use super::patch::FaceList;

/// A box of `size` = [width, height, depth] centred on the origin, each face split into
/// `segments`² quads: 12·segments² triangles, wound counter-clockwise seen from outside.
pub fn cuboid(size: Vec3, segments: u32) -> FaceList {
    let h = size * 0.5;
    let (x, y, z) = (Vec3::X * size.x, Vec3::Y * size.y, Vec3::Z * size.z);
    let mut faces = FaceList::default();
    faces.quad(Vec3::new(h.x, -h.y, h.z), -z, y, segments); // +X
    faces.quad(Vec3::new(-h.x, -h.y, -h.z), z, y, segments); // −X
    faces.quad(Vec3::new(-h.x, h.y, h.z), x, -z, segments); // +Y
    faces.quad(Vec3::new(-h.x, -h.y, -h.z), x, z, segments); // −Y
    faces.quad(Vec3::new(-h.x, -h.y, h.z), x, y, segments); // +Z
    faces.quad(Vec3::new(h.x, -h.y, -h.z), -x, y, segments); // −Z
    faces
}
