//! Alpha cut-outs (glTF `alphaMode: MASK`) in the Z-buffer's depth pass: a pixel centre where a
//! masked triangle's alpha is below its cutoff is no surface, so it writes no depth and the
//! surface behind shows. The point tested is where the pixel's primary ray meets the triangle's
//! plane, with the barycentrics, distance and level of detail the ray tracer's hit there has,
//! so the two algorithms cut the same texels.
//!
//! Worlds without a masked object never build a [`CutTest`]: their depth pass is unchanged.

use super::screen_triangle::ScreenTriangle;
use super::spans::solved_spans;
use crate::render::camera::View;
use crate::render::texturing::ObjectTextures;
use crate::world::World;

/// What the depth pass needs to cut masked triangles out.
pub struct CutTest<'a> {
    textures: ObjectTextures<'a>,
    world: &'a World,
    view: &'a View,
}

impl<'a> CutTest<'a> {
    /// The test for `world` seen through `view`; `None` when no object is masked.
    pub fn of(world: &'a World, view: &'a View) -> Option<CutTest<'a>> {
        let textures = ObjectTextures::new(world, view);
        textures.any_mask.then_some(CutTest {
            textures,
            world,
            view,
        })
    }

    /// Whether object `object` is cut out by alpha.
    #[inline]
    pub fn masks(&self, object: u32) -> bool {
        self.textures.is_masked(object as usize)
    }

    /// Whether the centre of pixel (`x`, `y`) of the view is cut out of screen triangle `t`.
    pub fn is_cut(&self, t: &ScreenTriangle, x: i32, y: i32) -> bool {
        let (origin, dir) = self.view.ray::<f32>(x as f32 + 0.5, y as f32 + 0.5);
        let (origin, dir) = (origin.to_vec3(), dir.to_vec3());
        let mesh = &self.world.objects[t.object as usize].mesh;
        let [a, b, c] = mesh.triangles[t.triangle as usize].map(|i| mesh.positions[i as usize]);
        // Möller–Trumbore on the triangle's plane: the pixel centre is inside (the coverage
        // test said so), so only the barycentrics and the distance are wanted.
        let (e1, e2) = (b - a, c - a);
        let p = dir.cross(e2);
        let det = e1.dot(p);
        if det == 0.0 || !det.is_finite() {
            return false;
        }
        let s = origin - a;
        let q = s.cross(e1);
        let (u, v, distance) = (s.dot(p) / det, dir.dot(q) / det, e2.dot(q) / det);
        self.textures.is_cut(
            t.object as usize,
            mesh,
            t.triangle,
            u,
            v,
            distance.max(0.0),
            dir,
        )
    }

    /// The depth test of masked triangle `t` (number `id` in its band) over rows `y0..=y1`:
    /// pixel by pixel, a centre nearer than the stored depth and not cut out stores its depth
    /// and `id`. `row_start(y)` is row `y`'s first index in `depth` and `ids`. Pixel k of a
    /// row's run has 1/w(run start) + k·(1/w per pixel), as the other depth tests compute it.
    pub fn depth_test(
        &self,
        t: &ScreenTriangle,
        (y0, y1): (i32, i32),
        row_start: impl Fn(i32) -> usize,
        depth: &mut [f32],
        ids: &mut [u32],
        id: u32,
    ) {
        solved_spans(t, y0, y1, |y, first, last| {
            let z0 = t.inv_w_at(first, y);
            let start = row_start(y) + first as usize;
            for k in 0..=(last - first) {
                let z = z0 + t.inv_w.per_x * k as f32;
                let at = start + k as usize;
                if z >= depth[at] && !self.is_cut(t, first + k, y) {
                    (depth[at], ids[at]) = (z, id);
                }
            }
        });
    }
}
