//! Large buffers backed by 2 MiB pages where the kernel offers them (Linux transparent huge
//! pages in `madvise` mode, the common default): one page-table entry then maps what took 512.
//! A BVH's build takes far fewer page faults, and its walk, which reads nodes and triangles
//! scattered over tens of megabytes, misses the TLB far less; Embree asks the same of its
//! allocations. The model loaders make their large arrays here too (an STL's body, the
//! welder's arrays, a PLY's columns and triangles, an OBJ's read-ahead blocks), each written on
//! every core, and so do `rastray info`'s placed shapes and edge rows.
//!
//! Measured gain, the reason for the `unsafe` here: see [`advise`].
#![allow(unsafe_code)]

use rayon::prelude::*;

/// Bytes in a huge page: only whole, aligned huge pages inside a buffer are advised.
const HUGE_PAGE: usize = 2 << 20;

/// Asks that the whole 2 MiB pages inside `buffer` be backed by huge pages. Call it before the
/// buffer is first written (a fresh large allocation is not yet backed by memory): pages already
/// faulted in stay small until the kernel merges them. A hint only: it changes no contents,
/// and a kernel that declines it leaves the buffer as it was.
///
/// Measured on the 1.31M-triangle icosphere (`../shared/perf/icosphere.toml`) at 640×360 on 2
/// threads, with and without this call alternating in one session: primary rays alone
/// (`bench throughput`, median of 9, four alternations) 14.5–14.7 ms with it and 14.8–15.5 ms
/// without; the build, in a fresh process as `../shared/perf/vs-embree.sh` times it (three
/// alternations), 170–201 ms with it and 217–230 ms without.
///
/// Loading the 9M-triangle grid of `examples/model_load` (three rounds taking turns, best of 3
/// each): the 450 MB binary STL 560–605 ms with 4 KiB pages and 330–363 ms with huge pages
/// (its arrays made on every core); the 184 MB PLY 336–392 ms and 226–278 ms.
pub(crate) fn advise<T>(buffer: &mut [T]) {
    #[cfg(target_os = "linux")]
    {
        let start = buffer.as_mut_ptr() as usize;
        let end = start + std::mem::size_of_val(buffer);
        let (first, last) = (
            start.next_multiple_of(HUGE_PAGE),
            end / HUGE_PAGE * HUGE_PAGE,
        );
        if first < last {
            // SAFETY: [first, last) lies inside `buffer`, which is borrowed mutably, so no other
            // code is using it; MADV_HUGEPAGE only changes which pages back the range, never
            // what it holds. A failure (an old kernel, huge pages turned off) is harmless.
            let _ = unsafe {
                rustix::mm::madvise(
                    first as *mut std::ffi::c_void,
                    last - first,
                    rustix::mm::Advice::LinuxHugepage,
                )
            };
        }
    }
    #[cfg(not(target_os = "linux"))]
    let _ = buffer;
}

/// An empty vector with room for `n` values, the room backed by huge pages (see [`advise`]).
pub(crate) fn with_capacity<T>(n: usize) -> Vec<T> {
    let mut buffer = Vec::with_capacity(n);
    advise(buffer.spare_capacity_mut());
    buffer
}

/// The items of `items` in a vector backed by huge pages, written on every core: the first
/// touch of a large buffer's pages (the kernel zeroes each one) is most of the cost of making
/// it, and is shared out.
pub(crate) fn collected<T: Send>(items: impl IndexedParallelIterator<Item = T>) -> Vec<T> {
    let mut buffer = with_capacity(items.len());
    buffer.par_extend(items);
    buffer
}

/// `n` copies of `value`, as [`collected`] makes them.
pub(crate) fn filled<T: Copy + Send>(n: usize, value: T) -> Vec<T> {
    collected(rayon::iter::repeat_n(value, n))
}

/// Appends `n` copies of `value` to `values`, written on every core (into the room it has,
/// such as [`with_capacity`] makes), and returns them to be overwritten in place.
pub(crate) fn extend_filled<T: Copy + Send>(values: &mut Vec<T>, n: usize, value: T) -> &mut [T] {
    let start = values.len();
    values.par_extend(rayon::iter::repeat_n(value, n));
    &mut values[start..]
}
