//! Parts of a glTF file that rastray reads past: the rest of the file still loads.

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
    /// A material whose base colour comes from a texture: rastray has no textures, so the
    /// colour is the base colour factor alone.
    TextureIgnored { material: String },
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
            ImportWarning::TextureIgnored { material } => write!(
                f,
                "{material} takes its base colour from a texture; rastray uses the base colour \
                 factor alone"
            ),
        }
    }
}
