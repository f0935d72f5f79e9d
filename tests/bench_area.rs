//! The figures the benchmark records (face counts, total projected face area) against values
//! worked out by hand, and the analysis of crossovers against hand-made series.

use std::path::Path;

use glam::Vec3;
use rastray::bench::analysis::{compare, geometric_mean, value_at};
use rastray::bench::experiments::{
    Experiment, REFERENCE_PIXELS, faces_scene, faces_scene_face_count, points, scene_area,
};
use rastray::bench::runner::summarize;
use rastray::bench::{face_count, total_face_area};
use rastray::mesh::Mesh;
use rastray::render::{Algorithm, Size, View};
use rastray::scene::{Camera, Material, Object, Scene, Shape};
use rastray::world::{World, WorldObject};

/// A camera at the origin looking down −Z with a 90° field of view: at distance d the image
/// spans [−d, d] vertically, so on a W-pixel-high square image one world unit at distance d
/// covers W / (2d) pixels.
fn camera() -> Camera {
    Camera {
        position: Vec3::ZERO,
        target: -Vec3::Z,
        up: Vec3::Y,
        fov: 90.0,
        ..Camera::default()
    }
}

/// A world holding one flat quad with corners `lo` and `hi` (x, y) at depth z.
fn quad_world(lo: (f32, f32), hi: (f32, f32), z: f32) -> World {
    let positions = vec![
        Vec3::new(lo.0, lo.1, z),
        Vec3::new(hi.0, lo.1, z),
        Vec3::new(hi.0, hi.1, z),
        Vec3::new(lo.0, hi.1, z),
    ];
    let mesh = Mesh {
        normals: vec![Vec3::Z; 4],
        positions,
        triangles: vec![[0, 1, 2], [0, 2, 3]],
        colors: None,
        uvs: None,
        flat: false,
    };
    world_of(vec![WorldObject::new(mesh, Material::default())])
}

fn world_of(objects: Vec<WorldObject>) -> World {
    World {
        objects,
        lights: Vec::new(),
        ambient: 0.1,
        background: Vec3::ZERO,
        max_depth: 0,
        falloff: Default::default(),
    }
}

fn scene_of(objects: Vec<Object>) -> Scene {
    Scene {
        camera: camera(),
        objects,
        ..Scene::default()
    }
}

#[test]
fn a_square_facing_the_camera_covers_its_side_squared_in_pixels() {
    // Side 1 at distance 2 on a 100×100 image: 1 · 100 / (2·2) = 25 pixels a side.
    let world = quad_world((-0.5, -0.5), (0.5, 0.5), -2.0);
    let view = View::new(&camera(), 100, 100);
    let area = total_face_area(&world, &view);
    assert!((area - 625.0).abs() < 0.01, "area {area}");
    assert_eq!(face_count(&world), 2);
}

#[test]
fn a_face_partly_off_screen_counts_only_its_visible_part() {
    // At distance 2 the image spans x in [−2, 2]; the quad runs from x = 0 to x = 10, so only
    // x in [0, 2] shows: 50 pixels wide and 1 · 100 / 4 = 25 pixels high.
    let world = quad_world((0.0, -0.5), (10.0, 0.5), -2.0);
    let view = View::new(&camera(), 100, 100);
    let area = total_face_area(&world, &view);
    assert!((area - 1250.0).abs() < 0.01, "area {area}");
}

#[test]
fn a_face_behind_the_eye_counts_nothing_and_one_through_it_is_clipped() {
    let behind = quad_world((-0.5, -0.5), (0.5, 0.5), 2.0);
    let view = View::new(&camera(), 100, 100);
    assert_eq!(total_face_area(&behind, &view), 0.0);
    // A floor running from behind the eye to far in front: finite, at most the lower half image.
    let mesh = Mesh {
        positions: vec![
            Vec3::new(-50.0, -1.0, 5.0),
            Vec3::new(50.0, -1.0, 5.0),
            Vec3::new(50.0, -1.0, -50.0),
            Vec3::new(-50.0, -1.0, -50.0),
        ],
        normals: vec![Vec3::Y; 4],
        triangles: vec![[0, 1, 2], [0, 2, 3]],
        colors: None,
        uvs: None,
        flat: false,
    };
    let floor = world_of(vec![WorldObject::new(mesh, Material::default())]);
    let area = total_face_area(&floor, &view);
    assert!(area > 4000.0 && area <= 5000.0 + 1e-6, "area {area}");
}

#[test]
fn a_box_of_12_faces_covers_twice_its_front_face() {
    // A cube of side 2 centred 5 units away: its front face, 4 units away, is 2 · 100 / 8 = 25
    // pixels a side. Seen from outside, a closed convex surface covers each pixel of its outline
    // twice (front and back faces), and its outline is the front face: 2 · 625 pixels.
    let cube = Object::new(Shape::Box {
        center: Vec3::new(0.0, 0.0, -5.0),
        size: Vec3::splat(2.0),
        segments: 1,
    });
    let scene = scene_of(vec![cube]);
    let world = World::build(&scene, Path::new(".")).unwrap();
    assert_eq!(face_count(&world), 12);
    let area = total_face_area(&world, &View::new(&camera(), 100, 100));
    assert!((area - 1250.0).abs() < 0.01, "area {area}");
}

#[test]
fn segments_add_faces_without_changing_the_area() {
    let box_with = |segments| {
        let scene = scene_of(vec![Object::new(Shape::Box {
            center: Vec3::new(0.3, -0.2, -5.0),
            size: Vec3::new(2.0, 1.0, 1.5),
            segments,
        })]);
        let world = World::build(&scene, Path::new(".")).unwrap();
        (
            face_count(&world),
            total_face_area(&world, &View::new(&camera(), 160, 120)),
        )
    };
    let (faces1, area1) = box_with(1);
    let (faces5, area5) = box_with(5);
    assert_eq!((faces1, faces5), (12, 12 * 25));
    assert!((area1 - area5).abs() < 1e-3 * area1, "{area1} vs {area5}");
}

#[test]
fn icosahedron_subdivisions_give_20_times_4_to_the_k_faces() {
    for (k, expected) in [(0, 20), (1, 80), (2, 320), (3, 1280)] {
        let scene = scene_of(vec![Object::new(Shape::Icosahedron {
            center: Vec3::new(0.0, 0.0, -5.0),
            radius: 1.0,
            subdivisions: k,
        })]);
        let world = World::build(&scene, Path::new(".")).unwrap();
        assert_eq!(face_count(&world), expected, "k = {k}");
    }
}

#[test]
fn the_face_sweep_scene_has_the_stated_face_count() {
    // k = 2, s = 3: 20·16 + 12·9 + 8·9 = 320 + 108 + 72 = 500.
    assert_eq!(faces_scene_face_count(2, 3), 500);
    let world = World::build(&faces_scene(2, 3, 1.0), Path::new(".")).unwrap();
    assert_eq!(face_count(&world), 500);
}

#[test]
fn the_sweeps_span_the_studys_range_at_full_hd() {
    let size = Size {
        width: 1920,
        height: 1080,
    };
    let area: Vec<f64> = points(Experiment::Area, size, true)
        .iter()
        .map(|p| scene_area(&p.scene, size))
        .collect();
    assert!((area[0] - 0.1e6).abs() < 0.01e6, "first {}", area[0]);
    assert!(*area.last().unwrap() >= 8.0e6, "last {:?}", area.last());
    assert!(area.windows(2).all(|w| w[0] < w[1]), "{area:?}");

    let faces = points(Experiment::Faces, size, true);
    let worlds: Vec<World> = [faces.first().unwrap(), faces.last().unwrap()]
        .iter()
        .map(|p| World::build(&p.scene, Path::new(".")).unwrap())
        .collect();
    assert_eq!(face_count(&worlds[0]), 40);
    assert!(face_count(&worlds[1]) >= 1_000_000);
    let view = View::new(&faces[0].scene.camera, 1920, 1080);
    let (a0, a1) = (
        total_face_area(&worlds[0], &view),
        total_face_area(&worlds[1], &view),
    );
    assert!((a0 - 2.0e6).abs() < 0.02e6, "{a0}");
    assert!((a1 - a0).abs() < 0.02 * a0, "{a0} vs {a1}");
    assert!((REFERENCE_PIXELS - 1920.0 * 1080.0).abs() < 1e-9);
}

#[test]
fn summaries_take_the_middle_value() {
    use std::time::Duration;
    let ms = |v: &[u64]| {
        v.iter()
            .map(|&m| Duration::from_millis(m))
            .collect::<Vec<_>>()
    };
    assert_eq!(summarize(&ms(&[30, 10, 20])), (20.0, 10.0, 30.0));
    assert_eq!(summarize(&ms(&[40, 10, 20, 30])), (25.0, 10.0, 40.0));
}

#[test]
fn crossings_are_interpolated_between_points() {
    // First: flat 10 ms; second: 5 ms at x = 0 rising to 15 ms at x = 2. The first is slower,
    // then equal at x = 1, then faster.
    let a = vec![(0.0, 10.0), (2.0, 10.0)];
    let b = vec![(0.0, 5.0), (2.0, 15.0)];
    let c = compare(Algorithm::Ray, &a, Algorithm::Gouraud, &b);
    assert!(!c.first_faster_at_start);
    assert_eq!(c.crossings.len(), 1);
    assert!((c.first_ahead_beyond().unwrap() - 1.0).abs() < 1e-12);
    let none = compare(Algorithm::Ray, &b, Algorithm::Gouraud, &b);
    assert!(none.crossings.is_empty());
    assert_eq!(value_at(&b, 0.5), Some(7.5));
    assert!((geometric_mean(&[2.0, 8.0]).unwrap() - 4.0).abs() < 1e-12);
}
