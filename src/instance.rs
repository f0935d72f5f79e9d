//! An instance: one placement of a mesh that several world objects share (a glTF mesh named by
//! several nodes). The mesh is tessellated once, in its own space, and held by an [`Arc`]; each
//! instance carries only that reference and the affine map from the mesh's space to the world.
//!
//! The ray tracer moves rays into the mesh's space instead of moving the mesh; the Z-buffer
//! places the mesh into world space for the frame ([`Instance::placed_mesh`]).

use std::sync::Arc;

use glam::{Affine3A, Mat3, Vec3};

use crate::mesh::{Mesh, UniquePositions};

/// A mesh shared by instances, in its own space.
#[derive(Debug)]
pub struct SharedMesh {
    /// Triangles and unit normals in the mesh's own space.
    pub mesh: Mesh,
    /// The mesh's distinct positions (see [`UniquePositions`]), in its own space.
    pub unique: UniquePositions,
    /// The file's texture coordinates at each corner of each triangle, when it has them.
    pub corner_uvs: Option<Vec<[glam::Vec2; 3]>>,
}

/// One placement of a [`SharedMesh`]. Invariant: `to_world` is finite and invertible, so
/// `to_object` and `normal_matrix` are finite.
#[derive(Debug, Clone)]
pub struct Instance {
    /// The mesh, shared with the other instances of it.
    pub shared: Arc<SharedMesh>,
    /// From the mesh's space to the world.
    pub to_world: Affine3A,
    /// From the world to the mesh's space: `to_world`'s inverse.
    pub to_object: Affine3A,
    /// Moves the mesh's normals into the world: the inverse transpose of `to_world`'s linear
    /// part (normalize after).
    pub normal_matrix: Mat3,
}

impl Instance {
    /// `shared` placed by `to_world`; `None` when the map is not finite or not invertible
    /// (the caller then bakes the placement into a mesh of its own, as before instancing).
    pub fn new(shared: Arc<SharedMesh>, to_world: Affine3A) -> Option<Instance> {
        let linear = Mat3::from(to_world.matrix3);
        let det = linear.determinant();
        if !to_world.is_finite() || !det.is_finite() || det == 0.0 {
            return None;
        }
        let to_object = to_world.inverse();
        let normal_matrix = linear.inverse().transpose();
        (to_object.is_finite() && normal_matrix.is_finite()).then_some(Instance {
            shared,
            to_world,
            to_object,
            normal_matrix,
        })
    }

    /// Whether the map mirrors (negative determinant): a placed copy then reverses its
    /// triangles' winding, so that fronts stay fronts.
    pub fn mirrors(&self) -> bool {
        Mat3::from(self.to_world.matrix3).determinant() < 0.0
    }

    /// A point of the mesh moved into the world.
    #[inline]
    pub fn point(&self, p: Vec3) -> Vec3 {
        self.to_world.transform_point3(p)
    }

    /// A unit normal of the mesh moved into the world, unit length (zero stays zero).
    #[inline]
    pub fn normal(&self, n: Vec3) -> Vec3 {
        (self.normal_matrix * n).normalize_or_zero()
    }

    /// The world positions and normals at vertices `abc` of the shared mesh.
    #[inline]
    pub fn corners(&self, abc: [u32; 3]) -> ([Vec3; 3], [Vec3; 3]) {
        let mesh = &self.shared.mesh;
        let abc = abc.map(|k| k as usize);
        (
            abc.map(|k| self.point(mesh.positions[k])),
            abc.map(|k| self.normal(mesh.normals[k])),
        )
    }

    /// The shared mesh placed in the world: positions moved, normals by the inverse transpose,
    /// and the winding reversed where the map mirrors. A transient copy for the Z-buffer.
    pub fn placed_mesh(&self) -> Mesh {
        let mesh = &self.shared.mesh;
        let mut triangles = mesh.triangles.clone();
        if self.mirrors() {
            for t in &mut triangles {
                t.swap(1, 2);
            }
        }
        Mesh {
            positions: mesh.positions.iter().map(|&p| self.point(p)).collect(),
            normals: mesh.normals.iter().map(|&n| self.normal(n)).collect(),
            triangles,
            colors: mesh.colors.clone(),
            uvs: mesh.uvs.clone(),
            flat: mesh.flat,
        }
    }

    /// The corner texture coordinates of the placed mesh, in its triangles' order (turned with
    /// the winding where the map mirrors).
    pub fn placed_corner_uvs(&self) -> Option<Vec<[glam::Vec2; 3]>> {
        let uvs = self.shared.corner_uvs.as_ref()?;
        Some(if self.mirrors() {
            uvs.iter().map(|&[a, b, c]| [a, c, b]).collect()
        } else {
            uvs.clone()
        })
    }

    /// The axis-aligned bounds (min, max) of the placed mesh's vertices, exact (every distinct
    /// position moved); `None` for an empty mesh.
    pub fn extent(&self) -> Option<(Vec3, Vec3)> {
        let mut points = self.shared.unique.positions.iter().map(|&p| self.point(p));
        let first = points.next()?;
        Some(points.fold((first, first), |(lo, hi), p| (lo.min(p), hi.max(p))))
    }

    /// The radius about `center` of a sphere enclosing every placed vertex.
    pub fn radius_about(&self, center: Vec3) -> f32 {
        self.shared
            .unique
            .positions
            .iter()
            .map(|&p| self.point(p).distance(center))
            .fold(0.0, f32::max)
    }
}
