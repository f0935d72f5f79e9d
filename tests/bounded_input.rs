//! Strict, bounded input: vectors have exactly three components; a model path must name a
//! regular file, and is refused before it is read when it does not; scene and model files above
//! their size caps are refused with their size; OBJ vertices keep to the scene's coordinate
//! limits, with errors that name the file and line.

mod common;

use std::path::Path;
use std::time::Duration;

use rastray::input_file::{MAX_MODEL_BYTES, MAX_SCENE_BYTES};
use rastray::mesh::{ObjProblem, load_obj};
use rastray::scene::{SceneError, from_toml_str};
use rastray::{Scene, World};

fn parse(text: &str) -> Result<Scene, SceneError> {
    from_toml_str(text, Path::new("s.toml"))
}

#[test]
fn a_vector_has_exactly_three_components() {
    for (text, length) in [
        (
            "[[object]]\ntype = \"box\"\nsize = [1, 1, 1]\ncenter = [1, 2, 3, 4]\n",
            4,
        ),
        (
            "[[object]]\ntype = \"box\"\nsize = [1, 1, 1]\nrotation = [0, 0, 0, 1e30, \"junk?\"]\n",
            5,
        ),
        ("[[object]]\ntype = \"box\"\nsize = [1, 1]\n", 2),
        ("background = [0.1, 0.1, 0.1, 0.1]\n", 4),
        ("[camera]\nup = [0, 1, 0, 0]\n", 4),
        ("[[light]]\nposition = [1, 2, 3]\ncolor = [1, 1, 1, 1]\n", 4),
        (
            "[[object]]\ntype = \"box\"\nsize = [1, 1, 1]\nmaterial.color = [1, 1, 1, 1]\n",
            4,
        ),
        (
            "[[object]]\ntype = \"mesh\"\npath = \"m.obj\"\nposition = []\n",
            0,
        ),
    ] {
        let error = parse(text).expect_err(text).to_string();
        assert!(
            error.contains(&format!(
                "invalid length {length}, expected an array of 3 numbers"
            )),
            "{text}: {error}"
        );
        let line = text.lines().count();
        assert!(error.starts_with(&format!("s.toml:{line}: ")), "{error}");
    }
    let scene = parse("[[object]]\ntype = \"box\"\nsize = [1, 2, 3]\ncenter = [4, 5, 6]\n")
        .expect("three components");
    assert_eq!(
        scene.objects[0].shape.center(),
        glam::Vec3::new(4.0, 5.0, 6.0)
    );
}

/// The error of building the world of a scene whose one mesh object has `path`.
fn mesh_error(path: &Path) -> String {
    let scene = parse(&format!(
        "[[object]]\ntype = \"mesh\"\npath = {:?}\n",
        path.display().to_string()
    ))
    .unwrap();
    World::build(&scene, Path::new("."))
        .expect_err("refused")
        .to_string()
}

#[test]
fn a_model_that_is_not_a_regular_file_is_refused_before_it_is_read() {
    let m = mesh_error(Path::new("/dev/zero"));
    assert!(
        m.contains("/dev/zero") && m.contains("a character device, not a regular file"),
        "{m}"
    );
    let dir = tempfile::tempdir().unwrap();
    let m = mesh_error(dir.path());
    assert!(m.contains("a directory, not a regular file"), "{m}");
    let gltf_dir = dir.path().join("folder.glb");
    std::fs::create_dir(&gltf_dir).unwrap();
    let m = mesh_error(&gltf_dir);
    assert!(m.contains("a directory, not a regular file"), "{m}");

    // A FIFO with no writer would block a read for ever: it is refused without one.
    let fifo = dir.path().join("pipe.obj");
    common::mkfifo(&fifo);
    let (send, receive) = std::sync::mpsc::channel();
    std::thread::spawn(move || send.send(mesh_error(&fifo)));
    let m = receive
        .recv_timeout(Duration::from_secs(30))
        .expect("refused without blocking");
    assert!(m.contains("a FIFO, not a regular file"), "{m}");
}

#[test]
fn files_above_their_caps_are_refused_with_their_size() {
    let dir = tempfile::tempdir().unwrap();
    // Sparse files: the size is real, the disk holds nothing.
    let scene = dir.path().join("big.toml");
    std::fs::File::create(&scene)
        .unwrap()
        .set_len(MAX_SCENE_BYTES + 1)
        .unwrap();
    let m = rastray::scene::load(&scene).unwrap_err().to_string();
    assert!(
        m.contains(
            "big.toml: the file is 16.0 MiB (16777217 bytes); a scene file may be at most 16 MiB"
        ),
        "{m}"
    );
    for name in ["big.obj", "big.glb"] {
        let model = dir.path().join(name);
        std::fs::File::create(&model)
            .unwrap()
            .set_len(MAX_MODEL_BYTES + 1)
            .unwrap();
        let m = mesh_error(&model);
        assert!(
            m.contains(name) && m.contains("(1073741825 bytes); a model file may be at most 1 GiB"),
            "{m}"
        );
    }
}

fn obj_file(text: &str) -> (tempfile::TempDir, std::path::PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("m.obj");
    std::fs::write(&path, text).unwrap();
    (dir, path)
}

#[test]
fn obj_vertices_keep_to_the_scene_coordinate_limits() {
    let (_dir, path) = obj_file("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 3.4e38 0 0\nf 1 2 3\nf 1 2 4\n");
    let e = load_obj(&path).unwrap_err();
    assert!(
        matches!(e.problem, ObjProblem::VertexOutOfRange { vertex: 4, .. }),
        "{e}"
    );
    assert_eq!(e.line, Some(4));
    let m = e.to_string();
    assert!(
        m.ends_with(
            "m.obj:4: vertex 4 has coordinate 3.4e38; coordinates must be between -1e6 and 1e6"
        ),
        "{m}"
    );
    let (_dir, path) = obj_file("v 0 0 0\nv 1 0 0\n\nv 0 -1000000.5 0\nf 1 2 3\n");
    let e = load_obj(&path).unwrap_err();
    assert_eq!(e.line, Some(4), "{e}");
    // At the limit itself: accepted, and the area is a number.
    let (_dir, path) = obj_file("v -1e6 0 0\nv 1e6 0 0\nv 0 1e6 0\nf 1 2 3\n");
    let model = load_obj(&path).expect("within the limits");
    let object = rastray::scene::Object::new(rastray::scene::Shape::Mesh {
        path: path.clone(),
        position: glam::Vec3::ZERO,
        scale: 1.0,
        up: Default::default(),
        materials: rastray::scene::MaterialSource::File,
    });
    let mesh = rastray::mesh::tessellate(&object, Some(&model));
    let area = mesh.surface_area();
    assert!((area - 1.0e12).abs() < 1.0e6, "area {area}");
}

#[test]
fn the_obj_reader_names_lines_and_reads_what_tobj_read() {
    // Faces: `v`, `v/vt`, `v//vn` and `v/vt/vn` corners, negative indices, a polygon fanned
    // from its first corner, groups merged, unused vertices dropped, CRLF line ends.
    let (_dir, path) = obj_file(
        "# a comment\r\nmtllib none.mtl\r\no first\r\nv 9 9 9\r\nv 0 0 0\r\nv 1 0 0\r\nv 1 1 0\r\n\
         v 0 1 0\r\nvt 0 0\r\nvn 0 0 1\r\ng second\r\nusemtl x\r\ns 1\r\n\
         f 2//1 3//1 4//1\r\nf -4/1/1 -2/1/-1 -1//1\r\nf 2 3 4 5\r\nl 2 3\r\nf 2 3\r\n",
    );
    let model = load_obj(&path).expect("loads");
    assert_eq!(model.positions.len(), 4, "the unused vertex 1 is dropped");
    assert_eq!(model.positions[0], glam::Vec3::ZERO);
    assert_eq!(
        model.triangles,
        vec![[0, 1, 2], [0, 2, 3], [0, 1, 2], [0, 2, 3]]
    );
    assert!(model.corner_normals.is_none(), "the quad has no normals");
    let (_dir, path) = obj_file("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 2\nf 1//1 2//1 3//1\n");
    let model = load_obj(&path).expect("loads");
    assert_eq!(
        model.corner_normals,
        Some(vec![[glam::Vec3::Z; 3]]),
        "normals are made unit"
    );
    for (text, line) in [
        ("v 0 0 0\nv 1 0\n", 2),
        ("v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 x\n", 5),
        ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1//1 2//1 3//1\n", 4),
        ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", 4),
        ("v 0 0 0\nvn 1 x 0\n", 2),
    ] {
        let (_dir, path) = obj_file(text);
        let e = load_obj(&path).unwrap_err();
        assert_eq!(e.line, Some(line), "{text:?}: {e}");
    }
    // A comment in Latin-1 is no obstacle; a number in it is no number.
    let dir = tempfile::tempdir().unwrap();
    let latin1 = dir.path().join("latin1.obj");
    std::fs::write(&latin1, b"# caf\xe9\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
    assert_eq!(load_obj(&latin1).expect("loads").triangles.len(), 1);
    std::fs::write(&latin1, b"v 0 0 0\nv 1 0 \xe9\n").unwrap();
    assert_eq!(load_obj(&latin1).unwrap_err().line, Some(2));
}

#[test]
fn an_obj_file_with_more_triangles_than_a_scene_may_hold_stops_where_it_passes_the_cap() {
    use std::io::Write;
    let limit = rastray::world::MAX_TRIANGLES as usize;
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("many.obj");
    let mut out = std::io::BufWriter::new(std::fs::File::create(&path).unwrap());
    out.write_all(b"v 0 0 0\nv 1 0 0\nv 0 1 0\n").unwrap();
    for _ in 0..limit / 2 {
        out.write_all(b"f 1 2 3 1\n").unwrap();
    }
    out.write_all(b"f 1 2 3\nf 1 2 3\n").unwrap();
    drop(out);
    let e = load_obj(&path).unwrap_err();
    assert!(
        matches!(e.problem, ObjProblem::TooManyTriangles { .. }),
        "{e}"
    );
    assert_eq!(e.line, Some(3 + limit / 2 + 1), "{e}");
}
