//! The surface a sample sees, as every algorithm finds it: the display modes and the overlays
//! are worked out from it, so that the Z-buffer and the ray tracer draw them alike.

use glam::Vec3;

use super::camera::View;
use crate::world::World;

/// The nearest surface at one sample: the object, its triangle, and the barycentric weights of
/// the triangle's second (`u`) and third (`v`) corners, perspective-correct (the first corner's
/// weight is 1 − u − v). `object` is [`SurfaceHit::NONE`] where the sample sees the background.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SurfaceHit {
    /// Object index in the world, or [`SurfaceHit::NONE`].
    pub object: u32,
    /// Triangle index in the object's mesh.
    pub triangle: u32,
    /// Weight of the triangle's second corner.
    pub u: f32,
    /// Weight of the triangle's third corner.
    pub v: f32,
}

impl SurfaceHit {
    /// The `object` of a sample that sees no surface.
    pub const NONE: u32 = u32::MAX;

    /// A sample that sees the background.
    pub const MISS: SurfaceHit = SurfaceHit {
        object: SurfaceHit::NONE,
        triangle: 0,
        u: 0.0,
        v: 0.0,
    };

    /// Whether the sample sees a surface.
    #[inline]
    pub fn is_hit(&self) -> bool {
        self.object != SurfaceHit::NONE
    }

    /// The corners of the hit triangle, world units.
    pub fn corners(&self, world: &World) -> [Vec3; 3] {
        world.objects[self.object as usize]
            .world_corners(self.triangle)
            .0
    }

    /// `values` (three corner values) weighted by the barycentrics.
    #[inline]
    pub fn blend<T>(&self, values: [T; 3]) -> T
    where
        T: std::ops::Mul<f32, Output = T> + std::ops::Add<Output = T> + Copy,
    {
        values[0] * (1.0 - self.u - self.v) + values[1] * self.u + values[2] * self.v
    }

    /// The hit point, world units.
    pub fn position(&self, world: &World) -> Vec3 {
        self.blend(self.corners(world))
    }

    /// The unit normal at the hit, interpolated as the shading interpolates it and turned
    /// toward the eye of `view` (a face seen from behind shows its other side).
    pub fn normal(&self, world: &World, view: &View) -> Vec3 {
        let corners = world.objects[self.object as usize]
            .world_corners(self.triangle)
            .1;
        let n = self.blend(corners).normalize_or_zero();
        // The direction the view looks at the point along: parallel rays see every point
        // along `forward`.
        let to_point = if view.orthographic {
            view.forward
        } else {
            self.position(world) - view.eye
        };
        if n.dot(to_point) > 0.0 { -n } else { n }
    }

    /// Depth of the hit along the view direction, world units.
    pub fn depth(&self, world: &World, view: &View) -> f32 {
        (self.position(world) - view.eye).dot(view.forward)
    }
}
