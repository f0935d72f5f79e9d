//! Z-buffer with Phong shading: interpolate the normal, light every pixel.

use glam::Vec3;

use super::fragments::Fragments;
use super::setup::RasterScratch;
use super::shader::Shader;
use super::varying::PerVertex;
use super::zbuffer::draw;
use crate::render::camera::View;
use crate::render::materials::ObjectMaterials;
use crate::render::progress::{Cancelled, Progress};
use crate::render::shading::Lighting;
use crate::render::simd::{Lanes8, V3};
use crate::world::World;

/// Renders `world` through `view` into `out` (`view.width`×`view.height` pixels).
pub fn render_phong(
    scratch: &mut RasterScratch,
    world: &World,
    view: &View,
    progress: &Progress,
    out: &mut [Vec3],
) -> Result<(), Cancelled> {
    let shader = PhongShader {
        view,
        lighting: Lighting::new(world),
        materials: ObjectMaterials::new(world),
    };
    // The varying is the vertex normal.
    draw(
        &mut scratch.geometry,
        world,
        view,
        progress,
        &mut PerVertex::normals(world),
        &shader,
        out,
    )
}

/// Lights every pixel with its interpolated normal. The surface point is found on the pixel's
/// ray at the interpolated depth, which is the perspective-correct interpolated position, and
/// the very point the ray tracer's primary ray meets.
struct PhongShader<'a> {
    view: &'a View,
    lighting: Lighting<'a>,
    materials: ObjectMaterials,
}

impl Shader for PhongShader<'_> {
    #[inline(always)]
    fn shade<L: Lanes8>(&self, fragments: &Fragments<L>, row: &mut [Vec3]) {
        let x = fragments.columns() + L::splat(0.5);
        let ray = self
            .view
            .pixel_direction(x, L::splat(fragments.y as f32 + 0.5));
        let p = V3::splat(self.view.eye) + ray * fragments.depth;
        let v = (-ray).normalize_or_zero();
        let n = fragments.varying.normalize_or_zero();
        let material = self.materials.of_lanes(&fragments.object);
        let color = self
            .lighting
            .shade_lanes(p, n, v, &material, |_, _, facing| facing);
        fragments.write(color, row);
    }
}
