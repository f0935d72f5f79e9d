//! Why a texture was not read. Every message names the file; a model loader turns it into a
//! warning and draws the part untextured.

use crate::model_folder::ReferenceError;

/// A texture that could not be read.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum TextureError {
    /// The file is missing, unreadable, or outside the model's folder.
    #[error("texture {name}: {error}")]
    Reference { name: String, error: ReferenceError },
    /// The bytes are not a PNG or JPEG image.
    #[error("texture {name}: not a PNG or JPEG image ({reason})")]
    NotImage { name: String, reason: String },
    /// The header declares a size rastray refuses before decoding.
    #[error(
        "texture {name}: its header declares {width}×{height} texels, more than the \
         {max_side} a side or {max_texels} in all rastray reads"
    )]
    TooLarge {
        name: String,
        width: u32,
        height: u32,
        max_side: u32,
        max_texels: u64,
    },
    /// Decoding the texture would take the model past the memory bound; nothing was decoded.
    #[error("texture {name}: decoding it would pass the memory bound: {figures}")]
    OverBudget { name: String, figures: String },
    /// The image is damaged past its header.
    #[error("texture {name}: {reason}")]
    Decode { name: String, reason: String },
}
