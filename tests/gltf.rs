//! glTF 2.0 import: triangle counts, bounds, node transforms and colours as the test files state
//! them (see tests/data/gltf/README.md), materials, warnings, and the world built from them.

mod common;

use std::path::{Path, PathBuf};

use glam::Vec3;
use rastray::Algorithm;
use rastray::mesh::gltf::{GltfModel, ImportWarning, load_gltf};
use rastray::mesh::{MeshFile, load_obj};
use rastray::world::{MeshFileCache, World};

/// Float tolerance for positions computed through a node transform (a few ulps of unit values).
const EPS: f32 = 1e-5;

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/gltf")
        .join(name)
}

fn load(name: &str) -> GltfModel {
    load_gltf(&data(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
}

fn near(a: Vec3, b: Vec3) -> bool {
    a.distance(b) < EPS
}

#[test]
fn the_box_has_twelve_triangles_turned_by_its_parent_node() {
    let model = load("box.glb");
    assert_eq!(model.parts.len(), 1);
    assert_eq!(model.triangle_count(), 12);
    assert!(model.warnings.is_empty(), "{:?}", model.warnings);
    // A 1×2×3 box turned −90° about X by the parent's matrix: its 2 along Y now lies along Z.
    let (lo, hi) = model.bounds();
    assert!(near(lo, Vec3::new(-0.5, -1.5, -1.0)), "{lo}");
    assert!(near(hi, Vec3::new(0.5, 1.5, 1.0)), "{hi}");
    let part = &model.parts[0];
    assert_eq!(part.label, "node 1 \"Box\", mesh 0 \"Box\" primitive 0");
    let material = part.material.expect("the box names a material");
    assert_eq!(material.color, Vec3::new(0.8, 0.0, 0.0));
    // roughness defaults to 1: no mirror, broadest highlight.
    assert_eq!((material.reflection, material.shininess), (0.0, 1.0));
    // 24 vertices at 8 corners: welded, with the file's (turned) face normals kept per corner.
    assert_eq!(part.geometry.positions.len(), 8);
    let normals = part.geometry.corner_normals.as_ref().expect("file normals");
    for (t, corner) in part.geometry.triangles.iter().zip(normals) {
        let p = t.map(|i| part.geometry.positions[i as usize]);
        let face = (p[1] - p[0]).cross(p[2] - p[0]).normalize();
        for n in corner {
            assert!(
                near(*n, face),
                "file normal {n} differs from the face's {face}"
            );
        }
    }
}

#[test]
fn the_box_reads_the_same_from_glb_from_json_with_an_external_buffer_and_from_the_world() {
    let glb = load("box.glb");
    let json = load("box.gltf");
    assert_eq!((&glb.parts, &glb.warnings), (&json.parts, &json.warnings));
    // Only the JSON file reads a buffer beside it.
    assert!(glb.buffer_files.is_empty());
    assert_eq!(json.buffer_files, vec![data("box data.bin")]);
    let mut cache = MeshFileCache::default();
    let file = cache.get(&data("box.gltf")).expect("loads");
    assert!(matches!(&*file, MeshFile::Gltf(m) if *m == json));
    assert_eq!(file.triangle_count(), 12);
}

/// The parts of `model` as drawn, every instance of a shared part placed on its own.
fn drawn(model: &GltfModel) -> Vec<rastray::mesh::gltf::GltfPart> {
    model.parts.iter().flat_map(|p| p.expanded()).collect()
}

/// The parts of scene.gltf as drawn, found by label.
fn part(model: &GltfModel, label: &str) -> rastray::mesh::gltf::GltfPart {
    drawn(model)
        .into_iter()
        .find(|p| p.label.contains(label))
        .unwrap_or_else(|| panic!("no part {label}"))
}

#[test]
fn the_scene_applies_the_node_hierarchy_of_its_default_scene() {
    let model = load("scene.gltf");
    let parts = drawn(&model);
    let labels: Vec<&str> = parts.iter().map(|p| p.label.as_str()).collect();
    assert_eq!(
        labels,
        [
            "node 1 \"Left\", mesh 0 \"Tri\" primitive 0",
            "node 3 \"Mirror\", mesh 0 \"Tri\" primitive 0",
            "node 2 \"Right\", mesh 1 \"Strip\" primitive 0",
            "node 4 \"Fan\", mesh 2 \"Fan\" primitive 0",
            "node 7 \"Textured\", mesh 4 \"Textured\" primitive 0",
        ],
        "scene 0 in depth-first order, a shared mesh's instances together where it is first met; \
         node 6 belongs to scene 1 only"
    );
    // Mesh 0 is named by two nodes: read once, drawn at both.
    assert_eq!(model.parts[0].label, "mesh 0 \"Tri\" primitive 0");
    assert_eq!(model.parts[0].instances.len(), 2);
    let counts: Vec<usize> = parts.iter().map(|p| p.geometry.triangles.len()).collect();
    assert_eq!(
        counts,
        [1, 1, 2, 6, 1],
        "a 4-vertex strip makes 2, an 8-vertex fan 6"
    );

    // Left: Root (translate (0,1,0), scale 2) ∘ Left (translate (−1,0,0)).
    let left = &part(&model, "Left").geometry;
    let corners = left.triangles[0].map(|i| left.positions[i as usize]);
    for (got, want) in corners.iter().zip([
        Vec3::new(-2.0, 1.0, 0.0),
        Vec3::new(0.0, 1.0, 0.0),
        Vec3::new(-2.0, 3.0, 0.0),
    ]) {
        assert!(near(*got, want), "{got} ≠ {want}");
    }
    // Right: Root ∘ (translate (1,0,0) · turn 90° about Z) of the unit square.
    let (lo, hi) = part(&model, "Right").geometry.bounds();
    assert!(
        near(lo, Vec3::new(0.0, 1.0, 0.0)) && near(hi, Vec3::new(2.0, 3.0, 0.0)),
        "{lo} {hi}"
    );
    let (lo, hi) = part(&model, "Fan").geometry.bounds();
    assert!(
        near(lo, Vec3::new(-1.0, -(3f32.sqrt()) / 2.0, -2.0)),
        "{lo}"
    );
    assert!(near(hi, Vec3::new(1.0, 3f32.sqrt() / 2.0, -2.0)), "{hi}");
    let (lo, _) = part(&model, "Textured").geometry.bounds();
    assert!(near(lo, Vec3::new(0.0, -3.0, 0.0)), "{lo}");
}

#[test]
fn a_mirroring_node_keeps_the_triangle_facing_forward() {
    let model = load("scene.gltf");
    for label in ["Left", "Mirror"] {
        let g = &part(&model, label).geometry;
        let p = g.triangles[0].map(|i| g.positions[i as usize]);
        let normal = (p[1] - p[0]).cross(p[2] - p[0]).normalize();
        assert!(near(normal, Vec3::Z), "{label}: winding gives {normal}");
    }
    let (lo, hi) = part(&model, "Mirror").geometry.bounds();
    assert!(near(lo, Vec3::new(-1.0, 0.0, 0.0)) && near(hi, Vec3::new(0.0, 1.0, 0.0)));
}

#[test]
fn materials_map_base_colour_roughness_and_metallic() {
    let model = load("scene.gltf");
    let green = part(&model, "Left").material.expect("Green");
    assert_eq!(green.color, Vec3::new(0.1, 0.6, 0.2));
    assert!(
        (green.shininess - 30.0).abs() < 1e-3,
        "roughness 0.5 → p = 30"
    );
    assert_eq!(green.reflection, 0.0);
    let chrome = part(&model, "Right").material.expect("Chrome");
    assert_eq!(
        (chrome.reflection, chrome.diffuse),
        (1.0, 0.0),
        "polished metal"
    );
    assert!(
        part(&model, "Fan").material.is_none(),
        "the fan names no material"
    );
    let painted = part(&model, "Textured").material.expect("Painted");
    assert_eq!(
        painted.color,
        Vec3::new(0.5, 0.5, 1.0),
        "the factor, texture ignored"
    );
}

#[test]
fn points_lines_and_textures_are_reported_once_each() {
    let model = load("scene.gltf");
    assert_eq!(
        model.warnings[..2],
        [
            ImportWarning::NotTriangles {
                primitive: "mesh 3 \"Wire\" primitive 0".into(),
                mode: "lines"
            },
            ImportWarning::NotTriangles {
                primitive: "mesh 3 \"Wire\" primitive 1".into(),
                mode: "points"
            },
        ]
    );
    // The texture, paint.png, is missing: a warning that names it, and the part untextured.
    let [ImportWarning::TextureUnreadable { material, reason }] = &model.warnings[2..] else {
        panic!("{:?}", model.warnings);
    };
    assert_eq!(material, "material 2 \"Painted\"");
    assert!(reason.starts_with("texture paint.png: "), "{reason}");
    assert!(
        model
            .parts
            .iter()
            .all(|p| p.appearance.base_color.is_none())
    );
}

fn scene_with(path: &str, extra: &str) -> rastray::Scene {
    common::scene(&format!(
        "[camera]\nposition = [0.0, 0.0, 6.0]\n[[light]]\nposition = [1.0, 2.0, 6.0]\n\
         [[object]]\ntype = \"mesh\"\npath = \"{path}\"\n{extra}"
    ))
}

#[test]
fn the_world_splits_the_file_into_one_object_per_primitive_with_its_material() {
    let scene = scene_with("tests/data/gltf/scene.gltf", "position = [1.0, 0.0, 0.0]\n");
    let report = World::build_report(
        &scene,
        Path::new(env!("CARGO_MANIFEST_DIR")),
        &mut MeshFileCache::default(),
    )
    .expect("builds");
    let world = &report.world;
    assert_eq!(world.objects.len(), 5);
    assert_eq!(report.sources.len(), 5);
    assert!(
        report
            .sources
            .iter()
            .all(|s| s.object == 0 && s.part.is_some())
    );
    assert_eq!(world.triangle_count(), 11);
    let colours: Vec<Vec3> = world.objects.iter().map(|o| o.material.color).collect();
    let default = rastray::scene::Material::default().color;
    assert_eq!(
        colours,
        [
            Vec3::new(0.1, 0.6, 0.2),
            Vec3::new(0.1, 0.6, 0.2),
            Vec3::splat(0.9),
            default,
            Vec3::new(0.5, 0.5, 1.0)
        ]
    );
    // The whole file's bounds are centred on the object's position: the parts stay together.
    let (lo, hi) = world.bounds().expect("bounds");
    assert!(near((lo + hi) / 2.0, Vec3::new(1.0, 0.0, 0.0)), "{lo} {hi}");
    assert_eq!(report.warnings.len(), 3);
    assert!(
        report.warnings[0]
            .to_string()
            .contains("scene.gltf: object[0]: mesh 3")
    );
}

#[test]
fn a_material_set_on_the_object_overrides_the_files() {
    let scene = scene_with(
        "tests/data/gltf/scene.gltf",
        "material = { color = [0.2, 0.3, 0.4] }\n",
    );
    let world = common::world(&scene);
    assert_eq!(world.objects.len(), 5);
    for object in &world.objects {
        assert_eq!(object.material, scene.objects[0].material);
    }
}

#[test]
fn scale_and_rotation_apply_after_the_node_transforms_as_for_obj() {
    let scene = scene_with(
        "tests/data/gltf/box.glb",
        "position = [0.0, 1.0, 0.0]\nscale = 2.0\nrotation = [0.0, 0.0, 90.0]\n",
    );
    let world = common::world(&scene);
    // The turned box is 1×3×2; scaled 2× it is 2×6×4; 90° about Z swaps X and Y.
    let (lo, hi) = world.bounds().expect("bounds");
    assert!(near(hi - lo, Vec3::new(6.0, 2.0, 4.0)), "{}", hi - lo);
    assert!(near((lo + hi) / 2.0, Vec3::Y), "{lo} {hi}");
}

#[test]
fn suzanne_from_glb_is_the_same_mesh_as_from_obj() {
    let obj = load_obj(&Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/suzanne.obj"))
        .expect("obj");
    let glb = load_gltf(&Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/models/suzanne.glb"))
        .expect("glb");
    assert_eq!(glb.parts.len(), 1);
    let g = &glb.parts[0].geometry;
    assert_eq!(
        g.triangles.len(),
        obj.triangles.len(),
        "same fan triangulation"
    );
    let (gn, on) = (
        g.corner_normals.as_ref().expect("glb normals"),
        obj.corner_normals.as_ref().expect("obj normals"),
    );
    for t in 0..g.triangles.len() {
        for k in 0..3 {
            let (a, b) = (
                g.positions[g.triangles[t][k] as usize],
                obj.positions[obj.triangles[t][k] as usize],
            );
            assert!(near(a, b), "triangle {t} corner {k}: {a} ≠ {b}");
            assert!(near(gn[t][k], on[t][k]), "triangle {t} corner {k} normal");
        }
    }
    // Drawn with the same material, the two files give the same picture (1e-4: the normals
    // were normalised once in double and once in single precision).
    let material = "material = { color = [0.9, 0.6, 0.1] }\nrotation = [10.0, 30.0, 0.0]\n";
    let from_obj = common::draw(
        &scene_with("tests/data/suzanne.obj", material),
        Algorithm::Phong,
        48,
        48,
    );
    let from_glb = common::draw(
        &scene_with("scenes/models/suzanne.glb", material),
        Algorithm::Phong,
        48,
        48,
    );
    let background = scene_with("tests/data/suzanne.obj", material).background;
    let covered = from_glb.pixels.iter().filter(|p| **p != background).count();
    assert!(covered > 200, "Suzanne covers {covered} pixels");
    let worst = from_obj
        .pixels
        .iter()
        .zip(&from_glb.pixels)
        .map(|(a, b)| (*a - *b).abs().max_element())
        .fold(0.0, f32::max);
    assert!(worst < 1e-4, "largest channel difference {worst}");
}

#[test]
fn gouraud_and_phong_agree_on_the_flat_box_and_share_its_coverage() {
    // Flat faces under a distant light: one normal per face, so interpolating colours equals
    // interpolating normals (the Z-buffer tests' tolerance: one 8-bit step).
    let scene = common::scene(
        "[camera]\nposition = [3.0, 2.5, 6.0]\n[[light]]\nposition = [300.0, 400.0, 500.0]\n\
         [[object]]\ntype = \"mesh\"\npath = \"tests/data/gltf/box.glb\"\nsmooth = false\n",
    );
    let gouraud = common::draw(&scene, Algorithm::Gouraud, 64, 64);
    let phong = common::draw(&scene, Algorithm::Phong, 64, 64);
    let background = scene.background;
    let mut covered = 0;
    for (g, p) in gouraud.pixels.iter().zip(&phong.pixels) {
        assert_eq!(*g == background, *p == background, "coverage differs");
        covered += usize::from(*p != background);
        assert!((*g - *p).abs().max_element() < 1.0 / 255.0, "{g} vs {p}");
    }
    assert!(covered > 300, "the box covers {covered} pixels");
}

#[test]
fn an_image_without_its_bytes_is_refused_naming_it() {
    // Found by the fuzzer: the gltf crate's `Image::source` unwraps a missing `uri`, and a
    // missing `mimeType` beside a `bufferView`. Such a file is refused, not a panic.
    let dir = tempfile::tempdir().unwrap();
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(data("box.gltf")).unwrap()).unwrap();
    for (image, problem) in [
        (serde_json::json!({}), "needs a uri or a bufferView"),
        (serde_json::json!({ "bufferView": 0 }), "needs its mimeType"),
    ] {
        let mut file = json.clone();
        file["images"] = serde_json::json!([image]);
        file["textures"] = serde_json::json!([{ "source": 0 }]);
        file["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] =
            serde_json::json!({ "index": 0 });
        let path = dir.path().join("box.gltf");
        std::fs::write(&path, serde_json::to_vec(&file).unwrap()).unwrap();
        std::fs::copy(data("box data.bin"), dir.path().join("box data.bin")).unwrap();
        let Err(error) = load_gltf(&path) else {
            panic!("{problem}: loaded");
        };
        let error = error.to_string();
        assert!(
            error.contains("images[0]") && error.contains(problem),
            "{error}"
        );
    }
}
