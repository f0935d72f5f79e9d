//! The bounding box of the selection, or of the scene, drawn as its twelve edges.

use glam::Vec3;

use super::canvas::Canvas;
use super::colors;
use super::set::Overlays;
use crate::world::World;

/// Line width, output pixels.
const WIDTH: f32 = 1.5;

/// The axis-aligned bounds (min, max) of the world objects `selected` (`first..end`), or of the
/// whole world when `None`; `None` when they are empty.
pub fn overlay_bounds(world: &World, selected: Option<(u32, u32)>) -> Option<(Vec3, Vec3)> {
    world
        .objects
        .iter()
        .enumerate()
        .filter(|(i, _)| Overlays::is_selected(selected, *i as u32))
        .filter_map(|(_, o)| o.extent)
        .reduce(|(a, b), (c, d)| (a.min(c), b.max(d)))
}

/// Draws the twelve edges of the box `(lo, hi)`, in front of everything.
pub fn draw((lo, hi): (Vec3, Vec3), canvas: &mut Canvas) {
    let corner = |k: usize| {
        Vec3::new(
            if k & 1 == 0 { lo.x } else { hi.x },
            if k & 2 == 0 { lo.y } else { hi.y },
            if k & 4 == 0 { lo.z } else { hi.z },
        )
    };
    // Corners k and k | bit differ along one axis: each such pair is an edge.
    for k in 0..8 {
        for bit in [1, 2, 4] {
            if k & bit == 0 {
                canvas.segment(corner(k), corner(k | bit), WIDTH, colors::BOUNDS, false);
            }
        }
    }
}
