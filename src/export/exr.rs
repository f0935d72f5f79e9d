//! OpenEXR files: the frame's linear colour as 32-bit floats, exactly as rendered (no clamping,
//! no tone curve); with alpha, RGBA with premultiplied colour, as OpenEXR specifies.

use std::io::Cursor;

use crate::render::Frame;

/// The frame as an OpenEXR file's bytes: RGB, or RGBA when the frame has alpha.
pub fn encode_exr(frame: &Frame) -> Result<Vec<u8>, image::ImageError> {
    use image::ExtendedColorType as Color;
    let (values, color): (Vec<f32>, _) = match &frame.alpha {
        None => (
            frame.pixels.iter().flat_map(|p| p.to_array()).collect(),
            Color::Rgb32F,
        ),
        Some(alpha) => (
            frame
                .pixels
                .iter()
                .zip(alpha)
                .flat_map(|(p, &a)| [p.x, p.y, p.z, a])
                .collect(),
            Color::Rgba32F,
        ),
    };
    let mut file = Cursor::new(Vec::new());
    let encoder = image::codecs::openexr::OpenExrEncoder::new(&mut file);
    image::ImageEncoder::write_image(
        encoder,
        bytemuck::cast_slice(&values),
        frame.width,
        frame.height,
        color,
    )?;
    Ok(file.into_inner())
}
