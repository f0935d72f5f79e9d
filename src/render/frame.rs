//! A rendered image in linear RGB with optional coverage, and its 8- and 16-bit sRGB encodings.

use std::iter::Sum;
use std::ops::{AddAssign, Mul};

use glam::Vec3;
use rayon::prelude::*;

use super::srgb_encode::{SrgbEncoder, encode_srgb, srgb_curve};
use crate::mesh::{srgb_byte_to_linear, srgb_to_linear};

/// A `width`×`height` image of linear RGB, row-major from the top-left pixel, with coverage
/// when the render was asked for it.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Frame {
    pub width: u32,
    pub height: u32,
    /// `width·height` linear RGB values (not clamped); premultiplied by [`Frame::alpha`] when
    /// that is present (the background left out).
    pub pixels: Vec<Vec3>,
    /// Coverage as alpha: per pixel, the fraction of its samples on which some surface lies, in
    /// [0, 1] (0 on the background, 1 inside an object). Present when the render was asked for
    /// it ([`crate::render::RenderOptions::alpha`]).
    pub alpha: Option<Vec<f32>>,
}

impl Frame {
    /// A frame filled with `color`.
    pub fn filled(width: u32, height: u32, color: Vec3) -> Frame {
        Frame {
            width,
            height,
            pixels: vec![color; width as usize * height as usize],
            alpha: None,
        }
    }

    /// The pixel at column `x`, row `y` (0 = top).
    #[inline]
    pub fn pixel(&self, x: u32, y: u32) -> Vec3 {
        self.pixels[y as usize * self.width as usize + x as usize]
    }

    /// The alpha of the pixel at column `x`, row `y`: its coverage, or 1 without alpha.
    #[inline]
    pub fn alpha_at(&self, x: u32, y: u32) -> f32 {
        self.alpha
            .as_ref()
            .map_or(1.0, |a| a[y as usize * self.width as usize + x as usize])
    }

    /// Makes this a `width`×`height` frame, with an alpha channel when `alpha`, whose pixels are
    /// about to be overwritten: each buffer is kept when it has that size already, else replaced
    /// by zeroed memory, whose pages the render threads then fault in as they write, in parallel.
    pub fn reshape(&mut self, width: u32, height: u32, alpha: bool) {
        let len = width as usize * height as usize;
        if self.pixels.len() != len {
            self.pixels = bytemuck::zeroed_vec(len);
        }
        match &mut self.alpha {
            Some(a) if alpha && a.len() == len => {}
            _ if alpha => self.alpha = Some(bytemuck::zeroed_vec(len)),
            _ => self.alpha = None,
        }
        (self.width, self.height) = (width, height);
    }

    /// 8-bit sRGB bytes, three per pixel: each channel clamped to [0, 1] then sRGB-encoded.
    pub fn to_srgb8(&self) -> Vec<u8> {
        // From pixels of three bytes to bytes: always the same memory.
        bytemuck::cast_vec(self.srgb8_pixels())
    }

    /// Each pixel's 8-bit sRGB colour, as [`Frame::to_srgb8`] encodes it.
    pub fn srgb8_pixels(&self) -> Vec<[u8; 3]> {
        /// Pixels a task encodes.
        const CHUNK: usize = 4096;
        let encoder = SrgbEncoder::new();
        let mut rgb = vec![[0u8; 3]; self.pixels.len()];
        rgb.par_chunks_mut(CHUNK)
            .zip(self.pixels.par_chunks(CHUNK))
            .for_each(|(rgb, pixels)| {
                for (rgb, p) in rgb.iter_mut().zip(pixels) {
                    *rgb = p.to_array().map(|c| encoder.encode(c));
                }
            });
        rgb
    }

    /// The 8-bit sRGB colour of one pixel.
    pub fn srgb8_at(&self, x: u32, y: u32) -> [u8; 3] {
        self.pixel(x, y).to_array().map(encode_srgb)
    }
}

/// Averages each `n`×`n` block of `samples`, an image `width` samples wide, into one pixel of
/// `out`, an image `width / n` pixels wide and as many rows as `out` holds: colours, or
/// coverage. Rows in parallel.
pub fn box_filter<T>(samples: &[T], width: u32, n: u32, out: &mut [T])
where
    T: Copy + Default + Send + Sync + Sum + AddAssign + Mul<f32, Output = T>,
{
    let (width, n) = (width as usize, n as usize);
    let out_width = width / n;
    let scale = 1.0 / (n * n) as f32;
    out.par_chunks_mut(out_width)
        .enumerate()
        .for_each(|(y, row)| {
            for (x, pixel) in row.iter_mut().enumerate() {
                let mut sum = T::default();
                for sy in 0..n {
                    let start = (y * n + sy) * width + x * n;
                    sum += samples[start..start + n].iter().copied().sum::<T>();
                }
                *pixel = sum * scale;
            }
        });
}

/// Linear [0, 1] (clamped) to a 16-bit sRGB code value.
#[inline]
pub fn encode_srgb16(linear: f32) -> u16 {
    (srgb_curve(linear) * 65535.0 + 0.5) as u16
}

/// An 8-bit sRGB code value back to linear [0, 1] (the mesh loaders' table: one decode for
/// file colours and frames alike).
#[inline]
pub fn decode_srgb(code: u8) -> f32 {
    srgb_byte_to_linear(code)
}

/// A 16-bit sRGB code value back to linear [0, 1].
#[inline]
pub fn decode_srgb16(code: u16) -> f32 {
    srgb_to_linear(code as f32 / 65535.0)
}
