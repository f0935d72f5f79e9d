//! The rasterizer's invariants, checked below the shaders: watertight coverage with the
//! top-left rule, near-plane clipping and the depth it keeps, and strips that join into the
//! whole image.

use std::path::Path;
use std::sync::Arc;

use glam::{Affine3A, Quat, Vec3};

use super::fragments::Fragments;
use super::setup::{Geometry, RasterScratch};
use super::shader::{Shader, VaryingColor};
use super::varying::PerVertex;
use super::zbuffer::{coverage_counts, draw};
use super::{render_gouraud, render_phong, render_phong_unpaired};
use crate::mesh::{FaceList, with_normals};
use crate::render::simd::{Lanes8, V3};
use crate::render::{Algorithm, Frame, Progress, RenderOptions, Renderer, View};
use crate::scene::{Camera, Material, Scene};
use crate::world::{World, WorldObject};

/// Parses a scene from TOML text (panics with the error: the tests' scenes are valid).
fn scene(toml: &str) -> Scene {
    crate::scene::from_toml_str(toml, Path::new("test.toml")).unwrap_or_else(|e| panic!("{e}"))
}

/// Builds the world of `scene` with OBJ paths relative to the crate root.
fn world(scene: &Scene) -> World {
    World::build(scene, Path::new(env!("CARGO_MANIFEST_DIR"))).unwrap_or_else(|e| panic!("{e}"))
}

/// The default scene file shipped in scenes/.
fn default_scene() -> Scene {
    crate::scene::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/default.toml"))
        .expect("default.toml")
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
    World {
        objects: vec![WorldObject::new(mesh, Material::default())],
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
    // 140 segments make cells of about 0.6 pixel: most triangles hold one centre or none, and are
    // tested exactly before setup.
    for (segments, angle) in [(16, 17.3), (33, 41.0), (7, 0.0), (140, 23.0)] {
        let world = tessellated_square(segments, angle);
        let camera = Camera {
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

/// A finely subdivided icosahedron (1,280 faces) seen from outside, a little off its axis.
fn closed_icosahedron() -> Scene {
    scene(
        r#"
[camera]
position = [0.3, 0.2, 4.0]
[[object]]
type = "icosahedron"
radius = 1.0
subdivisions = 3
"#,
    )
}

#[test]
fn a_closed_icosahedron_covers_each_inner_pixel_exactly_twice() {
    // Front and back faces both cover each pixel inside the silhouette: no more, no fewer.
    let scene = closed_icosahedron();
    let world = world(&scene);
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
    let scene = scene(toml);
    let mut frame = Frame::default();
    let world = Arc::new(world(&scene));
    Renderer::new(RenderOptions::new(Algorithm::Phong, 64, 48))
        .render(&world, &scene.camera, &Progress::new(), &mut frame)
        .expect("render");
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
    let mut normals = PerVertex::normals(&world);
    let progress = Progress::new();
    let mut drawn = vec![Vec3::NAN; 64 * 48];
    draw(
        &mut Geometry::default(),
        &world,
        &view,
        &progress,
        &mut normals,
        &WriteDepth,
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
fn strips_rendered_separately_join_into_the_whole_image() {
    // Large and supersampled images are rendered in horizontal strips; a strip must be exactly
    // the same rows of the whole render.
    let scene = default_scene();
    let world = world(&scene);
    let whole = View::new(&scene.camera, 160, 97);
    let progress = Progress::new();
    // One scratch for all renders, as a renderer keeps it: nothing may leak between frames.
    let mut scratch = RasterScratch::default();
    for algorithm in [Algorithm::Gouraud, Algorithm::Phong] {
        let mut draw = |view: &View| {
            let mut out = vec![Vec3::NAN; view.width as usize * view.height as usize];
            match algorithm {
                Algorithm::Gouraud => {
                    render_gouraud(&mut scratch, &world, view, &progress, &mut out)
                }
                _ => render_phong(&mut scratch, &world, view, &progress, &mut out),
            }
            .expect("render");
            out
        };
        let reference = draw(&whole);
        let mut joined = Vec::new();
        for (first, rows) in [(0, 40), (40, 1), (41, 56)] {
            joined.extend(draw(&whole.rows(first, rows)));
        }
        let differing = reference
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

/// A varying that records which triangles' corners it is asked for, and gives each triangle's
/// three corners its own index as the value: a pixel's interpolated varying then names the
/// triangle that drew it.
#[derive(Default)]
struct Recorder {
    asked: std::sync::Mutex<Vec<u32>>,
}

impl super::varying::Varying for Recorder {
    fn corners(&self, object: usize, triangles: &[u32], out: &mut Vec<[Vec3; 3]>) {
        assert_eq!(object, 0, "one object");
        self.asked.lock().expect("lock").extend(triangles);
        out.extend(triangles.iter().map(|&t| [Vec3::splat(t as f32); 3]));
    }
}

#[test]
fn only_the_triangles_a_frame_shows_have_their_varying_worked_out() {
    // A closed icosahedron: its back faces cover as many pixel centres as its front faces, and
    // all are hidden. The planes of the varying must be set up for exactly the triangles that
    // win some pixel, in every band (threads and band edges included).
    let scene = closed_icosahedron();
    let world = world(&scene);
    for (width, height) in [(160, 96), (61, 203)] {
        let view = View::new(&scene.camera, width, height);
        let mut recorder = Recorder::default();
        let mut drawn = vec![Vec3::NAN; (width * height) as usize];
        draw(
            &mut Geometry::default(),
            &world,
            &view,
            &Progress::new(),
            &mut recorder,
            &VaryingColor,
            &mut drawn,
        )
        .expect("draw");
        let shown: std::collections::BTreeSet<u32> = drawn
            .iter()
            .filter(|c| *c != &world.background)
            .map(|c| {
                let t = c.x.round();
                assert!(
                    (c.x - t).abs() < 0.01,
                    "a constant varying stays constant: {c}"
                );
                t as u32
            })
            .collect();
        let asked: std::collections::BTreeSet<u32> = recorder
            .asked
            .lock()
            .expect("lock")
            .iter()
            .copied()
            .collect();
        assert!(
            shown.len() > 200,
            "the front shows many triangles ({})",
            shown.len()
        );
        assert_eq!(
            asked, shown,
            "{width}×{height}: asked for hidden or missed shown triangles"
        );
        let triangles = world.objects[0].mesh.triangles.len();
        assert!(
            asked.len() < triangles * 6 / 10,
            "the back faces were not asked for"
        );
    }
}

/// Writes each pixel's depth w as its colour.
struct WriteDepth;

impl Shader for WriteDepth {
    fn shade<L: Lanes8>(&self, fragments: &Fragments<L>, row: &mut [Vec3]) {
        let depth = fragments.depth;
        fragments.write(V3::new(depth, depth, depth), row)
    }
}

#[test]
fn setup_compiled_for_avx2_draws_the_bits_of_the_baseline_build() {
    // Triangle setup, binning and the planes of the varying run compiled for AVX2 where the CPU
    // has it, small triangles are scanned and the rows are shaded on AVX registers, and where
    // it has AVX-512 too, Phong lights pairs of batches in 512-bit registers: the images must be
    // those of the baseline build, bit for bit, including triangles clipped at the near plane
    // and the guard band. (On a CPU without AVX2 all are the baseline.)
    use crate::render::cpu::{AVX2_AT_MOST, BASELINE_ONLY, BUILD_CHOICE};
    use std::sync::atomic::Ordering;
    let _choice = BUILD_CHOICE.lock().unwrap_or_else(|e| e.into_inner());
    let mut scenes = vec![default_scene()];
    let mut close = default_scene();
    close.camera.position = Vec3::new(0.3, 0.4, 0.9);
    close.camera.fov = 100.0;
    scenes.push(close);
    // Thousands of triangles of a few pixels each, scanned eight centres at a time on AVX2
    // registers where the CPU has them; some in front of others, some edge on.
    scenes.push(scene(
        r#"
camera = { position = [0.4, 0.3, 2.6], target = [0.0, 0.0, 0.0], fov = 45.0 }
light = [{ position = [3.0, 4.0, 5.0] }]
object = [
    { type = "icosahedron", radius = 1.0, subdivisions = 4 },
    { type = "icosahedron", center = [0.5, 0.2, -1.0], radius = 0.8, subdivisions = 3 },
]
"#,
    ));
    let progress = Progress::new();
    for scene in &scenes {
        let world = world(scene);
        let view = View::new(&scene.camera, 211, 97);
        let draw = |algorithm: Algorithm| {
            let mut out = vec![Vec3::NAN; (view.width * view.height) as usize];
            let mut scratch = RasterScratch::default();
            match algorithm {
                Algorithm::Gouraud => {
                    render_gouraud(&mut scratch, &world, &view, &progress, &mut out)
                }
                _ => render_phong(&mut scratch, &world, &view, &progress, &mut out),
            }
            .expect("render");
            out
        };
        for algorithm in [Algorithm::Gouraud, Algorithm::Phong] {
            let fastest = draw(algorithm);
            AVX2_AT_MOST.store(true, Ordering::Relaxed);
            let avx2 = draw(algorithm);
            AVX2_AT_MOST.store(false, Ordering::Relaxed);
            BASELINE_ONLY.store(true, Ordering::Relaxed);
            let baseline = draw(algorithm);
            BASELINE_ONLY.store(false, Ordering::Relaxed);
            for (build, fast) in [("widest", &fastest), ("AVX2", &avx2)] {
                let differing = fast
                    .iter()
                    .zip(&baseline)
                    .filter(|(a, b)| {
                        a.to_array().map(f32::to_bits) != b.to_array().map(f32::to_bits)
                    })
                    .count();
                assert_eq!(
                    differing, 0,
                    "{algorithm}, {build}: {differing} pixels differ"
                );
            }
            let fast = fastest;
            let covered = fast.iter().filter(|c| **c != world.background).count();
            assert!(covered > 2000, "the scene covers the view ({covered})");
        }
    }
}

/// A Z-buffer renderer's signature.
type Render = fn(
    &mut RasterScratch,
    &World,
    &View,
    &Progress,
    &mut [Vec3],
) -> Result<(), crate::render::progress::Cancelled>;

#[test]
fn phong_lights_pairs_of_batches_as_it_lights_each_alone() {
    // Phong lights the batches of eight pixels of a row two at a time (in one 512-bit register
    // where the CPU has AVX-512, else side by side): each pixel must come out as the batch
    // alone gives it. Dense spheres, so that most batches are packed from short runs of
    // several triangles, and a close flat face whose long spans make whole batches.
    use crate::render::cpu::{AVX2_AT_MOST, BASELINE_ONLY, BUILD_CHOICE};
    use std::sync::atomic::Ordering;
    let _choice = BUILD_CHOICE.lock().unwrap_or_else(|e| e.into_inner());
    let spheres = scene(
        r#"
camera = { position = [0.4, 0.3, 2.6], target = [0.0, 0.0, 0.0], fov = 45.0 }
light = [{ position = [3.0, 4.0, 5.0] }, { position = [-2.0, 1.0, 3.0], intensity = 0.5 }]
object = [
    { type = "icosahedron", radius = 1.0, subdivisions = 4, material = { color = [0.9, 0.5, 0.2], specular = 0.8, shininess = 20.0 } },
    { type = "icosahedron", center = [0.5, 0.2, -1.0], radius = 0.8, subdivisions = 3 },
    { type = "box", center = [0.0, 0.0, -2.0], size = [6.0, 4.0, 0.1], material = { color = [0.3, 0.6, 0.9] } },
]
"#,
    );
    // Textured (the Duck, the third varying) beside an untextured sphere, so that batches
    // mix textured and untextured lanes.
    let duck = scene(
        r#"
camera = { position = [1.2, 1.0, 3.0], target = [0.0, 0.0, 0.0], fov = 40.0 }
light = [{ position = [2.0, 3.0, 4.0] }]
object = [
    { type = "mesh", path = "../shared/models/gltf/Duck.glb" },
    { type = "icosahedron", center = [0.6, -0.4, 0.3], radius = 0.4, subdivisions = 3 },
]
"#,
    );
    for (name, scene) in [("spheres", spheres), ("textured Duck", duck)] {
        let world = world(&scene);
        let view = View::new(&scene.camera, 211, 97);
        let progress = Progress::new();
        let image = |render: Render| {
            let mut out = vec![Vec3::NAN; (view.width * view.height) as usize];
            render(
                &mut RasterScratch::default(),
                &world,
                &view,
                &progress,
                &mut out,
            )
            .expect("render");
            out.iter()
                .map(|c| c.to_array().map(f32::to_bits))
                .collect::<Vec<_>>()
        };
        for (build, flag) in [
            ("widest", None),
            ("AVX2", Some(&AVX2_AT_MOST)),
            ("baseline", Some(&BASELINE_ONLY)),
        ] {
            flag.inspect(|f| f.store(true, Ordering::Relaxed));
            let (paired, alone) = (image(render_phong), image(render_phong_unpaired));
            flag.inspect(|f| f.store(false, Ordering::Relaxed));
            let differing = paired.iter().zip(&alone).filter(|(a, b)| a != b).count();
            assert_eq!(differing, 0, "{name}, {build}: {differing} pixels differ");
        }
    }
}
