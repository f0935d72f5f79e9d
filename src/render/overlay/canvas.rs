//! One strip of samples to draw lines on, with the depth of the surface at each sample: world
//! segments projected by the render's `View`, depth-tested where asked.

use glam::{Vec2, Vec3};

use crate::render::camera::{NEAR, View};

/// The samples of one strip, the view they were rendered with, and the depth of the surface at
/// each (+∞ on the background).
pub struct Canvas<'a> {
    /// The strip's view, in samples.
    pub view: &'a View,
    /// Samples per pixel side: line widths are given in output pixels.
    pub samples: u32,
    /// The strip's samples, row-major.
    pub out: &'a mut [Vec3],
    /// Depth along the view of the surface at each sample, world units.
    pub depth: &'a [f32],
}

/// A line's end in the strip's pixel coordinates with its depth along the view.
#[derive(Debug, Clone, Copy)]
struct End {
    pixel: Vec2,
    depth: f32,
}

impl Canvas<'_> {
    /// Draws the world segment `a`–`b`, `width` output pixels wide, in `color`; with
    /// `depth_tested`, only where it is not behind a surface. The part nearer than the near
    /// plane is cut off.
    pub fn segment(&mut self, a: Vec3, b: Vec3, width: f32, color: Vec3, depth_tested: bool) {
        let depth = |p: Vec3| (p - self.view.eye).dot(self.view.forward);
        let (da, db) = (depth(a), depth(b));
        if da <= NEAR && db <= NEAR {
            return;
        }
        // Move an end behind the near plane onto it.
        let cut = |p: Vec3, dp: f32, q: Vec3, dq: f32| {
            if dp > NEAR {
                p
            } else {
                p + (q - p) * ((NEAR - dp) / (dq - dp))
            }
        };
        let (a, b) = (cut(a, da, b, db), cut(b, db, a, da));
        let end = |p: Vec3| {
            let clip = self.view.to_clip(p);
            End {
                pixel: self.view.clip_to_pixel(clip),
                depth: clip.z,
            }
        };
        self.line(end(a), end(b), width, color, depth_tested);
    }

    /// Draws the segment between pixel points `a` and `b` of the strip, in front of everything.
    pub fn flat_segment(&mut self, a: Vec2, b: Vec2, width: f32, color: Vec3) {
        let end = |pixel| End { pixel, depth: 0.0 };
        self.line(end(a), end(b), width, color, false);
    }

    /// Covers the samples whose centre lies within `width / 2` output pixels of the segment
    /// `a`–`b`, walking along its longer axis. The depth of a point of the segment is
    /// interpolated as 1/depth, linear on the screen.
    fn line(&mut self, a: End, b: End, width: f32, color: Vec3, depth_tested: bool) {
        let half = 0.5 * width * self.samples as f32;
        let (w, h) = (self.view.width as i64, self.view.height as i64);
        let d = b.pixel - a.pixel;
        let steep = d.y.abs() > d.x.abs();
        // (major, minor) coordinates, so one loop serves both directions.
        let swap = |p: Vec2| if steep { Vec2::new(p.y, p.x) } else { p };
        let (pa, pb) = (swap(a.pixel), swap(b.pixel));
        let (major_len, minor_len) = if steep { (h, w) } else { (w, h) };
        let (lo, hi) = (pa.x.min(pb.x) - half, pa.x.max(pb.x) + half);
        let first = (lo.floor() as i64).max(0);
        let last = (hi.ceil() as i64).min(major_len - 1);
        let length_squared = d.length_squared();
        let reach = half * std::f32::consts::SQRT_2 + 1.0;
        for major in first..=last {
            let mc = major as f32 + 0.5;
            let s = if pb.x != pa.x {
                ((mc - pa.x) / (pb.x - pa.x)).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let centre = pa.y + (pb.y - pa.y) * s;
            let from = ((centre - reach).floor() as i64).max(0);
            let to = ((centre + reach).ceil() as i64).min(minor_len - 1);
            for minor in from..=to {
                let (x, y) = if steep {
                    (minor, major)
                } else {
                    (major, minor)
                };
                let point = Vec2::new(x as f32 + 0.5, y as f32 + 0.5);
                // The nearest point of the segment, as a fraction t of the way from a to b.
                let t = if length_squared > 0.0 {
                    ((point - a.pixel).dot(d) / length_squared).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                if point.distance_squared(a.pixel + d * t) > half * half {
                    continue;
                }
                let index = y as usize * w as usize + x as usize;
                if depth_tested {
                    let depth = 1.0 / ((1.0 - t) / a.depth + t / b.depth);
                    // A line on a surface counts as in front of it (to a relative 1e-4).
                    if depth > self.depth[index] * (1.0 + 1.0e-4) {
                        continue;
                    }
                }
                self.out[index] = color;
            }
        }
    }
}
