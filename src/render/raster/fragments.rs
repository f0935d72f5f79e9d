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

/// Up to [`WIDTH`] covered pixels of one row, in lanes `L`. Lanes past `count` repeat the last
/// pixel.
#[derive(Clone, Copy)]
pub struct Fragments<L> {
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
    /// The perspective-correct varying.
    pub varying: V3<L>,
}

/// (0, 1, …, 7).
#[inline(always)]
fn lane_numbers<L: Lanes8>() -> L {
    L::from_array(std::array::from_fn(|k| k as f32))
}

impl<L: Lanes8> Fragments<L> {
    /// Pixels `run_start + k .. run_start + k + WIDTH` of row `y`, all drawn by one triangle of
    /// `object` whose interpolants (varying·1/w, 1/w) are `at_start` at the run's first pixel and
    /// change by `per_x` per pixel.
    #[inline(always)]
    pub fn span(
        y: u32,
        run_start: usize,
        k: usize,
        object: u32,
        at_start: Vec4,
        per_x: Vec4,
    ) -> Fragments<L> {
        let steps = L::splat(k as f32) + lane_numbers();
        let plane = |at: f32, per: f32| L::splat(at) + L::splat(per) * steps;
        let first = (run_start + k) as u32;
        Fragments::from_interpolants(
            y,
            WIDTH,
            std::array::from_fn(|lane| first + lane as u32),
            [object; WIDTH],
            [
                plane(at_start.x, per_x.x),
                plane(at_start.y, per_x.y),
                plane(at_start.z, per_x.z),
                plane(at_start.w, per_x.w),
            ],
        )
    }

    /// Divides the interpolants by 1/w: the depth and perspective-correct varying.
    #[inline(always)]
    fn from_interpolants(
        y: u32,
        count: usize,
        x: [u32; WIDTH],
        object: [u32; WIDTH],
        [vx, vy, vz, inv_w]: [L; 4],
    ) -> Fragments<L> {
        let depth = L::splat(1.0) / inv_w;
        Fragments {
            y,
            count,
            x,
            object,
            depth,
            varying: V3::new(vx * depth, vy * depth, vz * depth),
        }
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

/// Collects the short runs of one row into lanes: each run is worked out in eight lanes at once
/// and stored at the end of the lanes filled so far; lanes past the first eight wait for the next
/// batch.
#[derive(Debug, Clone, Default)]
pub struct Packer {
    count: usize,
    x: [u32; 2 * WIDTH],
    object: [u32; 2 * WIDTH],
    /// Interpolants (varying·1/w, 1/w) per lane, component by component.
    values: [[f32; 2 * WIDTH]; 4],
}

impl Packer {
    /// Adds the pixels `first..first + len` (`len` 1..=[`WIDTH`]) of a run of one triangle of
    /// `object` that starts in column `run_start` of row `y`, whose interpolants are `at_start`
    /// at the run's first pixel and change by `per_x` per pixel: pixel k gets
    /// `at_start + per_x·k`, as in [`Fragments::span`]. Returns the first eight fragments once
    /// there are eight.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    pub fn push_run<L: Lanes8>(
        &mut self,
        y: u32,
        run_start: usize,
        first: usize,
        len: usize,
        object: u32,
        at_start: Vec4,
        per_x: Vec4,
    ) -> Option<Fragments<L>> {
        debug_assert!((1..=WIDTH).contains(&len));
        let n = self.count;
        let steps = L::splat(first as f32) + lane_numbers();
        for (c, values) in self.values.iter_mut().enumerate() {
            let lanes = L::splat(at_start[c]) + L::splat(per_x[c]) * steps;
            values[n..n + WIDTH].copy_from_slice(&lanes.to_array());
        }
        let column = (run_start + first) as u32;
        for (lane, x) in self.x[n..n + WIDTH].iter_mut().enumerate() {
            *x = column + lane as u32;
        }
        self.object[n..n + WIDTH].fill(object);
        self.count = n + len;
        if self.count < WIDTH {
            return None;
        }
        let full = self.first_eight(y, WIDTH);
        self.count -= WIDTH;
        for values in &mut self.values {
            values.copy_within(WIDTH.., 0);
        }
        self.x.copy_within(WIDTH.., 0);
        self.object.copy_within(WIDTH.., 0);
        Some(full)
    }

    /// The fragments collected so far, as lanes of row `y`; `None` when there are none. Empties
    /// the packer.
    #[inline(always)]
    pub fn take<L: Lanes8>(&mut self, y: u32) -> Option<Fragments<L>> {
        let count = std::mem::take(&mut self.count);
        let last = count.checked_sub(1)?;
        for n in count..WIDTH {
            self.x[n] = self.x[last];
            self.object[n] = self.object[last];
            for values in &mut self.values {
                values[n] = values[last];
            }
        }
        Some(self.first_eight(y, count))
    }

    /// The first eight lanes as fragments of row `y`, `count` of them pixels.
    #[inline(always)]
    fn first_eight<L: Lanes8>(&self, y: u32, count: usize) -> Fragments<L> {
        let lanes = |values: &[u32; 2 * WIDTH]| -> [u32; WIDTH] {
            values[..WIDTH].try_into().expect("lanes")
        };
        let load =
            |values: &[f32; 2 * WIDTH]| L::from_array(values[..WIDTH].try_into().expect("lanes"));
        Fragments::from_interpolants(
            y,
            count,
            lanes(&self.x),
            lanes(&self.object),
            self.values.each_ref().map(load),
        )
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec4;

    use super::{Fragments, Packer};
    use crate::render::simd::{F32x8, WIDTH};

    #[test]
    fn a_span_and_packed_runs_interpolate_the_same_bits() {
        // Pixel k of a run is `start + per_x·k` whether it arrives in a span of eight or is packed
        // with other short runs: the image must not depend on how pixels were batched.
        let at_start = Vec4::new(0.3, -0.7, 0.11, 0.25);
        let per_x = Vec4::new(1.0e-3, -3.0e-4, 7.0e-5, -1.0e-5);
        let span = Fragments::<F32x8>::span(5, 100, 8, 2, at_start, per_x);
        let mut packer = Packer::default();
        assert!(
            packer
                .push_run::<F32x8>(5, 100, 8, 3, 2, at_start, per_x)
                .is_none()
        );
        let packed = packer
            .push_run::<F32x8>(5, 100, 11, 5, 2, at_start, per_x)
            .expect("eight fragments");
        assert_eq!(span.x, packed.x);
        assert_eq!((span.count, packed.count), (WIDTH, WIDTH));
        assert_eq!(span.depth.to_array(), packed.depth.to_array());
        assert_eq!(span.varying.to_vec3s(), packed.varying.to_vec3s());
        // Each lane is the one-pixel sum `start + per_x·k`, divided by its 1/w.
        for (lane, (depth, varying)) in packed
            .depth
            .to_array()
            .into_iter()
            .zip(packed.varying.to_vec3s())
            .enumerate()
        {
            let one = at_start + per_x * (8 + lane) as f32;
            assert_eq!(depth, 1.0 / one.w);
            assert_eq!(varying, one.truncate() * depth);
        }
        // Runs past the eighth lane wait for the next batch; a partly filled packer repeats
        // its last fragment and says how many are real.
        packer.push_run::<F32x8>(7, 40, 0, 6, 1, at_start, per_x);
        let full = packer
            .push_run::<F32x8>(7, 50, 2, 4, 3, at_start, per_x)
            .expect("ten");
        assert_eq!(full.x, [40, 41, 42, 43, 44, 45, 52, 53]);
        assert_eq!(full.object, [1, 1, 1, 1, 1, 1, 3, 3]);
        let rest = packer.take::<F32x8>(7).expect("two fragments");
        assert_eq!((rest.count, rest.x), (2, [54, 55, 55, 55, 55, 55, 55, 55]));
        assert!(packer.take::<F32x8>(7).is_none(), "take empties the packer");
    }
}
