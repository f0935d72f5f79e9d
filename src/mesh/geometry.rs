//! Triangles as a model file states them, before normals and placement.

use glam::{Vec2, Vec3};

/// Welded positions and the triangles between them, in the file's units and axes, with what the
/// file says of their appearance.
///
/// Invariants: every index is `< positions.len()`; when present, `corner_normals` and
/// `corner_uvs` have one entry per triangle, every normal is a finite unit vector and every
/// texture coordinate is finite; when present, `colors` has one entry per position, each
/// channel finite and in 0..=1.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ModelGeometry {
    /// Welded vertex positions in the file's units.
    pub positions: Vec<Vec3>,
    /// Position indices of each triangle, counter-clockwise seen from the front.
    pub triangles: Vec<[u32; 3]>,
    /// The file's unit normal for each triangle corner, when the file gave normals everywhere.
    pub corner_normals: Option<Vec<[Vec3; 3]>>,
    /// Linear RGB colour of each position, when the file colours every vertex (loaders decode
    /// the format's encoding: sRGB bytes become linear values).
    pub colors: Option<Vec<Vec3>>,
    /// Texture coordinates of each triangle corner, when the file gives them everywhere. One
    /// convention for every format: (0, 0) is the image's top-left corner and v grows downward
    /// (glTF's; OBJ and PLY loaders store 1 − v).
    pub corner_uvs: Option<Vec<[Vec2; 3]>>,
}

impl ModelGeometry {
    /// Axis-aligned bounds (min, max) of the positions; inverted (MAX, MIN) when empty.
    pub fn bounds(&self) -> (Vec3, Vec3) {
        self.positions.iter().fold(
            (Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)),
            |(lo, hi), &p| (lo.min(p), hi.max(p)),
        )
    }
}
