//! PNG samples and still PNG files: colour clamped to [0, 1] and sRGB-encoded at 8 or 16 bits
//! per channel. With alpha, the colour is straight (the frame's premultiplied colour divided by
//! its alpha) and the alpha is stored linearly, as PNG specifies.

use glam::Vec3;
use rayon::prelude::*;

use super::format::PngDepth;
use crate::render::{Frame, encode_srgb, encode_srgb16};

/// A frame's PNG samples, row-major, RGB or RGBA per pixel.
#[derive(Debug, Clone, PartialEq)]
pub enum PngSamples {
    Eight(Vec<u8>),
    /// Native-endian values (PNG files store them big-endian).
    Sixteen(Vec<u16>),
}

impl PngSamples {
    /// The samples of `frame` at `depth`: RGBA when the frame has alpha, else RGB.
    pub fn of(frame: &Frame, depth: PngDepth) -> PngSamples {
        match depth {
            PngDepth::Eight => PngSamples::Eight(samples8(frame)),
            PngDepth::Sixteen => PngSamples::Sixteen(samples(frame, encode_srgb16, |a| {
                (a.clamp(0.0, 1.0) * 65535.0 + 0.5) as u16
            })),
        }
    }

    /// The samples as PNG stores them: 16-bit values big-endian.
    pub fn to_png_bytes(&self) -> Vec<u8> {
        match self {
            PngSamples::Eight(bytes) => bytes.clone(),
            PngSamples::Sixteen(values) => values.iter().flat_map(|v| v.to_be_bytes()).collect(),
        }
    }
}

/// The 8-bit samples of `frame`: RGBA when the frame has alpha, else RGB.
pub fn samples8(frame: &Frame) -> Vec<u8> {
    if frame.alpha.is_none() {
        return frame.to_srgb8();
    }
    samples(frame, encode_srgb, |a| {
        (a.clamp(0.0, 1.0) * 255.0 + 0.5) as u8
    })
}

/// Each pixel's colour through `encode`, straight when the frame has alpha, followed by its
/// alpha through `encode_alpha`.
fn samples<T: Send>(frame: &Frame, encode: fn(f32) -> T, encode_alpha: fn(f32) -> T) -> Vec<T> {
    let Some(alpha) = &frame.alpha else {
        return frame
            .pixels
            .par_iter()
            .flat_map_iter(|p| p.to_array().map(encode))
            .collect();
    };
    frame
        .pixels
        .par_iter()
        .zip(alpha)
        .flat_map_iter(|(&p, &a)| {
            let [r, g, b] = straight(p, a).to_array().map(encode);
            [r, g, b, encode_alpha(a)]
        })
        .collect()
}

/// The straight colour of a pixel with premultiplied colour `premultiplied` and alpha `alpha`:
/// black where nothing covers it.
#[inline]
pub fn straight(premultiplied: Vec3, alpha: f32) -> Vec3 {
    if alpha > 0.0 {
        premultiplied / alpha
    } else {
        Vec3::ZERO
    }
}

/// The frame as a PNG file's bytes, at `depth`, RGBA when the frame has alpha.
pub fn encode_png(frame: &Frame, depth: PngDepth) -> Result<Vec<u8>, image::ImageError> {
    use image::ExtendedColorType as Color;
    let alpha = frame.alpha.is_some();
    let samples = PngSamples::of(frame, depth);
    let (bytes, color): (&[u8], _) = match (&samples, alpha) {
        (PngSamples::Eight(b), false) => (b, Color::Rgb8),
        (PngSamples::Eight(b), true) => (b, Color::Rgba8),
        (PngSamples::Sixteen(v), false) => (bytemuck::cast_slice(v), Color::Rgb16),
        (PngSamples::Sixteen(v), true) => (bytemuck::cast_slice(v), Color::Rgba16),
    };
    let mut file = Vec::new();
    let encoder = image::codecs::png::PngEncoder::new(&mut file);
    image::ImageEncoder::write_image(encoder, bytes, frame.width, frame.height, color)?;
    Ok(file)
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::{PngSamples, straight};
    use crate::export::format::PngDepth;
    use crate::render::{Frame, encode_srgb16};

    #[test]
    fn eight_bit_samples_without_alpha_are_the_frames_srgb_bytes() {
        let mut frame = Frame::filled(3, 2, Vec3::new(0.2, 0.5, 1.5));
        frame.pixels[4] = Vec3::new(-1.0, 0.001, 0.75);
        assert_eq!(
            PngSamples::of(&frame, PngDepth::Eight),
            PngSamples::Eight(frame.to_srgb8())
        );
    }

    #[test]
    fn alpha_follows_straight_colour() {
        // Premultiplied (0.25, 0.1, 0) at alpha ½ is straight (0.5, 0.2, 0).
        let mut frame = Frame::filled(2, 1, Vec3::new(0.25, 0.1, 0.0));
        frame.alpha = Some(vec![0.5, 0.0]);
        let PngSamples::Sixteen(values) = PngSamples::of(&frame, PngDepth::Sixteen) else {
            panic!("16-bit samples");
        };
        let expected = [0.5, 0.2, 0.0].map(encode_srgb16);
        assert_eq!(values[..3], expected);
        assert_eq!(
            values[3], 32768,
            "alpha ½ is stored linearly: 0.5·65535 rounded"
        );
        assert_eq!(
            values[4..],
            [0, 0, 0, 0],
            "an uncovered pixel is transparent black"
        );
        assert_eq!(straight(Vec3::ONE, 1.0), Vec3::ONE);
    }

    #[test]
    fn sixteen_bit_values_are_stored_big_endian() {
        let samples = PngSamples::Sixteen(vec![0x1234, 0xabcd]);
        assert_eq!(samples.to_png_bytes(), [0x12, 0x34, 0xab, 0xcd]);
    }
}
