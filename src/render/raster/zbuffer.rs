//! The Z-buffer rasterizer shared by Gouraud and Phong shading.
//!
//! Stages: vertex (clip coordinates) → triangle setup (near and guard-band clipping in homogeneous
//! space, fixed-point snapping, bounding box, and the screen-space planes of the interpolants
//! (varying·1/w, 1/w)) → binning into row bands → per band, in triangle order: coverage by exact
//! integer edge functions with the top-left rule, and a depth test on 1/w that keeps the nearest
//! triangle per pixel → per row, the covered pixels go to the shader eight at a time
//! ([`Fragments`]) with their depth and perspective-correct varying. Each pixel is shaded once,
//! however much overdraw the scene has, and Gouraud and Phong differ only in the varying they
//! interpolate (a lit vertex colour, or a normal).
//!
//! Bands run in parallel; each band's result depends only on the triangle order, so the output is
//! the same for any number of threads.

use std::ops::Range;

use glam::Vec3;
use rayon::prelude::*;

use super::fragments::{Fragments, Packer};
use super::screen_triangle::ScreenTriangle;
use super::setup::{BandBuffers, Geometry};
use super::spans::for_each_span;
use super::varying::Varying;
use crate::render::camera::View;
use crate::render::progress::{Cancelled, Progress};
use crate::render::simd::{F32x8, WIDTH, load};
use crate::world::World;
use wide::{CmpGe, u32x8};

/// Draws `world` seen through `view` into `out` (`view.width`×`view.height` pixels, every one
/// written), with `geometry` as working memory. Each band of rows is scan-converted with a
/// depth test on 1/w, keeping the nearest triangle per pixel centre; then the covered pixels of
/// each row are handed to `shade` eight at a time as [`Fragments`], with `varying`
/// interpolated perspective-correctly, and `shade` writes their colours into the row. Uncovered
/// pixels get the background. Shading after the depth test shades each pixel once however much
/// overdraw the scene has, and shading right after each band keeps the band's buffers in cache.
pub fn draw(
    geometry: &mut Geometry,
    world: &World,
    view: &View,
    progress: &Progress,
    varying: &mut dyn Varying,
    shade: impl Fn(&Fragments, &mut [Vec3]) + Sync,
    out: &mut [Vec3],
) -> Result<(), Cancelled> {
    let width = view.width;
    debug_assert_eq!(out.len(), width as usize * view.height as usize);
    let threads = rayon::current_num_threads().max(1);
    let mut pool = std::mem::take(&mut geometry.band_buffers);
    pool.resize_with(threads, Default::default);
    let bands = geometry.set_up(world, view, varying);
    let drawn = out
        .par_chunks_mut((bands.rows * width) as usize)
        .enumerate()
        .try_for_each_init(Vec::new, |triangles, (band, rows)| {
            progress.check()?;
            let top = band as u32 * bands.rows;
            let band_rows = rows.len() as u32 / width;
            let thread = rayon::current_thread_index().unwrap_or(0) % threads;
            // A thread draws one band at a time, so its buffers are free; were they not, the
            // band would draw into fresh ones rather than wait.
            let mut held = pool[thread].try_lock().ok();
            let mut fresh = BandBuffers::default();
            let BandBuffers { depth, id } = held.as_deref_mut().unwrap_or(&mut fresh);
            depth.clear();
            depth.resize(rows.len(), 0.0);
            id.clear();
            id.resize(rows.len(), 0);
            triangles.clear();
            let bin = bands.triangles(band).inspect(|t| triangles.push(*t));
            scan_band(bin, width, top, band_rows, |span, x, y, i, t| {
                let z0 = t.interpolants(x, y).w;
                depth_test(
                    &mut depth[span.clone()],
                    &mut id[span],
                    z0,
                    t.per_x.w,
                    i + 1,
                );
            });
            for (r, (out, ids)) in rows
                .chunks_mut(width as usize)
                .zip(id.chunks(width as usize))
                .enumerate()
            {
                let y = top + r as u32;
                shade_row(triangles, ids, y, world.background, &shade, out);
            }
            progress.advance(band_rows as u64);
            Ok(())
        });
    geometry.band_buffers = pool;
    drawn
}

/// Shades row `y`, whose pixels were drawn by `triangles[id − 1]` for each of `ids` (0 =
/// none): runs of one triangle go to `shade` as whole spans of eight, the rest packed in lanes.
#[inline]
fn shade_row(
    triangles: &[&ScreenTriangle],
    ids: &[u32],
    y: u32,
    background: Vec3,
    shade: &impl Fn(&Fragments, &mut [Vec3]),
    out: &mut [Vec3],
) {
    let mut packer = Packer::default();
    let mut x = 0;
    while x < ids.len() {
        let id = ids[x];
        let run = ids[x..].iter().take_while(|&&i| i == id).count();
        if id == 0 {
            out[x..x + run].fill(background);
        } else {
            let t = triangles[id as usize - 1];
            let at_start = t.interpolants(x as i32, y as i32);
            let whole = run - run % WIDTH;
            for k in (0..whole).step_by(WIDTH) {
                shade(&Fragments::span(y, x, k, t.object, at_start, t.per_x), out);
            }
            for k in whole..run {
                let interpolants = at_start + t.per_x * k as f32;
                if packer.push((x + k) as u32, t.object, interpolants) {
                    shade(&packer.take(y).expect("a full packer"), out);
                }
            }
        }
        x += run;
    }
    if let Some(rest) = packer.take(y) {
        shade(&rest, out);
    }
}

/// The depth test along one span: pixel k has 1/w = z0 + k·dz; where that is at least the stored
/// 1/w (larger is nearer), it is stored with the triangle's `id`. An exact tie goes to the later
/// triangle, the same whatever order the threads ran in. Eight pixels at a time, then one by one.
#[inline]
fn depth_test(depth: &mut [f32], ids: &mut [u32], z0: f32, dz: f32, id: u32) {
    let lanes = F32x8::from(std::array::from_fn::<f32, WIDTH, _>(|k| k as f32));
    let (z0_lanes, dz_lanes, id_lanes) = (F32x8::splat(z0), F32x8::splat(dz), u32x8::splat(id));
    let mut d_chunks = depth.chunks_exact_mut(WIDTH);
    let mut i_chunks = ids.chunks_exact_mut(WIDTH);
    let mut first = 0;
    for (d, i) in (&mut d_chunks).zip(&mut i_chunks) {
        // k + lane is an exact integer in f32, so each lane computes what the scalar loop would.
        let z = z0_lanes + dz_lanes * (F32x8::splat(first as f32) + lanes);
        let stored = load(d);
        let nearer = z.cmp_ge(stored);
        d.copy_from_slice(&nearer.blend(z, stored).to_array());
        let old: [u32; WIDTH] = (&*i).try_into().expect("lanes");
        let kept = bytemuck::cast::<_, u32x8>(nearer).blend(id_lanes, u32x8::from(old));
        i.copy_from_slice(&kept.to_array());
        first += WIDTH;
    }
    let rest = d_chunks.into_remainder().iter_mut();
    for (k, (d, i)) in rest.zip(i_chunks.into_remainder()).enumerate() {
        let z = z0 + dz * (first + k) as f32;
        if z >= *d {
            (*d, *i) = (z, id);
        }
    }
}

/// How many times each pixel centre is covered by some triangle, with no depth test: a closed
/// surface seen from outside covers each pixel it projects onto exactly twice (front and back),
/// a single flat patch exactly once. Used to check the fill rule.
#[cfg(test)]
pub fn coverage_counts(world: &World, view: &View) -> Vec<u32> {
    let (width, height) = (view.width, view.height);
    let mut geometry = Geometry::default();
    let mut normals = super::varying::PerVertex::normals(world);
    let bands = geometry.set_up(world, view, &mut normals);
    let mut counts = vec![0u32; width as usize * height as usize];
    counts
        .par_chunks_mut((bands.rows * width) as usize)
        .enumerate()
        .for_each(|(band, rows)| {
            let top = band as u32 * bands.rows;
            let band_rows = rows.len() as u32 / width;
            scan_band(
                bands.triangles(band),
                width,
                top,
                band_rows,
                |span, _, _, _, _| {
                    rows[span].iter_mut().for_each(|count| *count += 1);
                },
            );
        });
    counts
}

/// Scan-converts the band's triangles `bin` in order, calling `span(pixels, x, y, number,
/// triangle)` for each run of covered pixel centres, with the triangle's number in `bin`:
/// `pixels` indexes the band's own buffers, and the run starts at pixel (x, y) of the view. Rows
/// `top..top + rows` of a `width`-pixel image form the band.
#[inline]
fn scan_band<'a>(
    bin: impl Iterator<Item = &'a ScreenTriangle>,
    width: u32,
    top: u32,
    rows: u32,
    mut span: impl FnMut(Range<usize>, i32, i32, u32, &ScreenTriangle),
) {
    debug_assert!(width > 0);
    let bottom = (top + rows) as i32 - 1;
    for (i, t) in bin.enumerate() {
        let y0 = t.min_y.max(top as i32);
        let y1 = t.max_y.min(bottom);
        for_each_span(t, y0, y1, |y, first, last| {
            let start = (y as u32 - top) as usize * width as usize + first as usize;
            span(
                start..start + (last - first) as usize + 1,
                first,
                y,
                i as u32,
                t,
            );
        });
    }
}
