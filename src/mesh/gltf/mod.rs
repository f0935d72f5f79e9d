//! glTF 2.0 import (`.gltf` with its buffers, and `.glb`) through the `gltf` crate.

mod accessor;
mod appearance;
mod buffers;
mod error;
mod load;
mod material;
mod primitive;
mod warning;

pub use error::GltfError;
pub use load::{GltfInstance, GltfModel, GltfPart, MAX_NODE_INSTANCES, load_gltf, placed_bounds};
pub use material::phong_from_pbr;
pub use warning::ImportWarning;
