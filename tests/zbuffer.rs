//! The Z-buffer renderers: known answers, Gouraud/Phong agreement, watertight coverage,
//! near-plane clipping and thread-count determinism.

mod common;

use glam::{Affine3A, Quat, Vec3};
use rastray::mesh::{FaceList, with_normals};
use rastray::render::raster::fragments::Fragments;
use rastray::render::raster::zbuffer::coverage_counts;
use rastray::render::simd::lane_vec::V3;
use rastray::render::{Algorithm, View};
use rastray::world::WorldObject;
use rastray::{World, scene::Material};

/// A 2×2 square facing the camera (a thin box split in 2×2 so that a vertex sits at the centre),
/// camera and one light both 5 units in front of it on the axis.
const HEAD_ON: &str = r#"
ambient = 0.1
background = [0.0, 0.0, 0.0]
[camera]
position = [0.0, 0.0, 5.0]
target = [0.0, 0.0, 0.0]
fov = 40.0
[[light]]
position = [0.0, 0.0, 5.0]
intensity = 1.0
[[object]]
type = "box"
center = [0.0, 0.0, -0.05]
size = [2.0, 2.0, 0.1]
segments = 2
material = { color = [0.4, 0.2, 0.1], diffuse = 0.5, specular = 0.25, shininess = 10.0 }
"#;

#[test]
fn square_lit_head_on_has_the_analytic_colour_at_its_centre() {
    // At the centre N = L = V = +Z, so N·L = 1 and R·V = 1:
    // C = Ia·color + I·(Kd·color + Ks) per channel.
    let expected = Vec3::new(0.4, 0.2, 0.1) * (0.1 + 0.5) + Vec3::splat(0.25);
    for algorithm in [Algorithm::Gouraud, Algorithm::Phong] {
        // 33×33: the centre pixel's centre lies exactly on the view axis.
        let frame = common::draw(&common::scene(HEAD_ON), algorithm, 33, 33);
        let got = frame.pixel(16, 16);
        // Tolerance: f32 rounding only.
        assert!(
            (got - expected).abs().max_element() < 1e-4,
            "{algorithm}: got {got}, expected {expected}"
        );
        // The corner pixel is background: the square does not fill the view.
        assert_eq!(frame.pixel(0, 0), Vec3::ZERO, "{algorithm}");
    }
}

#[test]
fn gouraud_equals_phong_on_a_flat_face_under_a_distant_light() {
    let toml = r#"
ambient = 0.05
background = [0.0, 0.0, 0.0]
[camera]
position = [0.0, 0.0, 6.0]
target = [0.0, 0.0, 0.0]
[[light]]
position = [300.0, 500.0, 1000.0]
[[object]]
type = "box"
center = [0.0, 0.0, 0.0]
size = [3.0, 2.0, 0.2]
segments = 3
rotation = [10.0, 35.0, 0.0]
material = { color = [0.9, 0.6, 0.3], diffuse = 0.9, specular = 0.0 }
"#;
    let scene = common::scene(toml);
    let gouraud = common::draw(&scene, Algorithm::Gouraud, 120, 90);
    let phong = common::draw(&scene, Algorithm::Phong, 120, 90);
    let mut covered = 0;
    for (g, p) in gouraud.pixels.iter().zip(&phong.pixels) {
        // A light 1,000 units away changes N·L by well under 1e-3 across a 3-unit face, so the
        // vertex-lit and pixel-lit colours agree to that tolerance.
        assert!(
            (*g - *p).abs().max_element() < 1e-3,
            "gouraud {g} vs phong {p}"
        );
        covered += (*g != Vec3::ZERO) as usize;
    }
    assert!(
        covered > 1000,
        "the face covers a good part of the image ({covered} pixels)"
    );
}

/// A world holding one flat face split into `segments`² quads, rotated about the view axis.
fn tessellated_square(segments: u32, angle_degrees: f32) -> World {
    let mut face = FaceList::default();
    face.quad(
        Vec3::new(-1.5, -1.5, 0.0),
        Vec3::X * 3.0,
        Vec3::Y * 3.0,
        segments,
    );
    let mesh = with_normals(&face.positions, &face.triangles, false).transformed(
        Affine3A::from_quat(Quat::from_rotation_z(angle_degrees.to_radians())),
    );
    let bounds = mesh.bounding_sphere();
    World {
        objects: vec![WorldObject {
            mesh,
            material: Material::default(),
            bounds,
        }],
        lights: vec![],
        ambient: 1.0,
        background: Vec3::ZERO,
        max_depth: 0,
        falloff: Default::default(),
    }
}

/// Whether `p` is inside the convex polygon `poly` (either winding) by at least `margin` pixels.
fn inside_by(poly: &[glam::Vec2], p: glam::Vec2, margin: f32) -> bool {
    let n = poly.len();
    let signed: Vec<f32> = (0..n)
        .map(|i| {
            let (a, b) = (poly[i], poly[(i + 1) % n]);
            let e = b - a;
            (e.x * (p.y - a.y) - e.y * (p.x - a.x)) / e.length()
        })
        .collect();
    signed.iter().all(|&d| d > margin) || signed.iter().all(|&d| d < -margin)
}

#[test]
fn a_finely_tessellated_face_covers_every_pixel_exactly_once() {
    for (segments, angle) in [(16, 17.3), (33, 41.0), (7, 0.0)] {
        let world = tessellated_square(segments, angle);
        let camera = rastray::scene::Camera {
            position: Vec3::new(0.0, 0.0, 5.0),
            ..Default::default()
        };
        let view = View::new(&camera, 160, 120);
        let counts = coverage_counts(&world, &view);
        let corners: Vec<glam::Vec2> = [(-1.5, -1.5), (1.5, -1.5), (1.5, 1.5), (-1.5, 1.5)]
            .iter()
            .map(|&(x, y)| {
                let p = Quat::from_rotation_z(angle.to_radians()) * Vec3::new(x, y, 0.0);
                view.clip_to_pixel(view.to_clip(p))
            })
            .collect();
        let (mut inside, mut total) = (0, 0);
        for y in 0..view.height {
            for x in 0..view.width {
                let count = counts[(y * view.width + x) as usize];
                let centre = glam::Vec2::new(x as f32 + 0.5, y as f32 + 0.5);
                assert!(
                    count <= 1,
                    "pixel ({x}, {y}) written {count} times: a double write on a shared edge"
                );
                if inside_by(&corners, centre, 1e-3) {
                    assert_eq!(
                        count, 1,
                        "pixel ({x}, {y}) inside the face was never written: a crack"
                    );
                    inside += 1;
                }
                if !inside_by(&corners, centre, -1e-3) {
                    assert_eq!(count, 0, "pixel ({x}, {y}) outside the face was written");
                }
                total += count;
            }
        }
        assert!(inside > 3000, "the face covers many pixels ({inside})");
        assert!(total >= inside);
    }
}

#[test]
fn a_closed_icosahedron_covers_each_inner_pixel_exactly_twice() {
    // Front and back faces both cover each pixel inside the silhouette: no more, no fewer.
    let scene = common::scene(
        r#"
[camera]
position = [0.3, 0.2, 4.0]
[[object]]
type = "icosahedron"
radius = 1.0
subdivisions = 3
"#,
    );
    let world = common::world(&scene);
    let view = View::new(&scene.camera, 120, 100);
    let counts = coverage_counts(&world, &view);
    let twice = counts.iter().filter(|&&c| c == 2).count();
    assert!(
        counts.iter().all(|&c| c == 0 || c == 2),
        "some pixel was covered once or three times"
    );
    assert!(twice > 1500, "the icosahedron covers many pixels ({twice})");
}

#[test]
fn a_camera_inside_a_box_sees_its_inner_walls_at_the_right_depth() {
    // The camera sits inside a 4×3×5 box, near one wall, looking toward a corner: every wall
    // triangle behind the camera must be clipped at the near plane, and every pixel must show the
    // wall that the primary ray through its centre hits first.
    let toml = r#"
background = [1.0, 0.0, 1.0]
[camera]
position = [0.5, 0.2, 1.9]
target = [1.5, 1.0, -2.0]
fov = 100.0
[[light]]
position = [0.0, 0.0, 0.0]
[[object]]
type = "box"
size = [4.0, 3.0, 5.0]
material = { color = [0.5, 0.5, 0.5] }
"#;
    let scene = common::scene(toml);
    let frame = common::draw(&scene, rastray::Algorithm::Phong, 64, 48);
    let half = Vec3::new(2.0, 1.5, 2.5);
    let view = View::new(&scene.camera, 64, 48);
    for y in 0..48 {
        for x in 0..64 {
            let c = frame.pixel(x, y);
            assert!(c.is_finite(), "pixel ({x}, {y}) is {c}");
            assert_ne!(
                c,
                Vec3::new(1.0, 0.0, 1.0),
                "pixel ({x}, {y}) shows the background: a hole"
            );
        }
    }
    // Depth check against the analytic exit distance of each ray from the box.
    let world = common::world(&scene);
    let normals: Vec<&[Vec3]> = world.objects.iter().map(|o| &o.mesh.normals[..]).collect();
    let progress = rastray::render::Progress::new();
    let mut drawn = vec![Vec3::NAN; 64 * 48];
    let write_depth = |fragments: &Fragments, row: &mut [Vec3]| {
        let depth = fragments.depth;
        fragments.write(V3::new(depth, depth, depth), row)
    };
    rastray::render::raster::zbuffer::draw(
        &world,
        &view,
        &progress,
        &normals,
        write_depth,
        &mut drawn,
    )
    .expect("draw");
    let depths: Vec<f32> = drawn.iter().map(|d| d.x).collect();
    for y in 0..48u32 {
        for x in 0..64u32 {
            let d = view.ray_direction(x as f32 + 0.5, y as f32 + 0.5);
            let o = view.eye;
            let t = [0, 1, 2]
                .iter()
                .map(|&k| {
                    if d[k] > 0.0 {
                        (half[k] - o[k]) / d[k]
                    } else {
                        (-half[k] - o[k]) / d[k]
                    }
                })
                .fold(f32::INFINITY, f32::min);
            let expected = t * d.dot(view.forward);
            let got = depths[(y * 64 + x) as usize];
            assert!(
                (got - expected).abs() < 1e-3 * expected,
                "pixel ({x}, {y}): depth {got}, expected {expected}"
            );
        }
    }
}

#[test]
fn one_and_two_threads_give_the_same_bytes() {
    let scene = common::default_scene();
    for algorithm in [Algorithm::Gouraud, Algorithm::Phong] {
        let render_on = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .expect("pool");
            pool.install(|| common::draw(&scene, algorithm, 203, 117))
        };
        let (one, two) = (render_on(1), render_on(2));
        let bits = |f: &rastray::Frame| {
            f.pixels
                .iter()
                .flat_map(|p| p.to_array().map(f32::to_bits))
                .collect::<Vec<_>>()
        };
        assert_eq!(
            bits(&one),
            bits(&two),
            "{algorithm} differs between 1 and 2 threads"
        );
        assert_eq!(one.to_srgb8(), two.to_srgb8());
    }
}

#[test]
fn supersampling_averages_the_samples_of_each_pixel() {
    let scene = common::default_scene();
    let world = common::world(&scene);
    let options = rastray::RenderOptions {
        samples: 3,
        ..rastray::RenderOptions::new(Algorithm::Phong, 40, 30)
    };
    let progress = rastray::render::Progress::new();
    let smooth = rastray::render(&world, &scene.camera, &options, &progress).expect("render");
    let big = common::draw(&scene, Algorithm::Phong, 120, 90);
    assert_eq!((smooth.width, smooth.height), (40, 30));
    for (x, y) in [(0, 0), (13, 17), (39, 29), (20, 12)] {
        let mut sum = Vec3::ZERO;
        for sy in 0..3 {
            for sx in 0..3 {
                sum += big.pixel(x * 3 + sx, y * 3 + sy);
            }
        }
        assert!((smooth.pixel(x, y) - sum / 9.0).abs().max_element() < 1e-5);
    }
}

#[test]
fn strips_rendered_separately_join_into_the_whole_image() {
    // Large and supersampled images are rendered in horizontal strips; a strip must be exactly
    // the same rows of the whole render.
    let scene = common::default_scene();
    let world = common::world(&scene);
    let whole = View::new(&scene.camera, 160, 97);
    let progress = rastray::render::Progress::new();
    for algorithm in [Algorithm::Gouraud, Algorithm::Phong] {
        let draw = |view: &View| {
            match algorithm {
                Algorithm::Gouraud => {
                    rastray::render::raster::gouraud::render(&world, view, &progress)
                }
                _ => rastray::render::raster::phong::render(&world, view, &progress),
            }
            .expect("render")
        };
        let reference = draw(&whole);
        let mut joined = Vec::new();
        for (first, rows) in [(0, 40), (40, 1), (41, 56)] {
            joined.extend(draw(&whole.rows(first, rows)).pixels);
        }
        let differing = reference
            .pixels
            .iter()
            .zip(&joined)
            .filter(|(a, b)| a != b)
            .count();
        assert_eq!(
            differing, 0,
            "{algorithm}: {differing} pixels differ between strips and the whole"
        );
    }
}
