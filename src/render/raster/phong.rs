//! Z-buffer with Phong shading: interpolate the normal, light every pixel.

use glam::Vec3;

use super::setup::RasterScratch;
use super::varying::PerVertex;
use super::zbuffer::draw;
use crate::render::camera::View;
use crate::render::materials::ObjectMaterials;
use crate::render::progress::{Cancelled, Progress};
use crate::render::shading::Lighting;
use crate::render::simd::{F32x8, V3};
use crate::world::World;

/// Renders `world` through `view` into `out` (`view.width`×`view.height` pixels).
pub fn render_phong(
    scratch: &mut RasterScratch,
    world: &World,
    view: &View,
    progress: &Progress,
    out: &mut [Vec3],
) -> Result<(), Cancelled> {
    let lighting = Lighting::new(world);
    let materials = ObjectMaterials::new(world);
    // The varying is the vertex normal. The surface point is found on the pixel's ray at the
    // interpolated depth, which is the perspective-correct interpolated position, and the very
    // point the ray tracer's primary ray meets.
    draw(
        &mut scratch.geometry,
        world,
        view,
        progress,
        &mut PerVertex::normals(world),
        |fragments, row| {
            let x = F32x8::from(fragments.x.map(|c| c as f32 + 0.5));
            let ray = view.pixel_direction(x, F32x8::splat(fragments.y as f32 + 0.5));
            let p = V3::splat(view.eye) + ray * fragments.depth;
            let v = (-ray).normalize_or_zero();
            let n = fragments.varying.normalize_or_zero();
            let material = materials.of_lanes(&fragments.object);
            let color = lighting.shade_lanes(p, n, v, &material, |_, _, facing| facing);
            fragments.write(color, row);
        },
        out,
    )
}
