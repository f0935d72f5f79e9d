//! Scene files: round trips, and every kind of bad input refused with a message that names the
//! file, the line and the key.

mod common;

use std::path::Path;

use rastray::scene::{SceneError, default_scene, from_toml_str, to_toml_string};

#[test]
fn the_built_in_scene_matches_scenes_default_toml() {
    assert_eq!(default_scene(), common::default_scene());
    let scene = default_scene();
    assert!(scene.objects.len() >= 4 && scene.lights.len() == 2);
}

#[test]
fn loading_then_saving_gives_an_equal_scene() {
    let full = r#"
ambient = 0.2
background = [0.1, 0.2, 0.3]
max_depth = 3
falloff = { linear = 0.1, quadratic = 0.01 }
[camera]
position = [1.0, 2.0, 3.0]
target = [0.0, 0.5, 0.0]
up = [0.0, 1.0, 0.0]
fov = 60.0
[[light]]
name = "sun"
position = [5.0, 5.0, 5.0]
intensity = 0.7
color = [1.0, 0.9, 0.8]
[[object]]
type = "icosahedron"
name = "ball"
center = [1.0, 1.0, 1.0]
radius = 0.5
subdivisions = 2
smooth = true
material = { color = [0.1, 0.2, 0.3], diffuse = 0.4, specular = 0.5, shininess = 6.0, reflection = 0.7 }
[[object]]
type = "prism"
center = [0.0, 0.0, 0.0]
size = [1.0, 2.0, 3.0]
segments = 4
rotation = [10.0, 20.0, 30.0]
[[object]]
type = "mesh"
path = "models/suzanne.obj"
position = [0.0, 1.0, 0.0]
scale = 0.5
"#;
    for text in [full, rastray::scene::DEFAULT_SCENE_TOML] {
        let scene = from_toml_str(text, Path::new("a.toml")).expect("valid");
        let saved = to_toml_string(&scene);
        let again =
            from_toml_str(&saved, Path::new("b.toml")).unwrap_or_else(|e| panic!("{e}\n{saved}"));
        assert_eq!(scene, again, "round trip changed the scene:\n{saved}");
    }
}

#[test]
fn save_writes_atomically_and_load_reads_it_back() {
    let dir = tempfile::tempdir().expect("tempdir");
    let path = dir.path().join("s.toml");
    std::fs::write(&path, "old contents").expect("write");
    rastray::scene::save(&default_scene(), &path).expect("save");
    assert_eq!(rastray::scene::load(&path).expect("load"), default_scene());
    let leftovers: Vec<_> = std::fs::read_dir(dir.path()).expect("dir").collect();
    assert_eq!(leftovers.len(), 1, "no temporary file is left behind");
}

/// The message of the error for `text`, which must be refused.
fn refused(text: &str) -> (SceneError, String) {
    let error = from_toml_str(text, Path::new("scenes/bad.toml")).expect_err("must be refused");
    let message = error.to_string();
    assert!(
        message.starts_with("scenes/bad.toml"),
        "the file is named: {message}"
    );
    (error, message)
}

const CAMERA: &str = "[camera]\nposition = [0.0, 0.0, 5.0]\n";

#[test]
fn syntax_errors_name_the_line() {
    let (_, m) = refused(&format!(
        "{CAMERA}[[object]]\ntype = \"box\"\nsize = [1.0, 1.0\n"
    ));
    assert!(m.contains("bad.toml:5"), "{m}");
}

#[test]
fn unknown_keys_name_the_line_and_key() {
    let (_, m) = refused(&format!(
        "{CAMERA}[[object]]\ntype = \"icosahedron\"\nradius = 1.0\nradios = 2.0\n"
    ));
    assert!(m.contains("bad.toml:6") && m.contains("radios"), "{m}");
    let (_, m) = refused("ambiant = 0.1\n");
    assert!(m.contains("bad.toml:1") && m.contains("ambiant"), "{m}");
    let (_, m) = refused(&format!(
        "{CAMERA}[[object]]\ntype = \"box\"\nsize = [1.0, 1.0, 1.0]\nradius = 2.0\n"
    ));
    assert!(
        m.contains("radius") && m.contains("box"),
        "a key of another shape type is refused: {m}"
    );
}

#[test]
fn wrong_types_name_the_line() {
    let (_, m) = refused(&format!(
        "{CAMERA}[[object]]\ntype = \"icosahedron\"\nradius = \"big\"\n"
    ));
    assert!(m.contains("bad.toml:5") && m.contains("radius"), "{m}");
    let (_, m) = refused(&format!(
        "{CAMERA}[[object]]\ntype = \"cylinder\"\nradius = 1.0\n"
    ));
    assert!(m.contains("bad.toml:4") && m.contains("cylinder"), "{m}");
}

#[test]
fn out_of_range_values_name_the_line_and_field() {
    let cases = [
        (
            "[[object]]\ntype = \"box\"\nsize = [1.0, -2.0, 1.0]\n",
            "object[0].size",
            5,
        ),
        (
            "[[object]]\ntype = \"box\"\nsize = [1.0, 0.0, 1.0]\n",
            "object[0].size",
            5,
        ),
        (
            "[[object]]\ntype = \"icosahedron\"\nradius = nan\n",
            "object[0].radius",
            5,
        ),
        (
            "[[object]]\ntype = \"icosahedron\"\ncenter = [inf, 0.0, 0.0]\nradius = 1.0\n",
            "object[0].center",
            5,
        ),
        (
            "[[object]]\ntype = \"icosahedron\"\nradius = 1.0\nsubdivisions = 12\n",
            "object[0].subdivisions",
            6,
        ),
        (
            "[[object]]\ntype = \"icosahedron\"\nradius = 1.0\nmaterial = { diffuse = 1.5 }\n",
            "object[0].material.diffuse",
            6,
        ),
        (
            "[[light]]\nposition = [0.0, 1.0, 0.0]\nintensity = -1.0\n",
            "light[0].intensity",
            5,
        ),
    ];
    for (body, field, line) in cases {
        let (error, m) = refused(&format!("{CAMERA}{body}"));
        assert!(matches!(error, SceneError::Invalid { .. }), "{m}");
        assert!(m.contains(field), "names `{field}`: {m}");
        assert!(
            m.contains(&format!("bad.toml:{line}:")),
            "names line {line}: {m}"
        );
    }
    let (_, m) = refused(&format!("ambient = 2.0\n{CAMERA}"));
    assert!(m.contains("bad.toml:1:") && m.contains("`ambient`"), "{m}");
}

#[test]
fn a_camera_looking_at_itself_is_refused() {
    let (_, m) = refused("[camera]\nposition = [1.0, 1.0, 1.0]\ntarget = [1.0, 1.0, 1.0]\n");
    assert!(m.contains("camera.target"), "{m}");
}

#[test]
fn missing_and_malformed_obj_files_name_the_file() {
    let dir = tempfile::tempdir().expect("tempdir");
    let text = format!("{CAMERA}[[object]]\ntype = \"mesh\"\npath = \"nowhere.obj\"\n");
    let scene = from_toml_str(&text, Path::new("s.toml")).expect("parses");
    let error = rastray::World::build(&scene, dir.path()).expect_err("missing OBJ");
    assert!(error.to_string().contains("nowhere.obj"), "{error}");

    std::fs::write(dir.path().join("broken.obj"), "v 0 0 0\nv 1 0 0\nf 1 2 9\n").expect("write");
    let text = format!("{CAMERA}[[object]]\ntype = \"mesh\"\npath = \"broken.obj\"\n");
    let scene = from_toml_str(&text, Path::new("s.toml")).expect("parses");
    let error = rastray::World::build(&scene, dir.path()).expect_err("malformed OBJ");
    let message = error.to_string();
    assert!(
        message.contains("broken.obj:3: cannot load the OBJ model of object[0]")
            && message.contains("names vertex 9"),
        "{message}"
    );
}

#[test]
fn a_scene_too_large_to_tessellate_is_refused_with_the_limit() {
    // Past the Z-buffer's 24-bit triangle index, whatever the memory bound.
    let one = "[[object]]\ntype = \"box\"\nsize = [1.0, 1.0, 1.0]\nsegments = 512\n";
    let scene =
        from_toml_str(&one.repeat(6), Path::new("huge.toml")).expect("each object is valid");
    let error = rastray::World::build(&scene, Path::new(".")).expect_err("18.9 million triangles");
    let message = error.to_string();
    assert!(
        message.contains("18874368") && message.contains("16777215"),
        "{message}"
    );
}

#[test]
fn out_of_range_messages_state_the_accepted_range() {
    for (body, message) in [
        (
            "ambient = 2.0\n",
            "`ambient` must be between 0 and 1, got 2",
        ),
        (
            "[camera]\nfov = 180.0\n",
            "`camera.fov` must be between 0 and 180 degrees (exclusive), got 180",
        ),
        (
            "[[object]]\ntype = \"box\"\nsize = [1.0, 0.0, 1.0]\n",
            "`object[0].size` width, height and depth must each be a positive finite number at most 1e6, got [1, 0, 1]",
        ),
        (
            "[[object]]\ntype = \"icosahedron\"\nradius = 1.0\nsubdivisions = 9\n",
            "`object[0].subdivisions` must be between 0 and 8, got 9",
        ),
        (
            "[[light]]\nposition = [0.0, 2e6, 0.0]\n",
            "`light[0].position` coordinates must each be between -1e6 and 1e6, got [0, 2000000, 0]",
        ),
        (
            "falloff = { linear = -0.5 }\n",
            "`falloff.linear` must be between 0 and 1e6, got -0.5",
        ),
    ] {
        let (error, m) = refused(body);
        assert!(m.ends_with(message), "{m}");
        let SceneError::Invalid { error, .. } = error else {
            panic!("an out-of-range error: {m}")
        };
        assert!(m.contains(&error.path.to_string()), "{m}");
    }
}

#[test]
fn a_key_of_another_shape_is_a_typed_error() {
    use rastray::scene::{ObjectError, ShapeKind};
    let stray = ObjectError::Stray {
        key: "radius",
        kind: ShapeKind::Box,
    };
    let (error, m) = refused("[[object]]\ntype = \"box\"\nsize = [1.0, 1.0, 1.0]\nradius = 2.0\n");
    assert!(matches!(error, SceneError::Parse { .. }), "{m}");
    assert!(m.contains(&stray.to_string()), "{m}");
    let missing = ObjectError::Missing {
        key: "size",
        kind: ShapeKind::Prism,
    };
    let (_, m) = refused("[[object]]\ntype = \"prism\"\n");
    assert!(m.contains(&missing.to_string()), "{m}");
}

#[test]
fn no_falloff_has_one_form_however_the_file_spells_it() {
    use rastray::scene::Falloff;
    let load = |text: &str| from_toml_str(text, Path::new("f.toml")).expect("valid");
    for spelling in [
        "",
        "falloff = { linear = 0.0, quadratic = 0.0 }\n",
        "falloff = {}\n",
        "[falloff]\nlinear = 0.0\n",
    ] {
        let scene = load(spelling);
        assert_eq!(scene.falloff, None, "{spelling:?}");
        assert!(!to_toml_string(&scene).contains("falloff"), "{spelling:?}");
    }
    let scene = load("falloff = { quadratic = 0.25 }\n");
    assert_eq!(scene.falloff, Falloff::new(0.0, 0.25));
    assert_eq!(
        load(&to_toml_string(&scene)).falloff,
        scene.falloff,
        "kept by a round trip"
    );
    let world = rastray::World::build(&scene, Path::new(".")).expect("world");
    assert_eq!(
        world.falloff, scene.falloff,
        "the world holds the same value"
    );
}

#[test]
fn zero_falloff_renders_exactly_like_none() {
    let text = rastray::scene::DEFAULT_SCENE_TOML;
    let with_zeros = format!("falloff = {{ linear = 0.0, quadratic = 0.0 }}\n{text}");
    for algorithm in rastray::Algorithm::ALL {
        let plain = common::draw(&common::scene(text), algorithm, 48, 32);
        let zeros = common::draw(&common::scene(&with_zeros), algorithm, 48, 32);
        assert_eq!(plain.pixels, zeros.pixels, "{algorithm}");
    }
    let falling = format!("falloff = {{ linear = 0.2 }}\n{text}");
    let dimmer = common::draw(&common::scene(&falling), rastray::Algorithm::Phong, 48, 32);
    let plain = common::draw(&common::scene(text), rastray::Algorithm::Phong, 48, 32);
    assert_ne!(
        plain.pixels, dimmer.pixels,
        "a real falloff changes the image"
    );
}
