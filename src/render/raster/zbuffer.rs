//! The Z-buffer rasterizer shared by Gouraud and Phong shading.
//!
//! Stages: vertex (clip coordinates) → triangle setup (near and guard-band clipping in homogeneous
//! space, fixed-point snapping, bounding box, and the screen-space planes of the interpolants
//! (varying·1/w, 1/w)) → binning into row bands → per band, in triangle order: coverage by exact
//! integer edge functions with the top-left rule, and a depth test on 1/w that keeps the nearest
//! triangle per pixel → the planes of the varying for the triangles the band shows, and only
//! those → per row, the covered pixels go to the shader eight at a time ([`Fragments`]) with
//! their depth and perspective-correct varying. Each pixel is shaded once, however much
//! overdraw the scene has; a hidden triangle's varying is never worked out (at the preview's
//! size, half of the triangles that cover a pixel centre are behind others); and Gouraud and
//! Phong differ only in the varying they interpolate (a lit vertex colour, or a normal).
//!
//! Bands run in parallel; each band's result depends only on the triangle order, so the output is
//! the same for any number of threads.

use glam::Vec3;
use rayon::prelude::*;

use super::alpha_cut::CutTest;
use super::fragments::{Fragments, Packer, Run};
#[cfg(target_arch = "x86_64")]
use super::scan_avx2::{Avx2, Band};
use super::screen_triangle::{Planes, ScreenTriangle};
use super::setup::{BandBuffers, Bands, Geometry, PlanesOf};
use super::shader::Shader;
use super::spans::{fits_lanes, for_each_block, solved_spans};
use super::varying::Varying;
use crate::render::camera::View;
use crate::render::cpu::with_avx2;
use crate::render::prefetch;
use crate::render::progress::{Cancelled, Progress};
use crate::render::simd::{F32x8, Lanes8, LanesJob, WIDTH, load, run_on_best_lanes};
use crate::world::World;
use wide::{CmpEq, CmpGe, i32x8, u32x8};

/// Draws `world` seen through `view` into `out` (`view.width`×`view.height` pixels, every one
/// written), with `geometry` as working memory. Each band of rows is scan-converted with a
/// depth test on 1/w, keeping the nearest triangle per pixel centre; then the covered pixels of
/// each row are handed to `shader` eight at a time as [`Fragments`], on the widest lanes the
/// CPU has, with `varying`'s `K` values interpolated perspective-correctly, and it writes their
/// colours into the row. Uncovered pixels get the background. Shading after the depth test
/// shades each pixel once however much overdraw the scene has, and shading right after each
/// band keeps the band's buffers in cache.
pub fn draw<const K: usize>(
    geometry: &mut Geometry,
    world: &World,
    view: &View,
    progress: &Progress,
    varying: &mut dyn Varying,
    shader: &impl Shader<K>,
    out: &mut [Vec3],
) -> Result<(), Cancelled>
where
    BandBuffers: PlanesOf<K>,
{
    let width = view.width;
    debug_assert_eq!(out.len(), width as usize * view.height as usize);
    let threads = rayon::current_num_threads().max(1);
    let mut pool = std::mem::take(&mut geometry.band_buffers);
    pool.resize_with(threads, Default::default);
    let bands = geometry.set_up(world, view, varying);
    let varying = &*varying;
    let orthographic = view.orthographic;
    // The depth buffer before any triangle: below every 1/w (perspective), or every −w.
    let nothing = if orthographic { f32::NEG_INFINITY } else { 0.0 };
    let cut = CutTest::of(world, view);
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
            let buffers = held.as_deref_mut().unwrap_or(&mut fresh);
            let BandBuffers { depth, id, .. } = buffers;
            // A block of eight lanes may start at any pixel: the buffers run on past the band.
            depth.clear();
            depth.resize(rows.len() + WIDTH, nothing);
            id.clear();
            id.resize(rows.len() + WIDTH, 0);
            triangles.clear();
            let bin = bands.triangles(band).inspect(|t| triangles.push(*t));
            scan_band(bin, cut.as_ref(), width, top, band_rows, depth, id);
            mark_seen(
                &buffers.id[..rows.len()],
                triangles.len(),
                &mut buffers.seen,
            );
            let mut planes = std::mem::take(buffers.planes_of());
            with_avx2(
                #[inline(always)]
                || {
                    set_planes(
                        triangles,
                        &bands,
                        varying,
                        buffers,
                        &mut planes,
                        orthographic,
                    )
                },
            );
            run_on_best_lanes(ShadeRows {
                planes: &planes,
                ids: &buffers.id,
                width: width as usize,
                top,
                background: world.background,
                shader,
                rows,
            });
            *buffers.planes_of() = planes;
            progress.advance(band_rows as u64);
            Ok(())
        });
    geometry.band_buffers = pool;
    drawn
}

/// Sets `seen[id]` for each id in `ids` and clears it for the other ids up to `count` (ids of
/// the band's bin, 1-based; 0 = no triangle). Eight ids at a time: inside a triangle's span
/// the eight are one id.
fn mark_seen(ids: &[u32], count: usize, seen: &mut Vec<bool>) {
    seen.clear();
    seen.resize(count + 1, false);
    let mut blocks = ids.chunks_exact(WIDTH);
    for block in &mut blocks {
        let block: [u32; WIDTH] = block.try_into().expect("lanes");
        let first = i32x8::splat(block[0] as i32);
        if bytemuck::cast::<_, i32x8>(block).cmp_eq(first).all() {
            seen[block[0] as usize] = true;
        } else {
            block.iter().for_each(|&id| seen[id as usize] = true);
        }
    }
    blocks
        .remainder()
        .iter()
        .for_each(|&id| seen[id as usize] = true);
}

/// Sets up `planes[id]` for each id the band shows (`buffers.seen`) of its bin `triangles`:
/// the `K` varyings at the corners of each run of seen triangles of one object are asked of
/// `varying` at once.
#[inline(always)]
fn set_planes<const K: usize>(
    triangles: &[&ScreenTriangle],
    bands: &Bands,
    varying: &dyn Varying,
    buffers: &mut BandBuffers,
    planes: &mut Vec<Planes<K>>,
    orthographic: bool,
) {
    let BandBuffers {
        seen,
        mesh_triangles,
        ids,
        values,
        ..
    } = buffers;
    if planes.len() <= triangles.len() {
        planes.resize(triangles.len() + 1, Planes::default());
    }
    let mut next = 0;
    while next < triangles.len() {
        let object = triangles[next].object;
        mesh_triangles.clear();
        ids.clear();
        values.clear();
        while let Some(t) = triangles.get(next).filter(|t| t.object == object) {
            next += 1;
            if seen[next] {
                ids.push(next as u32);
                mesh_triangles.push(t.triangle);
                // Read below, once the varying is known: at 1920×1080 they are scattered
                // over megabytes.
                prefetch::ahead_all(bands.corners(t));
                varying.prefetch(object as usize, t.triangle);
            }
        }
        if ids.is_empty() {
            continue;
        }
        varying.corners(object as usize, mesh_triangles, values);
        debug_assert_eq!(values.len(), K * ids.len());
        let (values, _) = values.as_chunks::<K>();
        for (&id, values) in ids.iter().zip(values) {
            let t = triangles[id as usize - 1];
            planes[id as usize] = bands.corners(t).planes(t, *values, orthographic);
        }
    }
}

/// The shading of a band's rows, `top` down: `planes` and `ids` as [`shade_row`] takes them,
/// `ids` for the whole band and [`WIDTH`] past it.
struct ShadeRows<'a, S, const K: usize> {
    planes: &'a [Planes<K>],
    ids: &'a [u32],
    /// Pixels per row.
    width: usize,
    top: u32,
    background: Vec3,
    shader: &'a S,
    /// The band's pixels, row after row.
    rows: &'a mut [Vec3],
}

impl<S: Shader<K>, const K: usize> LanesJob for ShadeRows<'_, S, K> {
    type Output = ();

    #[inline(always)]
    fn run<L: Lanes8>(self) {
        let width = self.width;
        for (r, out) in self.rows.chunks_mut(width).enumerate() {
            let start = r * width;
            // The row's ids and the next row's (or the padding): runs are found in lanes.
            let ids = &self.ids[start..start + width + WIDTH];
            let y = self.top + r as u32;
            shade_row::<L, S, K>(self.planes, ids, y, self.background, self.shader, out);
        }
    }
}

/// The length of the run of equal ids from `ids[0]` on, within the first `row` ids; `ids`
/// holds at least [`WIDTH`] more, which are compared eight at a time.
#[inline(always)]
fn run_length(ids: &[u32], row: usize) -> usize {
    let id = i32x8::splat(ids[0] as i32);
    let mut run = 0;
    while run < row {
        let block: [u32; WIDTH] = ids[run..run + WIDTH].try_into().expect("lanes");
        let same = bytemuck::cast::<_, i32x8>(block).cmp_eq(id).move_mask() as u32;
        if same != 0xff {
            run += (!same).trailing_zeros() as usize;
            break;
        }
        run += WIDTH;
    }
    run.min(row)
}

/// Shades row `y`, whose pixels were drawn by the triangle whose interpolants are
/// `planes[id]` for each of `ids` (0 = none; [`WIDTH`] ids of the next row follow the row's):
/// runs of one triangle go to `shader` as whole spans of eight, the rest of each run packed in
/// lanes; a shader that [shades two batches at once](Shader::SHADES_TWO) gets them in pairs.
#[inline(always)]
fn shade_row<L: Lanes8, S: Shader<K>, const K: usize>(
    planes: &[Planes<K>],
    ids: &[u32],
    y: u32,
    background: Vec3,
    shader: &S,
    out: &mut [Vec3],
) {
    let mut packer = Packer::<L, K>::default();
    // A batch waiting for a second one (pixels are written once each, in any order).
    let mut waiting = None;
    let mut x = 0;
    let width = out.len();
    while x < width {
        let id = ids[x];
        let length = run_length(&ids[x..], width - x);
        if id == 0 {
            fill(&mut out[x..x + length], background);
        } else {
            let t = &planes[id as usize];
            let pixels = Run {
                start: x,
                object: t.object,
                at_start: t.at(x as i32, y as i32),
                per_x: t.per_x,
            };
            let whole = length - length % WIDTH;
            for k in (0..whole).step_by(WIDTH) {
                let span = Fragments::span(y, &pixels, k);
                shade_batch(shader, &mut waiting, span, out);
            }
            if whole < length
                && let Some(full) = packer.push_run(y, &pixels, whole, length - whole)
            {
                shade_batch(shader, &mut waiting, full, out);
            }
        }
        x += length;
    }
    if let Some(rest) = packer.take(y) {
        shade_batch(shader, &mut waiting, rest, out);
    }
    if let Some(last) = waiting {
        shader.shade(&last, out);
    }
}

/// Hands `batch` to `shader`: at once, or, where it [shades two](Shader::SHADES_TWO), with the
/// batch `waiting` if there is one, else as the one waiting.
#[inline(always)]
fn shade_batch<L: Lanes8, S: Shader<K>, const K: usize>(
    shader: &S,
    waiting: &mut Option<Fragments<L, K>>,
    batch: Fragments<L, K>,
    out: &mut [Vec3],
) {
    if !S::SHADES_TWO {
        shader.shade(&batch, out);
    } else if let Some(first) = waiting.take() {
        shader.shade_two(&first, &batch, out);
    } else {
        *waiting = Some(batch);
    }
}

/// Fills `pixels` with `color` eight at a time: a pixel is 12 bytes, and filling them one by
/// one takes two stores each, which at 1920×1080 cost more than the memory writes.
#[inline(always)]
fn fill(pixels: &mut [Vec3], color: Vec3) {
    let eight = [color; WIDTH];
    let mut blocks = pixels.chunks_exact_mut(WIDTH);
    for block in &mut blocks {
        block.copy_from_slice(&eight);
    }
    blocks.into_remainder().fill(color);
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

/// The depth test on one block of eight pixels starting at `depth[0]`, `ids[0]`: where a lane is
/// `covered` and its 1/w `z` is at least the stored one, `z` and `id` are stored. Computes what
/// [`depth_test`] does for the same pixels.
#[inline(always)]
fn depth_test_block(depth: &mut [f32], ids: &mut [u32], z: F32x8, covered: i32x8, id: u32) {
    let (depth, ids) = (&mut depth[..WIDTH], &mut ids[..WIDTH]);
    let stored = load(depth);
    let nearer = z.cmp_ge(stored) & bytemuck::cast::<_, F32x8>(covered);
    depth.copy_from_slice(&nearer.blend(z, stored).to_array());
    let old: [u32; WIDTH] = (&*ids).try_into().expect("lanes");
    let kept = bytemuck::cast::<_, u32x8>(nearer).blend(u32x8::splat(id), u32x8::from(old));
    ids.copy_from_slice(&kept.to_array());
}

/// How many times each pixel centre is covered by some triangle, with no depth test: a closed
/// surface seen from outside covers each pixel it projects onto exactly twice (front and back),
/// a single flat patch exactly once. Used to check the fill rule.
#[cfg(test)]
pub fn coverage_counts(world: &World, view: &View) -> Vec<u32> {
    use super::spans::for_each_span;
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
            let bottom = top as i32 + (rows.len() as u32 / width) as i32 - 1;
            for t in bands.triangles(band) {
                let (y0, y1) = (t.min_y.max(top as i32), t.max_y.min(bottom));
                for_each_span(t, y0, y1, |y, first, last| {
                    let start = (y as u32 - top) as usize * width as usize + first as usize;
                    let pixels = start..=start + (last - first) as usize;
                    rows[pixels].iter_mut().for_each(|count| *count += 1);
                });
            }
        });
    counts
}

/// Scan-converts the band's triangles `bin` in order into the band's depth buffer (1/w, 0 =
/// nothing) and `ids` (the triangle's number in `bin` + 1): rows `top..top + rows` of a
/// `width`-pixel image, and [`WIDTH`] entries past the band's end. Small triangles are tested
/// eight pixels at a time and their depth tested in the same lanes; large ones have each row's
/// span solved, then depth-tested along it. Both compute pixel k of a row's run of covered
/// centres as 1/w(run start) + k·(1/w per pixel). Triangles of objects that `cut` masks are
/// tested pixel by pixel, a centre cut out by alpha writing nothing.
#[inline]
fn scan_band<'a>(
    bin: impl Iterator<Item = &'a ScreenTriangle>,
    cut: Option<&CutTest>,
    width: u32,
    top: u32,
    rows: u32,
    depth: &mut [f32],
    ids: &mut [u32],
) {
    debug_assert!(width > 0);
    debug_assert!(depth.len() >= (rows * width) as usize + WIDTH);
    let bottom = (top + rows) as i32 - 1;
    let row_start = |y: i32| (y as u32 - top) as usize * width as usize;
    let lanes = F32x8::from(std::array::from_fn::<f32, WIDTH, _>(|k| k as f32));
    #[cfg(target_arch = "x86_64")]
    let avx2 = Avx2::detect();
    for (i, t) in bin.enumerate() {
        let id = i as u32 + 1;
        let y0 = t.min_y.max(top as i32);
        let y1 = t.max_y.min(bottom);
        if let Some(cut) = cut.filter(|cut| cut.masks(t.object)) {
            cut.depth_test(t, (y0, y1), row_start, depth, ids, id);
            continue;
        }
        #[cfg(target_arch = "x86_64")]
        if let Some(avx2) = avx2
            && fits_lanes(t)
        {
            let mut band = Band {
                top,
                width,
                depth,
                ids,
            };
            avx2.scan_small(t, y0, y1, &mut band, id);
            continue;
        }
        if fits_lanes(t) {
            let dz = F32x8::splat(t.inv_w.per_x);
            // 1/w at the first covered centre of row `row`.
            let (mut row, mut z0) = (-1, F32x8::splat(0.0));
            for_each_block(t, y0, y1, |y, first, x, covered| {
                if y != row {
                    (row, z0) = (y, F32x8::splat(t.inv_w_at(first, y)));
                }
                // x − first + lane is an exact integer in f32: each lane computes what the
                // span's depth test would.
                let z = z0 + dz * (F32x8::splat((x - first) as f32) + lanes);
                let at = row_start(y) + x as usize;
                depth_test_block(&mut depth[at..], &mut ids[at..], z, covered, id);
            });
        } else {
            solved_spans(t, y0, y1, |y, first, last| {
                let start = row_start(y) + first as usize;
                let pixels = start..=start + (last - first) as usize;
                let z0 = t.inv_w_at(first, y);
                depth_test(
                    &mut depth[pixels.clone()],
                    &mut ids[pixels],
                    z0,
                    t.inv_w.per_x,
                    id,
                );
            });
        }
    }
}
