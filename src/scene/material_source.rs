//! Where a mesh object's look comes from: its model file's materials and textures, or the
//! object's own material.

use serde::{Deserialize, Serialize};

use super::material::Material;

/// Which material a mesh object's parts are drawn with. The file's vertex colours tint either
/// (they belong to the geometry, as its normals do: albedo = material × texture × vertex colour).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum MaterialSource {
    /// Each part's material and texture from the file (MTL, glTF); a part the file gives no
    /// material takes the object's.
    File,
    /// The object's own material on every part; the file's materials and textures are not used.
    Object,
}

impl MaterialSource {
    /// Both, in the order the editor steps through them.
    pub const ALL: [MaterialSource; 2] = [MaterialSource::File, MaterialSource::Object];

    /// The spelling in files and in the editor: `file`, `object`.
    pub fn name(self) -> &'static str {
        match self {
            MaterialSource::File => "file",
            MaterialSource::Object => "object",
        }
    }

    /// The source spelled `name` (any case); `None` for anything else.
    pub fn from_name(name: &str) -> Option<MaterialSource> {
        MaterialSource::ALL
            .into_iter()
            .find(|s| s.name().eq_ignore_ascii_case(name))
    }

    /// The source of a scene that does not say, as rastray chose before the key existed: the
    /// file's materials while the object's material is the default, the object's once it sets
    /// one.
    pub fn implied_by(material: &Material) -> MaterialSource {
        if *material == Material::default() {
            MaterialSource::File
        } else {
            MaterialSource::Object
        }
    }
}
