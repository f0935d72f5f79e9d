//! Colour textures of model files: a PNG or JPEG read through the model's folder, read as linear
//! (decoded from sRGB) with its mip chain (`texture`, `decode`, `mip_chain`, `load`), its texels
//! held compactly (`texels`: 16-bit linear RGBA), its
//! memory committed from its header before decoding (`ledger`), sampled with wrap modes and
//! trilinear filtering (`sampler`), and what a model part carries of them (`appearance`).

mod appearance;
mod decode;
mod error;
mod ledger;
mod limits;
mod load;
mod mip_chain;
mod sampler;
mod texels;
#[allow(clippy::module_inception)]
mod texture;
mod uv_transform;

pub use appearance::{AlphaMode, Appearance, TextureBinding};
pub use decode::decode_texture;
pub use error::TextureError;
pub use ledger::{TextureLedger, decoded_texture_bytes};
pub use limits::{MAX_TEXTURE_BASE_TEXELS, MAX_TEXTURE_DECLARED_TEXELS, MAX_TEXTURE_SIDE};
pub use load::load_texture;
#[cfg(test)]
pub(crate) use mip_chain::mip_chain;
pub(crate) use sampler::neighbours;
pub use sampler::{Filter, MipFilter, Sampler, Wrap};
pub use texels::Texels;
pub(crate) use texels::U16_STEP;
pub use texture::{MipLevel, Texture};
pub use uv_transform::UvTransform;
