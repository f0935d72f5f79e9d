//! Overlays drawn over a render: a ground grid, an axis gizmo, a bounding box and an outline
//! around the selected object. Lines are projected with the render's own `View` and drawn into
//! the samples before they are filtered; the grid is depth-tested against the surfaces the
//! render found, so the model hides it.

mod bounds_box;
mod canvas;
mod dimensions;
mod gizmo;
mod grid;
mod outline;
mod set;

pub use bounds_box::overlay_bounds;
pub use colors as overlay_colors;
pub use grid::{Grid, ground_grid};
pub use set::{OverlayKind, Overlays, UnknownOverlay};

pub(super) use canvas::Canvas;

use super::camera::View;
use super::frame::Frame;
use super::surface_hit::SurfaceHit;
use crate::scene::Camera;
use crate::world::World;

/// Line colours, linear RGB.
pub mod colors {
    use glam::Vec3;
    /// The ground grid.
    pub const GRID: Vec3 = Vec3::new(0.32, 0.32, 0.36);
    /// The bounding box.
    pub const BOUNDS: Vec3 = Vec3::new(1.0, 0.75, 0.05);
    /// The outline of the selection.
    pub const OUTLINE: Vec3 = Vec3::new(1.0, 0.35, 0.0);
    /// The gizmo's X, Y and Z.
    pub const AXES: [Vec3; 3] = [
        Vec3::new(0.9, 0.08, 0.05),
        Vec3::new(0.1, 0.75, 0.1),
        Vec3::new(0.1, 0.3, 1.0),
    ];
}

pub(super) use outline::reach as outline_reach;

/// The surface hits of a strip's samples and of rows beyond it: `above` rows over its top, then
/// its own rows, then any below, all of the strip's width.
pub(super) struct GrownHits<'a> {
    pub hits: &'a [SurfaceHit],
    /// Rows of `hits` above the strip's first row.
    pub above: usize,
}

/// Draws `overlays` over `canvas` (one strip's samples), whose surfaces, with those of the rows
/// around it, are `hits`.
pub(super) fn draw_overlays(
    overlays: &Overlays,
    world: &World,
    hits: &GrownHits,
    canvas: &mut Canvas,
) {
    if overlays.grid
        && let Some(grid) = ground_grid(world)
    {
        grid.draw(canvas);
    }
    if overlays.outline {
        outline::draw(overlays.selected, hits, canvas);
    }
    if overlays.bbox
        && let Some(bounds) = overlay_bounds(world, overlays.selected)
    {
        bounds_box::draw(bounds, canvas);
    }
    if overlays.axes {
        gizmo::draw(canvas);
    }
}

/// Writes the bounding box's lengths into the finished `frame` (rendered through `camera`), when
/// `overlays` ask for them and the frame is high enough to read them.
pub(super) fn draw_labels(overlays: &Overlays, world: &World, camera: &Camera, frame: &mut Frame) {
    if !(overlays.bbox && overlays.labels) || frame.height < dimensions::MIN_HEIGHT {
        return;
    }
    let Some(bounds) = overlay_bounds(world, overlays.selected) else {
        return;
    };
    let view = View::new(camera, frame.width, frame.height);
    let text_height = (frame.height / 36).clamp(11, 40);
    dimensions::draw(&dimensions::labels(bounds, &view), text_height, frame);
}
