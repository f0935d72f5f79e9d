//! What an export writes, chosen from the file name, and the one function that renders a world
//! to a file: `rastray render` and the editor's export both come here.

use std::path::Path;
use std::sync::Arc;

use super::error::ExportError;
use super::format::{AnimationFormat, FormatError, ImageFormat};
use super::still::render_image;
use super::turntable::{Turntable, TurntableStats, render_turntable};
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
}

/// Renders `world` seen by `camera` with `options` into `path` as `output` says, atomically:
/// one image, or a turntable around `camera`. `progress` follows the work and cancels it; the
/// file is written only when everything was rendered.
pub fn render_to_file(
    world: &Arc<World>,
    camera: &Camera,
    options: &RenderOptions,
    output: Output,
    path: &Path,
    progress: &Progress,
) -> Result<Exported, ExportError> {
    Ok(match output {
        Output::Image(format) => Exported::Image(render_image(
            world, camera, options, format, path, progress,
        )?),
        Output::Turntable(turntable, format) => Exported::Turntable(render_turntable(
            world, camera, options, turntable, format, path, progress,
        )?),
    })
}
