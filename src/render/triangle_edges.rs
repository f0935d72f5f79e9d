//! How far a point of the image lies from the edges of a triangle, in pixels: where the display
//! modes draw the triangle edges. Worked out from the triangle and the view alone, so that the
//! Z-buffer and the ray tracer, given the same hit, draw the same line.

use glam::{DVec3, Vec3};

use super::camera::View;

/// Distance, in pixels of `view`, from the continuous pixel point (`x`, `y`) to the nearest of
/// the three lines the edges of triangle `corners` project to; +∞ for a triangle seen edge-on.
/// For a point inside the projected triangle this is its distance to the triangle's outline.
///
/// Each edge's line is the cross product of its ends in homogeneous pixel coordinates, so a
/// corner behind the eye (w < 0) still gives the right line.
pub fn edge_distance(view: &View, corners: [Vec3; 3], x: f32, y: f32) -> f32 {
    let ends = corners.map(|c| homogeneous_pixel(view, c));
    let point = DVec3::new(x as f64, y as f64, 1.0);
    (0..3)
        .filter_map(|k| {
            let line = ends[k].cross(ends[(k + 1) % 3]);
            let norm = line.x.hypot(line.y);
            (norm > 0.0).then(|| line.dot(point).abs() / norm)
        })
        .fold(f64::INFINITY, f64::min) as f32
}

/// World point `p` in homogeneous pixel coordinates (x·w, y·w, w) of `view`, as
/// [`View::clip_to_pixel`] maps clip space: dividing by w gives its pixel coordinates.
fn homogeneous_pixel(view: &View, p: Vec3) -> DVec3 {
    let clip = view.to_clip(p);
    // What x and y are divided by: w in perspective, 1 in orthographic.
    let w = view.divisor(clip) as f64;
    let c = clip.as_dvec3();
    let (width, height) = (view.width as f64, view.image_height as f64);
    DVec3::new(
        (c.x + w) * 0.5 * width,
        (w - c.y) * 0.5 * height - view.row_offset as f64 * w,
        w,
    )
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::edge_distance;
    use crate::render::camera::View;
    use crate::scene::Camera;

    #[test]
    fn a_point_beside_a_vertical_edge_is_its_horizontal_distance_away() {
        // Camera at z = 2 looking down −Z with a 90° fov on a 100×100 image: the plane z = 0
        // spans x, y in [−2, 2] over 100 pixels, 25 pixels per unit.
        let camera = Camera {
            position: Vec3::new(0.0, 0.0, 2.0),
            target: Vec3::ZERO,
            fov: 90.0,
            ..Camera::default()
        };
        let view = View::new(&camera, 100, 100);
        let triangle = [
            Vec3::new(0.0, -1.0, 0.0),
            Vec3::new(1.0, -1.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
        ];
        // x = 0 is column 50; the point (52.5, 50) is 2.5 px right of the edge x = 0 and
        // 25 px above the bottom edge y = −1 (row 75).
        let d = edge_distance(&view, triangle, 52.5, 50.0);
        assert!((d - 2.5).abs() < 1e-3, "{d}");
        // The same edge seen from a strip that starts at row 40.
        let d = edge_distance(&view.rows(40, 20), triangle, 52.5, 10.0);
        assert!((d - 2.5).abs() < 1e-3, "{d}");
    }
}
