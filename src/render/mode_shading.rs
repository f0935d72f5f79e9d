//! The display modes other than `shaded`, worked out per sample from the surface hit: the same
//! for the three algorithms, since they find the same hits.

use glam::{Vec2, Vec3};
use rayon::prelude::*;

use super::camera::View;
use super::display_mode::DisplayMode;
use super::surface_hit::SurfaceHit;
use super::triangle_edges::edge_distance;
use crate::mesh::srgb_to_linear;
use crate::world::World;

/// Half the width of an edge line, in output pixels: each of the two triangles beside an edge
/// draws this much of it, so lines are one pixel wide.
pub const EDGE_HALF_WIDTH: f32 = 0.5;

/// Checker squares per unit of texture coordinate, along u and along v.
pub const UV_CHECKS: f32 = 8.0;

/// The colour of edge lines (linear RGB).
const EDGE_COLOR: Vec3 = Vec3::ZERO;

/// How the modes colour the samples of one strip.
pub struct ModeShading<'a> {
    world: &'a World,
    /// The strip's view, in samples.
    view: &'a View,
    mode: DisplayMode,
    /// Half an edge line's width, in samples.
    edge_half_width: f32,
    /// Depths (along the view) of the scene's bounds' nearest and farthest corners, world units.
    depth_range: (f32, f32),
}

impl<'a> ModeShading<'a> {
    /// The shading of `mode` for the strip `view` of an image rendered with `samples`×`samples`
    /// samples per pixel.
    pub fn new(world: &'a World, view: &'a View, mode: DisplayMode, samples: u32) -> Self {
        ModeShading {
            world,
            view,
            mode,
            edge_half_width: EDGE_HALF_WIDTH * samples as f32,
            depth_range: depth_range(world, view),
        }
    }

    /// Colours `out` (the strip's samples, row-major) from `hits`. `wire` draws the edges over
    /// what `out` holds (the lit image); the other modes overwrite every sample.
    pub fn apply(&self, hits: &[SurfaceHit], out: &mut [Vec3]) {
        let width = self.view.width as usize;
        out.par_chunks_mut(width)
            .zip(hits.par_chunks(width))
            .enumerate()
            .for_each(|(y, (row, hits))| {
                for (x, (color, hit)) in row.iter_mut().zip(hits).enumerate() {
                    *color = self.sample(hit, x as f32 + 0.5, y as f32 + 0.5, *color);
                }
            });
    }

    /// The colour of the sample at continuous pixel point (`x`, `y`) that sees `hit`, over
    /// `lit`, the algorithm's colour there (used by `wire`).
    fn sample(&self, hit: &SurfaceHit, x: f32, y: f32, lit: Vec3) -> Vec3 {
        if !hit.is_hit() {
            return match self.mode {
                DisplayMode::Shaded | DisplayMode::Wire => lit,
                DisplayMode::Depth => Vec3::ZERO,
                _ => self.world.background,
            };
        }
        if self.mode.has_edges()
            && edge_distance(self.view, hit.corners(self.world), x, y) < self.edge_half_width
        {
            return EDGE_COLOR;
        }
        match self.mode {
            DisplayMode::Shaded | DisplayMode::Wire => lit,
            DisplayMode::HiddenLine => Vec3::ONE,
            DisplayMode::Normals => display((hit.normal(self.world, self.view) + 1.0) * 0.5),
            DisplayMode::Depth => {
                let (near, far) = self.depth_range;
                let depth = hit.depth(self.world, self.view);
                let level = if far > near {
                    (far - depth) / (far - near)
                } else {
                    1.0
                };
                display(Vec3::splat(level.clamp(0.0, 1.0)))
            }
            DisplayMode::Uv => match uv_at(self.world, hit) {
                Some(uv) => display(checker(uv)),
                None => display(Vec3::splat(0.5)),
            },
        }
    }
}

/// The linear colour whose 8-bit sRGB encoding is `shown` (each channel in [0, 1]): the modes
/// state what the image shows, as a normal map states its bytes.
fn display(shown: Vec3) -> Vec3 {
    Vec3::new(
        srgb_to_linear(shown.x),
        srgb_to_linear(shown.y),
        srgb_to_linear(shown.z),
    )
}

/// The depths of the nearest and the farthest corner of the world's bounds along the view,
/// world units; (0, 0) for an empty world.
pub fn depth_range(world: &World, view: &View) -> (f32, f32) {
    let Some((lo, hi)) = world.bounds() else {
        return (0.0, 0.0);
    };
    (0..8)
        .map(|k| {
            let corner = Vec3::new(
                if k & 1 == 0 { lo.x } else { hi.x },
                if k & 2 == 0 { lo.y } else { hi.y },
                if k & 4 == 0 { lo.z } else { hi.z },
            );
            (corner - view.eye).dot(view.forward)
        })
        .fold((f32::INFINITY, f32::NEG_INFINITY), |(near, far), d| {
            (near.min(d), far.max(d))
        })
}

/// The texture coordinates at `hit`, when its object's model gave them.
fn uv_at(world: &World, hit: &SurfaceHit) -> Option<Vec2> {
    let uvs = world.objects[hit.object as usize].local_corner_uvs()?;
    Some(hit.blend(*uvs.get(hit.triangle as usize)?))
}

/// The checker at `uv`: bright and dark squares, tinted by (u, v) so that the direction of each
/// coordinate shows; shown values in [0, 1].
fn checker(uv: Vec2) -> Vec3 {
    let cells = (uv * UV_CHECKS).floor();
    let bright = (cells.x + cells.y).rem_euclid(2.0) < 1.0;
    let tint = Vec3::new(uv.x.rem_euclid(1.0), uv.y.rem_euclid(1.0), 1.0);
    let level = if bright { 0.9 } else { 0.35 };
    tint.lerp(Vec3::ONE, 0.5) * level
}

/// How many of `world`'s objects have no texture coordinates: the `uv` mode draws them grey.
pub fn objects_without_uvs(world: &World) -> usize {
    world
        .objects
        .iter()
        .filter(|o| o.corner_uvs.is_none())
        .count()
}
