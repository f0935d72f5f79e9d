//! OBJ materials: `mtllib` libraries and `usemtl` groups become parts drawn with their MTL
//! colours in all three algorithms; names with spaces and Windows backslashes resolve inside the
//! model's folder and nowhere else; a missing library or texture is a warning, never a failure;
//! `materials = "object"` puts the object's own material back; `info` reports materials,
//! textures, measurements (a unit cube's volume 1.000, an icosphere within 0.5 %, the teapot
//! open).

mod common;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use glam::{Vec2, Vec3};
use rastray::mesh::{MeshFile, load_obj_model};
use rastray::render::{Algorithm, RenderOptions};
use rastray::scene::{MaterialSource, Shape};

const ALGORITHMS: [Algorithm; 3] = [Algorithm::Gouraud, Algorithm::Phong, Algorithm::Ray];

/// A folder of its own under the test binary's scratch folder, with `files` written in it
/// (names may hold folders); returns the folder.
fn folder(name: &str, files: &[(&str, &[u8])]) -> PathBuf {
    let dir = common::scratch().join(name);
    for (file, bytes) in files {
        let path = dir.join(file);
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(path, bytes).unwrap();
    }
    dir
}

fn rastray(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_rastray"))
        .args(args)
        .output()
        .expect("runs")
}

/// A PNG of `w`×`h` pixels, each (x, y, 0) scaled to bytes.
fn gradient_png(w: u32, h: u32) -> Vec<u8> {
    let image = image::RgbImage::from_fn(w, h, |x, y| {
        image::Rgb([(x * 255 / w) as u8, (y * 255 / h) as u8, 0])
    });
    common::textured_quad::png_bytes(&image)
}

/// Two squares side by side facing +Z, the left one `left`, the right one `right`, with texture
/// coordinates; `head` comes first (the `mtllib` line).
fn two_squares(head: &str, left: &str, right: &str) -> String {
    format!(
        "{head}\nv -1 -0.5 0\nv 0 -0.5 0\nv 0 0.5 0\nv -1 0.5 0\nv 1 -0.5 0\nv 1 0.5 0\n\
         vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n\
         usemtl {left}\nf 1/1 2/2 3/3 4/4\nusemtl {right}\nf 2/1 5/2 6/3 3/4\n"
    )
}

const LIBRARY: &str = "newmtl Red Paint\nKd 1 0 0\nKs 0.5 0.5 0.5\nNs 100\n\
    newmtl blue\nKd 0 0 1\nmap_Kd tex\\wood grain.png\n";

#[test]
fn each_material_is_a_part_with_its_colour_in_every_algorithm() {
    let dir = folder(
        "colours",
        &[
            (
                "model.obj",
                two_squares("mtllib my materials.mtl", "Red Paint", "blue").as_bytes(),
            ),
            ("my materials.mtl", LIBRARY.as_bytes()),
            ("tex/wood grain.png", &gradient_png(4, 2)),
        ],
    );
    let model = load_obj_model(&dir.join("model.obj")).expect("loads");
    assert_eq!(model.warnings, []);
    let labels: Vec<_> = model.parts.iter().map(|p| p.label.clone()).collect();
    assert_eq!(
        labels,
        [
            Some("material \"Red Paint\"".to_string()),
            Some("material \"blue\"".to_string())
        ]
    );
    let red = model.parts[0].material.expect("Red Paint");
    assert_eq!(red.color, Vec3::new(1.0, 0.0, 0.0));
    assert_eq!(
        (red.diffuse, red.specular, red.shininess),
        (1.0, 0.5, 100.0)
    );
    // The backslash path with a space found the texture beside the model.
    let (name, texture) = model.parts[1].texture.as_ref().expect("texture");
    assert_eq!(
        (name.as_str(), texture.size()),
        ("tex\\wood grain.png", (4, 2))
    );
    // OBJ puts v = 0 at the bottom: stored as 1 − v, the image's top-left origin.
    let uvs = model.parts[0].geometry.corner_uvs.as_ref().expect("uvs");
    assert_eq!(
        uvs[0],
        [
            Vec2::new(0.0, 1.0),
            Vec2::new(1.0, 1.0),
            Vec2::new(1.0, 0.0)
        ]
    );
    // The library, then the texture it names (watched by the editor's live reload).
    assert_eq!(
        model.material_files,
        [
            dir.join("my materials.mtl").canonicalize().unwrap(),
            dir.join("tex/wood grain.png").canonicalize().unwrap()
        ]
    );

    // Ambient 1 and no lights: each pixel is its albedo. The blue square is textured, which the
    // renderers do not draw yet, so only the red one's colour is checked.
    let scene = common::scene(&format!(
        "ambient = 1.0\nbackground = [0.0, 0.0, 0.0]\n[camera]\nposition = [0.0, 0.0, 3.0]\n\
         target = [0.0, 0.0, 0.0]\nfov = 60.0\n[[object]]\ntype = \"mesh\"\npath = {:?}\n",
        dir.join("model.obj").display().to_string()
    ));
    let world = common::world(&scene);
    assert_eq!(world.objects.len(), 2);
    assert!(world.objects[1].is_textured());
    for algorithm in ALGORITHMS {
        let mut options = RenderOptions::new(algorithm, 32, 32);
        options.shadows = false;
        let frame = common::render(&world, &scene.camera, options).0;
        // Pixel (8, 16) lies on the left square.
        let left = frame.pixel(8, 16);
        assert!(
            (left - Vec3::new(1.0, 0.0, 0.0)).abs().max_element() < 1e-3,
            "{algorithm:?} {left}"
        );
    }

    // The object's own material instead of the file's: both squares take it, untextured.
    let mut own = scene.clone();
    own.objects[0].material.color = Vec3::new(0.0, 1.0, 0.0);
    if let Shape::Mesh { materials, .. } = &mut own.objects[0].shape {
        *materials = MaterialSource::Object;
    }
    let world = common::world(&own);
    assert!(
        world
            .objects
            .iter()
            .all(|o| o.material.color == Vec3::Y && !o.is_textured())
    );
}

#[test]
fn a_scene_without_the_key_means_what_it_meant_and_the_key_round_trips() {
    let with = |rest: &str| {
        common::scene(&format!(
            "[[object]]\ntype = \"mesh\"\npath = \"m.obj\"\n{rest}"
        ))
    };
    let source = |scene: &rastray::Scene| match &scene.objects[0].shape {
        Shape::Mesh { materials, .. } => *materials,
        _ => unreachable!(),
    };
    // Before the key: the file's materials while the object's is the default, else its own.
    assert_eq!(source(&with("")), MaterialSource::File);
    assert_eq!(
        source(&with("material = { color = [1.0, 0.0, 0.0] }")),
        MaterialSource::Object
    );
    let explicit = with("materials = \"file\"\nmaterial = { color = [1.0, 0.0, 0.0] }");
    assert_eq!(source(&explicit), MaterialSource::File);
    let saved = rastray::scene::to_toml_string(&explicit);
    assert!(saved.contains("materials = \"file\""), "{saved}");
    assert_eq!(
        rastray::scene::from_toml_str(&saved, Path::new("s.toml")).unwrap(),
        explicit
    );
    let error = rastray::scene::from_toml_str(
        "[[object]]\ntype = \"box\"\nsize = [1.0, 1.0, 1.0]\nmaterials = \"file\"\n",
        Path::new("s.toml"),
    )
    .unwrap_err();
    assert!(error.to_string().contains("materials"), "{error}");
}

#[test]
fn missing_libraries_and_textures_warn_and_the_model_still_draws() {
    let dir = folder(
        "missing",
        &[
            (
                "none.obj",
                two_squares("mtllib gone.mtl", "a", "b").as_bytes(),
            ),
            (
                "notex.obj",
                two_squares("mtllib lib.mtl", "a", "b").as_bytes(),
            ),
            (
                "lib.mtl",
                b"newmtl a\nKd 0 1 0\nmap_Kd .\\lost.jpg\nnewmtl b\nmap_Kd ../outside.png\n",
            ),
            (
                "notimage.obj",
                two_squares("mtllib bad.mtl", "a", "a").as_bytes(),
            ),
            ("bad.mtl", b"newmtl a\nmap_Kd junk.png\nKd 1 0\n"),
            ("junk.png", b"not a png"),
        ],
    );
    std::fs::write(common::scratch().join("outside.png"), gradient_png(2, 2)).unwrap();
    for (file, expected) in [
        (
            "none.obj",
            &[
                "mtllib \"gone.mtl\" not read",
                "usemtl \"a\": no material library",
            ][..],
        ),
        (
            "notex.obj",
            &[
                "map_Kd \".\\lost.jpg\" not read",
                "map_Kd \"../outside.png\" not read: texture ../outside.png: refused: it leads outside",
            ][..],
        ),
        (
            "notimage.obj",
            &[
                "map_Kd \"junk.png\" not read",
                "bad.mtl:3: a colour is `r g b`",
            ][..],
        ),
    ] {
        let path = dir.join(file);
        let out = rastray(&["info", path.to_str().unwrap()]);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(0), "{file}: {stderr}");
        for text in expected {
            assert!(stderr.contains(text), "{file}: {text} not in {stderr}");
        }
        assert!(stderr.contains(path.to_str().unwrap()), "{stderr}");
        let png = common::scratch().join(format!("{file}.png"));
        let out = rastray(&[
            "render",
            path.to_str().unwrap(),
            "-s",
            "16x16",
            "-o",
            png.to_str().unwrap(),
        ]);
        assert_eq!(
            out.status.code(),
            Some(0),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
    // The green material still applies where its texture is lost.
    let model = load_obj_model(&dir.join("notex.obj")).unwrap();
    assert_eq!(model.parts[0].material.unwrap().color, Vec3::Y);
    assert!(model.parts.iter().all(|p| p.texture.is_none()));
}

#[test]
fn faces_before_usemtl_and_files_without_materials_stay_whole() {
    let dir = folder(
        "plain",
        &[
            ("plain.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"),
            ("late.obj", b"mtllib l.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nusemtl m\nf 2 4 3\nusemtl\nf 1 2 4\n"),
            ("l.mtl", b"newmtl m\nKd 0.5 0.5 0.5\n"),
        ],
    );
    let plain = load_obj_model(&dir.join("plain.obj")).unwrap();
    assert_eq!(plain.parts.len(), 1);
    assert_eq!(plain.parts[0].label, None);
    assert_eq!(plain.parts[0].material, None);
    let late = MeshFile::load(&dir.join("late.obj")).unwrap();
    let parts = late.parts();
    let labels: Vec<_> = parts.iter().map(|p| p.label).collect();
    assert_eq!(labels, [Some("no material"), Some("material \"m\"")]);
    assert_eq!(
        parts[0].geometry.triangles.len(),
        2,
        "before usemtl and after `usemtl` alone"
    );
    assert_eq!(
        parts[1].geometry.positions.len(),
        3,
        "only the positions it uses"
    );
}

/// The `info` line of object 0.
fn object_line(path: &Path) -> String {
    let out = rastray(&["info", path.to_str().unwrap()]);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    text.lines()
        .find(|l| l.trim_start().starts_with("[0]"))
        .unwrap_or_else(|| panic!("{text}"))
        .to_string()
}

/// The number after `word` in `line`.
fn number_after(line: &str, word: &str) -> f64 {
    let rest = &line[line
        .find(word)
        .unwrap_or_else(|| panic!("{word} in {line}"))
        + word.len()..];
    rest.split_whitespace()
        .next()
        .unwrap()
        .trim_matches(|c| c == '(' || c == ')')
        .parse()
        .unwrap()
}

#[test]
fn info_measures_volume_and_closure() {
    // A unit cube whose faces have their own vertices, scaled by the scene: measured in the
    // file's units.
    let mut cube = String::new();
    let faces = [
        (Vec3::Z, Vec3::X, Vec3::Y),
        (-Vec3::Z, -Vec3::X, Vec3::Y),
        (Vec3::X, -Vec3::Z, Vec3::Y),
        (-Vec3::X, Vec3::Z, Vec3::Y),
        (Vec3::Y, Vec3::X, -Vec3::Z),
        (-Vec3::Y, Vec3::X, Vec3::Z),
    ];
    for (k, (n, u, w)) in faces.iter().enumerate() {
        for (a, b) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
            let p = *n * 0.5 + *u * (0.5 * a) + *w * (0.5 * b);
            cube += &format!("v {} {} {}\n", p.x, p.y, p.z);
        }
        let b = 4 * k + 1;
        cube += &format!("f {} {} {} {}\n", b, b + 1, b + 2, b + 3);
    }
    let dir = folder(
        "measure",
        &[
            ("cube.obj", cube.as_bytes()),
            (
                "scene.toml",
                b"[[object]]\ntype = \"mesh\"\npath = \"cube.obj\"\nscale = 3.0\n\
                  [[object]]\ntype = \"icosahedron\"\nradius = 2.0\nsubdivisions = 5\n",
            ),
        ],
    );
    let line = object_line(&dir.join("cube.obj"));
    assert!(line.contains("closed  volume 1.000"), "{line}");
    let out = rastray(&["info", dir.join("scene.toml").to_str().unwrap()]);
    let text = String::from_utf8_lossy(&out.stdout);
    let sphere = text.lines().find(|l| l.contains("[1]")).unwrap();
    let exact = 4.0 / 3.0 * std::f64::consts::PI * 8.0;
    let volume = number_after(sphere, "volume ");
    assert!((volume - exact).abs() / exact < 0.005, "{sphere}");
    assert!(text.contains("closed  volume 1.000"), "{text}");
    // The scene's total is in world units: 27 for the cube scaled 3, plus the sphere.
    let total = text.lines().find(|l| l.starts_with("measure")).unwrap();
    assert!(
        (number_after(total, "volume ") - (27.0 + volume)).abs() < 0.01,
        "{total}"
    );

    // The teapot of ../shared (CI has it): its lid and spout leave edges open.
    let teapot = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/models/teapot.obj");
    let line = object_line(&teapot);
    assert!(line.contains("open (160 boundary edges)"), "{line}");
    assert!(!line.contains("volume"), "{line}");
}

/// The texel of `texture` (level 0) under `uv` ((0, 0) the image's top-left), nearest.
fn texel_at(texture: &rastray::mesh::texture::Texture, uv: Vec2) -> Vec3 {
    let (w, h) = texture.size();
    let x = ((uv.x * w as f32) as u32).min(w - 1);
    let y = ((uv.y * h as f32) as u32).min(h - 1);
    let [r, g, b, _] = texture.levels[0].texel(x, y);
    Vec3::new(r, g, b)
}

#[test]
fn blenders_obj_and_mtl_load_with_their_materials_and_an_upright_texture() {
    // Written by tests/data/make_blender_mtl.py with Blender 3.4.1's OBJ exporter.
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/obj_mtl");
    let cube = load_obj_model(&data.join("two_materials.obj")).expect("cube");
    assert_eq!(cube.warnings, []);
    let summary: Vec<_> = cube
        .parts
        .iter()
        .map(|p| (p.material_name.clone().unwrap(), p.geometry.triangles.len()))
        .collect();
    assert_eq!(
        summary,
        [("Red_Paint".to_string(), 2), ("Blue".to_string(), 10)]
    );
    let red = cube.parts[0].material.unwrap();
    assert_eq!(red.color, Vec3::X);
    assert_eq!((red.specular, red.shininess), (0.5, 250.0));
    let model = MeshFile::Obj(cube);
    let parts: Vec<_> = model
        .parts()
        .iter()
        .map(|p| (&p.geometry.positions[..], &p.geometry.triangles[..]))
        .collect();
    let m = rastray::mesh::measure(&parts);
    assert_eq!(m.closure(), "closed");
    assert!((m.volume.unwrap() - 8.0).abs() < 1e-6, "{m:?}");

    // The quad: the texture's name holds a space; each corner's coordinates, stored with the
    // image's top-left as origin, land on the image's texel at that corner of the picture.
    let quad = load_obj_model(&data.join("textured_quad.obj")).expect("quad");
    assert_eq!(quad.warnings, []);
    let part = &quad.parts[0];
    assert_eq!(
        part.material.unwrap().color,
        Vec3::ONE,
        "no Kd: the texture alone"
    );
    let (name, texture) = part.texture.as_ref().expect("texture");
    assert_eq!(
        (name.as_str(), texture.size()),
        ("textures/letter f.png", (16, 16))
    );
    let uvs = part.geometry.corner_uvs.as_ref().expect("uvs");
    for (triangle, corners) in part.geometry.triangles.iter().zip(uvs) {
        for (&i, &uv) in triangle.iter().zip(corners) {
            let p = part.geometry.positions[i as usize];
            // Blender painted red along x and green along y from the bottom-left.
            let expected = Vec3::new((p.x > 0.0) as u8 as f32, (p.y > 0.0) as u8 as f32, 0.0);
            let got = texel_at(texture, uv);
            assert!((got - expected).abs().max_element() < 1e-3, "{p}: {got}");
        }
    }
}

#[test]
fn info_counts_the_parts_drawn_with_the_files_materials() {
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/obj_mtl");
    for (file, expected) in [
        ("two_materials.obj", "2 parts with materials of the file's"),
        ("textured_quad.obj", "1 part with a material of the file's"),
    ] {
        let out = rastray(&["info", data.join(file).to_str().unwrap()]);
        let stdout = String::from_utf8_lossy(&out.stdout);
        assert_eq!(out.status.code(), Some(0), "{file}: {stdout}");
        let describe = stdout
            .lines()
            .find(|l| l.trim_start().starts_with("OBJ"))
            .unwrap_or_else(|| panic!("{file}: {stdout}"));
        assert!(describe.contains(expected), "{file}: {describe}");
    }
}
