//! The renderer core: one camera, one lighting function, three algorithms.

mod algorithm;
pub mod camera;
pub mod frame;
pub mod materials;
mod options;
pub mod progress;
pub mod raster;
pub mod ray;
pub mod shading;
pub mod simd;

pub use algorithm::Algorithm;
pub use camera::View;
pub use frame::Frame;
pub use options::{MAX_DIMENSION, MAX_SAMPLES, MAX_SAMPLES_TOTAL, RenderOptions, Size, SizeError};
pub use progress::{Cancelled, Progress};

use glam::Vec3;

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

/// As [`render`], into `frame`, whose buffer is kept when it already has the size asked for:
/// repeated renders (a live preview, a benchmark) then skip faulting in fresh memory, which for
/// a 1920×1080 frame of 25 MB can cost as much as the render itself.
pub fn render_into(
    world: &World,
    camera: &Camera,
    options: &RenderOptions,
    progress: &Progress,
    frame: &mut Frame,
) -> Result<(), RenderError> {
    render_prepared_into(world, None, camera, options, progress, frame)
}

/// As [`render`], reusing the ray tracer's acceleration structure when one built from this very
/// `world` is given (the editor keeps it while only the camera moves); built here when needed.
pub fn render_prepared(
    world: &World,
    accel: Option<&ray::accel::SceneAccel>,
    camera: &Camera,
    options: &RenderOptions,
    progress: &Progress,
) -> Result<Frame, RenderError> {
    let mut frame = Frame::default();
    render_prepared_into(world, accel, camera, options, progress, &mut frame)?;
    Ok(frame)
}

/// As [`render_prepared`], into `frame` (see [`render_into`]).
pub fn render_prepared_into(
    world: &World,
    accel: Option<&ray::accel::SceneAccel>,
    camera: &Camera,
    options: &RenderOptions,
    progress: &Progress,
    frame: &mut Frame,
) -> Result<(), RenderError> {
    options.check()?;
    let n = options.samples;
    let full = View::new(camera, options.width * n, options.height * n);
    progress.start(full.height as u64);
    let strip_rows = (STRIP_SAMPLES / (full.width as u64 * (n * n) as u64))
        .clamp(1, options.height as u64) as u32;
    frame.reshape(options.width, options.height);
    // The ray tracer's acceleration structure is built once for all strips.
    let built = match accel {
        None if options.algorithm == Algorithm::Ray => Some(ray::accel::SceneAccel::build(world)),
        _ => None,
    };
    let accel = accel.or(built.as_ref());
    let draw = |view: &View, out: &mut [Vec3]| match options.algorithm {
        Algorithm::Gouraud => raster::gouraud::render_into(world, view, progress, out),
        Algorithm::Phong => raster::phong::render_into(world, view, progress, out),
        Algorithm::Ray => {
            let accel = accel.expect("given or built above for the ray tracer");
            ray::tracer::trace_into(accel, world, view, options, progress, out).map(|_| ())
        }
    };
    let width = options.width as usize;
    // Supersampled strips are drawn into one scratch strip and box-filtered into the frame;
    // without supersampling a strip is drawn straight into the frame's rows.
    let mut samples = Vec::new();
    for first in (0..options.height).step_by(strip_rows as usize) {
        let rows = strip_rows.min(options.height - first);
        let view = full.rows(first * n, rows * n);
        let out = &mut frame.pixels[first as usize * width..(first + rows) as usize * width];
        if n == 1 {
            draw(&view, out)?;
        } else {
            samples.resize(view.width as usize * view.height as usize, Vec3::ZERO);
            draw(&view, &mut samples)?;
            frame::box_filter(&samples, view.width, n, out);
        }
    }
    Ok(())
}
