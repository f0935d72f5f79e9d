//! What an export writes, chosen from the file name, and the one function that renders a world
//! to a file: `rastray render` and the editor's export both come here.

use std::path::Path;
use std::sync::Arc;

use super::destination::Destination;
use super::error::ExportError;
use super::format::{AnimationFormat, FormatError, ImageFormat};
use super::still::render_image;
use super::turntable::{Turntable, TurntableStats, render_turntable};
use crate::memory_budget::{
    BYTES_PER_ANIMATION_PIXEL, BYTES_PER_STILL_PIXEL, Estimate, OverBudget,
};
use crate::render::{Progress, RenderOptions, RenderStats};
use crate::scene::Camera;
use crate::world::World;

/// What an export writes: one still image, or a turntable.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Output {
    Image(ImageFormat),
    Turntable(Turntable, AnimationFormat),
}

/// What an export did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Exported {
    Image(RenderStats),
    Turntable(TurntableStats),
}

impl Output {
    /// Refuses, before rendering, this output of `world` at `options`' size when its frame beside
    /// the world passes the memory bound (figures naming `file`): a still image's frame and its
    /// encoding, or one frame in flight of a turntable (which renders more at once only where
    /// the bound leaves room).
    pub fn check_memory(
        self,
        world: &World,
        options: &RenderOptions,
        file: &Path,
    ) -> Result<(), OverBudget> {
        let pixels = u64::from(options.width) * u64::from(options.height);
        let per_pixel = match self {
            Output::Image(_) => BYTES_PER_STILL_PIXEL,
            Output::Turntable(..) => BYTES_PER_ANIMATION_PIXEL,
        };
        Estimate::of_world(world)
            .with_frames(1, pixels, per_pixel)
            .check(file)
    }

    /// What to write to `path`: a turntable when `turntable` is given, else a still image; in
    /// the `requested` format, or the one the extension names.
    pub fn for_path(
        path: &Path,
        requested: Option<ImageFormat>,
        turntable: Option<Turntable>,
    ) -> Result<Output, FormatError> {
        Ok(match turntable {
            Some(t) => Output::Turntable(t, AnimationFormat::for_path(path, requested)?),
            None => Output::Image(ImageFormat::for_path(path, requested)?),
        })
    }

    /// As [`Output::for_path`] for `destination`; a stream whose name has no extension
    /// (standard output, `/dev/null`, a FIFO named `pipe`) takes the `requested` format, or PNG.
    pub fn for_destination(
        destination: &Destination,
        requested: Option<ImageFormat>,
        turntable: Option<Turntable>,
    ) -> Result<Output, FormatError> {
        let path = destination.path();
        if !destination.is_stream() || path.extension().is_some() {
            return Output::for_path(path, requested, turntable);
        }
        let format = requested.unwrap_or(ImageFormat::PNG8);
        Ok(match (turntable, format) {
            (None, format) => Output::Image(format),
            (Some(t), ImageFormat::Png(depth)) => {
                Output::Turntable(t, AnimationFormat::Apng(depth))
            }
            (Some(_), format) => {
                return Err(FormatError::NotAnimated {
                    path: path.to_path_buf(),
                    format,
                });
            }
        })
    }
}

/// Renders `world` seen by `camera` with `options` into `path` as `output` says: one image,
/// or a turntable around `camera`. A regular file is replaced atomically, a FIFO or character
/// device written as a stream ([`Destination::for_path`]). `progress` follows the work and
/// cancels it; a file is written only when everything was rendered and nothing cancelled.
pub fn render_to_file(
    world: &Arc<World>,
    camera: &Camera,
    options: &RenderOptions,
    output: Output,
    path: &Path,
    progress: &Progress,
) -> Result<Exported, ExportError> {
    let destination = Destination::for_path(path)?;
    render_to(world, camera, options, output, &destination, progress)
}

/// As [`render_to_file`], to a destination chosen by the caller (standard output, for one).
pub fn render_to(
    world: &Arc<World>,
    camera: &Camera,
    options: &RenderOptions,
    output: Output,
    destination: &Destination,
    progress: &Progress,
) -> Result<Exported, ExportError> {
    Ok(match output {
        Output::Image(format) => Exported::Image(render_image(
            world,
            camera,
            options,
            format,
            destination,
            progress,
        )?),
        Output::Turntable(turntable, format) => Exported::Turntable(render_turntable(
            world,
            camera,
            options,
            turntable,
            format,
            destination,
            progress,
        )?),
    })
}
