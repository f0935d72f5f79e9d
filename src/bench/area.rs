//! The figures the benchmark records for a scene: face count and total projected face area.
//!
//! Total face area is the study's measure of Z-buffer work: the sum, over every face, of the area
//! in pixels of the face projected onto the image, overdraw included. Back faces count too: the
//! rasterizer has no back-face culling, so it scan-converts them like any other face. Each face is
//! clipped against the near plane and the four sides of the view frustum in homogeneous space (the
//! same planes the rasterizer uses, without its guard band), so a face partly off screen counts
//! only its on-screen part and a face behind the eye counts nothing.

use glam::DVec3;

use crate::render::{NEAR, View};
use crate::world::World;

/// Number of triangles in `world`: the face count of the study.
pub fn face_count(world: &World) -> usize {
    world.triangle_count()
}

/// Sum over every triangle of `world` of its projected, clipped area on `view`'s image, in
/// square pixels (≥ 0).
pub fn total_face_area(world: &World, view: &View) -> f64 {
    world
        .objects
        .iter()
        .map(|object| {
            let placed;
            let object = match object.instance {
                Some(_) => {
                    placed = object.placed();
                    &placed
                }
                None => object,
            };
            let clip: Vec<DVec3> = object
                .mesh
                .positions
                .iter()
                .map(|&p| view.to_clip(p).as_dvec3())
                .collect();
            object
                .mesh
                .triangles
                .iter()
                .map(|t| projected_area(view, t.map(|i| clip[i as usize])))
                .sum::<f64>()
        })
        .sum()
}

/// Area in square pixels of one triangle given in clip coordinates (x, y, w), clipped to the
/// visible part of the view frustum.
fn projected_area(view: &View, triangle: [DVec3; 3]) -> f64 {
    // Each plane is "inside" where its function is ≥ 0: near, then right, left, top, bottom.
    let planes: [fn(DVec3) -> f64; 5] = [
        |p| p.z - NEAR as f64,
        |p| p.z - p.x,
        |p| p.z + p.x,
        |p| p.z - p.y,
        |p| p.z + p.y,
    ];
    let mut polygon = triangle.to_vec();
    for plane in planes {
        polygon = clip_polygon(&polygon, plane);
        if polygon.len() < 3 {
            return 0.0;
        }
    }
    // Project to continuous pixel coordinates, then the shoelace formula.
    let (w, h) = (view.width as f64, view.height as f64);
    let pixel = |c: DVec3| ((c.x / c.z + 1.0) * 0.5 * w, (1.0 - c.y / c.z) * 0.5 * h);
    let points: Vec<(f64, f64)> = polygon.iter().map(|&c| pixel(c)).collect();
    let twice: f64 = (0..points.len())
        .map(|i| {
            let (a, b) = (points[i], points[(i + 1) % points.len()]);
            a.0 * b.1 - b.0 * a.1
        })
        .sum();
    0.5 * twice.abs()
}

/// One Sutherland–Hodgman step: the part of `polygon` where `plane` ≥ 0.
fn clip_polygon(polygon: &[DVec3], plane: fn(DVec3) -> f64) -> Vec<DVec3> {
    let mut out = Vec::with_capacity(polygon.len() + 1);
    for i in 0..polygon.len() {
        let (a, b) = (polygon[i], polygon[(i + 1) % polygon.len()]);
        let (da, db) = (plane(a), plane(b));
        if da >= 0.0 {
            out.push(a);
        }
        if (da >= 0.0) != (db >= 0.0) {
            out.push(a.lerp(b, da / (da - db)));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use super::total_face_area;
    use crate::bench::experiments::area_scene;
    use crate::render::{View, coverage_counts};
    use crate::world::World;

    #[test]
    fn the_area_matches_the_pixels_the_rasterizer_covers() {
        // The rasterizer counts covered pixel centres with no depth test; over a whole scene that
        // sum approaches the analytic area, the difference coming from pixels cut by edges.
        let scene = area_scene(2.0);
        let world = World::build(&scene, Path::new(".")).expect("a built-in scene builds");
        let view = View::new(&scene.camera, 320, 240);
        let covered: u64 = coverage_counts(&world, &view)
            .iter()
            .map(|&c| c as u64)
            .sum();
        let area = total_face_area(&world, &view);
        assert!(area > 10_000.0, "area {area}");
        let error = (covered as f64 - area).abs() / area;
        assert!(error < 0.01, "covered {covered}, area {area}");
    }
}
