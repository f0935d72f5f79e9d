//! Fragments in lanes: up to eight covered pixels of one row with their depth, varying and
//! object. The rasterizer hands these to a Z-buffer shader, which lights or colours all eight at
//! once.
//!
//! A run of pixels drawn by one triangle becomes whole batches by stepping the triangle's planes
//! eight pixels at a time; the pixels left over (short runs, as on finely tessellated meshes) are
//! packed lane by lane. Both ways compute pixel k of a run the same way, as
//! `interpolants(run start) + per_x·k`, so a pixel's value does not depend on how it was batched.

use glam::{Vec3, Vec4};

use crate::render::simd::{F32x8, V3, WIDTH};

/// Up to [`WIDTH`] covered pixels of one row. Lanes past `count` repeat the last pixel.
#[derive(Debug, Clone, Copy)]
pub struct Fragments {
    /// Row within the view (0 = top).
    pub y: u32,
    /// Number of lanes that are pixels, 1..=[`WIDTH`].
    pub count: usize,
    /// Column of each lane.
    pub x: [u32; WIDTH],
    /// Object index in the world of each lane.
    pub object: [u32; WIDTH],
    /// Depth w of the surface along the view direction, world units (> 0).
    pub depth: F32x8,
    /// The perspective-correct varying.
    pub varying: V3<F32x8>,
}

/// (0, 1, …, 7).
fn lane_numbers() -> F32x8 {
    F32x8::from(std::array::from_fn::<f32, WIDTH, _>(|k| k as f32))
}

impl Fragments {
    /// Pixels `run_start + k .. run_start + k + WIDTH` of row `y`, all drawn by one triangle of
    /// `object` whose interpolants (varying·1/w, 1/w) are `at_start` at the run's first pixel and
    /// change by `per_x` per pixel.
    #[inline]
    pub fn span(
        y: u32,
        run_start: usize,
        k: usize,
        object: u32,
        at_start: Vec4,
        per_x: Vec4,
    ) -> Fragments {
        let steps = F32x8::splat(k as f32) + lane_numbers();
        let plane = |at: f32, per: f32| F32x8::splat(at) + F32x8::splat(per) * steps;
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
        [vx, vy, vz, inv_w]: [F32x8; 4],
    ) -> Fragments {
        let depth = F32x8::splat(1.0) / inv_w;
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
    #[inline]
    pub fn write(&self, colors: V3<F32x8>, out: &mut [Vec3]) {
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

/// Collects single fragments of one row into lanes.
#[derive(Debug, Clone, Default)]
pub struct Packer {
    count: usize,
    x: [u32; WIDTH],
    object: [u32; WIDTH],
    /// Interpolants (varying·1/w, 1/w) per lane, component by component.
    values: [[f32; WIDTH]; 4],
}

impl Packer {
    /// Adds the pixel in column `x` of `object` with `interpolants`; true when all lanes are full.
    #[inline]
    pub fn push(&mut self, x: u32, object: u32, interpolants: Vec4) -> bool {
        let n = self.count;
        self.x[n] = x;
        self.object[n] = object;
        for (c, value) in interpolants.to_array().into_iter().enumerate() {
            self.values[c][n] = value;
        }
        self.count += 1;
        self.count == WIDTH
    }

    /// The fragments collected so far, as lanes of row `y`; `None` when there are none. Empties
    /// the packer.
    #[inline]
    pub fn take(&mut self, y: u32) -> Option<Fragments> {
        let count = std::mem::take(&mut self.count);
        let last = count.checked_sub(1)?;
        for n in count..WIDTH {
            self.x[n] = self.x[last];
            self.object[n] = self.object[last];
            for values in &mut self.values {
                values[n] = values[last];
            }
        }
        Some(Fragments::from_interpolants(
            y,
            count,
            self.x,
            self.object,
            self.values.map(F32x8::from),
        ))
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec4;

    use super::{Fragments, Packer};
    use crate::render::simd::WIDTH;

    #[test]
    fn a_span_and_packed_pixels_interpolate_the_same_bits() {
        // Pixel k of a run is `start + per_x·k` whether it arrives in a span of eight or is packed
        // with other leftovers: the image must not depend on how pixels were batched.
        let at_start = Vec4::new(0.3, -0.7, 0.11, 0.25);
        let per_x = Vec4::new(1.0e-3, -3.0e-4, 7.0e-5, -1.0e-5);
        let span = Fragments::span(5, 100, 8, 2, at_start, per_x);
        let mut packer = Packer::default();
        for k in 8..16 {
            packer.push(100 + k as u32, 2, at_start + per_x * k as f32);
        }
        let packed = packer.take(5).expect("eight fragments");
        assert_eq!(span.x, packed.x);
        assert_eq!(span.count, WIDTH);
        assert_eq!(span.depth.to_array(), packed.depth.to_array());
        assert_eq!(span.varying.to_vec3s(), packed.varying.to_vec3s());
        // A partly filled packer repeats its last fragment and says how many are real.
        packer.push(7, 1, at_start);
        let one = packer.take(5).expect("one fragment");
        assert_eq!((one.count, one.x), (1, [7; WIDTH]));
        assert!(packer.take(5).is_none(), "take empties the packer");
    }
}
