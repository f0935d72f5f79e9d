//! The axis gizmo: the world's X, Y and Z as red, green and blue strokes from one point in the
//! bottom-left corner, turned as the camera sees them.

use glam::{Vec2, Vec3};

use super::canvas::Canvas;
use super::colors;

/// Length of an axis seen face-on, as a fraction of the image height.
const LENGTH: f32 = 0.08;

/// Line width, output pixels.
const WIDTH: f32 = 2.0;

/// Draws the gizmo, the axes pointing away from the viewer first so that the nearer ones cover
/// them.
pub fn draw(canvas: &mut Canvas) {
    let view = *canvas.view;
    let length = LENGTH * view.image_height as f32;
    // The corner point in the whole image, then in this strip.
    let origin = Vec2::new(1.5 * length, view.image_height as f32 - 1.5 * length)
        - Vec2::new(0.0, view.row_offset as f32);
    let mut axes: Vec<(Vec3, Vec3)> = [Vec3::X, Vec3::Y, Vec3::Z]
        .into_iter()
        .zip(colors::AXES)
        .collect();
    axes.sort_by(|a, b| b.0.dot(view.forward).total_cmp(&a.0.dot(view.forward)));
    for (axis, color) in axes {
        let on_screen = Vec2::new(axis.dot(view.right), -axis.dot(view.up));
        canvas.flat_segment(origin, origin + on_screen * length, WIDTH, color);
    }
}
