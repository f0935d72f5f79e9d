//! The renderer core: one camera, one lighting function, three algorithms.

pub mod accel;
mod algorithm;
pub mod bvh;
mod bvh_build;
pub mod camera;
pub mod frame;
pub mod gouraud;
pub mod intersect;
mod options;
pub mod phong;
pub mod progress;
pub mod raster;
pub mod ray;
pub mod raytrace;
pub mod shading;
pub mod zbuffer;

pub use algorithm::Algorithm;
pub use camera::View;
pub use frame::Frame;
pub use options::{MAX_DIMENSION, MAX_SAMPLES, MAX_SAMPLES_TOTAL, RenderOptions, Size, SizeError};
pub use progress::{Cancelled, Progress};

use crate::scene::Camera;
use crate::world::World;

/// Why a render produced no image.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum RenderError {
    #[error(transparent)]
    Size(#[from] SizeError),
    #[error(transparent)]
    Cancelled(#[from] Cancelled),
}

/// Renders `world` seen by `camera` with `options`: the one entry point behind the PNG export,
/// the terminal preview and the benchmark. Supersampling renders N× larger and box-filters down,
/// the same for every algorithm.
pub fn render(
    world: &World,
    camera: &Camera,
    options: &RenderOptions,
    progress: &Progress,
) -> Result<Frame, RenderError> {
    options.check()?;
    let n = options.samples;
    let view = View::new(camera, options.width * n, options.height * n);
    let frame = match options.algorithm {
        Algorithm::Gouraud => gouraud::render(world, &view, progress)?,
        Algorithm::Phong => phong::render(world, &view, progress)?,
        Algorithm::Ray => raytrace::render(world, &view, options, progress)?,
    };
    Ok(frame.downsample(n))
}
