//! Fixed-point screen positions: the sub-pixel grid vertices snap to, the guard band that keeps
//! them inside `i32`, and the exact integer edge function coverage is decided by.

/// Sub-pixel precision of snapped vertex coordinates: 1/256 pixel.
pub const SUBPIXEL_BITS: u32 = 8;
pub const SUBPIXEL: f32 = (1 << SUBPIXEL_BITS) as f32;
/// Half a pixel in fixed point: pixel i's centre is at i·256 + 128.
pub const HALF: i32 = 1 << (SUBPIXEL_BITS - 1);
/// Triangles are clipped to |x|, |y| ≤ GUARD·w, which keeps snapped coordinates far inside i32 and
/// edge-function products inside i64 for every image size the options accept.
pub const GUARD: f32 = 4.0;

/// `v` rounded to the nearest integer, halves away from zero: `f32::round`, which on baseline
/// x86-64 is a call into libm, done with a truncating conversion (|v| < 2^31).
#[inline(always)]
pub fn round(v: f32) -> i32 {
    let whole = v as i32;
    // The fractional part of a float is exact.
    let fraction = v - whole as f32;
    whole
        .saturating_add((fraction >= 0.5) as i32)
        .saturating_sub((fraction <= -0.5) as i32)
}

/// Twice the signed area of (a, b, p): positive when p is on the interior side of a→b.
#[inline(always)]
pub fn edge(ax: i32, ay: i32, bx: i32, by: i32, px: i32, py: i32) -> i64 {
    (bx - ax) as i64 * (py - ay) as i64 - (by - ay) as i64 * (px - ax) as i64
}

/// The first pixel whose centre is at or after fixed-point coordinate `lo`.
#[inline(always)]
pub fn first_centre(lo: i32) -> i32 {
    (lo - HALF + (1 << SUBPIXEL_BITS) - 1).div_euclid(1 << SUBPIXEL_BITS)
}

/// The last pixel whose centre is at or before fixed-point coordinate `hi`.
#[inline(always)]
pub fn last_centre(hi: i32) -> i32 {
    (hi - HALF).div_euclid(1 << SUBPIXEL_BITS)
}

#[cfg(test)]
mod tests {
    use super::round;

    #[test]
    fn round_is_f32_round() {
        let special = [
            0.5,
            -0.5,
            1.5,
            -2.5,
            0.499_999_97,
            -0.499_999_97,
            8_388_607.5,
            1.0e9,
        ];
        let steps = (-40_000..40_000).map(|k| k as f32 * 0.031_25 + 0.003);
        for v in special.into_iter().chain(steps) {
            assert_eq!(round(v), v.round() as i32, "{v}");
        }
    }
}
