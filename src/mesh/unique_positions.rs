//! A mesh's distinct positions. Flat-shaded meshes repeat each position once per face that meets
//! it (one vertex per position and normal); the Z-buffer projects each distinct position once.

use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};

use glam::Vec3;

use super::Mesh;

/// The distinct positions of a [`Mesh`] and its triangles re-indexed onto them.
///
/// Invariants: `positions` holds each bit pattern of the mesh's positions once, in order of
/// first use; `triangles[t][k]` is the index in `positions` of the position of the mesh's vertex
/// `triangles[t][k]`, so it has the same bits.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct UniquePositions {
    /// Distinct vertex positions, world units.
    pub positions: Vec<Vec3>,
    /// Indices into `positions` of each mesh triangle's corners, in the mesh's order.
    pub triangles: Vec<[u32; 3]>,
}

impl UniquePositions {
    /// The distinct positions of `mesh`, compared bit for bit (so 0.0 and −0.0 stay apart, and
    /// any arithmetic on a position gives the same result through either index).
    pub fn of(mesh: &Mesh) -> UniquePositions {
        let mut index: HashMap<u128, u32, BuildHasherDefault<BitsHasher>> =
            HashMap::with_capacity_and_hasher(mesh.positions.len(), Default::default());
        let mut positions = Vec::with_capacity(mesh.positions.len());
        let of_vertex: Vec<u32> = mesh
            .positions
            .iter()
            .map(|p| {
                let [x, y, z] = p.to_array().map(|c| c.to_bits() as u128);
                *index.entry(x | y << 32 | z << 64).or_insert_with(|| {
                    positions.push(*p);
                    (positions.len() - 1) as u32
                })
            })
            .collect();
        let triangles = mesh
            .triangles
            .iter()
            .map(|t| t.map(|v| of_vertex[v as usize]))
            .collect();
        UniquePositions {
            positions,
            triangles,
        }
    }
}

/// A multiply-rotate hash of a position's bits (as in rustc's FxHasher): the default SipHash
/// took about 280 instructions per vertex of the bunny (callgrind), several times this.
#[derive(Debug, Default)]
struct BitsHasher(u64);

impl BitsHasher {
    const K: u64 = 0xf135_7aea_2e62_a9c5;

    fn add(&mut self, word: u64) {
        self.0 = (self.0 ^ word).wrapping_mul(Self::K);
    }
}

impl Hasher for BitsHasher {
    fn finish(&self) -> u64 {
        // The product's high bits are the well-mixed ones; the table indexes by the low bits.
        self.0.rotate_left(26)
    }

    fn write(&mut self, bytes: &[u8]) {
        bytes.iter().for_each(|&b| self.add(b as u64));
    }

    fn write_u128(&mut self, v: u128) {
        self.add(v as u64);
        self.add((v >> 64) as u64);
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::UniquePositions;
    use crate::mesh::{cuboid, with_normals};

    #[test]
    fn a_flat_cube_has_eight_positions_and_the_same_corners() {
        let faces = cuboid(Vec3::ONE, 1);
        let flat = with_normals(&faces.positions, &faces.triangles, false);
        assert!(flat.positions.len() > 8, "flat shading splits vertices");
        let unique = UniquePositions::of(&flat);
        assert_eq!(unique.positions.len(), 8);
        assert_eq!(unique.triangles.len(), flat.triangles.len());
        for (t, u) in flat.triangles.iter().zip(&unique.triangles) {
            for k in 0..3 {
                let (a, b) = (
                    flat.positions[t[k] as usize],
                    unique.positions[u[k] as usize],
                );
                assert_eq!(
                    a.to_array().map(f32::to_bits),
                    b.to_array().map(f32::to_bits)
                );
            }
        }
    }

    #[test]
    fn zero_and_negative_zero_stay_apart() {
        let mesh = crate::mesh::Mesh {
            positions: vec![Vec3::ZERO, Vec3::new(-0.0, 0.0, 0.0), Vec3::X, Vec3::ZERO],
            normals: vec![Vec3::Z; 4],
            triangles: vec![[0, 1, 2], [3, 2, 1]],
            colors: None,
            uvs: None,
            flat: false,
        };
        let unique = UniquePositions::of(&mesh);
        assert_eq!(unique.positions.len(), 3);
        assert_eq!(unique.triangles, vec![[0, 1, 2], [0, 2, 1]]);
    }
}
