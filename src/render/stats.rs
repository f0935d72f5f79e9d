//! What a render did, and how long each of its stages took.

use std::ops::Add;
use std::time::Duration;

/// How many rays of each kind a render cast.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct RayCounts {
    /// Rays from the eye, one per sample.
    pub primary: u64,
    /// Rays toward lights from lit points.
    pub shadow: u64,
    /// Mirror rays from reflective surfaces.
    pub reflection: u64,
}

impl RayCounts {
    /// All rays cast.
    pub fn total(&self) -> u64 {
        self.primary + self.shadow + self.reflection
    }
}

impl Add for RayCounts {
    type Output = RayCounts;

    fn add(self, o: RayCounts) -> RayCounts {
        RayCounts {
            primary: self.primary + o.primary,
            shadow: self.shadow + o.shadow,
            reflection: self.reflection + o.reflection,
        }
    }
}

/// One render's figures: the wall-clock time of each stage, what was drawn and the rays cast.
/// The stages add up to the whole render ([`RenderStats::total`]).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
#[non_exhaustive]
pub struct RenderStats {
    /// Preparing the scene: building the ray tracer's BVH when no earlier render of the same
    /// world left one; zero when everything was kept.
    pub prepare: Duration,
    /// Drawing: the vertex stage, rasterization and shading of the Z-buffer, or tracing.
    pub draw: Duration,
    /// Box-filtering supersamples down to pixels; zero with one sample per pixel.
    pub filter: Duration,
    /// Triangles of the world the render drew, or traced rays against.
    pub triangles: usize,
    /// Rays cast, by kind; all zero for the Z-buffer.
    pub rays: RayCounts,
    /// How long the BVH in use took to build, in this render or in an earlier one it was kept
    /// from; zero when the algorithm uses none.
    pub bvh_build: Duration,
}

impl RenderStats {
    /// Wall-clock time of the whole render: every stage together.
    pub fn total(&self) -> Duration {
        self.prepare + self.draw + self.filter
    }
}
