//! Animated GIF: each frame quantized to its own 256-colour palette (NeuQuant) and
//! LZW-compressed on the render threads, then written in order. GIF has one bit of
//! transparency: a pixel is opaque when its alpha is at least ½.

use std::io::Write;

use super::png::samples8;
use crate::render::Frame;

/// NeuQuant's sampling: 1 is slowest and best, 30 fastest; 10 is the usual balance.
const QUANTIZER_SPEED: i32 = 10;

/// `frame` as a GIF frame shown for `delay` hundredths of a second, palette chosen and
/// compressed: ready for [`write_frame`].
pub fn gif_frame(frame: &Frame, delay: u16) -> gif::Frame<'static> {
    let (width, height) = gif_size(frame);
    gif_frame_of_samples(
        &samples8(frame),
        width,
        height,
        frame.alpha.is_some(),
        delay,
    )
}

/// As [`gif_frame`], from a frame's 8-bit sRGB samples (RGBA when `alpha`, else RGB): those a
/// still PNG of the frame stores, so a turntable joined from its frames' PNGs is the same GIF.
pub fn gif_frame_of_samples(
    samples: &[u8],
    width: u16,
    height: u16,
    alpha: bool,
    delay: u16,
) -> gif::Frame<'static> {
    let mut rgba: Vec<u8> = if alpha {
        samples
            .chunks_exact(4)
            .flat_map(|p| {
                let opaque = p[3] >= 128;
                [p[0], p[1], p[2], if opaque { 255 } else { 0 }]
            })
            .collect()
    } else {
        samples
            .chunks_exact(3)
            .flat_map(|p| [p[0], p[1], p[2], 255])
            .collect()
    };
    let mut out = gif::Frame::from_rgba_speed(width, height, &mut rgba, QUANTIZER_SPEED);
    out.delay = delay;
    // A transparent frame must not show the one before through its holes.
    out.dispose = if alpha {
        gif::DisposalMethod::Background
    } else {
        gif::DisposalMethod::Keep
    };
    out.make_lzw_pre_encoded();
    out
}

/// Starts a GIF of `width`×`height` frames (each at most 65 535) that loops forever.
pub fn start<W: Write>(
    out: W,
    width: u32,
    height: u32,
) -> Result<gif::Encoder<W>, gif::EncodingError> {
    let (width, height) = (to_u16(width), to_u16(height));
    let mut encoder = gif::Encoder::new(out, width, height, &[])?;
    encoder.set_repeat(gif::Repeat::Infinite)?;
    Ok(encoder)
}

/// Writes a frame made by [`gif_frame`].
pub fn write_frame<W: Write>(
    encoder: &mut gif::Encoder<W>,
    frame: &gif::Frame<'static>,
) -> Result<(), gif::EncodingError> {
    encoder.write_lzw_pre_encoded_frame(frame)
}

/// GIF sizes are 16-bit; the render limits keep every image within them.
fn gif_size(frame: &Frame) -> (u16, u16) {
    (to_u16(frame.width), to_u16(frame.height))
}

pub(super) fn to_u16(n: u32) -> u16 {
    const _: () = assert!(crate::render::MAX_DIMENSION <= u16::MAX as u32);
    n as u16
}
