//! Fragments in lanes: up to eight covered pixels of one row with their depth, varying and
//! object. The rasterizer hands these to a Z-buffer shader, which lights or colours all eight at
//! once.
//!
//! A run of pixels drawn by one triangle becomes whole batches by stepping the triangle's planes
//! eight pixels at a time; the pixels left over (short runs, as on finely tessellated meshes) are
//! worked out eight lanes at a time too and packed run after run. Both ways compute pixel k of a
//! run the same way, as `interpolants(run start) + per_x·k`, so a pixel's value does not depend
//! on how it was batched.

use glam::{Vec3, Vec4};

use crate::render::simd::{Lanes8, V3, WIDTH};

/// Up to [`WIDTH`] covered pixels of one row, in lanes `L`, with `K` varyings. Lanes past
/// `count` repeat the last pixel.
#[derive(Clone, Copy)]
pub struct Fragments<L, const K: usize = 1> {
    /// Row within the view (0 = top).
    pub y: u32,
    /// Number of lanes that are pixels, 1..=[`WIDTH`].
    pub count: usize,
    /// Column of each lane.
    pub x: [u32; WIDTH],
    /// Object index in the world of each lane.
    pub object: [u32; WIDTH],
    /// Depth w of the surface along the view direction, world units (> 0).
    pub depth: L,
    /// The perspective-correct varyings.
    pub varying: [V3<L>; K],
}

/// (0, 1, …, 7).
#[inline(always)]
fn lane_numbers<L: Lanes8>() -> L {
    L::from_array(std::array::from_fn(|k| k as f32))
}

impl<L: Lanes8, const K: usize> Fragments<L, K> {
    /// Pixels `k .. k + WIDTH` of `run`, in row `y`.
    #[inline(always)]
    pub fn span(y: u32, run: &Run<K>, k: usize) -> Fragments<L, K> {
        let steps = L::splat(k as f32) + lane_numbers();
        // Loops rather than closures over arrays, as the one-varying code had: the arithmetic
        // stays in the caller's AVX context.
        let mut values = [[L::splat(0.0); 4]; K];
        for (v, varying) in values.iter_mut().enumerate() {
            // The fourth component is 1/w for the first varying and unused for the others.
            let components = if v == 0 { 4 } else { 3 };
            for (c, value) in varying.iter_mut().take(components).enumerate() {
                *value = L::splat(run.at_start[v][c]) + L::splat(run.per_x[v][c]) * steps;
            }
        }
        let first = (run.start + k) as u32;
        Fragments::from_interpolants(
            y,
            WIDTH,
            std::array::from_fn(|lane| first + lane as u32),
            [run.object; WIDTH],
            values,
        )
    }

    /// Divides the interpolants by 1/w (the fourth of the first varying's): the depth and
    /// perspective-correct varyings; in an orthographic view the fourth is −w and the
    /// varyings are already affine.
    #[inline(always)]
    fn from_interpolants(
        y: u32,
        count: usize,
        x: [u32; WIDTH],
        object: [u32; WIDTH],
        values: [[L; 4]; K],
    ) -> Fragments<L, K> {
        // The depth key is 1/w (> 0) in perspective, −w (< 0) in an orthographic view, whose
        // varyings were interpolated unscaled.
        let key = values[0][3];
        let zero = L::splat(0.0);
        let perspective_depth = L::splat(1.0) / key;
        let orthographic = key.lt(zero);
        let depth = L::select(orthographic, -key, perspective_depth);
        let scale = L::select(orthographic, L::splat(1.0), perspective_depth);
        let mut varying = [V3::new(zero, zero, zero); K];
        for (out, [vx, vy, vz, _]) in varying.iter_mut().zip(values) {
            *out = V3::new(vx * scale, vy * scale, vz * scale);
        }
        Fragments {
            y,
            count,
            x,
            object,
            depth,
            varying,
        }
    }

    /// The column of each lane, as an f32 (exact: columns are below 2^23).
    #[inline(always)]
    pub fn columns(&self) -> L {
        // The bits of 2^23 + x, for an integer x in [0, 2^23), are those of 2^23 plus x.
        let shifted = self.x.map(|x| x + TWO_TO_23.to_bits());
        L::from_array(bytemuck::cast(shifted)) - L::splat(TWO_TO_23)
    }

    /// Writes the colours of the lanes that are pixels into `out`, the row's pixels.
    #[inline(always)]
    pub fn write(&self, colors: V3<L>, out: &mut [Vec3]) {
        let colors = colors.to_vec3s();
        let first = self.x[0] as usize;
        if self.count == WIDTH && self.x[WIDTH - 1] as usize == first + WIDTH - 1 {
            // Eight neighbouring pixels, as inside a span: one block copy.
            out[first..first + WIDTH].copy_from_slice(&colors);
        } else {
            for (&x, color) in self.x[..self.count].iter().zip(colors) {
                out[x as usize] = color;
            }
        }
    }
}

/// A run of pixels of one row drawn by one triangle: pixel k of it (column `start + k`) has the
/// interpolants (varying·1/w, 1/w) of each of its `K` varyings `at_start + per_x·k`, however it
/// is batched.
#[derive(Debug, Clone, Copy)]
pub struct Run<const K: usize = 1> {
    /// Column of the run's first pixel.
    pub start: usize,
    /// Object index in the world of the triangle.
    pub object: u32,
    /// The interpolants at the run's first pixel.
    pub at_start: [Vec4; K],
    /// Their change per pixel.
    pub per_x: [Vec4; K],
}

/// 2^23: the f32 from which the integers are one apart.
const TWO_TO_23: f32 = 8_388_608.0;

/// Collects the short runs of one row into lanes: each run is worked out in eight lanes at once
/// and lands in the lanes after those filled so far; the pixels past the eighth lane start the
/// next batch. The lanes stay in registers, and columns and objects become integers by the
/// bits of 2^23 + x rather than by a conversion per lane. At 1920×1080 the bunny's runs are 2.6
/// pixels long on average (161,000 runs a frame), so this is per-run work. Measured against
/// lanes kept in arrays with `as` conversions (bunny, 1920×1080, 1 thread, kept renderer,
/// median of 60, alternating): Phong 13.6–13.95 → 13.1–13.7 ms (four), Gouraud 11.5–11.7 →
/// 11.2–11.4 ms (two).
///
/// Invariant: lanes from `count` on repeat the last pixel pushed (once one was pushed).
#[derive(Clone, Copy)]
pub struct Packer<L, const K: usize = 1> {
    /// Lanes that are pixels, 0..[`WIDTH`].
    count: usize,
    /// Column of each lane, an exact integer.
    x: L,
    /// Object index of each lane, an exact integer.
    object: L,
    /// Interpolants (varying·1/w, 1/w) of each lane, varying by varying, component by
    /// component (the fourth component of varyings past the first is unused: zero).
    values: [[L; 4]; K],
}

impl<L: Lanes8, const K: usize> Default for Packer<L, K> {
    fn default() -> Self {
        let zero = L::splat(0.0);
        Packer {
            count: 0,
            x: zero,
            object: zero,
            values: [[zero; 4]; K],
        }
    }
}

impl<L: Lanes8, const K: usize> Packer<L, K> {
    /// Adds pixels `first..first + len` (`len` 1..=[`WIDTH`]) of `run`, in row `y`, computed as
    /// [`Fragments::span`] computes them. Returns the first eight fragments once there are
    /// eight.
    #[inline(always)]
    pub fn push_run(
        &mut self,
        y: u32,
        run: &Run<K>,
        first: usize,
        len: usize,
    ) -> Option<Fragments<L, K>> {
        debug_assert!((1..=WIDTH).contains(&len));
        let filled = self.count;
        // Lane `filled + j` takes pixel `first + j`; the lanes past the run repeat its last pixel.
        self.fill_from(filled as isize, run, first, len);
        self.count = filled + len;
        if self.count < WIDTH {
            return None;
        }
        let full = self.fragments(y, WIDTH);
        self.count -= WIDTH;
        if self.count > 0 {
            // The run's pixels past the eighth lane start the next batch.
            self.fill_from(filled as isize - WIDTH as isize, run, first, len);
        }
        Some(full)
    }

    /// Puts pixel `first + j` of `run` into lane `lane + j` for every lane from `lane` on
    /// (`lane` may be negative: the run's first pixels went into the last batch), the lanes past
    /// pixel `first + len − 1` taking that pixel. The pixel's step from the run's start, `first
    /// + j`, is an exact integer in f32, so each lane computes `at_start + per_x·k` as
    /// [`Fragments::span`] does.
    #[inline(always)]
    fn fill_from(&mut self, lane: isize, run: &Run<K>, first: usize, len: usize) {
        let lanes = lane_numbers::<L>();
        let last = L::splat((lane + len as isize - 1) as f32);
        let steps = lanes.min(last) + L::splat((first as isize - lane) as f32);
        let kept = lanes.lt(L::splat(lane as f32));
        for (v, varying) in self.values.iter_mut().enumerate() {
            // 1/w is the fourth component of the first varying alone.
            let components = if v == 0 { 4 } else { 3 };
            for (c, values) in varying.iter_mut().take(components).enumerate() {
                let fresh = L::splat(run.at_start[v][c]) + L::splat(run.per_x[v][c]) * steps;
                *values = L::select(kept, *values, fresh);
            }
        }
        self.x = L::select(kept, self.x, L::splat(run.start as f32) + steps);
        self.object = L::select(kept, self.object, L::splat(run.object as f32));
    }

    /// The fragments collected so far, as lanes of row `y`; `None` when there are none. Empties
    /// the packer.
    #[inline(always)]
    pub fn take(&mut self, y: u32) -> Option<Fragments<L, K>> {
        let count = std::mem::take(&mut self.count);
        (count > 0).then(|| self.fragments(y, count))
    }

    /// The lanes as fragments of row `y`, `count` of them pixels.
    #[inline(always)]
    fn fragments(&self, y: u32, count: usize) -> Fragments<L, K> {
        // x + 2^23 holds the integer x in its low mantissa bits for x in [0, 2^23): a lane-wise
        // add and subtract where `as u32` would take a saturating conversion per lane.
        let integers = |lanes: L| {
            let shifted: [u32; WIDTH] = bytemuck::cast((lanes + L::splat(TWO_TO_23)).to_array());
            shifted.map(|bits| bits - TWO_TO_23.to_bits())
        };
        Fragments::from_interpolants(
            y,
            count,
            integers(self.x),
            integers(self.object),
            self.values,
        )
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec4;

    use super::{Fragments, Packer, Run};
    use crate::render::simd::{F32x8, WIDTH};

    #[test]
    fn a_span_and_packed_runs_interpolate_the_same_bits() {
        // Pixel k of a run is `start + per_x·k` whether it arrives in a span of eight or is packed
        // with other short runs: the image must not depend on how pixels were batched.
        let at_start = Vec4::new(0.3, -0.7, 0.11, 0.25);
        let per_x = Vec4::new(1.0e-3, -3.0e-4, 7.0e-5, -1.0e-5);
        let run = |start, object| Run {
            start,
            object,
            at_start: [at_start],
            per_x: [per_x],
        };
        let span = Fragments::<F32x8>::span(5, &run(100, 2), 8);
        let mut packer = Packer::<F32x8>::default();
        assert!(packer.push_run(5, &run(100, 2), 8, 3).is_none());
        let packed = packer
            .push_run(5, &run(100, 2), 11, 5)
            .expect("eight fragments");
        assert_eq!(span.x, packed.x);
        assert_eq!((span.count, packed.count), (WIDTH, WIDTH));
        assert_eq!(span.depth.to_array(), packed.depth.to_array());
        assert_eq!(span.varying[0].to_vec3s(), packed.varying[0].to_vec3s());
        // Each lane is the one-pixel sum `start + per_x·k`, divided by its 1/w.
        for (lane, (depth, varying)) in packed
            .depth
            .to_array()
            .into_iter()
            .zip(packed.varying[0].to_vec3s())
            .enumerate()
        {
            let one = at_start + per_x * (8 + lane) as f32;
            assert_eq!(depth, 1.0 / one.w);
            assert_eq!(varying, one.truncate() * depth);
        }
        // Runs past the eighth lane wait for the next batch; a partly filled packer repeats
        // its last fragment and says how many are real.
        packer.push_run(7, &run(40, 1), 0, 6);
        let full = packer.push_run(7, &run(50, 3), 2, 4).expect("ten");
        assert_eq!(full.x, [40, 41, 42, 43, 44, 45, 52, 53]);
        assert_eq!(full.object, [1, 1, 1, 1, 1, 1, 3, 3]);
        let rest = packer.take(7).expect("two fragments");
        assert_eq!((rest.count, rest.x), (2, [54, 55, 55, 55, 55, 55, 55, 55]));
        assert!(packer.take(7).is_none(), "take empties the packer");
    }

    #[test]
    fn every_varying_is_interpolated_as_the_first_and_shares_its_depth() {
        // With three varyings, each is `start + per_x·k` divided by the first's 1/w, whether
        // the pixel comes in a span or packed; the unused fourth components change nothing.
        let at_start = [
            Vec4::new(0.3, -0.7, 0.11, 0.25),
            Vec4::new(0.9, 0.2, -0.4, 0.0),
            Vec4::new(-0.1, 0.5, 0.6, 0.0),
        ];
        let per_x = [
            Vec4::new(1.0e-3, -3.0e-4, 7.0e-5, -1.0e-5),
            Vec4::new(-2.0e-3, 5.0e-4, 1.0e-4, 0.0),
            Vec4::new(4.0e-4, 0.0, -6.0e-4, 0.0),
        ];
        let run = Run {
            start: 10,
            object: 0,
            at_start,
            per_x,
        };
        let span = Fragments::<F32x8, 3>::span(2, &run, 8);
        let mut packer = Packer::<F32x8, 3>::default();
        assert!(packer.push_run(2, &run, 8, 5).is_none());
        let packed = packer.push_run(2, &run, 13, 3).expect("eight fragments");
        assert_eq!(span.depth.to_array(), packed.depth.to_array());
        for v in 0..3 {
            assert_eq!(span.varying[v].to_vec3s(), packed.varying[v].to_vec3s());
            for (lane, (depth, varying)) in span
                .depth
                .to_array()
                .into_iter()
                .zip(span.varying[v].to_vec3s())
                .enumerate()
            {
                let k = (8 + lane) as f32;
                assert_eq!(depth, 1.0 / (at_start[0] + per_x[0] * k).w);
                assert_eq!(varying, (at_start[v] + per_x[v] * k).truncate() * depth);
            }
        }
    }
}
