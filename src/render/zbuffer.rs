//! What the two Z-buffer algorithms share besides the rasterizer: the lighting and interpolation
//! of per-vertex attributes.

use glam::Vec3;

use super::raster::Fragment;
use super::shading::Lighting;
use crate::world::World;

/// The lighting of `world`.
pub fn lighting(world: &World) -> Lighting<'_> {
    Lighting {
        lights: &world.lights,
        ambient: world.ambient,
        falloff: world.falloff,
    }
}

/// Interpolates a per-vertex attribute of the fragment's triangle with its barycentric weights.
#[inline]
pub fn interpolate(world: &World, f: &Fragment, attribute: impl Fn(usize, u32) -> Vec3) -> Vec3 {
    let object = f.object as usize;
    let [a, b, c] = world.objects[object].mesh.triangles[f.triangle as usize];
    let [w0, w1, w2] = f.weights();
    attribute(object, a) * w0 + attribute(object, b) * w1 + attribute(object, c) * w2
}
