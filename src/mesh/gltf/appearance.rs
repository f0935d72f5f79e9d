//! A glTF material's base colour texture and alpha mode as an [`Appearance`]: the image
//! (embedded in a buffer view or a data URI, or a file in the model's folder, decoded by
//! rastray), its sampler, its `texCoord` set and `KHR_texture_transform`.

use std::collections::HashMap;
use std::path::PathBuf;
use std::sync::Arc;

use ::gltf::material::AlphaMode as GltfAlphaMode;
use ::gltf::texture::{MagFilter, MinFilter, WrappingMode};
use glam::Vec2;

use super::buffers::read_uri;
use super::warning::ImportWarning;
use crate::mesh::texture::{
    AlphaMode, Appearance, Filter, MipFilter, Sampler, Texture, TextureBinding, UvTransform, Wrap,
    decode_texture,
};
use crate::model_folder::ModelFolder;

/// What a part needs of its material beyond the Phong colours: its appearance, and which
/// texture coordinate set feeds the texture, transformed how.
pub struct PartAppearance {
    pub appearance: Appearance,
    /// The `TEXCOORD_n` set and its transform, when the appearance has a texture.
    pub uv_set: Option<(u32, UvTransform)>,
}

/// The images of one file decoded once each, by image index (`None`: unreadable, warned).
pub struct ImageCache<'a> {
    pub folder: &'a ModelFolder,
    pub buffers: &'a [Vec<u8>],
    /// Files read beside the model.
    pub files: &'a mut Vec<PathBuf>,
    decoded: HashMap<usize, Option<Arc<Texture>>>,
}

impl<'a> ImageCache<'a> {
    /// A cache reading from `folder` and `buffers`, noting files read in `files`.
    pub fn new(
        folder: &'a ModelFolder,
        buffers: &'a [Vec<u8>],
        files: &'a mut Vec<PathBuf>,
    ) -> ImageCache<'a> {
        ImageCache {
            folder,
            buffers,
            files,
            decoded: HashMap::new(),
        }
    }

    /// The decoded `image`, or the reason it could not be had.
    fn texture(&mut self, image: &::gltf::Image) -> Result<Arc<Texture>, String> {
        if let Some(done) = self.decoded.get(&image.index()) {
            return done
                .clone()
                .ok_or_else(|| format!("image {} could not be read", image.index()));
        }
        let result = self.decode(image);
        self.decoded
            .insert(image.index(), result.as_ref().ok().cloned());
        result
    }

    fn decode(&mut self, image: &::gltf::Image) -> Result<Arc<Texture>, String> {
        let (name, bytes) = match image.source() {
            ::gltf::image::Source::View { view, .. } => {
                let name = named(image, &format!("buffer view {}", view.index()));
                let bytes = self
                    .buffers
                    .get(view.buffer().index())
                    .and_then(|b| b.get(view.offset()..view.offset().checked_add(view.length())?))
                    .ok_or_else(|| format!("{name}: the view lies outside its buffer"))?;
                (name, bytes.to_vec())
            }
            ::gltf::image::Source::Uri { uri, .. } => {
                let name = if uri.starts_with("data:") {
                    named(image, "data URI")
                } else {
                    image.name().map_or_else(|| uri.to_string(), str::to_string)
                };
                let bytes = read_uri(uri, self.folder, self.files)
                    .map_err(|reason| format!("texture {name}: {reason}"))?;
                (name, bytes)
            }
        };
        decode_texture(&bytes, &name, self.folder.textures())
            .map(Arc::new)
            .map_err(|e| e.to_string())
    }
}

/// The name `image` goes by in messages and `info`: its own name, or its index, with `source`
/// (where its bytes are) beside either.
fn named(image: &::gltf::Image, source: &str) -> String {
    match image.name() {
        Some(name) => format!("{name} ({source})"),
        None => format!("image {} ({source})", image.index()),
    }
}

/// The appearance of `material` (named `label` in warnings), with its texture read through
/// `images`; what cannot be drawn is added to `warnings`.
pub fn part_appearance(
    material: &::gltf::Material,
    label: &str,
    images: &mut ImageCache,
    warnings: &mut Vec<ImportWarning>,
) -> PartAppearance {
    let pbr = material.pbr_metallic_roughness();
    let alpha_mode = match material.alpha_mode() {
        GltfAlphaMode::Opaque => AlphaMode::Opaque,
        GltfAlphaMode::Mask => AlphaMode::Mask {
            cutoff: material.alpha_cutoff().unwrap_or(0.5),
        },
        GltfAlphaMode::Blend => {
            warnings.push(ImportWarning::BlendDrawnOpaque {
                material: label.to_string(),
            });
            AlphaMode::Opaque
        }
    };
    let mut appearance = Appearance {
        base_color: None,
        alpha_factor: pbr.base_color_factor()[3],
        alpha_mode,
        corner_alphas: None,
    };
    let Some(info) = pbr.base_color_texture() else {
        return PartAppearance {
            appearance,
            uv_set: None,
        };
    };
    let texture = info.texture();
    match images.texture(&texture.source()) {
        Ok(image) => {
            appearance.base_color = Some(TextureBinding {
                texture: image,
                sampler: sampler(&texture.sampler()),
            });
            let (set, transform) = match info.texture_transform() {
                Some(t) => (
                    t.tex_coord().unwrap_or(info.tex_coord()),
                    UvTransform {
                        offset: Vec2::from(t.offset()),
                        rotation: t.rotation(),
                        scale: Vec2::from(t.scale()),
                    },
                ),
                None => (info.tex_coord(), UvTransform::default()),
            };
            PartAppearance {
                appearance,
                uv_set: Some((set, transform)),
            }
        }
        Err(reason) => {
            warnings.push(ImportWarning::TextureUnreadable {
                material: label.to_string(),
                reason,
            });
            PartAppearance {
                appearance,
                uv_set: None,
            }
        }
    }
}

/// rastray's sampler for a glTF one; filters the file leaves open are linear and trilinear.
fn sampler(sampler: &::gltf::texture::Sampler) -> Sampler {
    let wrap = |mode| match mode {
        WrappingMode::Repeat => Wrap::Repeat,
        WrappingMode::ClampToEdge => Wrap::ClampToEdge,
        WrappingMode::MirroredRepeat => Wrap::MirroredRepeat,
    };
    let magnify = match sampler.mag_filter() {
        Some(MagFilter::Nearest) => Filter::Nearest,
        _ => Filter::Linear,
    };
    let (minify, mip) = match sampler.min_filter() {
        Some(MinFilter::Nearest) => (Filter::Nearest, MipFilter::None),
        Some(MinFilter::Linear) => (Filter::Linear, MipFilter::None),
        Some(MinFilter::NearestMipmapNearest) => (Filter::Nearest, MipFilter::Nearest),
        Some(MinFilter::LinearMipmapNearest) => (Filter::Linear, MipFilter::Nearest),
        Some(MinFilter::NearestMipmapLinear) => (Filter::Nearest, MipFilter::Linear),
        Some(MinFilter::LinearMipmapLinear) | None => (Filter::Linear, MipFilter::Linear),
    };
    Sampler {
        wrap: [wrap(sampler.wrap_s()), wrap(sampler.wrap_t())],
        magnify,
        minify,
        mip,
    }
}
