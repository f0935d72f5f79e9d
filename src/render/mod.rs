//! The renderer core: one camera, one lighting function, three algorithms, and the
//! [`Renderer`] that runs them.
//!
//! Shared by all three: the options (`options`, `algorithm`), the projection (`camera`), the
//! lighting function (`shading`, with each object's coefficients in `materials`), the image
//! (`frame`, its 8-bit sRGB codes by table in `srgb_encode`), progress and cancellation
//! (`progress`), and what a render reports (`stats`). The display modes (`display_mode`,
//! `mode_shading`, `triangle_edges`) and the overlays (`overlay/`) work from the surface each
//! sample sees (`surface_hit`), which every algorithm finds alike. The Z-buffer with Gouraud
//! and Phong shading lives in `raster/`, the ray tracer with its BVH in `ray/`, eight-lane
//! arithmetic in `simd/`. Only what is re-exported here is the contract.

mod algorithm;
mod camera;
mod cpu;
mod display_mode;
mod error;
mod frame;
mod materials;
mod mode_shading;
mod options;
mod overlay;
mod prefetch;
mod prepared;
mod progress;
mod raster;
mod ray;
mod renderer;
mod scratch;
mod shading;
mod simd;
mod srgb_encode;
mod stats;
mod surface_hit;
mod texturing;
mod triangle_edges;

pub use algorithm::Algorithm;
pub use camera::{NEAR, View};
pub use cpu::cpu_features;
pub use display_mode::{DisplayMode, UnknownMode};
pub use error::RenderError;
pub use frame::{Frame, decode_srgb, decode_srgb16, encode_srgb16};
pub use mode_shading::{EDGE_HALF_WIDTH, objects_without_uvs};
pub use options::{
    MAX_DIMENSION, MAX_SAMPLES, MAX_SAMPLES_TOTAL, MAX_THREADS, RenderOptions, Size, SizeError,
    thread_count,
};
pub use overlay::{
    Grid, OverlayKind, Overlays, UnknownOverlay, ground_grid, overlay_bounds, overlay_colors,
};
pub use progress::{Cancelled, Progress};
#[cfg(test)]
pub(crate) use raster::coverage_counts;
pub use renderer::Renderer;
pub use srgb_encode::encode_srgb;
pub use stats::{RayCounts, RenderStats};
pub use surface_hit::SurfaceHit;
