//! A rendered image in linear RGB, and its 8-bit sRGB encoding.

use glam::Vec3;
use rayon::prelude::*;

/// A `width`×`height` image of linear RGB, row-major from the top-left pixel.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Frame {
    pub width: u32,
    pub height: u32,
    /// `width·height` linear RGB values (not clamped).
    pub pixels: Vec<Vec3>,
}

impl Frame {
    /// A frame filled with `color`.
    pub fn filled(width: u32, height: u32, color: Vec3) -> Frame {
        Frame {
            width,
            height,
            pixels: vec![color; width as usize * height as usize],
        }
    }

    /// The pixel at column `x`, row `y` (0 = top).
    #[inline]
    pub fn pixel(&self, x: u32, y: u32) -> Vec3 {
        self.pixels[y as usize * self.width as usize + x as usize]
    }

    /// Makes this a `width`×`height` frame whose pixels are about to be overwritten: the buffer
    /// is kept when it has that size already, else replaced by zeroed memory, whose pages the
    /// render threads then fault in as they write, in parallel.
    pub fn reshape(&mut self, width: u32, height: u32) {
        let len = width as usize * height as usize;
        if self.pixels.len() != len {
            self.pixels = bytemuck::zeroed_vec(len);
        }
        (self.width, self.height) = (width, height);
    }

    /// 8-bit sRGB bytes, three per pixel: each channel clamped to [0, 1] then sRGB-encoded.
    pub fn to_srgb8(&self) -> Vec<u8> {
        self.pixels
            .iter()
            .flat_map(|p| p.to_array().map(encode_srgb))
            .collect()
    }

    /// The 8-bit sRGB colour of one pixel.
    pub fn srgb8_at(&self, x: u32, y: u32) -> [u8; 3] {
        self.pixel(x, y).to_array().map(encode_srgb)
    }
}

/// Averages each `n`×`n` block of `samples`, an image `width` samples wide, into one pixel of
/// `out`, an image `width / n` pixels wide and as many rows as `out` holds. Rows in parallel.
pub fn box_filter(samples: &[Vec3], width: u32, n: u32, out: &mut [Vec3]) {
    let (width, n) = (width as usize, n as usize);
    let out_width = width / n;
    let scale = 1.0 / (n * n) as f32;
    out.par_chunks_mut(out_width)
        .enumerate()
        .for_each(|(y, row)| {
            for (x, pixel) in row.iter_mut().enumerate() {
                let mut sum = Vec3::ZERO;
                for sy in 0..n {
                    let start = (y * n + sy) * width + x * n;
                    sum += samples[start..start + n].iter().copied().sum::<Vec3>();
                }
                *pixel = sum * scale;
            }
        });
}

/// Linear [0, 1] (clamped) to an 8-bit sRGB code value.
#[inline]
pub fn encode_srgb(linear: f32) -> u8 {
    let c = linear.clamp(0.0, 1.0);
    let s = if c <= 0.003_130_8 {
        12.92 * c
    } else {
        1.055 * c.powf(1.0 / 2.4) - 0.055
    };
    (s * 255.0 + 0.5) as u8
}

/// An 8-bit sRGB code value back to linear [0, 1].
#[inline]
pub fn decode_srgb(code: u8) -> f32 {
    let s = code as f32 / 255.0;
    if s <= 0.04045 {
        s / 12.92
    } else {
        ((s + 0.055) / 1.055).powf(2.4)
    }
}
