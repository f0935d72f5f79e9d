//! Z-buffer with Phong shading: interpolate the normal and position, light every pixel.

use super::camera::View;
use super::frame::Frame;
use super::progress::{Cancelled, Progress};
use super::raster::rasterize;
use super::zbuffer::{interpolate, lighting, resolve};
use crate::world::World;

/// Renders `world` through `view` (one sample per pixel).
pub fn render(world: &World, view: &View, progress: &Progress) -> Result<Frame, Cancelled> {
    let lighting = lighting(world);
    let visible = rasterize(world, view, progress)?;
    // Fragment stage: the varyings are the world position and the normal.
    Ok(resolve(world, &visible, |f| {
        let p = interpolate(world, f, |o, v| world.objects[o].mesh.positions[v as usize]);
        let n = interpolate(world, f, |o, v| world.objects[o].mesh.normals[v as usize])
            .normalize_or_zero();
        let material = &world.objects[f.object as usize].material;
        lighting.shade(p, n, (view.eye - p).normalize(), material, |_, _| true)
    }))
}
