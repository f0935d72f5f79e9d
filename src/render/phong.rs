//! Z-buffer with Phong shading: interpolate the normal and position, light every pixel.

use super::camera::View;
use super::frame::Frame;
use super::progress::{Cancelled, Progress};
use super::raster::draw;
use super::zbuffer::lighting;
use crate::world::World;

/// Renders `world` through `view` (one sample per pixel).
pub fn render(world: &World, view: &View, progress: &Progress) -> Result<Frame, Cancelled> {
    let lighting = lighting(world);
    // Fragment stage: the varyings are the world position and the normal. The ray tracer
    // interpolates its hits the same way (`raytrace::Tracer::trace`); a shared helper measured
    // 20% slower here, so the four lines stand twice.
    draw(world, view, progress, |f| {
        let mesh = &world.objects[f.object as usize].mesh;
        let [a, b, c] = mesh.triangles[f.triangle as usize].map(|i| i as usize);
        let [w0, w1, w2] = f.weights();
        let p = mesh.positions[a] * w0 + mesh.positions[b] * w1 + mesh.positions[c] * w2;
        let n = (mesh.normals[a] * w0 + mesh.normals[b] * w1 + mesh.normals[c] * w2)
            .normalize_or_zero();
        let material = &world.objects[f.object as usize].material;
        lighting.shade(p, n, (view.eye - p).normalize(), material, |_, _| true)
    })
}
