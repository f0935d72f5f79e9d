//! Triangle setup: from projected vertices to screen triangles ready for scan conversion.
//!
//! Setup runs in two steps so that shading work goes only to triangles that can show. The first,
//! [`setup_triangle`], needs positions alone: it rejects triangles outside the view or covering
//! no pixel centre (at the editor's preview size, most triangles of a real mesh), clips the rest
//! against the near plane and the guard band, snaps and orients them, and sets up the plane of
//! 1/w. The second, [`Corners::planes`], sets up the planes of the varying once its vertex
//! values are known, and only for triangles that won a pixel in the depth test: a Gouraud shader
//! lights only the vertices of triangles that show.

use glam::{DVec3, Vec2, Vec3, Vec4};

use wide::{CmpEq, CmpGt, CmpLt, f32x4, i32x4};

use super::projected::{NEEDS_CLIP, OUTSIDE, ProjectedVertices};
use super::snap::{GUARD, HALF, SUBPIXEL, SUBPIXEL_BITS, edge, first_centre, last_centre, round};
use crate::render::camera::{NEAR, View};
use crate::render::simd::WIDTH;

/// A triangle ready for scan conversion: snapped, counter-clockwise in fixed point, with the
/// screen-space plane of its 1/w, which the depth test needs. The planes of its varying are set
/// up only if it is seen ([`Corners::planes`]).
///
/// 1/w is affine in screen space: a plane `at_ref + per_x·(x − ref_x) + per_y·(y − ref_y)` over
/// pixel centres. The reference is the pixel holding vertex 0, so strips of an image evaluate
/// the plane exactly as the whole image does.
#[derive(Debug, Clone, Copy, Default)]
pub struct ScreenTriangle {
    /// Vertex pixel coordinates in 1/256 pixel.
    pub x: [i32; 3],
    pub y: [i32; 3],
    /// Inclusive pixel bounds, inside the image.
    pub min_x: i32,
    pub max_x: i32,
    pub min_y: i32,
    pub max_y: i32,
    /// The reference pixel.
    pub ref_x: i32,
    pub ref_y: i32,
    /// 1/w at the reference pixel's centre, and its change per pixel right and down.
    pub inv_w: DepthPlane,
    pub object: u32,
    /// The mesh triangle it came from, an index into its object's triangles.
    pub triangle: u32,
    /// Where the triangle's [`Corners`] are: the setup task that made it, and its place there.
    pub chunk: u32,
    pub slot: u32,
}

/// The plane of 1/w over pixel centres: its value at the reference pixel and its steps.
#[derive(Debug, Clone, Copy, Default)]
pub struct DepthPlane {
    pub at_ref: f32,
    pub per_x: f32,
    pub per_y: f32,
}

/// The planes of a seen triangle's interpolants: `K` varyings (3-vectors) times 1/w, and 1/w,
/// each `at_ref + per_x·(x − ref_x) + per_y·(y − ref_y)` over pixel centres. Varying k's plane
/// is the first three lanes of entry k; dividing them by 1/w gives the perspective-correct
/// varying. The fourth lane of entry 0 is the triangle's [`DepthPlane`], bit for bit; that of
/// the other entries is unused (zero). One varying (a normal, or a lit colour) is the layout
/// and arithmetic the Z-buffer had before it took more.
#[derive(Debug, Clone, Copy)]
pub struct Planes<const K: usize = 1> {
    pub at_ref: [Vec4; K],
    pub per_x: [Vec4; K],
    pub per_y: [Vec4; K],
    /// The triangle's reference pixel and object.
    pub ref_x: i32,
    pub ref_y: i32,
    pub object: u32,
}

impl<const K: usize> Default for Planes<K> {
    fn default() -> Self {
        Planes {
            at_ref: [Vec4::ZERO; K],
            per_x: [Vec4::ZERO; K],
            per_y: [Vec4::ZERO; K],
            ref_x: 0,
            ref_y: 0,
            object: 0,
        }
    }
}

/// Where a screen triangle's vertices lie on the mesh triangle it came from: what setting up
/// the planes of its varying needs beside the screen triangle itself. Kept small (36 bytes):
/// every triangle that covers a pixel centre gets one, at 1920×1080 most of a mesh's, and only
/// the seen ones are read again.
#[derive(Debug, Clone, Copy)]
pub struct Corners {
    /// Clip-space w at each screen vertex, in the screen triangle's vertex order.
    pub w: [f32; 3],
    /// Barycentrics of each screen vertex on the mesh triangle (weights of its vertices 1
    /// and 2): a clipped vertex lies between the triangle's own.
    pub bary: [Vec2; 3],
}

/// A clip-space vertex during clipping: position (x, y, w) and barycentrics on the original
/// triangle.
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

/// Barycentrics of a triangle's own three vertices.
const OWN_BARY: [Vec2; 3] = [Vec2::ZERO, Vec2::X, Vec2::Y];

/// Sets up mesh triangle `triangle` of `object`, whose vertices are `indices` into the object's
/// `projected` vertices (and world `positions`, for clipping): pushes the screen triangles it
/// yields (0, 1 or a fan of several) with their [`Corners`].
///
/// Always inlined into the AVX2 setup pass, as [`may_cover`] is: left to the compiler, a change
/// elsewhere (the Z-buffer's K varyings) made both calls of their own, compiled without AVX2.
/// Bunny, Phong, 1920×1080, one thread, callgrind: `setup_triangle` alone was 4% of the run;
/// with both inlined a frame took 195.9 M instructions, against 197.0 M with `may_cover` left
/// out of line (and 193.8 M before the K varyings).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub fn setup_triangle(
    view: &View,
    projected: &ProjectedVertices,
    positions: &[Vec3],
    indices: [u32; 3],
    object: u32,
    triangle: u32,
    out: &mut Vec<ScreenTriangle>,
    corners: &mut Vec<Corners>,
) {
    let [a, b, c] = indices.map(|i| projected.get(i as usize));
    // Trivial reject: all three vertices outside one plane of the view volume.
    if a.code & b.code & c.code & OUTSIDE != 0 {
        return;
    }
    if (a.code | b.code | c.code) & NEEDS_CLIP == 0 {
        emit(
            view,
            [a.x, b.x, c.x],
            [a.y, b.y, c.y],
            [a.w, b.w, c.w],
            OWN_BARY,
            object,
            triangle,
            out,
            corners,
        );
        return;
    }
    let v = indices.map(|i| view.to_clip(positions[i as usize]));
    let corner = |k: usize| ClipVertex {
        pos: v[k],
        bary: OWN_BARY[k],
    };
    // Sutherland–Hodgman in homogeneous space: near plane, then the guard band (in an
    // orthographic view the band's planes do not widen with depth).
    let planes: [fn(Vec3) -> f32; 5] = if view.orthographic {
        [
            |p| p.z - NEAR,
            |p| GUARD - p.x,
            |p| GUARD + p.x,
            |p| GUARD - p.y,
            |p| GUARD + p.y,
        ]
    } else {
        [
            |p| p.z - NEAR,
            |p| GUARD * p.z - p.x,
            |p| GUARD * p.z + p.x,
            |p| GUARD * p.z - p.y,
            |p| GUARD * p.z + p.y,
        ]
    };
    let mut poly: Vec<ClipVertex> = vec![corner(0), corner(1), corner(2)];
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
        let fan = [poly[0], poly[i], poly[i + 1]];
        let snapped = fan.map(|v| {
            let p = view.clip_to_pixel(v.pos);
            (round(p.x * SUBPIXEL), round(p.y * SUBPIXEL))
        });
        emit(
            view,
            snapped.map(|s| s.0),
            snapped.map(|s| s.1),
            fan.map(|v| v.pos.z),
            fan.map(|v| v.bary),
            object,
            triangle,
            out,
            corners,
        );
    }
}

/// Which of up to eight `triangles` (vertex indices into `projected`) may cover a pixel centre
/// of `view`, as bits (lane k is bit k): the cheap tests of [`setup_triangle`] in lanes, so
/// that the common case at small sizes, a triangle between pixel centres, costs no branch of
/// its own. A triangle outside one plane of the view volume, or within the guard band but
/// with no pixel centre inside its bounding box, is dropped; the rest are set up one by one.
/// Always inlined, as [`setup_triangle`] is (see there why), into the AVX2 setup pass.
#[inline(always)]
pub fn may_cover(view: &View, projected: &ProjectedVertices, triangles: &[[u32; 3]]) -> u32 {
    debug_assert!((1..=WIDTH).contains(&triangles.len()));
    let image = ImageBounds::of(view);
    // Four lanes at a time: the values of the tests then nearly fit the sixteen SSE registers,
    // where eight lanes spilled many (callgrind, bunny at 160×96: about 970 instructions per
    // eight triangles with eight lanes, 800 with four).
    let mut keep = 0;
    for (quarter, four) in triangles.chunks(4).enumerate() {
        keep |= may_cover_four(&image, projected, four) << (4 * quarter);
    }
    keep
}

/// The last pixel column and row of an image, in lanes.
struct ImageBounds {
    last_x: i32x4,
    last_y: i32x4,
}

impl ImageBounds {
    fn of(view: &View) -> ImageBounds {
        ImageBounds {
            last_x: i32x4::splat(view.width as i32 - 1),
            last_y: i32x4::splat(view.height as i32 - 1),
        }
    }
}

/// [`may_cover`] for up to four triangles, as bits.
#[inline(always)]
fn may_cover_four(
    image: &ImageBounds,
    projected: &ProjectedVertices,
    triangles: &[[u32; 3]],
) -> u32 {
    let last = triangles.len() - 1;
    // Each corner's four vertices, turned from (x, y, code, w) per vertex into lanes of x, of
    // y and of codes; lanes past the last triangle repeat it.
    let corner = |k: usize| {
        let v = std::array::from_fn(|lane| projected.lanes(triangles[lane.min(last)][k] as usize));
        let [x, y, code, _] = i32x4::transpose(v);
        (x, y, code)
    };
    let (x0, y0, c0) = corner(0);
    let (x1, y1, c1) = corner(1);
    let (x2, y2, c2) = corner(2);
    let zero = i32x4::splat(0);
    let not_outside = (c0 & c1 & c2 & i32x4::splat(OUTSIDE as i32)).cmp_eq(zero);
    let clipped = !((c0 | c1 | c2) & i32x4::splat(NEEDS_CLIP as i32)).cmp_eq(zero);
    let (lo_x, hi_x) = (x0.min(x1).min(x2), x0.max(x1).max(x2));
    let (lo_y, hi_y) = (y0.min(y1).min(y2), y0.max(y1).max(y2));
    // first_centre and last_centre: floor division by 256 is an arithmetic shift.
    let first = |lo: i32x4| (lo + i32x4::splat((1 << SUBPIXEL_BITS) - 1 - HALF)) >> SUBPIXEL_BITS;
    let last_c = |hi: i32x4| (hi - i32x4::splat(HALF)) >> SUBPIXEL_BITS;
    let min_x = first(lo_x).max(zero);
    let max_x = last_c(hi_x).min(image.last_x);
    let min_y = first(lo_y).max(zero);
    let max_y = last_c(hi_y).min(image.last_y);
    let empty = min_x.cmp_gt(max_x) | min_y.cmp_gt(max_y);
    // A small triangle whose box holds at most 2×2 centres has them tested exactly, as scan
    // conversion would: one that covers none of them draws nothing.
    let exact = i32x4::splat(EXACT_IN_F32_EXTENT);
    let small = (hi_x - lo_x).cmp_lt(exact) & (hi_y - lo_y).cmp_lt(exact);
    let two = i32x4::splat(2);
    let (columns, rows) = (max_x - min_x, max_y - min_y);
    let tested = small & columns.cmp_lt(two) & rows.cmp_lt(two) & !clipped & !empty;
    let covering = if tested.any() {
        covers_a_centre([x0, x1, x2], [y0, y1, y2], min_x, min_y, columns, rows)
    } else {
        zero
    };
    let keep = not_outside & (clipped | !empty) & (!tested | covering);
    (keep.move_mask() as u32) & ((1 << triangles.len()) - 1)
}

/// Vertex extents (fixed point, 8 pixels) below which [`covers_a_centre`] is exact in `f32`:
/// differences of coordinates are below 2^11, so products below 2^22 and every edge function
/// value below 2^24 are integers that `f32` holds exactly.
const EXACT_IN_F32_EXTENT: i32 = 1 << 11;

/// Which of four triangles (fixed-point vertices `x`, `y`, either orientation, each smaller
/// than [`EXACT_IN_F32_EXTENT`]) cover a pixel centre among columns `min_x..=min_x + columns`
/// and rows `min_y..=min_y + rows` (`columns`, `rows` 0 or 1), by the edge functions and
/// top-left rule that scan conversion uses once the triangle is turned counter-clockwise. A
/// triangle of no area covers nothing (setup drops it). Lanes of larger triangles give
/// unspecified results.
#[inline(always)]
fn covers_a_centre(
    x: [i32x4; 3],
    y: [i32x4; 3],
    min_x: i32x4,
    min_y: i32x4,
    columns: i32x4,
    rows: i32x4,
) -> i32x4 {
    let zero = f32x4::splat(0.0);
    let exact = |v: i32x4| v.round_float();
    // Coordinates relative to vertex 0, and the first centre's.
    let (x1, y1) = (exact(x[1] - x[0]), exact(y[1] - y[0]));
    let (x2, y2) = (exact(x[2] - x[0]), exact(y[2] - y[0]));
    let cx = exact((min_x << SUBPIXEL_BITS) + i32x4::splat(HALF) - x[0]);
    let cy = exact((min_y << SUBPIXEL_BITS) + i32x4::splat(HALF) - y[0]);
    let area = x1 * y2 - y1 * x2;
    // Clockwise triangles are turned: each edge reversed, its function negated.
    let sign = area
        .cmp_lt(zero)
        .blend(f32x4::splat(-1.0), f32x4::splat(1.0));
    let vx = [zero, x1, x2];
    let vy = [zero, y1, y2];
    let step = f32x4::splat(SUBPIXEL);
    let mut at = [f32x4::splat(f32::from_bits(u32::MAX)); 4];
    for k in 0..3 {
        let (a, b) = ((k + 1) % 3, (k + 2) % 3);
        let (dx, dy) = ((vx[b] - vx[a]) * sign, (vy[b] - vy[a]) * sign);
        let top_left = (dy.cmp_eq(zero) & dx.cmp_gt(zero)) | dy.cmp_lt(zero);
        // A centre is inside the edge where e ≥ 0 on a top or left edge, e > 0 on the others;
        // e is an integer, so that is e + 1/2 > 0 or e > 0.
        let e = dx * (cy - vy[a]) - dy * (cx - vx[a]) + (top_left & f32x4::splat(0.5));
        let (right, below) = (dy * step, dx * step);
        at[0] &= e.cmp_gt(zero);
        at[1] &= (e - right).cmp_gt(zero);
        at[2] &= (e + below).cmp_gt(zero);
        at[3] &= (e - right + below).cmp_gt(zero);
    }
    let mask = |m: f32x4| bytemuck::cast::<_, i32x4>(m);
    let izero = i32x4::splat(0);
    let (has_right, has_below) = (columns.cmp_gt(izero), rows.cmp_gt(izero));
    let covered = mask(at[0])
        | (mask(at[1]) & has_right)
        | (mask(at[2]) & has_below)
        | (mask(at[3]) & has_right & has_below);
    covered & !mask(area.cmp_eq(zero))
}

/// Orients a snapped triangle (fixed-point `x`, `y`, clip w, barycentrics on its mesh
/// triangle) and sets up its plane of 1/w; drops it when it covers no pixel centre's box or
/// has no area.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn emit(
    view: &View,
    mut x: [i32; 3],
    mut y: [i32; 3],
    mut w: [f32; 3],
    mut bary: [Vec2; 3],
    object: u32,
    triangle: u32,
    out: &mut Vec<ScreenTriangle>,
    corners: &mut Vec<Corners>,
) {
    let min_x = first_centre(x[0].min(x[1]).min(x[2])).max(0);
    let max_x = last_centre(x[0].max(x[1]).max(x[2])).min(view.width as i32 - 1);
    let min_y = first_centre(y[0].min(y[1]).min(y[2])).max(0);
    let max_y = last_centre(y[0].max(y[1]).max(y[2])).min(view.height as i32 - 1);
    if min_x > max_x || min_y > max_y {
        return;
    }
    let area = edge(x[0], y[0], x[1], y[1], x[2], y[2]);
    if area == 0 {
        return;
    }
    if area < 0 {
        x.swap(1, 2);
        y.swap(1, 2);
        w.swap(1, 2);
        bary.swap(1, 2);
    }
    let (ref_x, ref_y) = (x[0] >> SUBPIXEL_BITS, y[0] >> SUBPIXEL_BITS);
    let weights = Weights::new(x, y, ref_x, ref_y, area);
    let (at, per_x, per_y) = weights.plane(depth_key(view.orthographic, w));
    out.push(ScreenTriangle {
        x,
        y,
        min_x,
        max_x,
        min_y,
        max_y,
        ref_x,
        ref_y,
        inv_w: DepthPlane {
            at_ref: at as f32,
            per_x: per_x as f32,
            per_y: per_y as f32,
        },
        object,
        triangle,
        chunk: 0,
        slot: corners.len() as u32,
    });
    corners.push(Corners { w, bary });
}

/// 1/w at each vertex, in `f64`.
#[inline(always)]
fn inverse(w: [f32; 3]) -> [f64; 3] {
    w.map(|w| 1.0 / w as f64)
}

/// What the depth test compares at each vertex of depth `w`, larger nearer, affine in screen
/// space: 1/w in perspective (positive), −w in an orthographic view (negative, since w ≥
/// [`NEAR`]; the Z-buffer starts at −∞ there, and fragments tell the two apart by the sign).
#[inline(always)]
fn depth_key(orthographic: bool, w: [f32; 3]) -> [f64; 3] {
    if orthographic {
        w.map(|w| -(w as f64))
    } else {
        inverse(w)
    }
}

/// What each vertex's varying is scaled by before it is interpolated: 1/w in perspective
/// (interpolated, then divided by the interpolated 1/w: perspective-correct), 1 in an
/// orthographic view (affine in screen space as it is).
#[inline(always)]
fn varying_scale(orthographic: bool, w: [f32; 3]) -> [f64; 3] {
    if orthographic { [1.0; 3] } else { inverse(w) }
}

/// Each barycentric weight λk = (edge function opposite vertex k) / area is affine in the pixel
/// centre: its value at the reference pixel's centre, and its steps per pixel right and down.
#[derive(Debug, Clone, Copy)]
struct Weights {
    at: [f64; 3],
    step_x: [f64; 3],
    step_y: [f64; 3],
}

impl Weights {
    /// The weights of the counter-clockwise triangle (`x`, `y`) of twice-signed `area` (either
    /// orientation's), at reference pixel (`ref_x`, `ref_y`).
    #[inline(always)]
    fn new(x: [i32; 3], y: [i32; 3], ref_x: i32, ref_y: i32, area: i64) -> Weights {
        let (ref_px, ref_py) = (
            (ref_x << SUBPIXEL_BITS) + HALF,
            (ref_y << SUBPIXEL_BITS) + HALF,
        );
        let inv_area = 1.0 / area.abs() as f64;
        let mut weights = Weights {
            at: [0.0; 3],
            step_x: [0.0; 3],
            step_y: [0.0; 3],
        };
        for k in 0..3 {
            let (i, j) = ((k + 1) % 3, (k + 2) % 3);
            weights.at[k] = edge(x[i], y[i], x[j], y[j], ref_px, ref_py) as f64 * inv_area;
            weights.step_x[k] = -((y[j] - y[i]) as f64) * SUBPIXEL as f64 * inv_area;
            weights.step_y[k] = (x[j] - x[i]) as f64 * SUBPIXEL as f64 * inv_area;
        }
        weights
    }

    /// The plane Σ values[k]·λk: its value at the reference and steps right and down, summed
    /// in vertex order.
    #[inline(always)]
    fn plane(&self, values: [f64; 3]) -> (f64, f64, f64) {
        let (mut at, mut per_x, mut per_y) = (0.0, 0.0, 0.0);
        for (k, value) in values.into_iter().enumerate() {
            at += value * self.at[k];
            per_x += value * self.step_x[k];
            per_y += value * self.step_y[k];
        }
        (at, per_x, per_y)
    }
}

impl ScreenTriangle {
    /// 1/w at the centre of pixel (x, y).
    #[inline(always)]
    pub fn inv_w_at(&self, x: i32, y: i32) -> f32 {
        let plane = &self.inv_w;
        plane.at_ref + plane.per_x * (x - self.ref_x) as f32 + plane.per_y * (y - self.ref_y) as f32
    }
}

impl<const K: usize> Planes<K> {
    /// (varying·1/w, 1/w) at the centre of pixel (x, y), per varying. Its 1/w is
    /// [`ScreenTriangle::inv_w_at`]'s, bit for bit.
    #[inline(always)]
    pub fn at(&self, x: i32, y: i32) -> [Vec4; K] {
        let (dx, dy) = ((x - self.ref_x) as f32, (y - self.ref_y) as f32);
        let mut at = self.at_ref;
        for (k, at) in at.iter_mut().enumerate() {
            *at = *at + self.per_x[k] * dx + self.per_y[k] * dy;
        }
        at
    }
}

impl Corners {
    /// The planes of screen triangle `t`'s interpolants, given each varying at its mesh
    /// triangle's three vertices, `values[k]` (`self` are `t`'s corners). The varying of a
    /// clipped vertex is interpolated from the mesh triangle's. In an `orthographic` view the
    /// varying is affine in screen space and is interpolated unscaled.
    #[inline(always)]
    pub fn planes<const K: usize>(
        &self,
        t: &ScreenTriangle,
        values: [[Vec3; 3]; K],
        orthographic: bool,
    ) -> Planes<K> {
        // The weights the plane of 1/w was set up with, worked out again from the same
        // integers: the same bits, and cheaper than keeping them for every triangle.
        let area = edge(t.x[0], t.y[0], t.x[1], t.y[1], t.x[2], t.y[2]);
        let weights = Weights::new(t.x, t.y, t.ref_x, t.ref_y, area);
        let inv_w = varying_scale(orthographic, self.w);
        let mut planes = Planes {
            ref_x: t.ref_x,
            ref_y: t.ref_y,
            object: t.object,
            ..Planes::default()
        };
        for (k, values) in values.into_iter().enumerate() {
            let [a0, a1, a2] = values.map(|a| a.as_dvec3());
            let scaled: [DVec3; 3] = std::array::from_fn(|k| {
                let b = self.bary[k].as_dvec2();
                let varying = a0 + (a1 - a0) * b.x + (a2 - a0) * b.y;
                varying * inv_w[k]
            });
            for c in 0..3 {
                let (at, step_x, step_y) = weights.plane(scaled.map(|v| v[c]));
                planes.at_ref[k][c] = at as f32;
                planes.per_x[k][c] = step_x as f32;
                planes.per_y[k][c] = step_y as f32;
            }
        }
        let depth = &t.inv_w;
        (planes.at_ref[0].w, planes.per_x[0].w, planes.per_y[0].w) =
            (depth.at_ref, depth.per_x, depth.per_y);
        planes
    }
}
