//! PNG or JPEG bytes to a [`Texture`]: the header's size checked first and committed to the
//! model's memory account, then the image decoded, turned from sRGB to 16-bit linear (halved on
//! the way when it is larger than the base level may be) and given its mip chain.

use std::io::Cursor;

use image::{ImageFormat, ImageReader, Limits};

use super::error::TextureError;
use super::ledger::TextureLedger;
use super::limits::{MAX_TEXTURE_BASE_TEXELS, MAX_TEXTURE_DECLARED_TEXELS, MAX_TEXTURE_SIDE};
use super::mip_chain::{halved, halved_with, mip_chain};
use super::texture::{MipLevel, Texture};
use crate::mesh::srgb::srgb_byte_table;

/// Decodes `bytes`, a PNG or JPEG image, into a texture named `name`, once the size its header
/// declares is committed to `ledger`, the model's account. The colour channels are sRGB-encoded
/// and become linear; alpha is kept as it is.
///
/// Memory while decoding: the 8-bit image (4 bytes a declared texel, at most 268 MB) beside the
/// base level (8 bytes a texel of at most [`MAX_TEXTURE_BASE_TEXELS`], 134 MB) and, for an image
/// kept whole, its first halving (2 bytes a texel); the linear image at full size is never held
/// when it is halved, and the rest of the chain is made once the 8-bit image is gone. The most
/// is 402 MB, for an 8192×8192 image.
pub fn decode_texture(
    bytes: &[u8],
    name: &str,
    ledger: &TextureLedger,
) -> Result<Texture, TextureError> {
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
    ledger
        .commit(width, height)
        .map_err(|over| TextureError::OverBudget {
            name: name.to_string(),
            figures: over.figures(),
        })?;
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
    let finest = finest_levels(&rgba, MAX_TEXTURE_BASE_TEXELS);
    // The 8-bit image goes before the rest of the chain is made.
    drop(rgba);
    Ok(Texture {
        name: name.to_string(),
        file_size: (width, height),
        levels: chain(finest),
    })
}

/// `rgba`'s finest level: the image decoded when it has at most `max_texels`, else the image
/// halved in linear space until it does; and, for an image kept whole, its first halving. Each
/// first halving reads the 8-bit texels and decodes them exactly (the same sums as halving the
/// decoded image, without holding it whole, and without the rounding of the 16-bit level 0).
fn finest_levels(rgba: &image::RgbaImage, max_texels: u64) -> (MipLevel, Option<MipLevel>) {
    let (width, height) = rgba.dimensions();
    let srgb = srgb_byte_table();
    let linear = |x, y| decode_texel(srgb, rgba.get_pixel(x, y).0);
    if u64::from(width) * u64::from(height) > max_texels {
        let mut base = halved_with(width, height, linear);
        while u64::from(base.width) * u64::from(base.height) > max_texels {
            base = halved(&base);
        }
        return (base, None);
    }
    let image = MipLevel::linear(
        width,
        height,
        rgba.pixels().map(|p| decode_texel(srgb, p.0)),
    );
    let next = (width > 1 || height > 1).then(|| halved_with(width, height, linear));
    (image, next)
}

/// The whole mip chain from [`finest_levels`]: the finest level, then every halving of the
/// next one (or of the finest, when there is no next).
fn chain((finest, next): (MipLevel, Option<MipLevel>)) -> Vec<MipLevel> {
    match next {
        None => mip_chain(finest),
        Some(next) => std::iter::once(finest).chain(mip_chain(next)).collect(),
    }
}

/// The linear RGBA of an 8-bit texel: its colour decoded through `srgb` (the sRGB decode's
/// table), its alpha code / 255.
fn decode_texel(srgb: &[f32; 256], [r, g, b, a]: [u8; 4]) -> [f32; 4] {
    let [r, g, b] = [r, g, b].map(|c| srgb[usize::from(c)]);
    [r, g, b, f32::from(a) / 255.0]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::srgb_byte_to_linear;

    /// A PNG of `width × height` opaque texels, every one `rgb`.
    fn png(width: u32, height: u32, rgb: [u8; 3]) -> Vec<u8> {
        let image = image::RgbImage::from_pixel(width, height, image::Rgb(rgb));
        let mut bytes = Vec::new();
        image
            .write_to(&mut Cursor::new(&mut bytes), ImageFormat::Png)
            .unwrap();
        bytes
    }

    /// A fresh account for a model `m.gltf`.
    fn ledger() -> TextureLedger {
        TextureLedger::new(std::path::Path::new("m.gltf"))
    }

    #[test]
    fn a_png_decodes_to_linear_with_its_chain() {
        let ledger = ledger();
        let texture = decode_texture(&png(4, 2, [255, 128, 0]), "t.png", &ledger).unwrap();
        assert_eq!(ledger.committed(), texture.memory_bytes() as u64);
        assert_eq!(texture.size(), (4, 2));
        assert_eq!(texture.levels.len(), 3);
        let [r, g, b, a] = texture.levels[0].texel(3, 1);
        assert_eq!([r, b, a], [1.0, 0.0, 1.0]);
        // Within half a 16-bit step of the exact decode.
        assert!((g - srgb_byte_to_linear(128)).abs() <= 0.5 / 65535.0, "{g}");
        // 16-bit texels: 4×2, 2×1 and 1×1.
        assert_eq!(texture.memory_bytes(), 8 * (8 + 2 + 1));
        assert!(!texture.has_alpha());
    }

    // The refusal of an absurd declared size is tested in tests/textures.rs, on a PNG whose
    // header says 100000×100000.

    #[test]
    fn text_is_not_an_image() {
        let error = decode_texture(b"hello, world", "notes.png", &ledger()).unwrap_err();
        assert!(matches!(error, TextureError::NotImage { .. }), "{error:?}");
        assert!(
            error.to_string().starts_with("texture notes.png:"),
            "{error}"
        );
    }

    #[test]
    fn a_texture_past_the_model_s_budget_is_refused_before_decoding() {
        let ledger = ledger();
        ledger.count_model(crate::memory_budget::Estimate {
            triangles: crate::memory_budget::MAX_TRIANGLES,
            objects: 1,
            ..Default::default()
        });
        // The header alone is read: a body that is not a PNG's would fail to decode.
        let mut bytes = png(64, 64, [1, 2, 3]);
        let body = bytes.len() / 2;
        bytes[body..].fill(0);
        let error = decode_texture(&bytes, "big.png", &ledger).unwrap_err();
        assert!(
            matches!(error, TextureError::OverBudget { .. }),
            "{error:?}"
        );
        assert!(
            error
                .to_string()
                .starts_with("texture big.png: decoding it would pass the memory bound: "),
            "{error}"
        );
        assert!(ledger.refusal().is_some());
    }

    #[test]
    fn every_level_comes_from_the_exact_decode() {
        let image = image::RgbaImage::from_fn(7, 5, |x, y| {
            image::Rgba([
                (x * 37 + y * 11) as u8,
                (x * y * 13) as u8,
                (y * 50) as u8,
                200,
            ])
        });
        let srgb = srgb_byte_table();
        let exact = |x, y| decode_texel(srgb, image.get_pixel(x, y).0);
        let decoded = image.pixels().map(|p| decode_texel(srgb, p.0));
        let whole = chain(finest_levels(&image, u64::MAX));
        assert_eq!(whole[0], MipLevel::linear(7, 5, decoded));
        // Level 1 halves the exact decode, not the rounded level 0.
        let mut expected = halved_with(7, 5, exact);
        assert_eq!(whole[1], expected);
        assert_eq!(whole.len(), 3, "7×5, 3×2, 1×1");
        // An image past the limit: halved while it is decoded, with the same sums.
        for max_texels in [34, 6, 2, 1] {
            while u64::from(expected.width) * u64::from(expected.height) > max_texels {
                expected = halved(&expected);
            }
            let fused = chain(finest_levels(&image, max_texels));
            assert_eq!(fused[0], expected, "max {max_texels}");
        }
    }
}
