//! Working memory a renderer keeps from frame to frame, so that a render of the same size as the
//! last allocates nothing for it.

use glam::Vec3;

use super::raster::RasterScratch;
use super::surface_hit::SurfaceHit;

/// Buffers reused by every render of one [`crate::render::Renderer`].
#[derive(Debug, Default)]
pub(super) struct Scratch {
    /// One strip of the supersampled image, before it is box-filtered into the frame.
    pub(super) samples: Vec<Vec3>,
    /// The coverage of that strip's samples (1 covered, 0 not), when alpha is rendered.
    pub(super) coverage: Vec<f32>,
    /// The Z-buffer's projected vertices, screen triangles and bins.
    pub(super) raster: RasterScratch,
    /// The surface at each sample of the strip, for the display modes and overlays.
    pub(super) hits: Vec<SurfaceHit>,
    /// Working samples of the strip: the Z-buffer's hit pass draws into them, and the overlays
    /// keep the depth of each sample's surface in `depth`.
    pub(super) work: Vec<Vec3>,
    /// Depth along the view of each sample's surface (+∞ on the background), for overlays.
    pub(super) depth: Vec<f32>,
}
