//! Ray/triangle and ray/sphere intersection on hand-made cases: centre, edges, vertices, grazing
//! and parallel rays. Expected values come from the geometry of each case.

use glam::{Vec3, Vec3A};

use crate::render::ray::half_line::Ray;
use crate::render::ray::intersect::{Triangle, ray_box, ray_sphere, segment_meets_sphere};

/// The right triangle (0,0,0), (1,0,0), (0,1,0) in the z = 0 plane.
fn unit_triangle() -> Triangle {
    Triangle::new(Vec3::ZERO, Vec3::X, Vec3::Y)
}

/// A ray straight down −z onto the plane z = 0 at (x, y).
fn down_at(x: f32, y: f32) -> Ray {
    Ray::new(Vec3::new(x, y, 5.0), -Vec3::Z)
}

#[test]
fn triangle_interior_hit_gives_distance_and_barycentrics() {
    let h = unit_triangle()
        .intersect(&down_at(0.25, 0.5), 0.0, f32::INFINITY)
        .expect("hit");
    assert!((h.t - 5.0).abs() < 1e-6, "t = {}", h.t);
    // u weighs the second vertex (1,0,0), v the third (0,1,0): the point is u·X + v·Y.
    assert!(
        (h.u - 0.25).abs() < 1e-6 && (h.v - 0.5).abs() < 1e-6,
        "{h:?}"
    );
}

#[test]
fn triangle_is_hit_from_both_sides() {
    let from_below = Ray::new(Vec3::new(0.2, 0.2, -3.0), Vec3::Z);
    let h = unit_triangle()
        .intersect(&from_below, 0.0, f32::INFINITY)
        .expect("back face hit");
    assert!((h.t - 3.0).abs() < 1e-6);
}

#[test]
fn triangle_edges_and_vertices_count_as_inside() {
    let tri = unit_triangle();
    // Points on each of the three edges, then the three corners.
    for (x, y) in [
        (0.5, 0.0),
        (0.0, 0.5),
        (0.5, 0.5),
        (0.0, 0.0),
        (1.0, 0.0),
        (0.0, 1.0),
    ] {
        let h = tri.intersect(&down_at(x, y), 0.0, f32::INFINITY);
        assert!(h.is_some(), "({x}, {y}) on the boundary should hit");
    }
}

#[test]
fn triangle_points_just_outside_miss() {
    let tri = unit_triangle();
    let e = 1e-4;
    for (x, y) in [
        (0.5, -e),
        (-e, 0.5),
        (0.5 + e, 0.5 + e),
        (-e, -e),
        (1.0 + e, 0.0),
        (0.0, 1.0 + e),
    ] {
        assert!(
            tri.intersect(&down_at(x, y), 0.0, f32::INFINITY).is_none(),
            "({x}, {y}) is outside"
        );
    }
}

#[test]
fn parallel_rays_miss_in_and_off_the_plane() {
    let tri = unit_triangle();
    // In the plane, aimed across the triangle.
    let in_plane = Ray::new(Vec3::new(-1.0, 0.25, 0.0), Vec3::X);
    assert!(tri.intersect(&in_plane, 0.0, f32::INFINITY).is_none());
    // Above the plane, parallel to it.
    let above = Ray::new(Vec3::new(-1.0, 0.25, 0.1), Vec3::X);
    assert!(tri.intersect(&above, 0.0, f32::INFINITY).is_none());
}

#[test]
fn grazing_ray_hits_at_the_right_point() {
    let tri = unit_triangle();
    // One degree above the plane, crossing z = 0 at (0.3, 0.2).
    let angle = 1.0f32.to_radians();
    let dir = Vec3::new(angle.cos(), 0.0, -angle.sin());
    let target = Vec3::new(0.3, 0.2, 0.0);
    let origin = target - dir * 2.0;
    let h = tri
        .intersect(&Ray::new(origin, dir), 0.0, f32::INFINITY)
        .expect("grazing hit");
    assert!((h.t - 2.0).abs() < 1e-4, "t = {}", h.t);
    assert!(
        (h.u - 0.3).abs() < 1e-4 && (h.v - 0.2).abs() < 1e-4,
        "{h:?}"
    );
}

#[test]
fn triangle_respects_the_t_range() {
    let tri = unit_triangle();
    let ray = down_at(0.2, 0.2);
    assert!(tri.intersect(&ray, 0.0, 4.9).is_none(), "beyond t_max");
    assert!(tri.intersect(&ray, 5.1, 10.0).is_none(), "before t_min");
    let behind = Ray::new(Vec3::new(0.2, 0.2, -1.0), -Vec3::Z);
    assert!(
        tri.intersect(&behind, 0.0, f32::INFINITY).is_none(),
        "behind the origin"
    );
}

#[test]
fn degenerate_triangle_never_hits() {
    let sliver = Triangle::new(Vec3::ZERO, Vec3::X, Vec3::X * 2.0);
    assert!(
        sliver
            .intersect(&down_at(0.5, 0.0), 0.0, f32::INFINITY)
            .is_none()
    );
}

#[test]
fn sphere_from_outside_enters_and_leaves() {
    let ray = Ray::new(Vec3::new(0.0, 0.0, 10.0), -Vec3::Z);
    let (near, far) = ray_sphere(&ray, Vec3::new(0.0, 0.0, 1.0), 2.0).expect("hit");
    assert!(
        (near - 7.0).abs() < 1e-5 && (far - 11.0).abs() < 1e-5,
        "{near} {far}"
    );
}

#[test]
fn sphere_from_inside_has_one_root_behind() {
    let ray = Ray::new(Vec3::ZERO, Vec3::X);
    let (near, far) = ray_sphere(&ray, Vec3::ZERO, 3.0).expect("inside");
    assert!(
        (near + 3.0).abs() < 1e-5 && (far - 3.0).abs() < 1e-5,
        "{near} {far}"
    );
}

#[test]
fn sphere_tangent_and_miss() {
    // A line at distance exactly r touches the sphere once.
    let tangent = Ray::new(Vec3::new(-5.0, 2.0, 0.0), Vec3::X);
    let (near, far) = ray_sphere(&tangent, Vec3::ZERO, 2.0).expect("tangent");
    assert!(
        (near - 5.0).abs() < 1e-3 && (far - 5.0).abs() < 1e-3,
        "{near} {far}"
    );
    let miss = Ray::new(Vec3::new(-5.0, 2.01, 0.0), Vec3::X);
    assert!(ray_sphere(&miss, Vec3::ZERO, 2.0).is_none());
}

#[test]
fn segment_cull_agrees_with_the_roots() {
    let ray = Ray::new(Vec3::new(0.0, 0.0, 10.0), -Vec3::Z);
    let c = Vec3::ZERO;
    assert!(segment_meets_sphere(&ray, c, 1.0, 0.0, f32::INFINITY));
    assert!(
        !segment_meets_sphere(&ray, c, 1.0, 0.0, 8.5),
        "ends before the sphere"
    );
    assert!(segment_meets_sphere(&ray, c, 1.0, 0.0, 9.5), "ends inside");
    assert!(
        !segment_meets_sphere(&ray, c, 1.0, 11.5, 20.0),
        "starts past it"
    );
    let away = Ray::new(Vec3::new(0.0, 0.0, 10.0), Vec3::Z);
    assert!(
        !segment_meets_sphere(&away, c, 1.0, 0.0, f32::INFINITY),
        "behind"
    );
    let off = Ray::new(Vec3::new(0.0, 1.5, 10.0), -Vec3::Z);
    assert!(
        !segment_meets_sphere(&off, c, 1.0, 0.0, f32::INFINITY),
        "passes beside"
    );
}

#[test]
fn box_slabs_with_axis_parallel_rays() {
    let (lo, hi) = (Vec3A::splat(-1.0), Vec3A::splat(1.0));
    // Direction with zero components: inv_dir stays finite.
    let through = Ray::new(Vec3::new(0.0, 0.0, 5.0), -Vec3::Z);
    let t = ray_box(&through, lo, hi, 0.0, f32::INFINITY).expect("hit");
    assert!((t - 4.0).abs() < 1e-6);
    let beside = Ray::new(Vec3::new(1.5, 0.0, 5.0), -Vec3::Z);
    assert!(ray_box(&beside, lo, hi, 0.0, f32::INFINITY).is_none());
    // Along a face plane: the slab test keeps it (boxes are conservative).
    let on_face = Ray::new(Vec3::new(1.0, 0.0, 5.0), -Vec3::Z);
    assert!(ray_box(&on_face, lo, hi, 0.0, f32::INFINITY).is_some());
    assert!(
        ray_box(&through, lo, hi, 0.0, 3.0).is_none(),
        "t_max before the box"
    );
}

/// A hit at the f32 t that a bound `t_max` holds is no hit, on the edge path too: there the
/// distance is worked out in f64, and one just below `t_max` rounds to it. Accepting it made a
/// tie between two objects hit at the same f32 t go to whichever came second in a search.
#[test]
fn an_edge_hit_that_rounds_to_t_max_is_not_nearer_than_t_max() {
    // The hypotenuse of a slanted triangle, met by rays from many origins: about half of
    // their f64 distances lie below their f32 rounding, which a comparison in f64 accepted.
    let tri = Triangle::new(
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(1.0, 0.0, 0.3),
        Vec3::new(0.0, 1.0, 0.7),
    );
    let mut hits = 0;
    for k in 0..2000 {
        let s = k as f32 / 2000.0;
        let on_edge = Vec3::new(1.0 - s, s, 0.3 + 0.4 * s);
        let origin = Vec3::new(0.1 + 0.37 * s, -0.2 + 0.11 * s, 4.0 + 1.7 * s);
        let ray = Ray::new(origin, (on_edge - origin).normalize());
        let Some(hit) = tri.intersect_exact(ray.origin, ray.dir, 0.0, f32::INFINITY) else {
            continue;
        };
        hits += 1;
        // The same ray bounded by its own hit's t: never a hit; bounded by the next float: the
        // same hit.
        assert!(
            tri.intersect_exact(ray.origin, ray.dir, 0.0, hit.t)
                .is_none(),
            "ray {k}: a hit at t = t_max"
        );
        let again = tri.intersect_exact(ray.origin, ray.dir, 0.0, hit.t.next_up());
        assert_eq!(
            again.map(|h| h.t.to_bits()),
            Some(hit.t.to_bits()),
            "ray {k}"
        );
    }
    // The f32 points aimed at lie on either side of the exact edge: about half are hits.
    assert!(hits > 500, "only {hits} of 2000 rays hit the triangle");
}
