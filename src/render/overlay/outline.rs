//! The outline of the selection: samples off the selected objects within a line's width of a
//! sample on them, found from the surface hits.

use super::GrownHits;
use super::canvas::Canvas;
use super::colors;
use super::set::Overlays;

/// Line width, output pixels.
const WIDTH: f32 = 2.0;

/// How far the outline reaches from the selection, in samples, at `samples` per pixel side: the
/// rows of hits a strip needs beyond its top and bottom.
pub fn reach(samples: u32) -> u32 {
    (WIDTH * samples as f32).round().max(1.0) as u32
}

/// Colours the samples of `canvas` that see no selected object but lie within [`WIDTH`] pixels
/// (a square reach) of one that does. `hits` holds the strip's rows and those around it, so the
/// outline runs on across the strip's top and bottom.
pub fn draw(selected: Option<(u32, u32)>, hits: &GrownHits, canvas: &mut Canvas) {
    let w = canvas.view.width as usize;
    let h = hits.hits.len() / w.max(1);
    let on: Vec<bool> = hits
        .hits
        .iter()
        .map(|hit| hit.is_hit() && Overlays::is_selected(selected, hit.object))
        .collect();
    let reach = reach(canvas.samples) as usize;
    // A square dilation in two passes: along rows, then along columns.
    let rows = dilate(&on, w, h, reach, 1, w);
    let square = dilate(&rows, h, w, reach, w, 1);
    let first = hits.above * w;
    for (i, out) in canvas.out.iter_mut().enumerate() {
        if square[first + i] && !on[first + i] {
            *out = colors::OUTLINE;
        }
    }
}

/// `mask` dilated by `reach` along one axis: `lines` lines of `len` values, value k of line l
/// at `l·line_stride + k·step`.
fn dilate(
    mask: &[bool],
    len: usize,
    lines: usize,
    reach: usize,
    step: usize,
    line_stride: usize,
) -> Vec<bool> {
    let mut out = vec![false; mask.len()];
    for line in 0..lines {
        let at = |k: usize| line * line_stride + k * step;
        // Count of set values in the window [k − reach, k + reach].
        let mut count = (0..reach.min(len)).filter(|&k| mask[at(k)]).count();
        for k in 0..len {
            if k + reach < len && mask[at(k + reach)] {
                count += 1;
            }
            if k > reach && mask[at(k - reach - 1)] {
                count -= 1;
            }
            out[at(k)] = count > 0;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::dilate;

    #[test]
    fn dilation_reaches_as_far_as_asked_along_its_axis() {
        let mut mask = vec![false; 9];
        mask[4] = true;
        let out = dilate(&mask, 9, 1, 2, 1, 9);
        let set: Vec<usize> = (0..9).filter(|&k| out[k]).collect();
        assert_eq!(set, vec![2, 3, 4, 5, 6]);
        // Columns of a 3×3 image: the middle value reaches up and down.
        let mut grid = vec![false; 9];
        grid[4] = true;
        let out = dilate(&grid, 3, 3, 1, 3, 1);
        let set: Vec<usize> = (0..9).filter(|&k| out[k]).collect();
        assert_eq!(set, vec![1, 4, 7]);
    }
}
