//! Animated PNG: every frame a full image in the same encoding as a still PNG, sRGB at 8 or 16
//! bits per channel, straight alpha when rendered with alpha.

use std::io::Write;

use super::format::PngDepth;
use super::png::PngSamples;
use crate::render::Frame;

/// `frame` as an animated PNG frame's bytes: ready for [`write_frame`].
pub fn apng_frame(frame: &Frame, depth: PngDepth) -> Vec<u8> {
    PngSamples::of(frame, depth).to_png_bytes()
}

/// The shape of an animated PNG.
#[derive(Debug, Clone, Copy)]
pub struct ApngHeader {
    pub width: u32,
    pub height: u32,
    pub depth: PngDepth,
    pub alpha: bool,
    pub frames: u32,
    /// Frames per second, ≥ 1.
    pub fps: u32,
}

/// Starts an animated PNG of `header.frames` frames that loops forever.
pub fn start<W: Write>(out: W, header: ApngHeader) -> Result<png::Writer<W>, png::EncodingError> {
    let mut encoder = png::Encoder::new(out, header.width, header.height);
    encoder.set_color(if header.alpha {
        png::ColorType::Rgba
    } else {
        png::ColorType::Rgb
    });
    encoder.set_depth(match header.depth {
        PngDepth::Eight => png::BitDepth::Eight,
        PngDepth::Sixteen => png::BitDepth::Sixteen,
    });
    encoder.set_compression(png::Compression::Fast);
    encoder.set_animated(header.frames, 0)?;
    encoder.set_frame_delay(1, header.fps as u16)?;
    if header.alpha {
        // A transparent frame must not show the one before through its holes.
        encoder.set_dispose_op(png::DisposeOp::Background)?;
    }
    encoder.write_header()
}

/// Writes a frame made by [`apng_frame`].
pub fn write_frame<W: Write>(
    writer: &mut png::Writer<W>,
    frame: &[u8],
) -> Result<(), png::EncodingError> {
    writer.write_image_data(frame)
}
