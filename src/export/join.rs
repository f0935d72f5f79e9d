//! Joining still PNG frames into one animation (`rastray join frames/*.png -o spin.gif`): the
//! frames of a turntable rendered apart, on other machines or in ranges, become the file one
//! `--turntable` run writes, byte for byte. A frame's PNG holds exactly the samples the
//! animation's encoder takes from the render, so nothing is lost between the two.

use std::io::{BufWriter, Cursor};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use rayon::prelude::*;

use super::animation::{Animation, ReadyFrame};
use super::destination::Destination;
use super::error::ExportError;
use super::format::{AnimationFormat, ImageFormat, PngDepth};
use super::turntable::{MAX_FRAMES, Turntable};
use crate::input_file::{MAX_MODEL_BYTES, read_bounded};
use crate::render::{MAX_DIMENSION, Progress, RenderError};

/// The shape every frame of a join shares, taken from the first.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct FrameShape {
    width: u32,
    height: u32,
    depth: PngDepth,
    alpha: bool,
}

/// What a join did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JoinStats {
    pub frames: u32,
    pub width: u32,
    pub height: u32,
    /// Wall-clock time from the first frame read to the file written.
    pub elapsed: Duration,
}

/// Joins the PNG `frames`, in the order given, into one animation at `fps` frames per second
/// written to `destination` (a file atomically): a GIF for `.gif`, an animated PNG for `.png`
/// at the frames' depth (`requested` may name it and must match). Every frame must be a still
/// PNG of the first one's size, depth and channels, as `rastray render` writes them; a GIF is
/// made of 8-bit frames. Cancelling `progress` stops it and leaves a file untouched.
pub fn join_frames(
    frames: &[PathBuf],
    fps: u32,
    requested: Option<ImageFormat>,
    destination: &Destination,
    progress: &Progress,
) -> Result<JoinStats, ExportError> {
    let path = destination.path();
    let started = Instant::now();
    let count = frames.len().min(MAX_FRAMES as usize + 1) as u32;
    Turntable { frames: count, fps }.check()?;
    let first = &frames[0];
    let shape = read_frame(first)?.0;
    let format = animation_format(path, requested, shape, first)?;
    let animation = Animation {
        format,
        width: shape.width,
        height: shape.height,
        alpha: shape.alpha,
        frames: count,
        fps,
    };
    let encode_error = |message: String| ExportError::encode(path, format, message);
    let mut out = BufWriter::new(destination.open(progress)?);
    let mut writer = animation.start(&mut out).map_err(encode_error)?;
    progress.start(count.into());
    // Frames are read and made ready (a GIF's palette chosen) in parallel, a batch at a time,
    // and written in order.
    let batch = rayon::current_num_threads().max(1);
    for chunk in frames.chunks(batch) {
        progress.check().map_err(RenderError::from)?;
        let ready: Vec<Result<ReadyFrame, ExportError>> = chunk
            .par_iter()
            .map(|frame| {
                let (found, samples) = read_frame(frame)?;
                if found != shape {
                    return Err(ExportError::Join {
                        path: frame.clone(),
                        message: format!(
                            "this frame is {}, the first ({}) is {}: every frame of a join has one size, depth and set of channels",
                            describe(found),
                            first.display(),
                            describe(shape)
                        ),
                    });
                }
                Ok(animation.ready_samples(samples))
            })
            .collect();
        for frame in ready {
            writer.write(&frame?).map_err(encode_error)?;
            progress.advance(1);
        }
    }
    writer.finish().map_err(encode_error)?;
    let file = out
        .into_inner()
        .map_err(|e| ExportError::io(path, e.into_error()))?;
    file.commit(progress).map_err(|e| e.at(path))?;
    Ok(JoinStats {
        frames: count,
        width: shape.width,
        height: shape.height,
        elapsed: started.elapsed(),
    })
}

/// The animation written to `path`: GIF from 8-bit frames, or an animated PNG at the frames'
/// depth.
fn animation_format(
    path: &Path,
    requested: Option<ImageFormat>,
    shape: FrameShape,
    first: &Path,
) -> Result<AnimationFormat, ExportError> {
    let format = AnimationFormat::for_path(path, requested)?;
    match format {
        AnimationFormat::Gif if shape.depth == PngDepth::Sixteen => Err(ExportError::Join {
            path: first.to_path_buf(),
            message: "a GIF is joined from 8-bit frames; these are 16-bit (join them into a .png)"
                .to_string(),
        }),
        AnimationFormat::Apng(depth) if requested.is_some() && depth != shape.depth => {
            Err(ExportError::Join {
                path: first.to_path_buf(),
                message: format!(
                    "the frames are {}; --format asks for another depth",
                    describe(shape)
                ),
            })
        }
        AnimationFormat::Apng(_) => Ok(AnimationFormat::Apng(shape.depth)),
        AnimationFormat::Gif => Ok(AnimationFormat::Gif),
    }
}

/// "32x18 8-bit RGB", as messages describe a frame.
fn describe(shape: FrameShape) -> String {
    format!(
        "{}x{} {}-bit {}",
        shape.width,
        shape.height,
        if shape.depth == PngDepth::Eight {
            8
        } else {
            16
        },
        if shape.alpha { "RGBA" } else { "RGB" }
    )
}

/// The frame at `path`, read bounded: its shape and its samples as stored (16-bit values
/// big-endian).
fn read_frame(path: &Path) -> Result<(FrameShape, Vec<u8>), ExportError> {
    let bytes =
        read_bounded(path, MAX_MODEL_BYTES, "a frame").map_err(|e| ExportError::io(path, e))?;
    let not_a_frame = |message: String| ExportError::Join {
        path: path.to_path_buf(),
        message,
    };
    let mut decoder = png::Decoder::new(Cursor::new(bytes));
    decoder.set_transformations(png::Transformations::IDENTITY);
    let mut reader = decoder
        .read_info()
        .map_err(|e| not_a_frame(format!("not a PNG frame: {e}")))?;
    let depth = match reader.info().bit_depth {
        png::BitDepth::Eight => PngDepth::Eight,
        png::BitDepth::Sixteen => PngDepth::Sixteen,
        other => {
            return Err(not_a_frame(format!(
                "a {other:?}-bit PNG; frames are 8- or 16-bit, as rastray writes them"
            )));
        }
    };
    let alpha = match reader.info().color_type {
        png::ColorType::Rgb => false,
        png::ColorType::Rgba => true,
        other => {
            return Err(not_a_frame(format!(
                "a {other:?} PNG; frames are RGB or RGBA, as rastray writes them"
            )));
        }
    };
    let size = reader
        .output_buffer_size()
        .ok_or_else(|| not_a_frame("too large a frame".to_string()))?;
    let mut samples = vec![0; size];
    let info = reader
        .next_frame(&mut samples)
        .map_err(|e| not_a_frame(format!("cannot decode: {e}")))?;
    samples.truncate(info.buffer_size());
    if info.width > MAX_DIMENSION || info.height > MAX_DIMENSION {
        return Err(not_a_frame(format!(
            "{}x{} is larger than rastray renders (at most {MAX_DIMENSION} a side)",
            info.width, info.height
        )));
    }
    let shape = FrameShape {
        width: info.width,
        height: info.height,
        depth,
        alpha,
    };
    Ok((shape, samples))
}
