//! The scene model: what a `.toml` scene file holds, how it is read, checked and written.

mod error;
mod falloff;
mod field_path;
mod file;
pub mod limits;
mod material;
mod material_source;
mod model;
mod object;
mod projection;
mod up_axis;
mod validate;
mod vector;
mod warning;

pub use error::SceneError;
pub use falloff::Falloff;
pub use field_path::{FieldPath, PathSegment};
pub use file::{DEFAULT_SCENE_TOML, default_scene, from_toml_str, load, save, to_toml_string};
pub use limits::{CountLimits, Limits, MAX_DEPTH};
pub use material::Material;
pub use material_source::MaterialSource;
pub use model::{Camera, Light, Scene};
pub use object::{Object, ObjectError, Shape, ShapeKind};
pub use projection::{Projection, framing_fov, framing_height};
pub use up_axis::UpAxis;
pub use validate::{Components, Invalid, Problem, validate};
pub use warning::SceneWarning;
