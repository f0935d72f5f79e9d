//! One interface over the animation encoders: a rendered frame is made ready (converted,
//! quantized, compressed) on any thread, then written in order by one writer.

use std::io::Write;

use super::apng::{self, ApngHeader, apng_frame};
use super::format::{AnimationFormat, PngDepth};
use super::gif_animation::{self, gif_frame, gif_frame_of_samples, to_u16};
use crate::render::Frame;

/// A frame made ready to write.
pub enum ReadyFrame {
    Gif(gif::Frame<'static>),
    /// PNG sample bytes, big-endian.
    Png(Vec<u8>),
}

/// An animation file being written, frame by frame, in order.
pub enum AnimationWriter<W: Write> {
    Gif(gif::Encoder<W>),
    Apng(png::Writer<W>),
}

/// What every frame of an animation shares.
#[derive(Debug, Clone, Copy)]
pub struct Animation {
    pub format: AnimationFormat,
    pub width: u32,
    pub height: u32,
    /// Whether the frames carry alpha.
    pub alpha: bool,
    pub frames: u32,
    /// Frames per second, in 1..=[`super::turntable::MAX_FPS`].
    pub fps: u32,
}

impl Animation {
    /// `frame` made ready to write; runs on any thread.
    pub fn ready(&self, frame: &Frame) -> ReadyFrame {
        match self.format {
            AnimationFormat::Gif => ReadyFrame::Gif(gif_frame(frame, self.gif_delay())),
            AnimationFormat::Apng(depth) => ReadyFrame::Png(apng_frame(frame, depth)),
        }
    }

    /// A frame made ready from its samples as a still PNG of it stores them (8-bit, or 16-bit
    /// big-endian; RGBA when the animation has alpha, else RGB): the same frame as
    /// [`Animation::ready`] makes of the render itself. A GIF takes 8-bit samples only.
    pub fn ready_samples(&self, samples: Vec<u8>) -> ReadyFrame {
        match self.format {
            AnimationFormat::Gif => ReadyFrame::Gif(gif_frame_of_samples(
                &samples,
                to_u16(self.width),
                to_u16(self.height),
                self.alpha,
                self.gif_delay(),
            )),
            AnimationFormat::Apng(_) => ReadyFrame::Png(samples),
        }
    }

    /// GIF delays are in hundredths of a second.
    fn gif_delay(&self) -> u16 {
        (100.0 / self.fps as f32).round() as u16
    }

    /// Starts writing the animation to `out`.
    pub fn start<W: Write>(&self, out: W) -> Result<AnimationWriter<W>, String> {
        Ok(match self.format {
            AnimationFormat::Gif => AnimationWriter::Gif(
                gif_animation::start(out, self.width, self.height).map_err(|e| e.to_string())?,
            ),
            AnimationFormat::Apng(depth) => AnimationWriter::Apng(
                apng::start(out, self.apng_header(depth)).map_err(|e| e.to_string())?,
            ),
        })
    }

    fn apng_header(&self, depth: PngDepth) -> ApngHeader {
        ApngHeader {
            width: self.width,
            height: self.height,
            depth,
            alpha: self.alpha,
            frames: self.frames,
            fps: self.fps,
        }
    }
}

impl<W: Write> AnimationWriter<W> {
    /// Writes the next frame.
    pub fn write(&mut self, frame: &ReadyFrame) -> Result<(), String> {
        match (self, frame) {
            (AnimationWriter::Gif(encoder), ReadyFrame::Gif(frame)) => {
                gif_animation::write_frame(encoder, frame).map_err(|e| e.to_string())
            }
            (AnimationWriter::Apng(writer), ReadyFrame::Png(bytes)) => {
                apng::write_frame(writer, bytes).map_err(|e| e.to_string())
            }
            _ => unreachable!("frames are made ready for the writer's own format"),
        }
    }

    /// Ends the file after the last frame.
    pub fn finish(self) -> Result<(), String> {
        match self {
            AnimationWriter::Gif(encoder) => {
                encoder.into_inner().map(drop).map_err(|e| e.to_string())
            }
            AnimationWriter::Apng(writer) => writer.finish().map_err(|e| e.to_string()),
        }
    }
}
