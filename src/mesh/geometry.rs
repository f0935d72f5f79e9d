//! Triangles as a model file states them, before normals and placement.

use glam::Vec3;

/// Welded positions and the triangles between them, in the file's units and axes.
///
/// Invariants: every index is `< positions.len()`; when present, `corner_normals` has one entry
/// per triangle and every normal is a finite unit vector.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ModelGeometry {
    /// Welded vertex positions in the file's units.
    pub positions: Vec<Vec3>,
    /// Position indices of each triangle, counter-clockwise seen from the front.
    pub triangles: Vec<[u32; 3]>,
    /// The file's unit normal for each triangle corner, when the file gave normals everywhere.
    pub corner_normals: Option<Vec<[Vec3; 3]>>,
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
