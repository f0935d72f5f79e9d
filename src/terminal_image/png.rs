//! An 8-bit sRGB picture as PNG bytes, for the protocols that carry PNG.

use super::preview::PreviewImage;

/// `image` as an RGB PNG.
pub fn encode(image: &PreviewImage) -> Result<Vec<u8>, image::ImageError> {
    let mut bytes = Vec::new();
    let encoder = image::codecs::png::PngEncoder::new(&mut bytes);
    image::ImageEncoder::write_image(
        encoder,
        image.pixels.as_flattened(),
        image.width,
        image.height,
        image::ExtendedColorType::Rgb8,
    )?;
    Ok(bytes)
}
