//! A glTF mesh that several nodes name is read once and drawn at each node: instanced, it must
//! look as the same geometry baked into one mesh per node does, in all three algorithms, with
//! the shadows and reflections the instances cast on one another.

mod common;

use std::path::{Path, PathBuf};

use rastray::render::{Algorithm, DisplayMode, RenderOptions};
use rastray::world::{Detail, MeshFileCache, World};

/// The nodes: (translation, rotation quaternion xyzw, scale). A floor under four cubes, one
/// turned, one scaled unevenly and one mirrored (a negative scale), and a row of small ones:
/// more objects than the ray tracer searches without its tree over them.
const NODES: [([f32; 3], [f32; 4], [f32; 3]); 10] = [
    ([0.0, -1.6, 0.0], [0.0, 0.0, 0.0, 1.0], [5.0, 0.1, 4.0]),
    ([-1.6, 0.0, 0.0], [0.0, 0.0, 0.0, 1.0], [1.0, 1.0, 1.0]),
    ([1.5, 0.2, 0.3], [0.2, 0.3, 0.1, 0.927], [0.9, 0.9, 0.9]),
    ([0.0, 0.6, -1.2], [0.0, 0.0, 0.0, 1.0], [1.6, 0.5, 0.8]),
    ([0.1, -0.7, 1.4], [0.0, 0.38, 0.0, 0.925], [-0.7, 0.8, 1.1]),
    ([-2.0, -1.3, 1.6], [0.0, 0.0, 0.0, 1.0], [0.3, 0.4, 0.3]),
    ([-1.2, -1.3, 1.7], [0.0, 0.2, 0.0, 0.98], [0.3, 0.4, 0.3]),
    ([1.2, -1.3, 1.7], [0.0, 0.4, 0.0, 0.917], [0.3, 0.4, 0.3]),
    ([2.0, -1.3, 1.6], [0.1, 0.0, 0.0, 0.995], [0.3, 0.4, 0.3]),
    ([2.1, -1.2, -1.5], [0.0, 0.0, 0.0, 1.0], [0.5, 0.7, 0.5]),
];

/// A GLB of a unit cube (24 vertices with their face normals, 12 triangles) drawn by every node
/// of [`NODES`]: `shared`, one mesh every node names; else one mesh per node, each naming the
/// same accessors (each mesh used once, so each is baked as before instancing).
fn cubes_glb(shared: bool) -> Vec<u8> {
    let faces: [([f32; 3], [f32; 3], [f32; 3]); 6] = [
        ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]),
        ([-1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, 1.0, 0.0]),
        ([0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]),
        ([0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]),
        ([0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]),
        ([0.0, 0.0, -1.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]),
    ];
    let (mut positions, mut normals, mut indices) = (Vec::new(), Vec::new(), Vec::<u16>::new());
    for (n, a, b) in faces {
        let base = positions.len() as u16;
        for (s, t) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
            positions.push(std::array::from_fn::<f32, 3, _>(|k| {
                0.5 * (n[k] + s * a[k] + t * b[k])
            }));
            normals.push(n);
        }
        indices.extend([0, 1, 2, 0, 2, 3].map(|i| base + i));
    }
    let mut bin: Vec<u8> = indices.iter().flat_map(|i| i.to_le_bytes()).collect();
    let index_bytes = bin.len();
    let position_offset = bin.len();
    bin.extend(positions.iter().flatten().flat_map(|c| c.to_le_bytes()));
    let normal_offset = bin.len();
    bin.extend(normals.iter().flatten().flat_map(|c| c.to_le_bytes()));
    let primitive = serde_json::json!({
        "attributes": { "POSITION": 1, "NORMAL": 2 }, "indices": 0
    });
    let meshes: Vec<_> = (0..if shared { 1 } else { NODES.len() })
        .map(|_| serde_json::json!({ "primitives": [primitive.clone()] }))
        .collect();
    let nodes: Vec<_> = NODES
        .iter()
        .enumerate()
        .map(|(i, (t, r, s))| {
            serde_json::json!({
                "mesh": if shared { 0 } else { i },
                "translation": t, "rotation": r, "scale": s
            })
        })
        .collect();
    let document = serde_json::json!({
        "asset": { "version": "2.0" },
        "scene": 0,
        "scenes": [{ "nodes": (0..NODES.len()).collect::<Vec<_>>() }],
        "nodes": nodes,
        "meshes": meshes,
        "buffers": [{ "byteLength": bin.len() }],
        "bufferViews": [
            { "buffer": 0, "byteOffset": 0, "byteLength": index_bytes },
            { "buffer": 0, "byteOffset": position_offset, "byteLength": 12 * positions.len() },
            { "buffer": 0, "byteOffset": normal_offset, "byteLength": 12 * normals.len() }
        ],
        "accessors": [
            { "bufferView": 0, "componentType": 5123, "count": indices.len(), "type": "SCALAR" },
            { "bufferView": 1, "componentType": 5126, "count": positions.len(), "type": "VEC3",
              "min": [-0.5, -0.5, -0.5], "max": [0.5, 0.5, 0.5] },
            { "bufferView": 2, "componentType": 5126, "count": normals.len(), "type": "VEC3" }
        ]
    });
    common::glb(&document, bin)
}

/// The cubes GLB (`shared` or baked), written once into the test binary's scratch folder (the
/// tests run at once, and must not read a file another is rewriting).
fn write_cubes(shared: bool) -> PathBuf {
    static WRITTEN: [std::sync::OnceLock<PathBuf>; 2] =
        [std::sync::OnceLock::new(), std::sync::OnceLock::new()];
    WRITTEN[shared as usize]
        .get_or_init(|| {
            let name = if shared { "shared.glb" } else { "baked.glb" };
            let path = common::scratch().join(name);
            std::fs::write(&path, cubes_glb(shared)).unwrap();
            path
        })
        .clone()
}

/// The cubes seen from above and aside, lit by a light over them (its shadows fall on the floor
/// and on the lower cubes); every cube reflects.
fn scene_of(model: &Path) -> rastray::Scene {
    common::scene(&format!(
        "ambient = 0.1\nbackground = [0.05, 0.05, 0.1]\nmax_depth = 2\n\
         [camera]\nposition = [2.0, 4.0, 7.0]\ntarget = [0.0, -0.3, 0.0]\nfov = 50.0\n\
         [[light]]\nposition = [1.0, 8.0, 2.0]\nintensity = 0.9\n\
         [[light]]\nposition = [-5.0, 2.0, 4.0]\nintensity = 0.4\n\
         [[object]]\ntype = \"mesh\"\npath = {:?}\nscale = 1.0\n\
         material = {{ color = [0.7, 0.5, 0.3], diffuse = 0.8, specular = 0.5, shininess = 30.0, reflection = 0.3 }}\n",
        model.display().to_string(),
    ))
}

/// The image of `scene` by `algorithm` in display mode `mode` at 160×120, 8-bit RGB.
fn image(scene: &rastray::Scene, algorithm: Algorithm, mode: DisplayMode) -> Vec<u8> {
    let mut options = RenderOptions::new(algorithm, 160, 120);
    options.mode = mode;
    let (frame, _) = common::render(&common::world(scene), &scene.camera, options);
    frame.to_srgb8()
}

#[test]
fn an_instanced_mesh_is_stored_once_and_placed_at_every_node() {
    let shared = World::build_report(
        &scene_of(&write_cubes(true)),
        Path::new("."),
        &mut MeshFileCache::default(),
    )
    .expect("builds");
    let baked = common::world(&scene_of(&write_cubes(false)));
    let world = &shared.world;
    assert_eq!(world.objects.len(), NODES.len());
    assert!(world.objects.iter().all(|o| o.instance.is_some()));
    assert!(baked.objects.iter().all(|o| o.instance.is_none()));
    // Placed, the same 120 triangles; stored, 12 against 120.
    assert_eq!(world.triangle_count(), 120);
    assert_eq!(baked.triangle_count(), 120);
    assert_eq!(world.stored_triangle_count(), 12);
    assert_eq!(baked.stored_triangle_count(), 120);
    let first = world.objects[0].instance.as_ref().unwrap();
    for o in &world.objects {
        assert!(std::sync::Arc::ptr_eq(
            &o.instance.as_ref().unwrap().shared,
            &first.shared
        ));
    }
    // Each instance's bounds are its placed cube's, as the baked mesh's are.
    for (a, b) in world.objects.iter().zip(&baked.objects) {
        let ((lo, hi), (blo, bhi)) = (a.extent.unwrap(), b.extent.unwrap());
        assert!(lo.distance(blo) < 1e-5 && hi.distance(bhi) < 1e-5, "{a:?}");
    }
    let labels: Vec<_> = shared.sources.iter().map(|s| s.part.clone()).collect();
    assert_eq!(labels[1].as_deref(), Some("node 1, mesh 0 primitive 0"));
}

/// `rastray info` builds instances as bare shapes: one shared mesh with no normals, and the
/// same counts and bounds, bit for bit, as the world the renderers draw.
#[test]
fn a_shape_world_places_bare_shared_shapes_where_the_render_world_places_its_instances() {
    let scene = scene_of(&write_cubes(true));
    let build = |detail| {
        World::build_report_with(
            &scene,
            Path::new("."),
            &mut MeshFileCache::default(),
            detail,
        )
        .expect("builds")
        .world
    };
    let (render, shape) = (build(Detail::Render), build(Detail::Shape));
    assert_eq!(shape.objects.len(), NODES.len());
    assert_eq!(shape.triangle_count(), render.triangle_count());
    assert_eq!(shape.stored_triangle_count(), 12);
    assert_eq!(shape.bounds(), render.bounds());
    for (s, r) in shape.objects.iter().zip(&render.objects) {
        let shared = &s.instance.as_ref().expect("an instance").shared;
        assert!(
            shared.mesh.normals.is_empty(),
            "a bare shape has no normals"
        );
        assert!(shared.corner_uvs.is_none());
        assert!(!r.instance.as_ref().unwrap().shared.mesh.normals.is_empty());
        assert_eq!(s.extent, r.extent);
        assert_eq!(s.material.color, r.material.color);
    }
}

#[test]
fn instances_render_as_the_same_geometry_baked_in_all_three_algorithms() {
    let shared = scene_of(&write_cubes(true));
    let baked = scene_of(&write_cubes(false));
    for algorithm in [Algorithm::Gouraud, Algorithm::Phong, Algorithm::Ray] {
        // The display modes read the surface at each hit: its corners, normals and depth.
        for mode in [
            DisplayMode::Shaded,
            DisplayMode::Normals,
            DisplayMode::Depth,
            DisplayMode::HiddenLine,
        ] {
            let (a, b) = (
                image(&shared, algorithm, mode),
                image(&baked, algorithm, mode),
            );
            // Instances differ from the baked mesh by the rounding of where their points and
            // normals are moved (a ray moved into the mesh's space, normals moved out): at
            // most a few pixels of an edge, and a level here and there.
            let psnr = common::psnr(&a, &b);
            eprintln!("{algorithm:?} {mode:?}: instanced against baked, {psnr:.1} dB");
            assert!(psnr >= 40.0, "{algorithm:?} {mode:?}: {psnr:.1} dB");
        }
        let a = image(&shared, algorithm, DisplayMode::Shaded);
        // The picture is not empty: the cubes and their floor cover a good part of it (the
        // top-left corner sees the background).
        let background = &a[..3];
        let covered = a.chunks(3).filter(|p| p != &background).count();
        assert!(covered > 160 * 120 / 8, "{algorithm:?}: {covered} pixels");
    }
}

#[test]
fn instances_shadow_and_reflect_one_another_in_the_ray_tracer() {
    let shared = scene_of(&write_cubes(true));
    let world = common::world(&shared);
    let draw = |shadows: bool, depth: u32| {
        let mut options = RenderOptions::new(Algorithm::Ray, 160, 120);
        options.shadows = shadows;
        options.max_depth = Some(depth);
        common::render(&world, &shared.camera, options).0.to_srgb8()
    };
    let plain = draw(false, 0);
    let shadowed = draw(true, 0);
    let mirrored = draw(false, 2);
    // Shadows only darken, and darken a good part of the floor under the cubes.
    let darker = plain.iter().zip(&shadowed).filter(|(p, s)| s < p).count();
    assert!(plain.iter().zip(&shadowed).all(|(p, s)| s <= p));
    assert!(darker > 1000, "{darker} channels in shadow");
    // Reflections only add, and add where the cubes see one another or the floor.
    let brighter = plain.iter().zip(&mirrored).filter(|(p, m)| m > p).count();
    assert!(plain.iter().zip(&mirrored).all(|(p, m)| m >= p));
    assert!(brighter > 1000, "{brighter} channels reflecting");
    // And the baked geometry shows the same shadows and reflections.
    let baked = scene_of(&write_cubes(false));
    let baked_world = common::world(&baked);
    let options = RenderOptions::new(Algorithm::Ray, 160, 120);
    let a = common::render(&world, &shared.camera, options).0;
    let b = common::render(&baked_world, &baked.camera, options).0;
    let psnr = common::psnr(&a.to_srgb8(), &b.to_srgb8());
    assert!(psnr >= 40.0, "{psnr:.1} dB");
}
