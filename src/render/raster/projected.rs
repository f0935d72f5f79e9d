//! The vertex stage: every mesh vertex projected once per frame, eight at a time, to what
//! triangle setup needs of it: its snapped pixel position, its depth w, and which planes of the
//! view volume and of the guard band it lies outside.
//!
//! Each lane computes exactly what [`View::to_clip`], [`View::clip_to_pixel`] and the snapping
//! compute for one vertex, in the same order, so a triangle set up from projected vertices gets
//! the same bits as one set up from its clip-space corners.

use glam::Vec3;
use rayon::prelude::*;
use wide::{CmpGe, CmpGt, CmpLe, CmpLt, i32x4, i32x8};

use super::snap::{GUARD, SUBPIXEL};
use crate::render::camera::{NEAR, View};
use crate::render::simd::{F32x8, V3, WIDTH};

/// Outside the near plane (w < [`NEAR`]).
pub const BEHIND: u32 = 1;
/// Outside the view volume's four side planes: x > w, x < −w, y > w, y < −w.
pub const PAST_RIGHT: u32 = 1 << 1;
pub const PAST_LEFT: u32 = 1 << 2;
pub const PAST_TOP: u32 = 1 << 3;
pub const PAST_BOTTOM: u32 = 1 << 4;
/// The planes a triangle is trivially rejected by when all three vertices lie outside one.
pub const OUTSIDE: u32 = BEHIND | PAST_RIGHT | PAST_LEFT | PAST_TOP | PAST_BOTTOM;
/// Not strictly inside the near plane and the guard band (|x|, |y| ≤ GUARD·w): a triangle with
/// such a vertex is clipped, and the vertex's snapped position is not used.
pub const NEEDS_CLIP: u32 = 1 << 5;

/// One vertex after the vertex stage.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ProjectedVertex {
    /// Pixel coordinates in 1/256 pixel, rounded to nearest (halves away from zero). Only
    /// meaningful without [`NEEDS_CLIP`].
    pub x: i32,
    pub y: i32,
    /// Outcode bits: [`BEHIND`] … [`NEEDS_CLIP`].
    pub code: u32,
    /// Clip-space w: the depth along the view direction, world units.
    pub w: f32,
}

/// The projected vertices of one mesh, each kept as four lanes (x, y, code and the bits of w)
/// so that setup reads all it tests of a vertex with one 16-byte load.
#[derive(Debug, Clone, Default)]
pub struct ProjectedVertices {
    vertices: Vec<i32x4>,
}

impl ProjectedVertices {
    /// Vertex `i`.
    #[inline(always)]
    pub fn get(&self, i: usize) -> ProjectedVertex {
        let [x, y, code, w] = self.vertices[i].to_array();
        ProjectedVertex {
            x,
            y,
            code: code as u32,
            w: f32::from_bits(w as u32),
        }
    }

    /// Vertex `i` in four lanes: x, y, code and the bits of w.
    #[inline(always)]
    pub fn lanes(&self, i: usize) -> i32x4 {
        self.vertices[i]
    }

    /// Hints that vertex `i` is read soon (see [`prefetch`](crate::render::prefetch)).
    #[inline(always)]
    pub fn prefetch(&self, i: usize) {
        crate::render::prefetch::ahead_in(&self.vertices, i);
    }

    /// Makes room for `len` vertices; the values are overwritten by [`project`]. New room is
    /// filled on all threads: a world's first frame faults its pages in, 80 MB for a scan of
    /// 5M vertices, which one thread took tens of milliseconds to do.
    pub fn resize(&mut self, len: usize) {
        let more = len.saturating_sub(self.vertices.len());
        self.vertices.truncate(len);
        if more > 0 {
            self.vertices
                .par_extend(rayon::iter::repeat_n(i32x4::default(), more));
        }
    }

    /// The vertices as disjoint runs of `len`, each with the index of its first vertex, for
    /// projecting in parallel.
    pub fn runs_mut(&mut self, len: usize) -> impl IndexedParallelIterator<Item = Run<'_>> {
        self.vertices
            .par_chunks_mut(len)
            .enumerate()
            .map(move |(k, vertices)| Run {
                first: k * len,
                vertices,
            })
    }
}

/// A run of projected vertices to fill.
pub struct Run<'a> {
    /// Index of the run's first vertex.
    pub first: usize,
    vertices: &'a mut [i32x4],
}

impl Run<'_> {
    /// Number of vertices in the run.
    pub fn len(&self) -> usize {
        self.vertices.len()
    }
}

/// Projects `positions` (world space) through `view` into `out`, as long.
pub fn project(view: &View, positions: &[Vec3], out: Run<'_>) {
    if view.orthographic {
        project_with::<true>(view, positions, out);
    } else {
        project_with::<false>(view, positions, out);
    }
}

/// [`project`] for one projection: `ORTHOGRAPHIC` divides clip x and y by 1 rather than w, and
/// its guard band is |x|, |y| ≤ GUARD (the view volume a box rather than a pyramid).
#[inline(always)]
fn project_with<const ORTHOGRAPHIC: bool>(view: &View, positions: &[Vec3], out: Run<'_>) {
    debug_assert_eq!(positions.len(), out.vertices.len());
    let eye = V3::splat(view.eye);
    let (right, up, forward) = (
        V3::splat(view.right),
        V3::splat(view.up),
        V3::splat(view.forward),
    );
    let scale_x = F32x8::splat(view.half_height * view.aspect);
    let scale_y = F32x8::splat(view.half_height);
    let (one, half) = (F32x8::splat(1.0), F32x8::splat(0.5));
    let width = F32x8::splat(view.width as f32);
    let height = F32x8::splat(view.image_height as f32);
    let row_offset = F32x8::splat(view.row_offset as f32);
    let (near, guard, subpixel) = (
        F32x8::splat(NEAR),
        F32x8::splat(GUARD),
        F32x8::splat(SUBPIXEL),
    );
    for (k, chunk) in positions.chunks(WIDTH).enumerate() {
        // View::to_clip.
        let d = gather(chunk) - eye;
        let cx = d.dot(right) / scale_x;
        let cy = d.dot(up) / scale_y;
        let w = d.dot(forward);
        // View::clip_to_pixel, then snapping.
        let divisor = if ORTHOGRAPHIC { one } else { w };
        let inv_w = one / divisor;
        let px = (cx * inv_w + one) * half * width;
        let py = (one - cy * inv_w) * half * height - row_offset;
        let (x, y) = (round(px * subpixel), round(py * subpixel));
        let bit =
            |mask: F32x8, bit: u32| bytemuck::cast::<_, i32x8>(mask) & i32x8::splat(bit as i32);
        let inside =
            w.cmp_ge(near) & cx.abs().cmp_le(guard * divisor) & cy.abs().cmp_le(guard * divisor);
        let code = bit(w.cmp_lt(near), BEHIND)
            | bit(cx.cmp_gt(divisor), PAST_RIGHT)
            | bit(cx.cmp_lt(-divisor), PAST_LEFT)
            | bit(cy.cmp_gt(divisor), PAST_TOP)
            | bit(cy.cmp_lt(-divisor), PAST_BOTTOM)
            | (!bytemuck::cast::<_, i32x8>(inside) & i32x8::splat(NEEDS_CLIP as i32));
        // Lanes of x, y, code and w turned into one (x, y, code, w) vector per vertex.
        let halves = |v: i32x8| bytemuck::cast::<i32x8, [i32x4; 2]>(v);
        let (x, y, code, w) = (
            halves(x),
            halves(y),
            halves(code),
            halves(bytemuck::cast::<F32x8, i32x8>(w)),
        );
        let packed: [i32x4; WIDTH] = bytemuck::cast([
            i32x4::transpose([x[0], y[0], code[0], w[0]]),
            i32x4::transpose([x[1], y[1], code[1], w[1]]),
        ]);
        let out = &mut out.vertices[k * WIDTH..k * WIDTH + chunk.len()];
        match <&mut [i32x4; WIDTH]>::try_from(&mut *out) {
            Ok(all) => *all = packed,
            Err(_) => out.copy_from_slice(&packed[..out.len()]),
        }
    }
}

/// Up to eight vectors in lanes; lanes past the last repeat it.
#[inline(always)]
fn gather(vectors: &[Vec3]) -> V3<F32x8> {
    let Ok(eight) = <&[Vec3; WIDTH]>::try_from(vectors) else {
        return V3::gather(vectors);
    };
    // A fixed-size array: the loads are plain moves, with no index arithmetic.
    let lane = |c: fn(&Vec3) -> f32| F32x8::from(eight.map(|v| c(&v)));
    V3::new(lane(|v| v.x), lane(|v| v.y), lane(|v| v.z))
}

/// [`super::snap::round`] lane by lane, for |v| < 2^31 (other lanes give unspecified values).
#[inline(always)]
fn round(v: F32x8) -> i32x8 {
    let whole = v.trunc_int();
    // The fractional part of a float is exact.
    let fraction = v - whole.round_float();
    let up: i32x8 = bytemuck::cast(fraction.cmp_ge(F32x8::splat(0.5)));
    let down: i32x8 = bytemuck::cast(fraction.cmp_le(F32x8::splat(-0.5)));
    // A true mask is −1.
    whole - up + down
}

#[cfg(test)]
mod tests {
    use glam::Vec3;
    use rayon::prelude::*;

    use super::{NEEDS_CLIP, ProjectedVertices, project};
    use crate::render::camera::View;
    use crate::render::raster::snap::{SUBPIXEL, round};
    use crate::scene::Camera;

    #[test]
    fn lanes_project_as_the_scalar_view_does() {
        let camera = Camera {
            position: Vec3::new(0.3, 0.4, 3.0),
            target: Vec3::ZERO,
            up: Vec3::Y,
            fov: 50.0,
            ..Camera::default()
        };
        let view = View::new(&camera, 161, 97).rows(13, 40);
        let positions: Vec<Vec3> = (0..1000)
            .map(|k| {
                let t = k as f32 * 0.37;
                Vec3::new(t.sin() * 2.5, (t * 1.3).cos() * 2.0, (t * 0.7).sin() * 3.5)
            })
            .collect();
        let mut projected = ProjectedVertices::default();
        projected.resize(positions.len());
        let run = projected
            .runs_mut(positions.len())
            .collect::<Vec<_>>()
            .pop()
            .expect("one run");
        project(&view, &positions, run);
        let mut inside = 0;
        for (i, p) in positions.iter().enumerate() {
            let v = projected.get(i);
            let clip = view.to_clip(*p);
            assert_eq!(v.w.to_bits(), clip.z.to_bits());
            if v.code & NEEDS_CLIP == 0 {
                inside += 1;
                let pixel = view.clip_to_pixel(clip);
                assert_eq!(
                    (v.x, v.y),
                    (round(pixel.x * SUBPIXEL), round(pixel.y * SUBPIXEL))
                );
            }
        }
        assert!(
            inside > 500,
            "most points are inside the guard band ({inside})"
        );
        assert!(inside < 1000, "some points are clipped");
    }
}
