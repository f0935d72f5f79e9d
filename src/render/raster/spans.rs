//! The covered pixel centres of a screen triangle, row by row: in each row, the run of centres
//! where all three edge functions, biased by the top-left rule, are ≥ 0 (a triangle is convex,
//! so the run is one piece).
//!
//! Small triangles (most of a real mesh) test eight centres at a time in `i32` lanes and hand
//! on the lane masks, which the depth test uses as they are: no division. Larger ones solve each
//! row's run from the three edge functions in `i64`, one division per edge and row, which their
//! longer rows pay for.
//! Both accept exactly the centres the exact integer edge functions accept.

use wide::{CmpGt, i32x8};

use super::screen_triangle::ScreenTriangle;
use super::snap::{HALF, SUBPIXEL_BITS, edge};

/// A triangle whose vertices span less than this many fixed-point units (32 pixels) in x and in
/// y is scanned in `i32` lanes: every edge function value at a centre of its bounding box, or
/// up to seven columns past it, is below 2·2^13·2^14 = 2^28 in magnitude.
const LANE_SPAN_EXTENT: i32 = 1 << 13;

/// One edge of a counter-clockwise screen triangle: its function at the first centre scanned
/// (top-left bias included) and its change per column and per row, fixed-point products.
#[derive(Clone, Copy)]
pub(super) struct Edge {
    pub(super) at_start: i64,
    pub(super) per_x: i64,
    pub(super) per_y: i64,
}

/// The three edges of `t`, evaluated from the centre of pixel (`t.min_x`, `y0`). Edge k is
/// opposite vertex k: it runs from vertex k+1 to vertex k+2, and its function is vertex k's
/// unnormalised barycentric weight.
#[inline(always)]
pub(super) fn edges(t: &ScreenTriangle, y0: i32) -> [Edge; 3] {
    let (px, py) = (
        (t.min_x << SUBPIXEL_BITS) + HALF,
        (y0 << SUBPIXEL_BITS) + HALF,
    );
    std::array::from_fn(|k| {
        let (a, b) = ((k + 1) % 3, (k + 2) % 3);
        let (dx, dy) = (t.x[b] - t.x[a], t.y[b] - t.y[a]);
        // Top-left rule: a centre exactly on an edge belongs to the triangle only when the edge
        // is a top edge (horizontal, interior below) or a left edge (interior to the right).
        // Other edges get a bias of −1 so that "on the edge" tests as outside.
        let top_left = (dy == 0 && dx > 0) || dy < 0;
        let bias = if top_left { 0 } else { -1 };
        Edge {
            at_start: edge(t.x[a], t.y[a], t.x[b], t.y[b], px, py) + bias,
            per_x: -(dy as i64) << SUBPIXEL_BITS,
            per_y: (dx as i64) << SUBPIXEL_BITS,
        }
    })
}

/// Calls `span(y, first, last)` for each row `y` of `y0..=y1` in which `t` covers pixel centres,
/// with the first and last covered column (inclusive), top row first.
#[cfg(test)]
pub fn for_each_span(t: &ScreenTriangle, y0: i32, y1: i32, span: impl FnMut(i32, i32, i32)) {
    if fits_lanes(t) {
        small_spans(t, y0, y1, span);
    } else {
        solved_spans(t, y0, y1, span);
    }
}

/// Whether `t` is small enough for [`for_each_block`]: its vertices span less than
/// [`LANE_SPAN_EXTENT`] in x and in y.
#[inline(always)]
pub fn fits_lanes(t: &ScreenTriangle) -> bool {
    let extent = |v: [i32; 3]| v[0].max(v[1]).max(v[2]) - v[0].min(v[1]).min(v[2]);
    extent(t.x) < LANE_SPAN_EXTENT && extent(t.y) < LANE_SPAN_EXTENT
}

/// Calls `block(y, first, x, covered)` for each block of eight columns `x..x + 8` of each row
/// `y` of `y0..=y1` in which the small triangle `t` ([`fits_lanes`]) covers pixel centres:
/// `covered` has all bits set in the lanes whose centre is covered, and `first` is the row's
/// first covered column. A row's blocks come left to right, top row first, and start at
/// `t.min_x`; lanes past `t.max_x` are never covered. Each row is tested eight centres at a
/// time, in `i32` lanes.
#[inline(always)]
pub fn for_each_block(
    t: &ScreenTriangle,
    y0: i32,
    y1: i32,
    mut block: impl FnMut(i32, i32, i32, i32x8),
) {
    let edges = edges(t, y0);
    // The values fit in i32 by LANE_SPAN_EXTENT.
    let lanes = i32x8::from([0, 1, 2, 3, 4, 5, 6, 7]);
    let mut row: [i32x8; 3] =
        edges.map(|e| i32x8::splat(e.at_start as i32) + lanes * i32x8::splat(e.per_x as i32));
    let per_block = edges.map(|e| i32x8::splat((e.per_x * 8) as i32));
    let per_row = edges.map(|e| i32x8::splat(e.per_y as i32));
    let last = t.max_x - t.min_x;
    let outside = i32x8::splat(-1);
    for y in y0..=y1 {
        let mut e = row;
        let mut first = -1;
        let mut column = 0;
        while column <= last {
            let in_box = i32x8::splat(last - column).cmp_gt(lanes - i32x8::splat(1));
            let inside =
                e[0].cmp_gt(outside) & e[1].cmp_gt(outside) & e[2].cmp_gt(outside) & in_box;
            let bits = inside.move_mask() as u32;
            if bits != 0 {
                if first < 0 {
                    first = column + bits.trailing_zeros() as i32;
                }
                block(y, t.min_x + first, t.min_x + column, inside);
            } else if first >= 0 {
                // The run has ended: a row of a convex triangle holds one.
                break;
            }
            column += 8;
            for k in 0..3 {
                e[k] += per_block[k];
            }
        }
        for k in 0..3 {
            row[k] += per_row[k];
        }
    }
}

/// The spans of a triangle smaller than [`LANE_SPAN_EXTENT`], from its blocks.
#[cfg(test)]
fn small_spans(t: &ScreenTriangle, y0: i32, y1: i32, mut span: impl FnMut(i32, i32, i32)) {
    // The row, first and last covered column of the run being gathered.
    let mut run: Option<(i32, i32, i32)> = None;
    for_each_block(t, y0, y1, |y, first, x, covered| {
        let end = x + 31 - (covered.move_mask() as u32).leading_zeros() as i32;
        match &mut run {
            Some((row, _, last)) if *row == y => *last = end,
            _ => {
                if let Some((row, first, last)) = run {
                    span(row, first, last);
                }
                run = Some((y, first, end));
            }
        }
    });
    if let Some((row, first, last)) = run {
        span(row, first, last);
    }
}

/// The spans of any triangle, each row's solved from the three edge functions (each linear in
/// x): the columns where all three are ≥ 0.
#[inline(always)]
pub fn solved_spans(t: &ScreenTriangle, y0: i32, y1: i32, mut span: impl FnMut(i32, i32, i32)) {
    let edges = edges(t, y0);
    let mut row_start = edges.map(|e| e.at_start);
    let columns = (t.max_x - t.min_x) as i64;
    for y in y0..=y1 {
        let (mut lo, mut hi) = (0i64, columns);
        for (e, edge) in row_start.iter().zip(&edges) {
            let (e, s) = (*e, edge.per_x);
            if s > 0 {
                if e < 0 {
                    lo = lo.max((-e + s - 1) / s);
                }
            } else if s < 0 {
                hi = if e < 0 { -1 } else { hi.min(e / -s) };
            } else if e < 0 {
                hi = -1;
            }
        }
        if lo <= hi {
            debug_assert!(
                row_start
                    .iter()
                    .zip(&edges)
                    .all(|(e, edge)| e + lo * edge.per_x >= 0 && e + hi * edge.per_x >= 0),
                "span solved wrongly"
            );
            span(y, t.min_x + lo as i32, t.min_x + hi as i32);
        }
        for (e, edge) in row_start.iter_mut().zip(&edges) {
            *e += edge.per_y;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{small_spans, solved_spans};
    use crate::render::raster::screen_triangle::ScreenTriangle;
    use crate::render::raster::snap::{first_centre, last_centre};

    /// A counter-clockwise screen triangle (fixed-point vertices) with its bounding box.
    fn triangle(x: [i32; 3], y: [i32; 3]) -> ScreenTriangle {
        ScreenTriangle {
            x,
            y,
            min_x: first_centre(x[0].min(x[1]).min(x[2])),
            max_x: last_centre(x[0].max(x[1]).max(x[2])),
            min_y: first_centre(y[0].min(y[1]).min(y[2])),
            max_y: last_centre(y[0].max(y[1]).max(y[2])),
            ..ScreenTriangle::default()
        }
    }

    #[test]
    fn lanes_find_the_spans_division_finds() {
        // Small triangles of every shape and orientation on a pseudo-random walk, including
        // vertices exactly on pixel centres and edges through them (the top-left rule decides).
        let mut seed = 0x2545_f491_u32;
        let mut next = |range: i32| {
            seed ^= seed << 13;
            seed ^= seed >> 17;
            seed ^= seed << 5;
            (seed % range as u32) as i32
        };
        let mut spans_seen = 0;
        for _ in 0..20_000 {
            let size = [64, 256, 600, 3000, 8000][next(5) as usize];
            let on_grid = next(3) == 0;
            let mut corner = || {
                let v = 4096 + next(size);
                if on_grid { v & !127 } else { v }
            };
            let (mut x, mut y) = ([0; 3], [0; 3]);
            for k in 0..3 {
                (x[k], y[k]) = (corner(), corner());
            }
            let area = super::edge(x[0], y[0], x[1], y[1], x[2], y[2]);
            if area == 0 {
                continue;
            }
            if area < 0 {
                x.swap(1, 2);
                y.swap(1, 2);
            }
            let t = triangle(x, y);
            if t.min_x > t.max_x || t.min_y > t.max_y {
                continue;
            }
            let (mut lanes, mut solved) = (Vec::new(), Vec::new());
            small_spans(&t, t.min_y, t.max_y, |y, a, b| lanes.push((y, a, b)));
            solved_spans(&t, t.min_y, t.max_y, |y, a, b| solved.push((y, a, b)));
            assert_eq!(lanes, solved, "{x:?} {y:?}");
            spans_seen += lanes.len();
        }
        assert!(
            spans_seen > 10_000,
            "the walk covers centres ({spans_seen})"
        );
    }
}
