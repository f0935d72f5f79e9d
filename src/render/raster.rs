//! The Z-buffer rasterizer shared by Gouraud and Phong shading.
//!
//! It writes a visibility buffer: for each pixel, the nearest triangle and the perspective-correct
//! barycentric coordinates of the pixel centre on it. Shading is a separate pass over that buffer,
//! so each pixel is shaded once however much overdraw the scene has, and Gouraud and Phong differ
//! only in what they interpolate (a colour or a normal and position).
//!
//! Stages: vertex (clip coordinates) → triangle setup (near and guard-band clipping in homogeneous
//! space, fixed-point snapping, bounding box) → binning into row bands → per band, in triangle
//! order: coverage by integer edge functions with the top-left rule, depth test on 1/w.
//! Bands run in parallel; each band's result depends only on the triangle order, so the output is
//! the same for any number of threads.

use glam::{Vec2, Vec3};
use rayon::prelude::*;

use super::camera::{NEAR, View};
use super::frame::Frame;
use super::progress::{Cancelled, Progress};
use crate::world::World;

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

/// The nearest surface at one pixel centre.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Fragment {
    /// 1/w of the surface (w = depth along the view direction): larger is nearer.
    pub inv_w: f32,
    /// Object index in the world.
    pub object: u32,
    /// Triangle index within the object's mesh.
    pub triangle: u32,
    /// Perspective-correct barycentric weights of the triangle's 2nd and 3rd vertices
    /// (the 1st has 1 − b1 − b2).
    pub b1: f32,
    pub b2: f32,
}

impl Fragment {
    /// No surface.
    pub const EMPTY: Fragment = Fragment {
        inv_w: 0.0,
        object: u32::MAX,
        triangle: 0,
        b1: 0.0,
        b2: 0.0,
    };

    /// Whether a surface was drawn here.
    #[inline]
    pub fn is_covered(&self) -> bool {
        self.object != u32::MAX
    }

    /// The three barycentric weights.
    #[inline]
    pub fn weights(&self) -> [f32; 3] {
        [1.0 - self.b1 - self.b2, self.b1, self.b2]
    }
}

/// A triangle ready for scan conversion: snapped, counter-clockwise in fixed point.
#[derive(Debug, Clone, Copy)]
struct ScreenTriangle {
    /// Vertex pixel coordinates in 1/256 pixel.
    x: [i32; 3],
    y: [i32; 3],
    /// 1/w at each vertex.
    inv_w: [f32; 3],
    /// Original-triangle barycentrics (b1, b2) at each vertex, premultiplied by 1/w.
    bary_w: [Vec2; 3],
    /// 1 / (twice the area in square fixed-point units), > 0.
    inv_area: f32,
    object: u32,
    triangle: u32,
    /// Inclusive pixel bounds, inside the image.
    min_x: i32,
    max_x: i32,
    min_y: i32,
    max_y: i32,
}

impl ScreenTriangle {
    /// The fragment at the centre of pixel (x, y), where the surface's 1/w is `inv_w`.
    #[inline]
    fn fragment(&self, x: i32, y: i32, inv_w: f32) -> Fragment {
        let half = 1 << (SUBPIXEL_BITS - 1);
        let (px, py) = ((x << SUBPIXEL_BITS) + half, (y << SUBPIXEL_BITS) + half);
        let (tx, ty) = (&self.x, &self.y);
        // Screen-space weights of the vertices, then perspective-correct original barycentrics.
        let l1 = edge(tx[2], ty[2], tx[0], ty[0], px, py) as f32 * self.inv_area;
        let l2 = edge(tx[0], ty[0], tx[1], ty[1], px, py) as f32 * self.inv_area;
        let l0 = 1.0 - l1 - l2;
        let b = (self.bary_w[0] * l0 + self.bary_w[1] * l1 + self.bary_w[2] * l2) * inv_w.recip();
        Fragment {
            inv_w,
            object: self.object,
            triangle: self.triangle,
            b1: b.x,
            b2: b.y,
        }
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

/// Draws `world` seen through `view`: rasterizes each band into a visibility buffer (the nearest
/// triangle per pixel centre), then calls `shade` once per covered pixel with the fragment there.
/// Uncovered pixels get the background. Shading right after each band keeps the band's buffer in
/// cache, and each pixel is shaded once however much overdraw the scene has.
pub fn draw(
    world: &World,
    view: &View,
    progress: &Progress,
    shade: impl Fn(&Fragment) -> Vec3 + Sync,
) -> Result<Frame, Cancelled> {
    let (width, height) = (view.width, view.height);
    let triangles = setup(world, view);
    let bins = bin(&triangles, height);
    let mut pixels = vec![world.background; width as usize * height as usize];
    pixels
        .par_chunks_mut((BAND_ROWS * width) as usize)
        .zip(bins.par_iter())
        .enumerate()
        .try_for_each_init(Vec::new, |samples: &mut Vec<u64>, (band, (rows, bin))| {
            progress.check()?;
            let top = band as u32 * BAND_ROWS;
            let band_rows = rows.len() as u32 / width;
            // Each sample packs the nearest surface's 1/w (f32 bits, high half) with the number + 1
            // of the screen triangle that drew it (low half); 0 is empty. Positive floats order like
            // their bits, so one integer max is the depth test, and an exact depth tie goes to the
            // later triangle whatever order the threads ran in.
            samples.clear();
            samples.resize(rows.len(), 0);
            scan_band(
                &triangles,
                bin,
                width,
                top,
                band_rows,
                |index, i, tri, lambda| {
                    let inv_w = lambda[0] * tri.inv_w[0]
                        + lambda[1] * tri.inv_w[1]
                        + lambda[2] * tri.inv_w[2];
                    let sample = ((inv_w.to_bits() as u64) << 32) | (i as u64 + 1);
                    samples[index] = samples[index].max(sample);
                },
            );
            for (r, (row, row_samples)) in rows
                .chunks_mut(width as usize)
                .zip(samples.chunks(width as usize))
                .enumerate()
            {
                for (x, (pixel, &sample)) in row.iter_mut().zip(row_samples).enumerate() {
                    let id = (sample & 0xffff_ffff) as usize;
                    if id != 0 {
                        let inv_w = f32::from_bits((sample >> 32) as u32);
                        let fragment =
                            triangles[id - 1].fragment(x as i32, (top + r as u32) as i32, inv_w);
                        *pixel = shade(&fragment);
                    }
                }
            }
            progress.advance(band_rows as u64);
            Ok(())
        })?;
    Ok(Frame {
        width,
        height,
        pixels,
    })
}

/// How many times each pixel centre is covered by some triangle, with no depth test: a closed
/// surface seen from outside covers each pixel it projects onto exactly twice (front and back),
/// a single flat patch exactly once. Used to check the fill rule.
pub fn coverage_counts(world: &World, view: &View) -> Vec<u32> {
    let (width, height) = (view.width, view.height);
    let triangles = setup(world, view);
    let bins = bin(&triangles, height);
    let mut counts = vec![0u32; width as usize * height as usize];
    counts
        .par_chunks_mut((BAND_ROWS * width) as usize)
        .zip(bins.par_iter())
        .enumerate()
        .for_each(|(band, (rows, bin))| {
            let top = band as u32 * BAND_ROWS;
            scan_band(
                &triangles,
                bin,
                width,
                top,
                rows.len() as u32 / width,
                |index, _, _, _| rows[index] += 1,
            );
        });
    counts
}

/// Vertex stage and triangle setup for every triangle of the world, in object then triangle order.
fn setup(world: &World, view: &View) -> Vec<ScreenTriangle> {
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
            let clip = &clip[*object];
            let mut out = Vec::with_capacity(range.len());
            for t in range.clone() {
                let [a, b, c] = mesh.triangles[t];
                let v = [clip[a as usize], clip[b as usize], clip[c as usize]];
                setup_triangle(view, v, *object as u32, t as u32, &mut out);
            }
            out
        })
        .collect();
    chunks.concat()
}

/// Clips one triangle and pushes the screen triangles it yields (0, 1 or a fan of several).
fn setup_triangle(
    view: &View,
    v: [Vec3; 3],
    object: u32,
    triangle: u32,
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
        emit(view, corners, object, triangle, out);
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
            let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
            let (da, db) = (plane(a.pos), plane(b.pos));
            if da >= 0.0 {
                next.push(a);
            }
            if (da >= 0.0) != (db >= 0.0) {
                next.push(a.lerp(b, da / (da - db)));
            }
        }
        poly = next;
        if poly.len() < 3 {
            return;
        }
    }
    for i in 1..poly.len() - 1 {
        emit(view, [poly[0], poly[i], poly[i + 1]], object, triangle, out);
    }
}

/// Projects, snaps and orients a clipped triangle; drops it when it covers no pixel centre's box.
fn emit(
    view: &View,
    v: [ClipVertex; 3],
    object: u32,
    triangle: u32,
    out: &mut Vec<ScreenTriangle>,
) {
    let mut x = [0i32; 3];
    let mut y = [0i32; 3];
    let mut inv_w = [0f32; 3];
    let mut bary_w = [Vec2::ZERO; 3];
    for k in 0..3 {
        let p = view.clip_to_pixel(v[k].pos);
        x[k] = (p.x * SUBPIXEL).round() as i32;
        y[k] = (p.y * SUBPIXEL).round() as i32;
        inv_w[k] = 1.0 / v[k].pos.z;
        bary_w[k] = v[k].bary * inv_w[k];
    }
    let area = edge(x[0], y[0], x[1], y[1], x[2], y[2]);
    if area == 0 {
        return;
    }
    if area < 0 {
        x.swap(1, 2);
        y.swap(1, 2);
        inv_w.swap(1, 2);
        bary_w.swap(1, 2);
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
    out.push(ScreenTriangle {
        x,
        y,
        inv_w,
        bary_w,
        inv_area: 1.0 / area.abs() as f32,
        object,
        triangle,
        min_x,
        max_x,
        min_y,
        max_y,
    });
}

/// Twice the signed area of (a, b, p): positive when p is on the interior side of a→b.
#[inline]
fn edge(ax: i32, ay: i32, bx: i32, by: i32, px: i32, py: i32) -> i64 {
    (bx - ax) as i64 * (py - ay) as i64 - (by - ay) as i64 * (px - ax) as i64
}

/// Triangle indices per band of [`BAND_ROWS`] rows, in triangle order.
fn bin(triangles: &[ScreenTriangle], height: u32) -> Vec<Vec<u32>> {
    let bands = height.div_ceil(BAND_ROWS) as usize;
    let mut bins = vec![Vec::new(); bands];
    for (i, t) in triangles.iter().enumerate() {
        for band in (t.min_y as u32 / BAND_ROWS)..=(t.max_y as u32 / BAND_ROWS) {
            bins[band as usize].push(i as u32);
        }
    }
    bins
}

/// Scan-converts the band's triangles in order, calling `fragment(index in band, triangle
/// number, triangle, λ)`
/// for every covered pixel centre; λ are the screen-space barycentric weights of the vertices.
#[inline]
fn scan_band(
    triangles: &[ScreenTriangle],
    bin: &[u32],
    width: u32,
    top: u32,
    rows: u32,
    mut fragment: impl FnMut(usize, u32, &ScreenTriangle, [f32; 3]),
) {
    let bottom = (top + rows) as i32 - 1;
    let half = 1 << (SUBPIXEL_BITS - 1);
    for &i in bin {
        let t = &triangles[i as usize];
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
        let mut bias = [0i64; 3];
        for k in 0..3 {
            let (a, b) = ((k + 1) % 3, (k + 2) % 3);
            let (dx, dy) = (t.x[b] - t.x[a], t.y[b] - t.y[a]);
            // Top-left rule: a centre exactly on an edge belongs to the triangle only when the
            // edge is a top edge (horizontal, interior below) or a left edge (interior to the
            // right). Other edges get a bias of −1 so that "on the edge" tests as outside.
            let top_left = (dy == 0 && dx > 0) || dy < 0;
            bias[k] = if top_left { 0 } else { -1 };
            row_start[k] = edge(t.x[a], t.y[a], t.x[b], t.y[b], px, py) + bias[k];
            step_x[k] = -(dy as i64) << SUBPIXEL_BITS;
            step_y[k] = (dx as i64) << SUBPIXEL_BITS;
        }
        let inv_area = t.inv_area;
        let columns = (t.max_x - t.min_x) as i64;
        for y in y0..=y1 {
            // The covered span of this row, solved from the three edge functions (each is
            // linear in x), so the loop below visits covered pixel centres only.
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
            let row = (y as u32 - top) as usize * width as usize + t.min_x as usize;
            let mut e = [0i64; 3];
            for k in 0..3 {
                e[k] = row_start[k] + lo * step_x[k] - bias[k];
            }
            for n in lo..=hi {
                debug_assert!(
                    e.iter().zip(bias).all(|(&e, b)| e + b >= 0),
                    "span solved wrongly"
                );
                let lambda = [
                    e[0] as f32 * inv_area,
                    e[1] as f32 * inv_area,
                    e[2] as f32 * inv_area,
                ];
                fragment(row + n as usize, i, t, lambda);
                e[0] += step_x[0];
                e[1] += step_x[1];
                e[2] += step_x[2];
            }
            for k in 0..3 {
                row_start[k] += step_y[k];
            }
        }
    }
}
