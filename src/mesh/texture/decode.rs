//! PNG or JPEG bytes to a [`Texture`]: the header's size checked first, then the image decoded,
//! halved until it fits, turned from sRGB to linear and given its mip chain.

use std::io::Cursor;

use image::{ImageFormat, ImageReader, Limits};

use super::error::TextureError;
use super::limits::{MAX_TEXTURE_BASE_TEXELS, MAX_TEXTURE_DECLARED_TEXELS, MAX_TEXTURE_SIDE};
use super::mip_chain::{halved, mip_chain};
use super::texture::{MipLevel, Texture};
use crate::mesh::srgb_byte_to_linear;

/// Decodes `bytes`, a PNG or JPEG image, into a texture named `name`. The colour channels are
/// sRGB-encoded and become linear; alpha is kept as it is.
pub fn decode_texture(bytes: &[u8], name: &str) -> Result<Texture, TextureError> {
    let not_image = |reason: String| TextureError::NotImage {
        name: name.to_string(),
        reason,
    };
    let reader = || -> Result<ImageReader<Cursor<&[u8]>>, TextureError> {
        let reader = ImageReader::new(Cursor::new(bytes))
            .with_guessed_format()
            .map_err(|e| not_image(e.to_string()))?;
        match reader.format() {
            Some(ImageFormat::Png | ImageFormat::Jpeg) => Ok(reader),
            Some(other) => Err(not_image(format!("a {other:?} image"))),
            None => Err(not_image("unknown content".into())),
        }
    };
    // The header alone: nothing the size of the image is allocated before this check.
    let (width, height) = reader()?
        .into_dimensions()
        .map_err(|e| not_image(e.to_string()))?;
    if width == 0
        || height == 0
        || width > MAX_TEXTURE_SIDE
        || height > MAX_TEXTURE_SIDE
        || u64::from(width) * u64::from(height) > MAX_TEXTURE_DECLARED_TEXELS
    {
        return Err(TextureError::TooLarge {
            name: name.to_string(),
            width,
            height,
            max_side: MAX_TEXTURE_SIDE,
            max_texels: MAX_TEXTURE_DECLARED_TEXELS,
        });
    }
    let mut decoder = reader()?;
    let mut limits = Limits::default();
    limits.max_image_width = Some(MAX_TEXTURE_SIDE);
    limits.max_image_height = Some(MAX_TEXTURE_SIDE);
    // RGBA at 16 bits a channel is the most a decoder holds: 8 bytes a texel.
    limits.max_alloc = Some(8 * MAX_TEXTURE_DECLARED_TEXELS + (1 << 20));
    decoder.limits(limits);
    let image = decoder.decode().map_err(|e| TextureError::Decode {
        name: name.to_string(),
        reason: e.to_string(),
    })?;
    let rgba = image.into_rgba8();
    let mut base = MipLevel {
        width: rgba.width(),
        height: rgba.height(),
        texels: rgba
            .pixels()
            .map(|p| {
                let [r, g, b, a] = p.0;
                [
                    srgb_byte_to_linear(r),
                    srgb_byte_to_linear(g),
                    srgb_byte_to_linear(b),
                    f32::from(a) / 255.0,
                ]
            })
            .collect(),
    };
    drop(rgba);
    while u64::from(base.width) * u64::from(base.height) > MAX_TEXTURE_BASE_TEXELS {
        base = halved(&base);
    }
    Ok(Texture {
        name: name.to_string(),
        file_size: (width, height),
        levels: mip_chain(base),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A PNG of `width × height` opaque texels, every one `rgb`.
    fn png(width: u32, height: u32, rgb: [u8; 3]) -> Vec<u8> {
        let image = image::RgbImage::from_pixel(width, height, image::Rgb(rgb));
        let mut bytes = Vec::new();
        image
            .write_to(&mut Cursor::new(&mut bytes), ImageFormat::Png)
            .unwrap();
        bytes
    }

    #[test]
    fn a_png_decodes_to_linear_with_its_chain() {
        let texture = decode_texture(&png(4, 2, [255, 128, 0]), "t.png").unwrap();
        assert_eq!(texture.size(), (4, 2));
        assert_eq!(texture.levels.len(), 3);
        let texel = texture.levels[0].texel(3, 1);
        assert_eq!(texel, [1.0, srgb_byte_to_linear(128), 0.0, 1.0]);
        assert!(!texture.has_alpha());
    }

    // The refusal of an absurd declared size is tested in tests/textures.rs, on a PNG whose
    // header says 100000×100000.

    #[test]
    fn text_is_not_an_image() {
        let error = decode_texture(b"hello, world", "notes.png").unwrap_err();
        assert!(matches!(error, TextureError::NotImage { .. }), "{error:?}");
        assert!(
            error.to_string().starts_with("texture notes.png:"),
            "{error}"
        );
    }
}
