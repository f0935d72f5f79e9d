//! The surface at each pixel centre as the Z-buffer finds it: the same scan conversion and
//! depth test that draw the colours, with the barycentrics and the triangle as the varyings.

use std::sync::atomic::{AtomicU64, Ordering};

use glam::Vec3;
use rayon::prelude::*;

use super::fragments::Fragments;
use super::setup::RasterScratch;
use super::shader::Shader;
use super::varying::Varying;
use super::zbuffer::draw;
use crate::render::camera::View;
use crate::render::progress::{Cancelled, Progress};
use crate::render::simd::{Lanes8, V3};
use crate::render::surface_hit::SurfaceHit;
use crate::world::World;

/// Triangle indices travel as two varyings of 12 bits each (`MAX_TRIANGLES` is below 2^24): a
/// value interpolated perspective-correctly comes back within a rounding error, and below 4096
/// that error is far below the ½ that rounding to the integer forgives.
const TRIANGLE_BITS: u32 = 12;

/// Two varyings per triangle: its barycentric corners (1,0,0), (0,1,0), (0,0,1), then its index
/// as (low 12 bits, high bits, 0) at all three corners.
struct BarycentricsAndIndex;

impl Varying for BarycentricsAndIndex {
    fn corners(&self, _object: usize, triangles: &[u32], out: &mut Vec<[Vec3; 3]>) {
        let low = (1 << TRIANGLE_BITS) - 1;
        for &t in triangles {
            out.push([Vec3::X, Vec3::Y, Vec3::Z]);
            let index = Vec3::new((t & low) as f32, (t >> TRIANGLE_BITS) as f32, 0.0);
            out.push([index; 3]);
        }
    }
}

/// Writes (u, v, 0) into the row and (object + 1) << 32 | triangle into `ids` (row-major over
/// the view; 0 stays where no triangle is drawn).
struct HitShader<'a> {
    width: usize,
    ids: &'a [AtomicU64],
}

impl Shader<2> for HitShader<'_> {
    #[inline(always)]
    fn shade<L: Lanes8>(&self, fragments: &Fragments<L, 2>, row: &mut [Vec3]) {
        let [weights, index] = fragments.varying;
        fragments.write(V3::new(weights.y, weights.z, L::splat(0.0)), row);
        let index = index.to_vec3s();
        let first = fragments.y as usize * self.width;
        let lanes = index.iter().zip(&fragments.object).zip(&fragments.x);
        for ((index, &object), &x) in lanes.take(fragments.count) {
            let triangle = index.x.round() as u64 | (index.y.round() as u64) << TRIANGLE_BITS;
            let id = (object as u64 + 1) << 32 | triangle;
            self.ids[first + x as usize].store(id, Ordering::Relaxed);
        }
    }
}

/// Writes into `hits` the surface the Z-buffer shows at each pixel centre of `view`
/// (`view.width`×`view.height`); `work` is as large and is overwritten.
pub fn raster_hits(
    scratch: &mut RasterScratch,
    world: &World,
    view: &View,
    progress: &Progress,
    work: &mut [Vec3],
    hits: &mut [SurfaceHit],
) -> Result<(), Cancelled> {
    let ids: Vec<AtomicU64> = (0..hits.len()).map(|_| AtomicU64::new(0)).collect();
    let shader = HitShader {
        width: view.width as usize,
        ids: &ids,
    };
    let varying = &mut BarycentricsAndIndex;
    draw::<2>(
        &mut scratch.geometry,
        world,
        view,
        progress,
        varying,
        &shader,
        work,
    )?;
    hits.par_iter_mut()
        .zip(ids.par_iter().zip(work.par_iter()))
        .for_each(|(hit, (id, weights))| {
            let id = id.load(Ordering::Relaxed);
            *hit = if id == 0 {
                SurfaceHit::MISS
            } else {
                SurfaceHit {
                    object: (id >> 32) as u32 - 1,
                    triangle: id as u32,
                    u: weights.x,
                    v: weights.y,
                }
            };
        });
    Ok(())
}
