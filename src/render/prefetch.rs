//! Cache prefetch hints: the BVH walk asks for the next nodes and triangles it may read while it
//! still tests the current ones, so that on large meshes (whose tree does not fit in the cache)
//! the loads overlap instead of waiting one after another; the BVH build, laying the triangles
//! out in leaf order, asks for the mesh data of the ones a few places ahead; the Z-buffer's
//! setup asks for the projected corners of the triangles a few groups ahead when another thread
//! may have projected them, and its bands ask for the corners of each triangle a band shows
//! while they are still finding them.
//!
//! Measured gain, the reason for the `unsafe` here: see [`ahead`].
#![allow(unsafe_code)]

/// Hints that the cache line holding the start of `value` is read soon. A hint only: it never
/// faults, changes no memory and no result.
///
/// Measured on the 1.31M-triangle icosphere (`../shared/perf/icosphere.toml`) at 640×360 on 2
/// threads, BVH kept, 30 frames per run, the build with the hints and one without them
/// alternating five times on a shared, loaded machine: CPU time per frame 49.0–54.2 ms with
/// them, 54.5–59.1 ms without (about 10% less).
#[inline(always)]
pub(crate) fn ahead<T>(value: &T) {
    line((value as *const T).cast());
}

/// Hints that `values[i]` is read soon, without a bounds check (an index past the end hints an
/// address no value holds, which is harmless: a hint never faults).
#[inline(always)]
pub(crate) fn ahead_in<T>(values: &[T], i: usize) {
    line(values.as_ptr().wrapping_add(i).cast());
}

/// Hints that all of `value` is read soon: each cache line it touches (the Z-buffer's
/// 36-byte corners of a triangle may straddle two).
#[inline(always)]
pub(crate) fn ahead_all<T>(value: &T) {
    let start = (value as *const T).cast::<u8>();
    let size = std::mem::size_of::<T>();
    for offset in (0..size).step_by(LINE) {
        line(start.wrapping_add(offset));
    }
    if size > 0 {
        line(start.wrapping_add(size - 1));
    }
}

/// Bytes per cache line.
const LINE: usize = 64;

/// Hints that the cache line holding `address` is read soon. Any address may be hinted.
#[inline(always)]
fn line(address: *const u8) {
    #[cfg(target_arch = "x86_64")]
    // SAFETY: `prefetcht0` only hints the cache: it reads nothing the program sees and cannot
    // fault, whatever the address (the callers pass addresses in or just past live values).
    unsafe {
        use std::arch::x86_64::{_MM_HINT_T0, _mm_prefetch};
        _mm_prefetch::<_MM_HINT_T0>(address.cast());
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = address;
}
