//! The renderer core: one camera, one lighting function, three algorithms, and the
//! [`Renderer`] that runs them.
//!
//! Shared by all three: the options (`options`, `algorithm`), the projection (`camera`), the
//! lighting function (`shading`, with each object's coefficients in `materials`), the image
//! (`frame`), progress and cancellation (`progress`), and what a render reports (`stats`). The
//! Z-buffer with Gouraud and Phong shading lives in `raster/`, the ray tracer with its BVH in
//! `ray/`, eight-lane arithmetic in `simd/`. Only what is re-exported here is the contract.

mod algorithm;
mod camera;
mod cpu;
mod error;
mod frame;
mod materials;
mod options;
mod prefetch;
mod prepared;
mod progress;
mod raster;
mod ray;
mod renderer;
mod scratch;
mod shading;
mod simd;
mod stats;
mod texturing;

pub use algorithm::Algorithm;
pub use camera::{NEAR, View};
pub use error::RenderError;
pub use frame::{Frame, decode_srgb, decode_srgb16, encode_srgb, encode_srgb16};
pub use options::{MAX_DIMENSION, MAX_SAMPLES, MAX_SAMPLES_TOTAL, RenderOptions, Size, SizeError};
pub use progress::{Cancelled, Progress};
#[cfg(test)]
pub(crate) use raster::coverage_counts;
pub use renderer::Renderer;
pub use stats::{RayCounts, RenderStats};
