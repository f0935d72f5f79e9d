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
        super::face_list::bounds_of(
            &self.positions,
            (Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)),
        )
    }

    /// The triangles `chosen` (indices into `triangles`, in the order given) with the positions
    /// they use renumbered in first-use order, and their normals, colours and UVs.
    pub fn subset(&self, chosen: &[u32]) -> ModelGeometry {
        let mut new_index = vec![u32::MAX; self.positions.len()];
        let mut positions = Vec::new();
        let mut colors = self.colors.as_ref().map(|_| Vec::new());
        let triangles = chosen
            .iter()
            .map(|&t| {
                self.triangles[t as usize].map(|i| {
                    let slot = &mut new_index[i as usize];
                    if *slot == u32::MAX {
                        *slot = positions.len() as u32;
                        positions.push(self.positions[i as usize]);
                        if let (Some(out), Some(all)) = (&mut colors, &self.colors) {
                            out.push(all[i as usize]);
                        }
                    }
                    *slot
                })
            })
            .collect();
        let pick = |corners: &Vec<[Vec3; 3]>| chosen.iter().map(|&t| corners[t as usize]).collect();
        ModelGeometry {
            positions,
            triangles,
            corner_normals: self.corner_normals.as_ref().map(pick),
            colors,
            corner_uvs: self
                .corner_uvs
                .as_ref()
                .map(|uvs| chosen.iter().map(|&t| uvs[t as usize]).collect()),
        }
    }
}
