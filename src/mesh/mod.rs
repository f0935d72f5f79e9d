//! Face-list meshes: indexed triangles with per-vertex normals, and the shapes that make them.

mod byte_source;
mod corner_uvs;
mod cuboid;
mod face_list;
mod geometry;
pub mod gltf;
mod icosahedron;
mod line_blocks;
mod measure;
mod mesh_file;
mod model_error;
mod model_format;
mod mtl;
mod mtl_phong;
mod normals;
mod obj;
mod obj_error;
mod obj_model;
mod obj_number;
mod obj_piece;
mod patch;
mod piece_room;
mod placed_shape;
pub mod ply;
mod prism;
mod srgb;
pub mod stl;
mod tessellate;
pub mod texture;
mod unique_positions;
mod used_vertices;
mod weld;

pub use corner_uvs::with_corner_uvs;
pub use cuboid::cuboid;
pub use face_list::{Mesh, Sphere};
pub use geometry::ModelGeometry;
pub use icosahedron::icosahedron;
pub use measure::{Measurements, measure};
pub use mesh_file::{MeshFile, MeshFileError, ModelPart};
pub use model_error::{ModelError, Place};
pub use model_format::{EXPECTED_MODEL, ModelFormat};
pub use mtl::{MtlMaterial, MtlNote, parse_mtl};
pub use mtl_phong::phong_from_mtl;
pub use normals::{CREASE_ANGLE_DEGREES, unit_or_zero, with_colors_and_normals, with_normals};
pub use obj::{ObjRead, load_obj, read_obj, read_obj_in_blocks};
pub use obj_error::{ObjError, ObjProblem};
pub use obj_model::{MAX_MTL_BYTES, ObjModel, ObjPart, load_obj_model};
pub use patch::FaceList;
pub use placed_shape::{placed_shape, shared_shape};
pub use ply::{PlyEncoding, PlyError, PlyModel, load_ply};
pub use prism::prism;
pub use srgb::{srgb_byte_to_linear, srgb_to_linear};
pub use stl::{StlEncoding, StlError, StlModel, load_stl};
pub use tessellate::{
    instance_transform, object_transform, placed_positions, tessellate, tessellate_part,
    tessellate_shared,
};
pub use unique_positions::UniquePositions;
