//! Face-list meshes: indexed triangles with per-vertex normals, and the shapes that make them.

mod byte_source;
mod cuboid;
mod face_list;
mod geometry;
pub mod gltf;
mod icosahedron;
mod mesh_file;
mod model_error;
mod model_format;
mod normals;
mod obj;
mod obj_error;
mod patch;
pub mod ply;
mod prism;
mod srgb;
pub mod stl;
mod tessellate;
mod unique_positions;
mod weld;

pub use cuboid::cuboid;
pub use face_list::{Mesh, Sphere};
pub use geometry::ModelGeometry;
pub use icosahedron::icosahedron;
pub use mesh_file::{MeshFile, MeshFileError};
pub use model_error::{ModelError, Place};
pub use model_format::{EXPECTED_MODEL, ModelFormat};
pub use normals::{CREASE_ANGLE_DEGREES, with_normals};
pub use obj::{ObjModel, load_obj};
pub use obj_error::{ObjError, ObjProblem};
pub use patch::FaceList;
pub use ply::{PlyEncoding, PlyError, PlyModel, load_ply};
pub use prism::prism;
pub use stl::{StlEncoding, StlError, StlModel, load_stl};
pub use tessellate::{object_transform, tessellate, tessellate_part};
pub use unique_positions::UniquePositions;
