//! Per-vertex colours: the albedo at a point is the material colour times the vertex colour
//! interpolated there, the same in all three algorithms; Gouraud shading keeps the specular
//! colour apart from the albedo; and the files that carry colours (OBJ `v x y z r g b`, glTF
//! `COLOR_0`) are read into them.

mod common;

use std::fmt::Write;
use std::path::{Path, PathBuf};

use glam::Vec3;
use rastray::Frame;
use rastray::mesh::load_obj;
use rastray::render::{Algorithm, RenderOptions};

const ALGORITHMS: [Algorithm; 3] = [Algorithm::Gouraud, Algorithm::Phong, Algorithm::Ray];

/// Writes `text` to `name` in the test binary's scratch folder; returns its path.
fn write(name: &str, text: &str) -> PathBuf {
    let path = common::scratch().join(name);
    std::fs::write(&path, text).expect("write");
    path
}

/// A scene of one mesh object from `model` (a path), at the origin with `material`, seen from
/// (0, 0, 3), with `rest` (ambient, lights) before it.
fn scene_of(model: &Path, material: &str, rest: &str) -> rastray::Scene {
    common::scene(&format!(
        "background = [0.0, 0.0, 0.0]\n{rest}\n[camera]\nposition = [0.0, 0.0, 3.0]\n\
         target = [0.0, 0.0, 0.0]\nfov = 60.0\n[[object]]\ntype = \"mesh\"\npath = {:?}\n\
         material = {material}\n",
        model.display().to_string()
    ))
}

/// Renders `scene` with `algorithm` at `size`², without shadows or reflections.
fn render(scene: &rastray::Scene, algorithm: Algorithm, size: u32) -> Frame {
    let mut options = RenderOptions::new(algorithm, size, size);
    options.shadows = false;
    options.max_depth = Some(0);
    common::render(&common::world(scene), &scene.camera, options).0
}

#[test]
fn a_red_green_blue_triangle_shows_its_interpolated_colours_in_every_algorithm() {
    // Facing the camera, so screen-space and world-space barycentrics are equal; ambient 1 and
    // no lights: every algorithm's colour is the albedo, white × the interpolated vertex
    // colour. Pure 0 and 1 are exact through the OBJ's sRGB decode.
    let corners = [
        Vec3::new(-1.0, -1.0, 0.0),
        Vec3::new(1.0, -1.0, 0.0),
        Vec3::new(0.0, 1.0, 0.0),
    ];
    let obj = write(
        "rgb.obj",
        "v -1 -1 0 1 0 0\nv 1 -1 0 0 1 0\nv 0 1 0 0 0 1\nf 1 2 3\n",
    );
    let scene = scene_of(&obj, "{ color = [1.0, 1.0, 1.0] }", "ambient = 1.0");
    let size = 64;
    // Where the ray through the centre of pixel (i, j) meets z = 0: 3·tan(30°) per unit of NDC.
    let reach = 3.0 * 30f32.to_radians().tan();
    let weights = |i: u32, j: u32| {
        let x = (2.0 * (i as f32 + 0.5) / size as f32 - 1.0) * reach;
        let y = (1.0 - 2.0 * (j as f32 + 0.5) / size as f32) * reach;
        let [a, b, c] = corners;
        let (v0, v1, v2) = (b - a, c - a, Vec3::new(x, y, 0.0) - a);
        let d = v0.x * v1.y - v1.x * v0.y;
        let u = (v2.x * v1.y - v1.x * v2.y) / d;
        let v = (v0.x * v2.y - v2.x * v0.y) / d;
        Vec3::new(1.0 - u - v, u, v)
    };
    for algorithm in ALGORITHMS {
        let frame = render(&scene, algorithm, size);
        let mut checked = 0;
        for j in 0..size {
            for i in 0..size {
                let expected = weights(i, j);
                let got = frame.pixel(i, j);
                if expected.min_element() > 0.02 {
                    // Tolerance: f32 interpolation and the perspective divide, well under
                    // one 8-bit step.
                    assert!(
                        (got - expected).abs().max_element() < 1e-3,
                        "{algorithm} ({i}, {j}): got {got}, expected {expected}"
                    );
                    checked += 1;
                } else if expected.min_element() < -0.02 {
                    assert_eq!(got, Vec3::ZERO, "{algorithm} ({i}, {j}) is background");
                }
            }
        }
        assert!(checked > 500, "{algorithm}: {checked} pixels inside");
        // Near each corner the colour is nearly that corner's alone.
        for k in 0..3 {
            let nearly = |p: &&Vec3| p[k] > 0.8 && (0..3).all(|c| c == k || p[c] < 0.15);
            assert!(frame.pixels.iter().any(|p| nearly(&p)), "{algorithm}: {k}");
        }
    }
}

/// A unit sphere in latitude–longitude quads, `rings` × 2·`rings`, each vertex coloured by its
/// position (sRGB (p + 1)/2), as OBJ text.
fn coloured_sphere(rings: usize) -> String {
    let mut obj = String::new();
    let segments = 2 * rings;
    for r in 0..=rings {
        let theta = std::f32::consts::PI * r as f32 / rings as f32;
        for s in 0..segments {
            let phi = std::f32::consts::TAU * s as f32 / segments as f32;
            let p = Vec3::new(
                theta.sin() * phi.cos(),
                theta.cos(),
                theta.sin() * phi.sin(),
            );
            let c = (p + 1.0) * 0.5;
            writeln!(obj, "v {} {} {} {} {} {}", p.x, p.y, p.z, c.x, c.y, c.z).unwrap();
        }
    }
    let at = |r: usize, s: usize| r * segments + s % segments + 1;
    for r in 0..rings {
        for s in 0..segments {
            let (a, b, c, d) = (at(r, s), at(r, s + 1), at(r + 1, s + 1), at(r + 1, s));
            writeln!(obj, "f {a} {b} {c}\nf {a} {c} {d}").unwrap();
        }
    }
    obj
}

const TWO_LIGHTS: &str = "ambient = 0.1\n[[light]]\nposition = [-3.0, 4.0, 5.0]\nintensity = 0.8\n\
     [[light]]\nposition = [4.0, -1.0, 3.0]\nintensity = 0.4\ncolor = [0.7, 0.8, 1.0]";

#[test]
fn phong_and_the_ray_tracer_agree_on_a_vertex_coloured_sphere() {
    let obj = write("sphere.obj", &coloured_sphere(24));
    let scene = scene_of(
        &obj,
        "{ color = [0.9, 0.8, 0.7], specular = 0.4, shininess = 24.0 }",
        TWO_LIGHTS,
    );
    let phong = render(&scene, Algorithm::Phong, 160);
    let ray = render(&scene, Algorithm::Ray, 160);
    let db = common::psnr(&phong.to_srgb8(), &ray.to_srgb8());
    assert!(db >= 40.0, "PSNR {db:.2} dB < 40 dB");
    // The colours show: the sphere's left is more cyan than its right (colour follows x).
    let (left, right) = (phong.pixel(45, 80), phong.pixel(115, 80));
    assert!(
        right.x - right.z > left.x - left.z + 0.1,
        "{left} vs {right}"
    );
}

/// A flat 2×2 square in z = 0 cut into `n` × `n` quads, coloured by a smooth pattern, as OBJ.
fn coloured_square(n: usize) -> String {
    let mut obj = String::new();
    for j in 0..=n {
        for i in 0..=n {
            let (x, y) = (
                2.0 * i as f32 / n as f32 - 1.0,
                2.0 * j as f32 / n as f32 - 1.0,
            );
            let c = Vec3::new(
                0.5 + 0.5 * (3.0 * x).sin(),
                0.5 + 0.5 * y,
                0.5 - 0.4 * x * y,
            );
            writeln!(obj, "v {x} {y} 0 {} {} {}", c.x, c.y, c.z).unwrap();
        }
    }
    let at = |i: usize, j: usize| j * (n + 1) + i + 1;
    for j in 0..n {
        for i in 0..n {
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            writeln!(obj, "f {a} {b} {c}\nf {a} {c} {d}").unwrap();
        }
    }
    obj
}

#[test]
fn gouraud_and_phong_agree_on_a_finely_cut_coloured_square_under_a_distant_light() {
    // One normal everywhere and a light 1,000 units away: D is the same at every vertex, and
    // on quads 1/20 of the square wide the specular colour is nearly linear across each, so the
    // separate-specular Gouraud colour albedo ⊙ D + S matches Phong's per-pixel lighting.
    let obj = write("square.obj", &coloured_square(40));
    let scene = scene_of(
        &obj,
        "{ color = [1.0, 0.9, 0.8], specular = 0.3, shininess = 8.0 }\nrotation = [20.0, -25.0, 0.0]",
        "ambient = 0.1\n[[light]]\nposition = [300.0, 500.0, 1000.0]",
    );
    let gouraud = render(&scene, Algorithm::Gouraud, 96);
    let phong = render(&scene, Algorithm::Phong, 96);
    let mut covered = 0;
    for (g, p) in gouraud.pixels.iter().zip(&phong.pixels) {
        assert!(
            (*g - *p).abs().max_element() < 2e-3,
            "gouraud {g} vs phong {p}"
        );
        covered += usize::from(*p != Vec3::ZERO);
    }
    assert!(covered > 2000, "the square covers {covered} pixels");
    // And the pattern shows: not one flat colour.
    let spread = phong
        .pixels
        .iter()
        .filter(|p| **p != Vec3::ZERO)
        .fold((Vec3::MAX, Vec3::MIN), |(lo, hi), p| {
            (lo.min(*p), hi.max(*p))
        });
    assert!((spread.1 - spread.0).max_element() > 0.3, "{spread:?}");
}

#[test]
fn a_highlight_on_a_red_surface_stays_white() {
    // Every vertex pure red, a white light and a strong highlight: the specular colour is the
    // light's, not multiplied by the albedo, so at the highlight green and blue rise with red.
    // Gouraud keeps it apart (OpenGL's separate specular); had it lit the vertex colour in,
    // green and blue would be 0 everywhere.
    let obj = coloured_sphere(32)
        .lines()
        .map(|line| match line.strip_prefix("v ") {
            Some(rest) => {
                let xyz: Vec<&str> = rest.split(' ').take(3).collect();
                format!("v {} 1 0 0\n", xyz.join(" "))
            }
            None => format!("{line}\n"),
        })
        .collect::<String>();
    let obj = write("red.obj", &obj);
    let scene = scene_of(
        &obj,
        "{ color = [1.0, 1.0, 1.0], diffuse = 0.6, specular = 0.8, shininess = 30.0 }",
        "ambient = 0.05\n[[light]]\nposition = [2.0, 3.0, 6.0]",
    );
    for algorithm in ALGORITHMS {
        let frame = render(&scene, algorithm, 96);
        let brightest = frame
            .pixels
            .iter()
            .copied()
            .max_by(|a, b| a.y.total_cmp(&b.y))
            .expect("pixels");
        assert!(
            brightest.y > 0.4 && (brightest.y - brightest.z).abs() < 1e-3,
            "{algorithm}: the highlight is white: {brightest}"
        );
        assert!(
            brightest.x > brightest.y,
            "{algorithm}: on red: {brightest}"
        );
        // Away from the highlight the surface is red alone.
        let dim = frame.pixel(30, 60);
        assert!(dim.x > 0.04 && dim.y < 1e-3, "{algorithm}: {dim}");
    }
}

#[test]
fn box_vertex_colors_glb_renders_with_its_colours() {
    // Khronos' BoxVertexColors (CC0): COLOR_0 as float RGB. Ambient light alone shows the
    // colours as they are; the material is the default grey, so without them every pixel would
    // be grey.
    let model = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/gltf/BoxVertexColors.glb");
    let geometry = match rastray::mesh::MeshFile::load(&model).expect("loads") {
        rastray::mesh::MeshFile::Gltf(model) => model,
        other => panic!("read as {other:?}"),
    };
    assert!(geometry.parts.iter().all(|p| p.geometry.colors.is_some()));
    let mut scene = scene_of(&model, "{ color = [1.0, 1.0, 1.0] }", "ambient = 1.0");
    scene.camera.position = glam::Vec3::new(1.6, 1.3, 2.2);
    // 128² so that the odd pixel where the rasterizer's and the ray's edges part (one here)
    // weighs as little as it does in the other agreement tests.
    let frames = ALGORITHMS.map(|a| render(&scene, a, 128));
    for (algorithm, frame) in ALGORITHMS.iter().zip(&frames) {
        let shown = frame.pixels.iter().filter(|p| **p != Vec3::ZERO);
        // Distinct hues: some pixels mostly red, some mostly green, some mostly blue.
        let hue = |k: usize| {
            shown
                .clone()
                .filter(|p| (0..3).all(|c| c == k || p[k] > p[c] + 0.2))
                .count()
        };
        let (reds, greens, blues) = (hue(0), hue(1), hue(2));
        assert!(
            reds > 40 && greens > 40 && blues > 40,
            "{algorithm}: {reds} red, {greens} green, {blues} blue pixels"
        );
    }
    let db = common::psnr(&frames[1].to_srgb8(), &frames[2].to_srgb8());
    assert!(db >= 40.0, "Phong vs ray tracer: PSNR {db:.2} dB < 40 dB");
}

#[test]
fn obj_vertex_colours_are_srgb_decoded_and_kept_only_when_every_vertex_has_one() {
    let all = write(
        "all.obj",
        "v 0 0 0 1 0.5 0\nv 1 0 0 0 0 1\nv 0 1 0 0.2 0.2 0.2\nf 1 2 3\n",
    );
    let geometry = load_obj(&all).expect("loads");
    let colors = geometry.colors.expect("every vertex has a colour");
    // sRGB 0.5 is 0.214 in linear light, 0.2 is 0.0331.
    assert!(
        (colors[0] - Vec3::new(1.0, 0.2140, 0.0))
            .abs()
            .max_element()
            < 1e-4
    );
    assert_eq!(colors[1], Vec3::Z);
    assert!((colors[2] - Vec3::splat(0.03310)).abs().max_element() < 1e-4);
    let some = write(
        "some.obj",
        "v 0 0 0 1 0 0\nv 1 0 0\nv 0 1 0 0 0 1\nf 1 2 3\n",
    );
    assert_eq!(load_obj(&some).expect("loads").colors, None);
    // `v x y z w` is a homogeneous weight, not a colour.
    let weighted = write("w.obj", "v 0 0 0 1\nv 1 0 0 1\nv 0 1 0 1\nf 1 2 3\n");
    assert_eq!(load_obj(&weighted).expect("loads").colors, None);
}

#[test]
fn objects_without_colours_keep_their_bits_beside_one_with_colours() {
    // A coloured triangle hidden inside the crate switches every algorithm to its coloured path
    // for the whole world (inside, it moves neither the scene's bounds nor any pixel); the
    // objects without colours must still get exactly the bits they get in a world without any.
    let scene = common::default_scene();
    let plain = common::world(&scene);
    let mut coloured = (*plain).clone();
    let behind = rastray::mesh::Mesh {
        positions: vec![
            Vec3::new(0.4, 0.7, -0.6),
            Vec3::new(0.8, 0.7, -0.6),
            Vec3::new(0.6, 0.9, -0.6),
        ],
        normals: vec![Vec3::Z; 3],
        triangles: vec![[0, 1, 2]],
        colors: Some(vec![Vec3::X, Vec3::Y, Vec3::Z]),
        uvs: None,
        flat: true,
    };
    coloured.objects.push(rastray::world::WorldObject::new(
        behind,
        rastray::scene::Material::default(),
    ));
    let coloured = std::sync::Arc::new(coloured);
    for algorithm in ALGORITHMS {
        let mut options = RenderOptions::new(algorithm, 160, 96);
        options.max_depth = Some(0);
        let a = common::render(&plain, &scene.camera, options).0;
        let b = common::render(&coloured, &scene.camera, options).0;
        let bits = |f: &Frame| -> Vec<u32> {
            f.pixels
                .iter()
                .flat_map(|p| p.to_array().map(f32::to_bits))
                .collect()
        };
        assert!(bits(&a) == bits(&b), "{algorithm} changed");
    }
}

#[test]
fn gltf_color_0_reads_normalized_8_and_16_bit_rgba_as_linear_rgb() {
    use base64::Engine;
    // One triangle drawn twice: COLOR_0 as normalized UNSIGNED_BYTE VEC4, then as normalized
    // UNSIGNED_SHORT VEC4. glTF colours are linear: no sRGB decode; alpha is dropped.
    let mut bytes = Vec::new();
    for p in [[0.0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]] {
        p.iter().for_each(|c| bytes.extend(c.to_le_bytes()));
    }
    bytes.extend([255, 0, 0, 255, 0, 255, 0, 128, 0, 0, 51, 255]);
    for c in [
        [0u16, 65535, 0, 1],
        [0, 0, 65535, 1],
        [13107, 13107, 13107, 0],
    ] {
        c.iter().for_each(|c| bytes.extend(c.to_le_bytes()));
    }
    let data = base64::engine::general_purpose::STANDARD.encode(&bytes);
    let gltf = format!(
        r#"{{"asset": {{"version": "2.0"}}, "scene": 0, "scenes": [{{"nodes": [0]}}],
  "nodes": [{{"mesh": 0}}],
  "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0, "COLOR_0": 1}}}},
                             {{"attributes": {{"POSITION": 0, "COLOR_0": 2}}}}]}}],
  "buffers": [{{"byteLength": {}, "uri": "data:application/octet-stream;base64,{data}"}}],
  "bufferViews": [{{"buffer": 0, "byteOffset": 0, "byteLength": 36}},
                  {{"buffer": 0, "byteOffset": 36, "byteLength": 12}},
                  {{"buffer": 0, "byteOffset": 48, "byteLength": 24}}],
  "accessors": [
    {{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
      "min": [0, 0, 0], "max": [1, 1, 0]}},
    {{"bufferView": 1, "componentType": 5121, "normalized": true, "count": 3, "type": "VEC4"}},
    {{"bufferView": 2, "componentType": 5123, "normalized": true, "count": 3, "type": "VEC4"}}]}}"#,
        bytes.len()
    );
    let path = write("colours.gltf", &gltf);
    let model = match rastray::mesh::MeshFile::load(&path).expect("loads") {
        rastray::mesh::MeshFile::Gltf(model) => model,
        other => panic!("read as {other:?}"),
    };
    let colours: Vec<Vec<Vec3>> = model
        .parts
        .iter()
        .map(|p| p.geometry.colors.clone().expect("COLOR_0 read"))
        .collect();
    let expected = [
        [Vec3::X, Vec3::Y, Vec3::new(0.0, 0.0, 0.2)],
        [Vec3::Y, Vec3::Z, Vec3::splat(0.2)],
    ];
    assert_eq!(colours.len(), 2);
    for (got, expected) in colours.iter().zip(expected) {
        for (g, e) in got.iter().zip(expected) {
            assert!((*g - e).abs().max_element() < 1e-6, "{g} vs {e}");
        }
    }
}
