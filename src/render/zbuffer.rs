//! The shading pass over a visibility buffer, shared by the two Z-buffer algorithms.

use glam::Vec3;
use rayon::prelude::*;

use super::frame::Frame;
use super::raster::{Fragment, VisibilityBuffer};
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

/// Colours every pixel of `visible`: `shade` for covered pixels, the background elsewhere.
pub fn resolve(
    world: &World,
    visible: &VisibilityBuffer,
    shade: impl Fn(&Fragment) -> Vec3 + Sync,
) -> Frame {
    let pixels = visible
        .fragments
        .par_iter()
        .with_min_len(4096)
        .map(|f| {
            if f.is_covered() {
                shade(f)
            } else {
                world.background
            }
        })
        .collect();
    Frame {
        width: visible.width,
        height: visible.height,
        pixels,
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
