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

use glam::{DVec4, Vec2, Vec3, Vec4};
use rayon::prelude::*;

use super::fragments::{Fragments, Packer};
use crate::render::camera::{NEAR, View};
use crate::render::progress::{Cancelled, Progress};
use crate::render::simd::{F32x8, WIDTH, load};
use crate::world::World;
use wide::{CmpGe, u32x8};

/// Sub-pixel precision of snapped vertex coordinates: 1/256 pixel.
const SUBPIXEL_BITS: u32 = 8;
const SUBPIXEL: f32 = (1 << SUBPIXEL_BITS) as f32;
/// Rows per band: the unit of parallel work and of progress.
const BAND_ROWS: u32 = 8;
/// Triangles are clipped to |x|, |y| ≤ GUARD·w, which keeps snapped coordinates far inside i32 and
/// edge-function products inside i64 for every image size the options accept.
const GUARD: f32 = 4.0;
/// Triangles per parallel setup task.
const SETUP_CHUNK: usize = 4096;
/// Bits of a screen triangle's index within its setup chunk (see [`ScreenTriangles`]).
const INDEX_BITS: u32 = 15;
/// Clipping against the near plane and the four guard-band planes turns a triangle into a polygon
/// of at most 3 + 5 vertices: a fan of at most this many triangles.
const MAX_FAN: usize = 6;
const _: () = assert!(SETUP_CHUNK * MAX_FAN < 1 << INDEX_BITS);

/// A triangle ready for scan conversion: snapped, counter-clockwise in fixed point, with the
/// screen-space plane of its interpolants.
///
/// The interpolants are (varying·1/w, 1/w): both are affine in screen space, so each is a plane
/// `at_ref + per_x·(x − ref_x) + per_y·(y − ref_y)` over pixel centres, and dividing by the
/// fourth gives the perspective-correct varying. The reference is the pixel holding vertex 0, so
/// strips of an image evaluate the planes exactly as the whole image does.
#[derive(Debug, Clone, Copy)]
struct ScreenTriangle {
    /// Vertex pixel coordinates in 1/256 pixel.
    x: [i32; 3],
    y: [i32; 3],
    /// Inclusive pixel bounds, inside the image.
    min_x: i32,
    max_x: i32,
    min_y: i32,
    max_y: i32,
    /// The reference pixel.
    ref_x: i32,
    ref_y: i32,
    /// Interpolants at the reference pixel's centre, and their change per pixel right and down.
    at_ref: Vec4,
    per_x: Vec4,
    per_y: Vec4,
    object: u32,
}

impl ScreenTriangle {
    /// (varying·1/w, 1/w) at the centre of pixel (x, y).
    #[inline(always)]
    fn interpolants(&self, x: i32, y: i32) -> Vec4 {
        self.at_ref + self.per_x * (x - self.ref_x) as f32 + self.per_y * (y - self.ref_y) as f32
    }
}

/// The screen triangles of a frame, kept in the chunks that set them up in parallel (joining
/// them would copy a hundred megabytes for a million-triangle mesh). A triangle's id is its chunk
/// times 2^[`INDEX_BITS`] plus its index in the chunk; ids increase in triangle order.
#[derive(Debug, Default)]
struct ScreenTriangles {
    chunks: Vec<Vec<ScreenTriangle>>,
}

impl ScreenTriangles {
    /// The triangle with id `id`.
    #[inline(always)]
    fn get(&self, id: u32) -> &ScreenTriangle {
        &self.chunks[(id >> INDEX_BITS) as usize][(id & ((1 << INDEX_BITS) - 1)) as usize]
    }

    /// Every triangle with its id, in triangle order.
    fn iter(&self) -> impl Iterator<Item = (u32, &ScreenTriangle)> {
        self.chunks.iter().enumerate().flat_map(|(c, chunk)| {
            let first = (c as u32) << INDEX_BITS;
            chunk
                .iter()
                .enumerate()
                .map(move |(i, t)| (first + i as u32, t))
        })
    }
}

/// A clip-space vertex during clipping: position (x, y, w) and barycentrics on the original triangle.
#[derive(Debug, Clone, Copy)]
struct ClipVertex {
    pos: Vec3,
    bary: Vec2,
}

impl ClipVertex {
    fn lerp(self, other: ClipVertex, t: f32) -> ClipVertex {
        ClipVertex {
            pos: self.pos.lerp(other.pos, t),
            bary: self.bary.lerp(other.bary, t),
        }
    }
}

/// Per-band buffers, reused by each worker thread from band to band.
#[derive(Debug, Default)]
struct BandBuffers {
    /// 1/w of the nearest surface so far (0 = nothing).
    depth: Vec<f32>,
    /// Number + 1 of the screen triangle that drew the pixel (0 = nothing).
    id: Vec<u32>,
}

/// Draws `world` seen through `view` into `out` (`view.width`×`view.height` pixels, every one
/// written). Each band of rows is scan-converted with a depth test on
/// 1/w, keeping the nearest triangle per pixel centre; then the covered pixels of each row are
/// handed to `shade` eight at a time as [`Fragments`], with `varyings[object][vertex]`
/// interpolated perspective-correctly, and `shade` writes their colours into the row. Uncovered
/// pixels get the background. Shading after the depth test shades each pixel once however much
/// overdraw the scene has, and shading right after each band keeps the band's buffers in cache.
pub fn draw(
    world: &World,
    view: &View,
    progress: &Progress,
    varyings: &[&[Vec3]],
    shade: impl Fn(&Fragments, &mut [Vec3]) + Sync,
    out: &mut [Vec3],
) -> Result<(), Cancelled> {
    let (width, height) = (view.width, view.height);
    debug_assert_eq!(out.len(), width as usize * height as usize);
    let triangles = setup(world, view, varyings);
    let bins = bin(&triangles, height);
    out.par_chunks_mut((BAND_ROWS * width) as usize)
        .zip(bins.par_iter())
        .enumerate()
        .try_for_each_init(BandBuffers::default, |buffers, (band, (rows, bin))| {
            progress.check()?;
            let top = band as u32 * BAND_ROWS;
            let band_rows = rows.len() as u32 / width;
            let BandBuffers { depth, id } = buffers;
            depth.clear();
            depth.resize(rows.len(), 0.0);
            id.clear();
            id.resize(rows.len(), 0);
            scan_band(
                &triangles,
                bin,
                width,
                top,
                band_rows,
                |span, x, y, i, t| {
                    let z0 = t.interpolants(x, y).w;
                    depth_test(
                        &mut depth[span.clone()],
                        &mut id[span],
                        z0,
                        t.per_x.w,
                        i + 1,
                    );
                },
            );
            for (r, (out, ids)) in rows
                .chunks_mut(width as usize)
                .zip(id.chunks(width as usize))
                .enumerate()
            {
                let y = top + r as u32;
                shade_row(&triangles, ids, y, world.background, &shade, out);
            }
            progress.advance(band_rows as u64);
            Ok(())
        })
}

/// Shades row `y`, whose pixels were drawn by screen triangles `ids` (number + 1; 0 = none):
/// runs of one triangle go to `shade` as whole spans of eight, the rest packed into lanes.
#[inline]
fn shade_row(
    triangles: &ScreenTriangles,
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
            let t = triangles.get(id - 1);
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
    let normals: Vec<&[Vec3]> = world.objects.iter().map(|o| &o.mesh.normals[..]).collect();
    let triangles = setup(world, view, &normals);
    let bins = bin(&triangles, height);
    let mut counts = vec![0u32; width as usize * height as usize];
    counts
        .par_chunks_mut((BAND_ROWS * width) as usize)
        .zip(bins.par_iter())
        .enumerate()
        .for_each(|(band, (rows, bin))| {
            let top = band as u32 * BAND_ROWS;
            let band_rows = rows.len() as u32 / width;
            scan_band(
                &triangles,
                bin,
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

/// Vertex stage and triangle setup for every triangle of the world, in object then triangle
/// order, carrying `varyings[object][vertex]`.
fn setup(world: &World, view: &View, varyings: &[&[Vec3]]) -> ScreenTriangles {
    debug_assert_eq!(varyings.len(), world.objects.len());
    let clip: Vec<Vec<Vec3>> = world
        .objects
        .par_iter()
        .map(|o| {
            o.mesh
                .positions
                .par_iter()
                .map(|&p| view.to_clip(p))
                .collect()
        })
        .collect();
    let mut jobs = Vec::new();
    for (object, o) in world.objects.iter().enumerate() {
        let n = o.mesh.triangles.len();
        for start in (0..n).step_by(SETUP_CHUNK) {
            jobs.push((object, start..(start + SETUP_CHUNK).min(n)));
        }
    }
    let chunks: Vec<Vec<ScreenTriangle>> = jobs
        .par_iter()
        .map(|(object, range)| {
            let mesh = &world.objects[*object].mesh;
            let (clip, varying) = (&clip[*object], varyings[*object]);
            let mut out = Vec::with_capacity(range.len());
            for t in range.clone() {
                let corners = mesh.triangles[t].map(|i| i as usize);
                let v = corners.map(|i| clip[i]);
                let a = corners.map(|i| varying[i]);
                setup_triangle(view, v, a, *object as u32, &mut out);
            }
            out
        })
        .collect();
    ScreenTriangles { chunks }
}

/// Clips one triangle (clip-space corners `v`, vertex varyings `a`) and pushes the screen
/// triangles it yields (0, 1 or a fan of several).
fn setup_triangle(
    view: &View,
    v: [Vec3; 3],
    a: [Vec3; 3],
    object: u32,
    out: &mut Vec<ScreenTriangle>,
) {
    // Trivial reject: all three vertices outside one plane of the view volume.
    let outside = |f: &dyn Fn(Vec3) -> bool| v.iter().all(|&p| f(p));
    if outside(&|p| p.z < NEAR)
        || outside(&|p| p.x > p.z)
        || outside(&|p| p.x < -p.z)
        || outside(&|p| p.y > p.z)
        || outside(&|p| p.y < -p.z)
    {
        return;
    }
    let corners = [
        ClipVertex {
            pos: v[0],
            bary: Vec2::ZERO,
        },
        ClipVertex {
            pos: v[1],
            bary: Vec2::X,
        },
        ClipVertex {
            pos: v[2],
            bary: Vec2::Y,
        },
    ];
    let inside_all = |p: Vec3| p.z >= NEAR && p.x.abs() <= GUARD * p.z && p.y.abs() <= GUARD * p.z;
    if v.iter().all(|&p| inside_all(p)) {
        emit(view, corners, a, object, out);
        return;
    }
    // Sutherland–Hodgman in homogeneous space: near plane, then the guard band.
    let planes: [fn(Vec3) -> f32; 5] = [
        |p| p.z - NEAR,
        |p| GUARD * p.z - p.x,
        |p| GUARD * p.z + p.x,
        |p| GUARD * p.z - p.y,
        |p| GUARD * p.z + p.y,
    ];
    let mut poly: Vec<ClipVertex> = corners.to_vec();
    for plane in planes {
        let mut next = Vec::with_capacity(poly.len() + 1);
        for i in 0..poly.len() {
            let (p, q) = (poly[i], poly[(i + 1) % poly.len()]);
            let (dp, dq) = (plane(p.pos), plane(q.pos));
            if dp >= 0.0 {
                next.push(p);
            }
            if (dp >= 0.0) != (dq >= 0.0) {
                next.push(p.lerp(q, dp / (dp - dq)));
            }
        }
        poly = next;
        if poly.len() < 3 {
            return;
        }
    }
    for i in 1..poly.len() - 1 {
        emit(view, [poly[0], poly[i], poly[i + 1]], a, object, out);
    }
}

/// Projects, snaps and orients a clipped triangle of the original triangle with vertex varyings
/// `a`, and sets up its interpolant planes; drops it when it covers no pixel centre's box.
fn emit(view: &View, v: [ClipVertex; 3], a: [Vec3; 3], object: u32, out: &mut Vec<ScreenTriangle>) {
    let mut x = [0i32; 3];
    let mut y = [0i32; 3];
    // (varying·1/w, 1/w) at each vertex; the varying of a clipped vertex is the original
    // triangle's, interpolated at its barycentrics.
    let mut values = [DVec4::ZERO; 3];
    for k in 0..3 {
        let p = view.clip_to_pixel(v[k].pos);
        x[k] = round(p.x * SUBPIXEL);
        y[k] = round(p.y * SUBPIXEL);
        let inv_w = 1.0 / v[k].pos.z as f64;
        let b = v[k].bary.as_dvec2();
        let [a0, a1, a2] = a.map(|a| a.as_dvec3());
        let varying = a0 + (a1 - a0) * b.x + (a2 - a0) * b.y;
        values[k] = (varying * inv_w).extend(inv_w);
    }
    let area = edge(x[0], y[0], x[1], y[1], x[2], y[2]);
    if area == 0 {
        return;
    }
    if area < 0 {
        x.swap(1, 2);
        y.swap(1, 2);
        values.swap(1, 2);
    }
    // Pixel i's centre is at i·256 + 128 in fixed point.
    let half = 1 << (SUBPIXEL_BITS - 1);
    let first = |lo: i32| (lo - half + (1 << SUBPIXEL_BITS) - 1).div_euclid(1 << SUBPIXEL_BITS);
    let last = |hi: i32| (hi - half).div_euclid(1 << SUBPIXEL_BITS);
    let min_x = first(*x.iter().min().unwrap()).max(0);
    let max_x = last(*x.iter().max().unwrap()).min(view.width as i32 - 1);
    let min_y = first(*y.iter().min().unwrap()).max(0);
    let max_y = last(*y.iter().max().unwrap()).min(view.height as i32 - 1);
    if min_x > max_x || min_y > max_y {
        return;
    }
    // Each interpolant is Σ values[k]·λk, where λk = (edge function opposite vertex k) / area
    // is affine in the pixel centre: its plane follows from the edge functions' steps.
    let (ref_x, ref_y) = (x[0] >> SUBPIXEL_BITS, y[0] >> SUBPIXEL_BITS);
    let (ref_px, ref_py) = (
        (ref_x << SUBPIXEL_BITS) + half,
        (ref_y << SUBPIXEL_BITS) + half,
    );
    let inv_area = 1.0 / area.abs() as f64;
    let (mut at_ref, mut per_x, mut per_y) = (DVec4::ZERO, DVec4::ZERO, DVec4::ZERO);
    for (k, &value) in values.iter().enumerate() {
        let (i, j) = ((k + 1) % 3, (k + 2) % 3);
        let at = edge(x[i], y[i], x[j], y[j], ref_px, ref_py) as f64 * inv_area;
        let step_x = -((y[j] - y[i]) as f64) * SUBPIXEL as f64 * inv_area;
        let step_y = (x[j] - x[i]) as f64 * SUBPIXEL as f64 * inv_area;
        at_ref += value * at;
        per_x += value * step_x;
        per_y += value * step_y;
    }
    out.push(ScreenTriangle {
        x,
        y,
        min_x,
        max_x,
        min_y,
        max_y,
        ref_x,
        ref_y,
        at_ref: at_ref.as_vec4(),
        per_x: per_x.as_vec4(),
        per_y: per_y.as_vec4(),
        object,
    });
}

/// `v` rounded to the nearest integer, halves away from zero: `f32::round`, which on baseline
/// x86-64 is a call into libm, done with a truncating conversion (|v| < 2^31).
#[inline(always)]
fn round(v: f32) -> i32 {
    let whole = v as i32;
    // The fractional part of a float is exact.
    let fraction = v - whole as f32;
    whole
        .saturating_add((fraction >= 0.5) as i32)
        .saturating_sub((fraction <= -0.5) as i32)
}

/// Twice the signed area of (a, b, p): positive when p is on the interior side of a→b.
#[inline]
fn edge(ax: i32, ay: i32, bx: i32, by: i32, px: i32, py: i32) -> i64 {
    (bx - ax) as i64 * (py - ay) as i64 - (by - ay) as i64 * (px - ax) as i64
}

/// Triangle ids per band of [`BAND_ROWS`] rows, in triangle order.
fn bin(triangles: &ScreenTriangles, height: u32) -> Vec<Vec<u32>> {
    let bands = height.div_ceil(BAND_ROWS) as usize;
    let mut bins = vec![Vec::new(); bands];
    for (id, t) in triangles.iter() {
        for band in (t.min_y as u32 / BAND_ROWS)..=(t.max_y as u32 / BAND_ROWS) {
            bins[band as usize].push(id);
        }
    }
    bins
}

/// Scan-converts the band's triangles in order, calling `span(pixels, x, y, triangle id,
/// triangle)` for each run of covered pixel centres: `pixels` indexes the band's own buffers,
/// and the run starts at pixel (x, y) of the view. Rows `top..top + rows` of a `width`-pixel
/// image form the band.
#[inline]
fn scan_band(
    triangles: &ScreenTriangles,
    bin: &[u32],
    width: u32,
    top: u32,
    rows: u32,
    mut span: impl FnMut(Range<usize>, i32, i32, u32, &ScreenTriangle),
) {
    debug_assert!(width > 0);
    let bottom = (top + rows) as i32 - 1;
    let half = 1 << (SUBPIXEL_BITS - 1);
    for &i in bin {
        let t = triangles.get(i);
        let y0 = t.min_y.max(top as i32);
        let y1 = t.max_y.min(bottom);
        let (px, py) = (
            (t.min_x << SUBPIXEL_BITS) + half,
            (y0 << SUBPIXEL_BITS) + half,
        );
        // Edge k is opposite vertex k: it runs from vertex k+1 to vertex k+2, and its edge
        // function is vertex k's unnormalised barycentric weight.
        let mut row_start = [0i64; 3];
        let mut step_x = [0i64; 3];
        let mut step_y = [0i64; 3];
        for k in 0..3 {
            let (a, b) = ((k + 1) % 3, (k + 2) % 3);
            let (dx, dy) = (t.x[b] - t.x[a], t.y[b] - t.y[a]);
            // Top-left rule: a centre exactly on an edge belongs to the triangle only when the
            // edge is a top edge (horizontal, interior below) or a left edge (interior to the
            // right). Other edges get a bias of −1 so that "on the edge" tests as outside.
            let top_left = (dy == 0 && dx > 0) || dy < 0;
            let bias = if top_left { 0 } else { -1 };
            row_start[k] = edge(t.x[a], t.y[a], t.x[b], t.y[b], px, py) + bias;
            step_x[k] = -(dy as i64) << SUBPIXEL_BITS;
            step_y[k] = (dx as i64) << SUBPIXEL_BITS;
        }
        let columns = (t.max_x - t.min_x) as i64;
        for y in y0..=y1 {
            // The covered span of this row, solved from the three edge functions (each is
            // linear in x): the centres where all three are ≥ 0.
            let (mut lo, mut hi) = (0i64, columns);
            for k in 0..3 {
                let (e, s) = (row_start[k], step_x[k]);
                if s > 0 {
                    if e < 0 {
                        lo = lo.max((-e + s - 1) / s);
                    }
                } else if s < 0 {
                    hi = if e < 0 { -1 } else { hi.min(e / -s) };
                } else if e < 0 {
                    hi = -1;
                }
            }
            if lo <= hi {
                debug_assert!(
                    (0..3).all(|k| row_start[k] + lo * step_x[k] >= 0
                        && row_start[k] + hi * step_x[k] >= 0),
                    "span solved wrongly"
                );
                let x = t.min_x + lo as i32;
                let start = (y as u32 - top) as usize * width as usize + x as usize;
                span(start..start + (hi - lo) as usize + 1, x, y, i, t);
            }
            for k in 0..3 {
                row_start[k] += step_y[k];
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::round;

    #[test]
    fn round_is_f32_round() {
        let special = [
            0.5,
            -0.5,
            1.5,
            -2.5,
            0.499_999_97,
            -0.499_999_97,
            8_388_607.5,
            1.0e9,
        ];
        let steps = (-40_000..40_000).map(|k| k as f32 * 0.031_25 + 0.003);
        for v in special.into_iter().chain(steps) {
            assert_eq!(round(v), v.round() as i32, "{v}");
        }
    }
}
