//! Parts of a model file that rastray reads past (glTF primitives, OBJ materials and the files
//! they name, textures): the rest of the file still loads.

use std::fmt;

/// Something in a glTF file that rastray does not draw.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub enum ImportWarning {
    /// A primitive of points or lines: rastray draws triangles only.
    NotTriangles {
        /// Which primitive, as "mesh 0 (\"Name\") primitive 1".
        primitive: String,
        /// The glTF mode, such as "LINES".
        mode: &'static str,
    },
    /// A required extension rastray does not implement.
    UnsupportedExtension { name: String },
    /// A primitive whose positions are not plain 32-bit floats in a buffer (compressed or
    /// quantized by an extension).
    UnreadablePositions { primitive: String, reason: String },
    /// An OBJ's `mtllib` that could not be read (missing, outside the model's folder, not a
    /// file): the faces of its materials take the object's material.
    MaterialLibraryNotRead {
        reference: String,
        line: usize,
        reason: String,
    },
    /// Lines of an MTL file that were skipped: the first one and how many in all.
    MaterialLinesSkipped {
        library: String,
        line: usize,
        problem: &'static str,
        count: usize,
    },
    /// An OBJ's `usemtl` names a material no library defines.
    UnknownMaterial { name: String },
    /// A material's texture that could not be read: the material is drawn without it.
    TextureNotRead {
        material: String,
        reference: String,
        reason: String,
    },
    /// A material whose base colour texture could not be read (missing, outside the model's
    /// folder, not a PNG or JPEG, too large): its parts are drawn untextured.
    TextureUnreadable { material: String, reason: String },
    /// A textured primitive without the texture coordinate set its material names: drawn
    /// untextured.
    NoTextureCoordinates { primitive: String, set: u32 },
    /// A model's texture (a PLY `comment TextureFile`, an MTL `map_Kd`) that could not be read:
    /// `reason` names the file. The model is drawn untextured.
    ModelTextureUnreadable { reason: String },
    /// A material with `alphaMode: BLEND`: rastray draws it opaque.
    BlendDrawnOpaque { material: String },
}

impl fmt::Display for ImportWarning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ImportWarning::NotTriangles { primitive, mode } => {
                write!(f, "{primitive} skipped: it draws {mode}, not triangles")
            }
            ImportWarning::UnsupportedExtension { name } => write!(
                f,
                "the file requires extension {name}, which rastray does not read; \
                 what depends on it is skipped or drawn without it"
            ),
            ImportWarning::UnreadablePositions { primitive, reason } => {
                write!(f, "{primitive} skipped: {reason}")
            }
            ImportWarning::TextureUnreadable { material, reason } => write!(
                f,
                "{material} is drawn without its base colour texture: {reason}"
            ),
            ImportWarning::NoTextureCoordinates { primitive, set } => write!(
                f,
                "{primitive} is drawn untextured: its material's texture reads TEXCOORD_{set}, \
                 which it does not have"
            ),
            ImportWarning::ModelTextureUnreadable { reason } => {
                write!(f, "drawn untextured: {reason}")
            }
            ImportWarning::BlendDrawnOpaque { material } => write!(
                f,
                "{material} asks for alpha blending (alphaMode BLEND); rastray draws it opaque"
            ),
            ImportWarning::MaterialLibraryNotRead {
                reference,
                line,
                reason,
            } => write!(
                f,
                "line {line}: mtllib \"{reference}\" not read: {reason}; its materials are \
                 drawn with the object's material"
            ),
            ImportWarning::MaterialLinesSkipped {
                library,
                line,
                problem,
                count,
            } => {
                write!(f, "{library}:{line}: {problem}; line skipped")?;
                match count.saturating_sub(1) {
                    0 => Ok(()),
                    more => write!(f, " (and {more} more)"),
                }
            }
            ImportWarning::UnknownMaterial { name } => write!(
                f,
                "usemtl \"{name}\": no material library defines it; its faces take the \
                 object's material"
            ),
            ImportWarning::TextureNotRead {
                material,
                reference,
                reason,
            } => write!(
                f,
                "material \"{material}\": map_Kd \"{reference}\" not read: {reason}; drawn \
                 without it"
            ),
        }
    }
}
