//! The texture colour of Z-buffer fragments: the coordinates interpolated, the level from the
//! footprint of the pixel's ray at its depth (the ray tracer's formula, see
//! [`crate::render::texturing`]), so Phong and ray tracing read the same texels.

use glam::Vec3;

use super::fragments::Fragments;
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
    let x = fragments.columns() + L::splat(0.5);
    // Each fragment's ray: through its pixel from the eye, or along the view direction for
    // every pixel of an orthographic view.
    let rays = if view.orthographic {
        [view.forward; WIDTH]
    } else {
        view.pixel_direction(x, L::splat(fragments.y as f32 + 0.5))
            .to_vec3s()
    };
    let depth = fragments.depth.to_array();
    let normals = normal.normalize_or_zero().to_vec3s();
    let uvd = uvd.to_vec3s();
    let texels: [Vec3; WIDTH] = std::array::from_fn(|k| {
        let object = fragments.object[k] as usize;
        if !textures.is_textured(object) {
            return Vec3::ONE;
        }
        // The ray's length per unit of depth turns depth into distance along it.
        let length = rays[k].length();
        let (distance, cos) = (depth[k] * length, normals[k].dot(rays[k] / length));
        textures
            .sample(object, uvd[k].truncate(), uvd[k].z, distance, cos)
            .truncate()
    });
    V3::gather(&texels)
}
