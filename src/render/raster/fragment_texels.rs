//! The texture colour of Z-buffer fragments: the coordinates interpolated, the level from the
//! footprint of the pixel's ray at its depth (the ray tracer's formula, see
//! [`crate::render::texturing`]), so Phong and ray tracing read the same texels.
//!
//! The footprint and level are worked out in lanes; where the eight lanes are one textured
//! object the texels are read in lanes too ([`sample_rgb`]), else lane by lane, for the lanes
//! that are pixels. Both give the one-point sampler's bits.

use glam::Vec3;

use super::fragments::Fragments;
use super::lane_sampler::sample_rgb;
use crate::render::camera::View;
use crate::render::simd::{Lanes8, V3, WIDTH};
use crate::render::texturing::ObjectTextures;

/// The texture colours (RGB; exactly white on untextured objects) of `fragments` seen through
/// `view`, with interpolated normals `normal` and (u, v, texel density) `uvd`.
#[inline(always)]
pub fn fragment_texels<L: Lanes8, const K: usize>(
    textures: &ObjectTextures,
    view: &View,
    fragments: &Fragments<L, K>,
    normal: V3<L>,
    uvd: V3<L>,
) -> V3<L> {
    // Plain loops here and below, not `array::map`: the compiler leaves a map's closure out of
    // line, outside the wide-register code (a fifth of the textured Gouraud frame on the Duck).
    let mut objects = [0usize; WIDTH];
    for (object, &o) in objects.iter_mut().zip(&fragments.object) {
        *object = o as usize;
    }
    if !objects.iter().any(|&o| textures.is_textured(o)) {
        return V3::splat(Vec3::ONE);
    }
    let one_object = objects.iter().all(|&o| o == objects[0]);
    // Each fragment's ray: through its pixel from the eye, or along the view direction for
    // every pixel of an orthographic view.
    let rays = if view.orthographic {
        V3::splat(view.forward)
    } else {
        let x = fragments.columns() + L::splat(0.5);
        view.pixel_direction(x, L::splat(fragments.y as f32 + 0.5))
    };
    // The ray's length per unit of depth turns depth into distance along it.
    let length = rays.length_squared().sqrt();
    let distance = fragments.depth * length;
    let cos = normal.normalize_or_zero().dot(rays) / length;
    let texels = if one_object {
        L::splat(textures.texel_count(objects[0]))
    } else {
        let mut texels = [0.0; WIDTH];
        for (count, &o) in texels.iter_mut().zip(&objects) {
            *count = textures.texel_count(o);
        }
        L::from_array(texels)
    };
    let lod = textures.level_of_detail(texels, uvd.z, distance, cos);
    // One textured object in all lanes, as mostly: the eight are sampled together.
    if one_object
        && let Some(binding) = textures.binding(objects[0])
        && let Some(rgb) = sample_rgb(&binding.sampler, &binding.texture, uvd.x, uvd.y, lod)
    {
        return rgb;
    }
    let (lod, u, v) = (lod.to_array(), uvd.x.to_array(), uvd.y.to_array());
    // Lanes past `count` repeat the last pixel: they take its colour without reading it again.
    let mut colors = [Vec3::ONE; WIDTH];
    for k in 0..fragments.count {
        let uv = glam::Vec2::new(u[k], v[k]);
        colors[k] = textures.sample_at_level(objects[k], uv, lod[k]).truncate();
    }
    let last = colors[fragments.count - 1];
    colors[fragments.count..].fill(last);
    V3::gather(&colors)
}
