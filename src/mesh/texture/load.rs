//! A texture file a model names, read from the model's folder.

use std::sync::Arc;

use super::decode::decode_texture;
use super::error::TextureError;
use super::limits::MAX_TEXTURE_DECLARED_TEXELS;
use super::texture::Texture;
use crate::model_folder::{ModelFolder, ReferenceKind};

/// Most bytes a texture file may hold: an uncompressed 8192×8192 RGBA image and a margin.
const MAX_TEXTURE_FILE_BYTES: u64 = 4 * MAX_TEXTURE_DECLARED_TEXELS + (1 << 20);

/// Reads and decodes the PNG or JPEG `reference` names inside `folder` (a glTF URI or an MTL or
/// PLY path, as `kind` says). Errors name the reference; the caller warns and goes untextured.
pub fn load_texture(
    folder: &ModelFolder,
    reference: &str,
    kind: ReferenceKind,
) -> Result<Arc<Texture>, TextureError> {
    let bytes = folder
        .read(reference, kind, MAX_TEXTURE_FILE_BYTES, "a texture")
        .map_err(|error| TextureError::Reference {
            name: reference.to_string(),
            error,
        })?;
    decode_texture(&bytes, reference, folder.textures()).map(Arc::new)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_texture_is_read_inside_the_model_folder_and_nowhere_else() {
        let dir = tempfile::tempdir().unwrap();
        let model = dir.path().join("m.gltf");
        std::fs::write(&model, "{}").unwrap();
        image::RgbImage::from_pixel(2, 2, image::Rgb([10, 20, 30]))
            .save(dir.path().join("wood.png"))
            .unwrap();
        let folder = ModelFolder::of(&model).unwrap();
        let texture = load_texture(&folder, "wood.png", ReferenceKind::Path).unwrap();
        assert_eq!(texture.size(), (2, 2));
        let missing = load_texture(&folder, "stone.jpg", ReferenceKind::Path).unwrap_err();
        assert!(
            missing.to_string().starts_with("texture stone.jpg: "),
            "{missing}"
        );
        let outside = load_texture(&folder, "../wood.png", ReferenceKind::Path).unwrap_err();
        assert!(
            matches!(
                outside,
                TextureError::Reference {
                    error: crate::model_folder::ReferenceError::Outside(_),
                    ..
                }
            ),
            "{outside:?}"
        );
    }
}
