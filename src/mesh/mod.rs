//! Face-list meshes: indexed triangles with per-vertex normals, and the shapes that make them.

mod cuboid;
mod face_list;
mod geometry;
pub mod gltf;
mod icosahedron;
mod mesh_file;
mod normals;
mod obj;
mod obj_error;
mod patch;
mod prism;
mod srgb;
mod tessellate;
mod unique_positions;

pub use cuboid::cuboid;
pub use face_list::{Mesh, Sphere};
pub use geometry::ModelGeometry;
pub use icosahedron::icosahedron;
pub use mesh_file::{MeshFile, MeshFileError};
pub use normals::{CREASE_ANGLE_DEGREES, unit_or_zero, with_colors_and_normals, with_normals};
pub use obj::{ObjModel, load_obj};
pub use obj_error::{ObjError, ObjProblem};
pub use patch::FaceList;
pub use prism::prism;
pub use srgb::srgb_to_linear;
pub use tessellate::{object_transform, tessellate, tessellate_part};
pub use unique_positions::UniquePositions;
