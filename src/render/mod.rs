//! The renderer core: one camera, one lighting function, three algorithms.

pub mod accel;
mod algorithm;
pub mod bvh;
mod bvh_build;
pub mod camera;
pub mod fragments;
pub mod frame;
pub mod gouraud;
pub mod intersect;
pub mod lane_vec;
pub mod lanes;
pub mod materials;
mod options;
pub mod packet;
pub mod phong;
pub mod pow;
pub mod progress;
pub mod raster;
pub mod ray;
pub mod raytrace;
pub mod shading;

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

/// Samples rendered at once: larger images are rendered in strips of about this many samples,
/// each box-filtered before the next starts, so memory stays bounded and progress flows.
const STRIP_SAMPLES: u64 = 1 << 22;

/// Renders `world` seen by `camera` with `options`: the one entry point behind the PNG export,
/// the terminal preview and the benchmark. Supersampling renders N× larger and box-filters down,
/// the same for every algorithm. `progress` counts rows of the supersampled image.
pub fn render(
    world: &World,
    camera: &Camera,
    options: &RenderOptions,
    progress: &Progress,
) -> Result<Frame, RenderError> {
    render_prepared(world, None, camera, options, progress)
}

/// As [`render`], reusing the ray tracer's acceleration structure when one built from this very
/// `world` is given (the editor keeps it while only the camera moves); built here when needed.
pub fn render_prepared(
    world: &World,
    accel: Option<&accel::SceneAccel>,
    camera: &Camera,
    options: &RenderOptions,
    progress: &Progress,
) -> Result<Frame, RenderError> {
    options.check()?;
    let n = options.samples;
    let full = View::new(camera, options.width * n, options.height * n);
    progress.start(full.height as u64);
    let strip_rows = (STRIP_SAMPLES / (full.width as u64 * (n * n) as u64))
        .clamp(1, options.height as u64) as u32;
    let mut pixels = Vec::with_capacity(options.width as usize * options.height as usize);
    // The ray tracer's acceleration structure is built once for all strips.
    let built = match accel {
        None if options.algorithm == Algorithm::Ray => Some(accel::SceneAccel::build(world)),
        _ => None,
    };
    let accel = accel.or(built.as_ref());
    for first in (0..options.height).step_by(strip_rows as usize) {
        let rows = strip_rows.min(options.height - first);
        let view = full.rows(first * n, rows * n);
        let strip = match options.algorithm {
            Algorithm::Gouraud => gouraud::render(world, &view, progress)?,
            Algorithm::Phong => phong::render(world, &view, progress)?,
            Algorithm::Ray => {
                let accel = accel.expect("given or built above for the ray tracer");
                raytrace::render_with(accel, world, &view, options, progress)?
            }
        };
        let strip = strip.downsample(n);
        if rows == options.height {
            return Ok(strip); // One strip is the whole image: no copy.
        }
        pixels.extend(strip.pixels);
    }
    Ok(Frame {
        width: options.width,
        height: options.height,
        pixels,
    })
}
