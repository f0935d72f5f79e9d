//! The camera as every renderer sees it: one projection shared by rays and rasterizer.
//!
//! Pixel (i, j), j = 0 the top row, has its centre at (i + 0.5, j + 0.5). Normalised device
//! coordinates are x = 2(i + 0.5)/W − 1 and y = 1 − 2(j + 0.5)/H. The rasterizer projects a vertex
//! to exactly the continuous pixel coordinates whose primary ray passes through it.
//!
//! Two projections share these coordinates. Perspective: rays leave the eye, and a point at depth
//! w lands at NDC (x/w, y/w) of its clip coordinates. Orthographic: rays leave the plane through
//! the eye, all along the view direction, and a point lands at NDC (x, y): the clip coordinates
//! are the same expressions with `half_height` a world-space half height, and the divisor is 1.

use glam::{Vec2, Vec3};

use super::simd::{Lanes, V3};
use crate::scene::{Camera, Projection};

/// Distance of the near clipping plane in front of the eye, world units.
pub const NEAR: f32 = 1.0e-3;

/// A camera fixed to an image size.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct View {
    /// Eye position, world units.
    pub eye: Vec3,
    /// Unit view direction.
    pub forward: Vec3,
    /// Unit right vector, perpendicular to `forward`.
    pub right: Vec3,
    /// Unit up vector, perpendicular to both.
    pub up: Vec3,
    /// Half the image height, world units: at distance 1 in perspective (tan(fov / 2)), at
    /// every distance in orthographic.
    pub half_height: f32,
    /// Parallel rays (orthographic) rather than rays from the eye (perspective).
    pub orthographic: bool,
    /// Width / height.
    pub aspect: f32,
    /// Image width in pixels.
    pub width: u32,
    /// Rows in this view: the whole image, or a horizontal strip of it (see [`View::rows`]).
    pub height: u32,
    /// First image row of this view (0 for the whole image).
    pub row_offset: u32,
    /// Height of the whole image, pixels: the projection depends on it, not on the strip.
    pub image_height: u32,
}

impl View {
    /// The view of `camera` on a `width`×`height` image (both ≥ 1).
    pub fn new(camera: &Camera, width: u32, height: u32) -> View {
        let forward = (camera.target - camera.position).normalize();
        let right = forward.cross(camera.up).normalize();
        let up = right.cross(forward);
        View {
            eye: camera.position,
            forward,
            right,
            up,
            half_height: match (camera.projection, camera.height) {
                (Projection::Orthographic, Some(height)) => 0.5 * height,
                _ => (camera.fov.to_radians() * 0.5).tan(),
            },
            orthographic: camera.projection == Projection::Orthographic && camera.height.is_some(),
            aspect: width as f32 / height as f32,
            width,
            height,
            row_offset: 0,
            image_height: height,
        }
    }

    /// The strip of `count` rows starting at row `first` of this view: the same projection,
    /// with row 0 of the strip being row `first`. Renders of strips put side by side equal a
    /// render of the whole, in a fraction of the memory.
    pub fn rows(&self, first: u32, count: u32) -> View {
        debug_assert!(first + count <= self.height, "strip outside the view");
        View {
            height: count,
            row_offset: self.row_offset + first,
            ..*self
        }
    }

    /// Unit direction of the ray through continuous pixel coordinates (x, y); the centre of pixel
    /// (i, j) is (i + 0.5, j + 0.5).
    #[inline(always)]
    pub fn ray_direction(&self, x: f32, y: f32) -> Vec3 {
        self.ray(x, y).1.to_vec3()
    }

    /// Origin and unit direction of the primary ray through continuous pixel coordinates (x, y)
    /// of each lane: from the eye (perspective), or from the pixel's point on the plane through
    /// the eye, along the view direction (orthographic).
    #[inline(always)]
    pub fn ray<L: Lanes>(&self, x: L, y: L) -> (V3<L>, V3<L>) {
        if self.orthographic {
            (
                V3::splat(self.eye) + self.pixel_offset(x, y),
                V3::splat(self.forward),
            )
        } else {
            (
                V3::splat(self.eye),
                self.pixel_direction(x, y).normalize_or_zero(),
            )
        }
    }

    /// Direction from the eye through continuous pixel coordinates (x, y) of each lane, scaled
    /// so that its component along `forward` is 1: the point at depth w on that ray is
    /// `eye + direction·w` (perspective). Rays and rasterizer both call this.
    #[inline(always)]
    pub fn pixel_direction<L: Lanes>(&self, x: L, y: L) -> V3<L> {
        let (sx, sy) = self.image_plane(x, y);
        V3::splat(self.forward) + V3::splat(self.right) * sx + V3::splat(self.up) * sy
    }

    /// The image-plane offset of continuous pixel coordinates (x, y) of each lane, across the
    /// view: on the plane through the eye (orthographic).
    #[inline(always)]
    fn pixel_offset<L: Lanes>(&self, x: L, y: L) -> V3<L> {
        let (sx, sy) = self.image_plane(x, y);
        V3::splat(self.right) * sx + V3::splat(self.up) * sy
    }

    /// Coordinates along `right` and `up` of continuous pixel coordinates (x, y) of each lane on
    /// the image plane: at distance 1 (perspective) or through the eye (orthographic).
    #[inline(always)]
    fn image_plane<L: Lanes>(&self, x: L, y: L) -> (L, L) {
        let ndc_x = L::splat(2.0) * x / L::splat(self.width as f32) - L::splat(1.0);
        let ndc_y = L::splat(1.0)
            - L::splat(2.0) * (y + L::splat(self.row_offset as f32))
                / L::splat(self.image_height as f32);
        let sx = ndc_x * L::splat(self.half_height * self.aspect);
        let sy = ndc_y * L::splat(self.half_height);
        (sx, sy)
    }

    /// The surface point at depth `depth` (along the view direction) behind continuous pixel
    /// coordinates (x, y) of each lane, and the unit direction from it toward the viewer.
    #[inline(always)]
    pub fn surface_point<L: Lanes>(&self, x: L, y: L, depth: L) -> (V3<L>, V3<L>) {
        if self.orthographic {
            let p = V3::splat(self.eye) + self.pixel_offset(x, y) + V3::splat(self.forward) * depth;
            (p, -V3::splat(self.forward))
        } else {
            let ray = self.pixel_direction(x, y);
            (
                V3::splat(self.eye) + ray * depth,
                (-ray).normalize_or_zero(),
            )
        }
    }

    /// Where the viewer is, for lighting a point anywhere in the view.
    pub fn viewer(&self) -> Viewer {
        if self.orthographic {
            Viewer::Along(-self.forward)
        } else {
            Viewer::Eye(self.eye)
        }
    }

    /// Homogeneous clip coordinates (x, y, w) of world point `p`: w is the depth along the view
    /// direction, and x/w, y/w are normalised device coordinates.
    #[inline]
    pub fn to_clip(&self, p: Vec3) -> Vec3 {
        let d = p - self.eye;
        Vec3::new(
            d.dot(self.right) / (self.half_height * self.aspect),
            d.dot(self.up) / self.half_height,
            d.dot(self.forward),
        )
    }

    /// What clip x and y are divided by to give NDC: w (perspective) or 1 (orthographic).
    #[inline]
    pub fn divisor(&self, c: Vec3) -> f32 {
        if self.orthographic { 1.0 } else { c.z }
    }

    /// Continuous pixel coordinates (within this view's rows) of a clip-space point with w > 0.
    #[inline]
    pub fn clip_to_pixel(&self, c: Vec3) -> Vec2 {
        let inv_w = 1.0 / self.divisor(c);
        Vec2::new(
            (c.x * inv_w + 1.0) * 0.5 * self.width as f32,
            (1.0 - c.y * inv_w) * 0.5 * self.image_height as f32 - self.row_offset as f32,
        )
    }
}

/// The viewer as lighting sees it: the direction toward it from a point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Viewer {
    /// A perspective eye at this position.
    Eye(Vec3),
    /// An orthographic view: toward the viewer is this unit direction everywhere.
    Along(Vec3),
}

impl Viewer {
    /// Unit direction from points `p` toward the viewer.
    #[inline(always)]
    pub fn toward<L: Lanes>(&self, p: V3<L>) -> V3<L> {
        match *self {
            Viewer::Eye(eye) => (V3::splat(eye) - p).normalize_or_zero(),
            Viewer::Along(direction) => V3::splat(direction),
        }
    }
}
