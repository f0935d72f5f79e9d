//! The scan of a small triangle ([`fits_lanes`](super::spans::fits_lanes)) on AVX2 registers,
//! chosen at run time where the CPU has AVX2.
//!
//! The build targets baseline x86-64, where `wide`'s eight `i32` or `f32` lanes are two SSE
//! registers, even inside code compiled for AVX2. This is
//! [`for_each_block`](super::spans::for_each_block) with the depth test of `zbuffer` on one
//! 256-bit register per value: the same integer edge functions, the same IEEE operations on
//! 1/w in the same order (no fused multiply-add), so the depth and ids it leaves are the same
//! bits.
//!
//! Measured gain, the reason for the `unsafe` here: see [`Avx2`].
#![allow(unsafe_code)]

use std::arch::x86_64::{
    __m256, __m256i, _CMP_GE_OQ, _mm256_add_epi32, _mm256_add_ps, _mm256_and_si256,
    _mm256_blendv_ps, _mm256_castps_si256, _mm256_castsi256_ps, _mm256_cmp_ps, _mm256_cmpgt_epi32,
    _mm256_movemask_ps, _mm256_mul_ps, _mm256_mullo_epi32, _mm256_set1_epi32, _mm256_set1_ps,
    _mm256_setr_epi32, _mm256_setr_ps,
};

use super::screen_triangle::ScreenTriangle;
use super::spans::edges;
use crate::render::simd::WIDTH;

/// Proof that this CPU has AVX2 (and BMI1/2, LZCNT): made only by [`Avx2::detect`].
///
/// Measured on the bunny (`../shared/perf/bunny.toml`) at 1920×1080 on 1 thread, frames of a
/// kept renderer (median of 60, three alternations with the `wide` scan in one session): Phong
/// 14.1–14.6 → 12.1–12.7 ms; Gouraud (median of 40, two alternations) 13.8–14.1 → 11.7–12.9
/// ms. The same scan compiled for AVX2 but on `wide`'s lanes gained 1–4%.
#[derive(Debug, Clone, Copy)]
pub(super) struct Avx2(());

/// The rows of a band being scanned: its depth buffer (1/w, 0 = nothing) and triangle ids,
/// each running [`WIDTH`] entries past the band's end.
pub(super) struct Band<'a> {
    /// The band's first row in the image.
    pub top: u32,
    /// Pixels per row.
    pub width: u32,
    pub depth: &'a mut [f32],
    pub ids: &'a mut [u32],
}

impl Avx2 {
    /// `Some` where the CPU has what [`scan_small`] is compiled for.
    #[inline]
    pub(super) fn detect() -> Option<Avx2> {
        crate::render::cpu::has_avx2_bmi().then_some(Avx2(()))
    }

    /// Scan-converts the small triangle `t`, number `id` of the band's bin, over rows
    /// `y0..=y1` into `band`, as `zbuffer`'s scan of a band does.
    #[inline]
    pub(super) fn scan_small(self, t: &ScreenTriangle, y0: i32, y1: i32, band: &mut Band, id: u32) {
        // SAFETY: an `Avx2` exists only once `detect` found the features `scan_small` is
        // compiled for.
        unsafe { scan_small(t, y0, y1, band, id) }
    }
}

#[target_feature(enable = "avx2,bmi1,bmi2,lzcnt")]
fn scan_small(t: &ScreenTriangle, y0: i32, y1: i32, band: &mut Band, id: u32) {
    let edges = edges(t, y0);
    // The values fit in i32 by LANE_SPAN_EXTENT.
    let lanes = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
    let lanes_f = _mm256_setr_ps(0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0);
    let mut row: [__m256i; 3] = edges.map(|e| {
        _mm256_add_epi32(
            _mm256_set1_epi32(e.at_start as i32),
            _mm256_mullo_epi32(lanes, _mm256_set1_epi32(e.per_x as i32)),
        )
    });
    let per_block = edges.map(|e| _mm256_set1_epi32((e.per_x * 8) as i32));
    let per_row = edges.map(|e| _mm256_set1_epi32(e.per_y as i32));
    let last = t.max_x - t.min_x;
    let outside = _mm256_set1_epi32(-1);
    let below_lanes = _mm256_setr_epi32(-1, 0, 1, 2, 3, 4, 5, 6);
    let dz = _mm256_set1_ps(t.inv_w.per_x);
    let id_lanes = _mm256_castsi256_ps(_mm256_set1_epi32(id as i32));
    for y in y0..=y1 {
        let mut e = row;
        let mut first = -1;
        let mut z0 = _mm256_set1_ps(0.0);
        let row_start = (y as u32 - band.top) as usize * band.width as usize;
        let mut column = 0;
        while column <= last {
            let in_box = _mm256_cmpgt_epi32(_mm256_set1_epi32(last - column), below_lanes);
            let inside = _mm256_and_si256(
                _mm256_and_si256(
                    _mm256_cmpgt_epi32(e[0], outside),
                    _mm256_cmpgt_epi32(e[1], outside),
                ),
                _mm256_and_si256(_mm256_cmpgt_epi32(e[2], outside), in_box),
            );
            let covered = _mm256_castsi256_ps(inside);
            let bits = _mm256_movemask_ps(covered) as u32;
            if bits != 0 {
                if first < 0 {
                    first = column + bits.trailing_zeros() as i32;
                    z0 = _mm256_set1_ps(t.inv_w_at(t.min_x + first, y));
                }
                // column − first + lane is an exact integer in f32.
                let steps = _mm256_add_ps(_mm256_set1_ps((column - first) as f32), lanes_f);
                let z = _mm256_add_ps(z0, _mm256_mul_ps(dz, steps));
                let at = row_start + (t.min_x + column) as usize;
                let d: &mut [f32; WIDTH] =
                    (&mut band.depth[at..at + WIDTH]).try_into().expect("lanes");
                let i: &mut [u32; WIDTH] =
                    (&mut band.ids[at..at + WIDTH]).try_into().expect("lanes");
                let stored: __m256 = bytemuck::cast(*d);
                let nearer = _mm256_castsi256_ps(_mm256_and_si256(
                    _mm256_castps_si256(_mm256_cmp_ps::<_CMP_GE_OQ>(z, stored)),
                    inside,
                ));
                *d = bytemuck::cast(_mm256_blendv_ps(stored, z, nearer));
                let old: __m256 = bytemuck::cast(*i);
                *i = bytemuck::cast(_mm256_blendv_ps(old, id_lanes, nearer));
            } else if first >= 0 {
                // The run has ended: a row of a convex triangle holds one.
                break;
            }
            column += 8;
            for k in 0..3 {
                e[k] = _mm256_add_epi32(e[k], per_block[k]);
            }
        }
        for k in 0..3 {
            row[k] = _mm256_add_epi32(row[k], per_row[k]);
        }
    }
}
