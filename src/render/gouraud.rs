//! Z-buffer with Gouraud shading: light the vertices, interpolate the colour.

use glam::Vec3;
use rayon::prelude::*;

use super::camera::View;
use super::frame::Frame;
use super::progress::{Cancelled, Progress};
use super::raster::draw;
use super::zbuffer::{interpolate, lighting};
use crate::world::World;

/// Renders `world` through `view` (one sample per pixel).
pub fn render(world: &World, view: &View, progress: &Progress) -> Result<Frame, Cancelled> {
    let lighting = lighting(world);
    // Vertex stage: the varying is the lit colour of each vertex.
    let colors: Vec<Vec<Vec3>> = world
        .objects
        .par_iter()
        .map(|o| {
            o.mesh
                .positions
                .par_iter()
                .zip(o.mesh.normals.par_iter())
                .map(|(&p, &n)| {
                    lighting.shade(p, n, (view.eye - p).normalize(), &o.material, |_, _| true)
                })
                .collect()
        })
        .collect();
    // Fragment stage: interpolate the vertex colours.
    draw(world, view, progress, |f| {
        interpolate(world, f, |o, v| colors[o][v as usize])
    })
}
