//! Primary rays: the packet through eight pixel centres, which the tracer shades, and coverage
//! for alpha, which asks only whether each of those rays hits anything, and the surface each
//! meets, for the display modes.

use rayon::prelude::*;

use super::accel::SceneAccel;
use super::alpha_cut::CutScene;
use super::packet::{PacketHits, RayPacket};
use crate::render::camera::{NEAR, View};
use crate::render::progress::{Cancelled, Progress};
use crate::render::simd::{F32x8, V3, WIDTH};
use crate::render::surface_hit::SurfaceHit;
use crate::render::texturing::ObjectTextures;
use crate::world::World;

/// The primary rays of `view` through continuous pixel coordinates (`x`, `y`) of each lane:
/// from the eye (or the image plane, orthographic), unit directions, starting where the rasterizer's near plane cuts each ray, so
/// that both see the same.
#[inline]
pub fn primary_packet(view: &View, x: F32x8, y: F32x8) -> RayPacket {
    let (origin, dir) = view.ray(x, y);
    let t_min = F32x8::splat(NEAR) / dir.dot(V3::splat(view.forward));
    RayPacket::new(origin, dir, t_min)
}

/// Writes 1 into `covered` where the primary ray through the pixel centre of `view` hits a
/// surface and 0 where it misses (`view.width`×`view.height` values). Each lane of a packet
/// finds the hit its ray would find alone, so the tracer's 4×2 packets and these rows of eight
/// agree on every pixel.
pub fn primary_coverage(
    accel: &SceneAccel,
    world: &World,
    view: &View,
    progress: &Progress,
    covered: &mut [f32],
) -> Result<(), Cancelled> {
    trace_rows(accel, world, view, progress, covered, |found, out| {
        let hits = found.hit().move_mask();
        for (k, c) in out.iter_mut().enumerate() {
            *c = (hits >> k & 1) as f32;
        }
    })
}

/// Writes into `hits` the surface the primary ray through each pixel centre of `view` meets
/// (`view.width`×`view.height` values): the hit the tracer shades there, lane by lane the same.
pub fn primary_hits(
    accel: &SceneAccel,
    world: &World,
    view: &View,
    progress: &Progress,
    hits: &mut [SurfaceHit],
) -> Result<(), Cancelled> {
    trace_rows(accel, world, view, progress, hits, |found, out| {
        let mask = found.hit().move_mask();
        let (u, v) = (found.u.to_array(), found.v.to_array());
        let (object, triangle) = (found.object.to_array(), found.triangle.to_array());
        for (k, hit) in out.iter_mut().enumerate() {
            *hit = if mask >> k & 1 == 1 {
                SurfaceHit {
                    object: object[k],
                    triangle: triangle[k],
                    u: u[k],
                    v: v[k],
                }
            } else {
                SurfaceHit::MISS
            };
        }
    })
}

/// Traces the primary rays of `view`'s pixel centres, rows in parallel and eight pixels a
/// packet, and has `write` turn each packet's hits into its (up to eight) values of `out`
/// (`view.width`×`view.height` values). Lanes past the right edge repeat the last pixel and
/// are not written. Masked objects are cut out as the tracer cuts them.
fn trace_rows<T: Send>(
    accel: &SceneAccel,
    world: &World,
    view: &View,
    progress: &Progress,
    out: &mut [T],
    write: impl Fn(&PacketHits, &mut [T]) + Sync,
) -> Result<(), Cancelled> {
    let width = view.width as usize;
    debug_assert_eq!(out.len(), width * view.height as usize);
    let textures = ObjectTextures::new(world, view);
    let scene = CutScene {
        accel,
        world,
        textures: &textures,
    };
    out.par_chunks_mut(width)
        .enumerate()
        .try_for_each(|(y, row)| {
            progress.check()?;
            let y = F32x8::splat(y as f32 + 0.5);
            for (left, out) in (0..width).step_by(WIDTH).zip(row.chunks_mut(WIDTH)) {
                let x = std::array::from_fn(|k| (left + k).min(width - 1) as f32 + 0.5);
                let packet = primary_packet(view, F32x8::from(x), y);
                write(&scene.intersect_packet(&packet, &[0.0; WIDTH]), out);
            }
            progress.advance(1);
            Ok(())
        })
}
