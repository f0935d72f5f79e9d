//! Fuzzing MTL libraries: random, edge-valued and broken statements, texture names with options,
//! spaces, backslashes and ways out of the folder, and arbitrary bytes. Reading never panics and
//! never fails the OBJ that names the library: the model loads with one part per material used,
//! every triangle in one part, every file material within the scene's limits, and what was
//! skipped as warnings.
//!
//! CI runs proptest's default 256 cases; `scripts/fuzz.sh` runs a long session.

mod common;

use proptest::prelude::*;
use rastray::mesh::{load_obj_model, parse_mtl};
use rastray::scene::{Object, Scene, Shape, ShapeKind, validate};

/// A number as an MTL file might spell it.
fn number() -> impl Strategy<Value = String> {
    prop_oneof![
        6 => (-2.0f32..2.0).prop_map(|x| x.to_string()),
        2 => (0.0f32..2000.0).prop_map(|x| x.to_string()),
        1 => Just("1e39".to_string()),
        1 => Just("nan".to_string()),
        1 => Just("-inf".to_string()),
        1 => Just("x".to_string()),
        1 => Just(String::new()),
    ]
}

/// A texture reference with options, as exporters and hand-edited files write them.
fn texture_name() -> impl Strategy<Value = String> {
    let name = prop::sample::select(vec![
        "t.png",
        "sub\\t.png",
        ".\\t.png",
        "my t.png",
        "../t.png",
        "/etc/passwd",
        "C:\\t.png",
        "missing.jpg",
        "notimage.png",
        "sub",
        "",
        "%2e%2e/t.png",
    ]);
    let option = prop::sample::select(vec![
        "",
        "-s 1 1 1 ",
        "-o 0.5 ",
        "-clamp on ",
        "-mm 0 ",
        "-bm ",
    ]);
    (option, name).prop_map(|(o, n)| format!("{o}{n}"))
}

/// One line of an MTL file.
fn line() -> impl Strategy<Value = String> {
    let names = prop::sample::select(vec!["a", "b", "two words", "", "a"]);
    prop_oneof![
        3 => names.prop_map(|n| format!("newmtl {n}")),
        3 => (prop::sample::select(vec!["Kd", "Ks", "Ka"]), prop::collection::vec(number(), 0..5))
            .prop_map(|(k, xs)| format!("{k} {}", xs.join(" "))),
        2 => number().prop_map(|x| format!("Ns {x}")),
        2 => texture_name().prop_map(|t| format!("map_Kd {t}")),
        1 => prop::sample::select(vec!["Kd spectral f.rfl 1", "Kd xyz 1 1 1", "illum 2", "d 0.5", "# c", "\t"])
            .prop_map(str::to_string),
        1 => "[ -~]{0,24}",
    ]
}

/// An OBJ of two triangles with texture coordinates, naming `library` and using materials `a`,
/// `two words` and an undefined one.
const OBJ: &str = "mtllib lib.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n\
    usemtl a\nf 1/1 2/2 3/3\nusemtl two words\nf 2/2 4/1 3/3\nusemtl undefined\nf 1 2 4\n";

/// Writes the case's folder (one per test thread): the OBJ, its library and the textures it may
/// name.
fn write_case(library: &[u8]) -> std::path::PathBuf {
    let dir = common::scratch().join(format!("case-{:?}", std::thread::current().id()));
    if !dir.join("t.png").exists() {
        std::fs::create_dir_all(dir.join("sub")).unwrap();
        let png = image::RgbImage::from_pixel(2, 2, image::Rgb([200, 10, 10]));
        for copy in ["t.png", "sub/t.png", "my t.png"] {
            png.save(dir.join(copy)).unwrap();
        }
        png.save(common::scratch().join("t.png")).unwrap();
        std::fs::write(dir.join("notimage.png"), b"\x89PNG not really").unwrap();
    }
    std::fs::write(dir.join("model.obj"), OBJ).unwrap();
    std::fs::write(dir.join("lib.mtl"), library).unwrap();
    dir.join("model.obj")
}

/// Checks what `library` gives the OBJ: it loads, whole, with materials a scene accepts.
fn check(library: &[u8]) -> Result<(), TestCaseError> {
    let path = write_case(library);
    let model = load_obj_model(&path).map_err(|e| TestCaseError::fail(e.to_string()))?;
    prop_assert_eq!(model.parts.len(), 3);
    prop_assert_eq!(model.triangle_count(), 3);
    for warning in &model.warnings {
        prop_assert!(!warning.to_string().is_empty());
    }
    for part in &model.parts {
        if let Some(material) = part.material {
            let mut object = Object::new(Shape::new(ShapeKind::Box, glam::Vec3::ZERO, "".into()));
            object.material = material;
            let scene = Scene {
                objects: vec![object],
                ..Scene::default()
            };
            prop_assert!(validate(&scene).is_ok(), "{:?}", material);
        }
        if let Some((name, texture)) = &part.texture {
            prop_assert_eq!(texture.size(), (2, 2), "{}", name);
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::default())]

    #[test]
    fn mtl_libraries_never_fail_their_model(lines in prop::collection::vec(line(), 0..30), crlf in any::<bool>()) {
        let text = lines.join(if crlf { "\r\n" } else { "\n" });
        check(text.as_bytes())?;
    }

    #[test]
    fn arbitrary_bytes_parse_without_panic(bytes in prop::collection::vec(any::<u8>(), 0..300)) {
        let (materials, notes) = parse_mtl(&bytes);
        prop_assert!(notes.iter().all(|n| n.line >= 1));
        prop_assert!(materials.iter().all(|m| !m.name.is_empty()));
        check(&bytes)?;
    }
}

/// A texture outside the model's folder is never read, even when it exists.
#[test]
fn a_texture_outside_the_folder_is_refused() {
    let path = write_case(b"newmtl a\nmap_Kd ../t.png\n");
    let model = load_obj_model(&path).unwrap();
    assert!(model.parts.iter().all(|p| p.texture.is_none()));
    let text: Vec<String> = model.warnings.iter().map(|w| w.to_string()).collect();
    assert!(text.iter().any(|w| w.contains("refused")), "{text:?}");
}
