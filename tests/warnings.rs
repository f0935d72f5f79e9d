//! Scene warnings from the library: no lights, objects behind the camera, triangles without area.

mod common;

use std::path::Path;

use rastray::warnings::{ObjectName, Warning, warnings};
use rastray::{Scene, World};

/// A camera at z = 5 looking down −Z (its plane is z = 5; behind it is z ≥ 5) and one light.
const CAMERA_AND_LIGHT: &str = r#"
[camera]
position = [0.0, 0.0, 5.0]
target = [0.0, 0.0, 0.0]
[[light]]
position = [2.0, 3.0, 4.0]
"#;

fn box_at(name: &str, z: f32, size: [f32; 3]) -> String {
    format!(
        "[[object]]\ntype = \"box\"\nname = \"{name}\"\ncenter = [0.0, 0.0, {z:?}]\nsize = {size:?}\n"
    )
}

fn warnings_of(scene: &Scene, base: &Path) -> Vec<Warning> {
    let world = World::build(scene, base).unwrap_or_else(|e| panic!("{e}"));
    warnings(scene, &scene.camera, &world)
}

fn name(index: usize, label: &str) -> ObjectName {
    ObjectName {
        index,
        label: label.to_string(),
    }
}

#[test]
fn the_default_scene_has_no_warnings() {
    let scene = common::default_scene();
    assert_eq!(warnings_of(&scene, Path::new(".")), []);
}

#[test]
fn a_scene_without_lights_is_warned_about() {
    let scene = common::scene(&box_at("b", 0.0, [1.0, 1.0, 1.0]));
    let found = warnings_of(&scene, Path::new("."));
    assert_eq!(found, [Warning::NoLights]);
    assert_eq!(
        found[0].to_string(),
        "the scene has no lights; only ambient light will show"
    );
    let lit = common::scene(&format!("{CAMERA_AND_LIGHT}{}", box_at("b", 0.0, [1.0; 3])));
    assert_eq!(warnings_of(&lit, Path::new(".")), []);
}

#[test]
fn only_objects_entirely_behind_the_camera_plane_are_warned_about() {
    let scene = common::scene(&format!(
        "{CAMERA_AND_LIGHT}{}{}{}{}",
        box_at("in front", 0.0, [1.0; 3]),
        box_at("behind", 9.0, [1.0; 3]),
        // Straddles the camera plane: part of it can show.
        box_at("across", 5.0, [1.0; 3]),
        // Thin and wide: its bounding sphere crosses the plane but every vertex is behind it.
        box_at("sliver", 5.6, [4.0, 0.1, 0.1]),
    ));
    let found = warnings_of(&scene, Path::new("."));
    assert_eq!(
        found,
        [
            Warning::BehindCamera(name(1, "behind")),
            Warning::BehindCamera(name(3, "sliver")),
        ]
    );
    assert_eq!(
        found[0].to_string(),
        "object[1] \"behind\" is entirely behind the camera and will not show"
    );
    // The camera passed in decides, not the scene's: turned around, the others are behind.
    let mut turned = scene.camera;
    turned.target = glam::Vec3::new(0.0, 0.0, 10.0);
    let world = World::build(&scene, Path::new(".")).expect("world");
    let behind: Vec<usize> = warnings(&scene, &turned, &world)
        .iter()
        .map(|w| match w {
            Warning::BehindCamera(o) => o.index,
            other => panic!("{other}"),
        })
        .collect();
    assert_eq!(behind, [0]);
}

#[test]
fn zero_area_triangles_and_objects_without_area_are_warned_about() {
    let dir = tempfile::tempdir().expect("tempdir");
    // Two triangles, the second with two corners at one point.
    std::fs::write(
        dir.path().join("some.obj"),
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 2\n",
    )
    .expect("write");
    // Corners on one line: no area at all.
    std::fs::write(
        dir.path().join("flat.obj"),
        "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\nf 3 2 1\n",
    )
    .expect("write");
    let scene = common::scene(&format!(
        "{CAMERA_AND_LIGHT}{}",
        "[[object]]\ntype = \"mesh\"\npath = \"some.obj\"\n\
         [[object]]\ntype = \"mesh\"\nname = \"line\"\npath = \"flat.obj\"\n"
    ));
    let found = warnings_of(&scene, dir.path());
    assert_eq!(
        found,
        [
            Warning::ZeroAreaTriangles {
                object: name(0, "mesh"),
                count: 1,
                total: 2,
            },
            Warning::NoArea(name(1, "line")),
        ]
    );
    assert_eq!(
        found[0].to_string(),
        "object[0] \"mesh\": 1 of its 2 triangles have zero area and will not show"
    );
    assert_eq!(
        found[1].to_string(),
        "object[1] \"line\": every triangle has zero area; the object will not show"
    );
}

#[test]
fn the_shipped_scenes_have_no_warnings() {
    let scenes = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
    for entry in std::fs::read_dir(&scenes).expect("scenes/") {
        let path = entry.expect("entry").path();
        if path.extension().is_some_and(|e| e == "toml") {
            let scene = rastray::scene::load(&path).expect("loads");
            assert_eq!(warnings_of(&scene, &scenes), [], "{}", path.display());
        }
    }
}

#[test]
fn many_warnings_of_one_kind_are_summarised_after_the_first_few() {
    let mut text = CAMERA_AND_LIGHT.to_string();
    for i in 0..12 {
        text += &box_at(&format!("behind{i}"), 9.0, [1.0, 1.0, 1.0]);
    }
    text += &box_at("front", 0.0, [1.0, 1.0, 1.0]);
    let scene = rastray::scene::from_toml_str(&text, Path::new("many.toml")).expect("scene");
    let all = warnings_of(&scene, Path::new("."));
    assert_eq!(all.len(), 12);
    let lines = rastray::warnings::summarised(&all, 5);
    assert_eq!(lines.len(), 6, "{lines:#?}");
    assert!(lines[0].contains("behind0"), "{lines:#?}");
    assert!(lines[4].contains("behind4"), "{lines:#?}");
    assert_eq!(lines[5], "and 7 more objects entirely behind the camera");
    // Few enough are all shown.
    assert_eq!(rastray::warnings::summarised(&all, 12).len(), 12);
}
