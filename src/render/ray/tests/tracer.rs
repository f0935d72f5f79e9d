//! Reflected rays traced as packets against the same rays traced one by one: between facing
//! mirrors, with shadows, down to the depth limit, every lane must get the bits and the ray
//! counts its ray gets alone, whichever lanes take part. And the surface of a flat-shaded
//! triangle, taken from the BVH's copy of it, against the one its mesh corners give.

use std::path::Path;

use glam::Vec3;
use proptest::prelude::*;

use super::bvh::{direction, point};
use crate::render::options::RenderOptions;
use crate::render::progress::Progress;
use crate::render::ray::accel::SceneAccel;
use crate::render::ray::half_line::Ray;
use crate::render::ray::packet::RayPacket;
use crate::render::ray::tracer::Tracer;
use crate::render::simd::{F32x8, V3, WIDTH};
use crate::render::{Algorithm, RayCounts};
use crate::scene::from_toml_str;
use crate::world::World;

/// Two mirrors facing each other across an icosahedron that reflects too, a matte box, and two
/// lights: rays bounce several times, some escape, some are shadowed. The boxes are flat-shaded
/// and the icosahedron smooth, so a packet mixes both ways of finding a surface.
const HALL_OF_MIRRORS: &str = r#"
ambient = 0.1
background = [0.2, 0.3, 0.4]
max_depth = 5
[camera]
position = [0.0, 0.0, 6.0]
target = [0.0, 0.0, 0.0]
[[light]]
position = [1.0, 4.0, 2.0]
[[light]]
position = [-2.0, -1.0, 3.0]
intensity = 0.5
[[object]]
type = "box"
name = "left mirror"
center = [-3.0, 0.0, 0.0]
size = [0.2, 6.0, 6.0]
material = { color = [0.2, 0.2, 0.2], diffuse = 0.2, specular = 0.5, reflection = 0.8 }
[[object]]
type = "box"
name = "right mirror"
center = [3.0, 0.3, 0.0]
size = [0.2, 6.0, 6.0]
material = { color = [0.3, 0.2, 0.1], diffuse = 0.3, specular = 0.2, reflection = 0.6 }
[[object]]
type = "icosahedron"
name = "ball"
center = [0.0, 0.0, 0.0]
radius = 1.0
subdivisions = 2
smooth = true
material = { color = [0.9, 0.1, 0.1], diffuse = 0.7, specular = 0.4, shininess = 16.0, reflection = 0.3 }
[[object]]
type = "box"
name = "block"
center = [0.5, -2.0, 1.0]
size = [1.0, 1.0, 1.0]
material = { color = [0.1, 0.8, 0.2], diffuse = 0.8, specular = 0.0 }
"#;

/// The world of [`HALL_OF_MIRRORS`] and its acceleration structure.
fn hall_of_mirrors() -> (World, SceneAccel) {
    let scene = from_toml_str(HALL_OF_MIRRORS, Path::new("hall.toml")).expect("valid scene");
    let world = World::build(&scene, Path::new(".")).expect("world");
    let accel = SceneAccel::build(&world, &Progress::new()).expect("not cancelled");
    (world, accel)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 128, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn a_packet_with_its_reflections_gives_each_lane_what_its_ray_gives_alone(
        rays in prop::collection::vec((point(2.5), direction()), WIDTH),
        lanes in 1u32..(1 << WIDTH),
        shadows in any::<bool>(),
    ) {
        let (world, accel) = hall_of_mirrors();
        let options = RenderOptions { shadows, ..RenderOptions::new(Algorithm::Ray, 8, 8) };
        let tracer = Tracer::new(&accel, &world, &options);

        let packet = RayPacket::new(
            V3::<F32x8>::gather(&std::array::from_fn::<Vec3, WIDTH, _>(|k| rays[k].0)),
            V3::<F32x8>::gather(&std::array::from_fn::<Vec3, WIDTH, _>(|k| rays[k].1)),
            F32x8::ZERO,
        );
        let mut together = RayCounts::default();
        let colours = tracer.trace_lanes(&packet, lanes, 0, &[0.0; WIDTH], &mut together);

        let mut alone = RayCounts::default();
        for (k, &(origin, dir)) in rays.iter().enumerate() {
            let expected = if lanes & 1 << k != 0 {
                tracer.trace(&Ray::new(origin, dir), 0.0, 0, 0.0, &mut alone)
            } else {
                world.background
            };
            prop_assert_eq!(colours[k].to_array().map(f32::to_bits), expected.to_array().map(f32::to_bits), "lane {}", k);
        }
        prop_assert_eq!(together, alone);
    }
}

/// The scene above does send rays through several reflections, so the test covers them.
#[test]
fn the_hall_of_mirrors_reflects_rays_more_than_once() {
    let (world, accel) = hall_of_mirrors();
    let tracer = Tracer::new(&accel, &world, &RenderOptions::new(Algorithm::Ray, 8, 8));
    let mut counts = RayCounts::default();
    // Sideways, between the mirrors: each ray bounces to the depth limit.
    let origins = V3::<F32x8>::gather(&std::array::from_fn::<Vec3, WIDTH, _>(|k| {
        Vec3::new(0.0, 2.0, -2.5 + 0.1 * k as f32)
    }));
    let dirs = V3::<F32x8>::gather(&std::array::from_fn::<Vec3, WIDTH, _>(|k| {
        Vec3::new(1.0, 0.002 * k as f32, 0.0).normalize()
    }));
    tracer.trace_lanes(
        &RayPacket::new(origins, dirs, F32x8::ZERO),
        0xff,
        0,
        &[0.0; WIDTH],
        &mut counts,
    );
    assert_eq!(
        counts.reflection,
        8 * 5,
        "eight rays, five reflections each: {counts:?}"
    );
}

/// On a flat-shaded mesh the tracer reads the surface from the BVH's copy of the triangle hit
/// (v0 + u·e1 + v·e2, and the face normal) rather than from the mesh: it must be the surface the
/// mesh corners give, to within rounding, and lift secondary rays to the same side.
#[test]
fn a_flat_triangle_read_from_the_bvh_has_the_surface_of_its_mesh_corners() {
    let (world, accel) = hall_of_mirrors();
    let tracer = Tracer::new(&accel, &world, &RenderOptions::new(Algorithm::Ray, 8, 8));
    let (mut flat, mut smooth) = (0, 0);
    for i in 0..40 {
        for j in 0..40 {
            // From the camera over the whole scene, and from inside the hall sideways.
            let (origin, target) = if (i + j) % 2 == 0 {
                (
                    Vec3::new(0.0, 0.0, 6.0),
                    Vec3::new(-4.0 + 0.2 * i as f32, -4.0 + 0.2 * j as f32, 0.0),
                )
            } else {
                (
                    Vec3::new(0.0, 0.5, 1.5),
                    Vec3::new(
                        if i % 4 == 1 { 3.0 } else { -3.0 },
                        -3.0 + 0.15 * j as f32,
                        -2.0 + 0.1 * i as f32,
                    ),
                )
            };
            let dir = (target - origin).normalize();
            let Some(hit) = accel.intersect(&Ray::new(origin, dir), 0.0, f32::INFINITY) else {
                continue;
            };
            let mesh = &world.objects[hit.object as usize].mesh;
            let Some(face) = tracer.face(hit.object, hit.slot) else {
                assert!(!mesh.flat, "a flat mesh's triangle is read from the BVH");
                smooth += 1;
                continue;
            };
            assert!(mesh.flat, "a smooth mesh's surface comes from its corners");
            let abc = mesh.triangles[hit.triangle as usize];
            let from_mesh = tracer.surface_at(&tracer.corners(hit.object, abc), hit.u, hit.v, dir);
            let from_bvh = tracer.face_surface(face, hit.u, hit.v, dir);
            // Positions within a few units in the last place of the scene's coordinates (≤ 6).
            assert!(
                from_bvh.p.distance(from_mesh.p) < 4.0e-6,
                "{:?} against {:?}",
                from_bvh.p,
                from_mesh.p
            );
            assert!(
                from_bvh.n.distance(from_mesh.n) < 1.0e-6,
                "{:?} against {:?}",
                from_bvh.n,
                from_mesh.n
            );
            let lift = |s: &crate::render::ray::tracer::Surface| (s.origin - s.p).dot(dir);
            assert!(
                lift(&from_bvh) < 0.0 && lift(&from_mesh) < 0.0,
                "lifted back toward the ray's origin"
            );
            assert!(from_bvh.origin.distance(from_mesh.origin) < 4.0e-6);
            flat += 1;
        }
    }
    assert!(
        flat > 300 && smooth > 20,
        "both kinds hit: {flat} flat, {smooth} smooth"
    );
}
