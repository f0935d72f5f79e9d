//! Z-buffer with Gouraud shading: light the vertices, interpolate the colour.

use glam::Vec3;
use rayon::prelude::*;

use super::zbuffer::draw;
use crate::render::camera::View;
use crate::render::materials::ObjectMaterials;
use crate::render::progress::{Cancelled, Progress};
use crate::render::shading::Lighting;
use crate::render::simd::{V3, WIDTH};
use crate::world::World;

/// Renders `world` through `view` into `out` (`view.width`×`view.height` pixels).
pub fn render_gouraud(
    world: &World,
    view: &View,
    progress: &Progress,
    out: &mut [Vec3],
) -> Result<(), Cancelled> {
    let colors = vertex_colors(world, view);
    let colors: Vec<&[Vec3]> = colors.iter().map(Vec::as_slice).collect();
    // Fragment stage: the interpolated colour is the pixel's colour.
    draw(
        world,
        view,
        progress,
        &colors,
        |fragments, row| {
            fragments.write(fragments.varying, row);
        },
        out,
    )
}

/// Vertex stage: every vertex lit with its normal, seen from the eye; `[object][vertex]`.
fn vertex_colors(world: &World, view: &View) -> Vec<Vec<Vec3>> {
    let lighting = Lighting::new(world);
    let materials = ObjectMaterials::new(world);
    world
        .objects
        .par_iter()
        .zip(&materials.lanes)
        .map(|(o, material)| {
            let mut colors = Vec::with_capacity(o.mesh.positions.len());
            for (p, n) in o
                .mesh
                .positions
                .chunks(WIDTH)
                .zip(o.mesh.normals.chunks(WIDTH))
            {
                let (count, p, n) = (p.len(), V3::gather(p), V3::gather(n));
                let v = (V3::splat(view.eye) - p).normalize_or_zero();
                let c = lighting.shade_lanes(p, n, v, material, |_, _, facing| facing);
                colors.extend_from_slice(&c.to_vec3s()[..count]);
            }
            colors
        })
        .collect()
}
