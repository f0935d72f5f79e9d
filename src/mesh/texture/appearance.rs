//! What a model part carries of its look beside its material: its colour texture and how alpha
//! cuts it out. `Appearance::default()` is an untextured, opaque part: the renderers then run
//! the code they run without textures.

use std::sync::Arc;

use super::sampler::Sampler;
use super::texture::Texture;

/// A colour texture as a part uses it. The part's mesh carries the texture coordinates (already
/// chosen from the file's sets and transformed).
#[derive(Debug, Clone, PartialEq)]
pub struct TextureBinding {
    /// The decoded image, shared by every part that names it.
    pub texture: Arc<Texture>,
    /// Wrap and filters.
    pub sampler: Sampler,
}

/// How a part's alpha is used.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum AlphaMode {
    /// Alpha is ignored (glTF `OPAQUE`, and `BLEND`, which rastray draws opaque).
    #[default]
    Opaque,
    /// A point whose alpha (base colour factor × texture × vertex colour) is below `cutoff` is
    /// no surface: rays pass it, shadow rays included, and the Z-buffer draws nothing there.
    Mask { cutoff: f32 },
}

/// A part's look beyond its [`crate::scene::Material`]: the albedo is the material colour ×
/// the texture × the vertex colour, each 1 where absent.
#[derive(Debug, Clone, PartialEq)]
pub struct Appearance {
    /// The base colour texture, when the part has one and it could be read.
    pub base_color: Option<TextureBinding>,
    /// The alpha of the base colour factor (glTF's fourth component), 1 elsewhere.
    pub alpha_factor: f32,
    /// How alpha cuts the part out.
    pub alpha_mode: AlphaMode,
    /// The vertex colours' alpha (glTF `COLOR_0`'s fourth component) at each triangle's corners,
    /// one entry per triangle of the part's mesh, in its triangle order and corner order. Kept
    /// only for a `MASK` part whose vertex alpha is below 1 somewhere; `None` is alpha 1.
    pub corner_alphas: Option<Arc<[[f32; 3]]>>,
}

impl Default for Appearance {
    fn default() -> Appearance {
        Appearance::plain()
    }
}

impl Appearance {
    /// An untextured, opaque appearance.
    pub fn plain() -> Appearance {
        Appearance {
            base_color: None,
            alpha_factor: 1.0,
            alpha_mode: AlphaMode::Opaque,
            corner_alphas: None,
        }
    }

    /// Opaque, coloured by `texture` with the default sampler (repeat, linear) when there is one.
    pub fn textured_by(texture: Option<&Arc<Texture>>) -> Appearance {
        Appearance {
            base_color: texture.map(|texture| TextureBinding {
                texture: texture.clone(),
                sampler: Sampler::default(),
            }),
            ..Appearance::plain()
        }
    }

    /// This appearance for a copy of its mesh whose triangles have their second and third
    /// corners swapped (a mirrored placement): the corner alphas swap with them.
    pub fn with_corners_swapped(&self) -> Appearance {
        Appearance {
            corner_alphas: self
                .corner_alphas
                .as_ref()
                .map(|alphas| alphas.iter().map(|&[a, b, c]| [a, c, b]).collect()),
            ..self.clone()
        }
    }

    /// Whether nothing but the material and vertex colours decides the look.
    pub fn is_plain(&self) -> bool {
        self.base_color.is_none() && self.alpha_mode == AlphaMode::Opaque
    }
}
