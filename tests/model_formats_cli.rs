//! STL and PLY through the command line: broken files are refused with one line that names
//! the file and where in it, exit code 2 and no panic, opened on their own or from a scene;
//! a model is never read as a scene; `--up` and a mesh object's `up` turn the model.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn rastray(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_rastray"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("runs")
}

fn binary_stl(header: &[u8], count: u32, triangles: &[[f32; 9]]) -> Vec<u8> {
    let mut bytes = header.to_vec();
    bytes.resize(80, b' ');
    bytes.extend(count.to_le_bytes());
    for t in triangles {
        bytes.extend([0u8; 12]);
        bytes.extend(t.iter().flat_map(|c| c.to_le_bytes()));
        bytes.extend([0, 0]);
    }
    bytes
}

const TRIANGLE: [f32; 9] = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0];

const PLY_HEADER: &str = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n\
    property float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\n\
    end_header\n";

fn binary_ply_header(vertices: u64) -> String {
    format!(
        "ply\nformat binary_little_endian 1.0\nelement vertex {vertices}\nproperty float x\n\
         property float y\nproperty float z\nelement face 1\n\
         property list uchar int vertex_indices\nend_header\n"
    )
}

fn binary_ply(indices: [i32; 3]) -> Vec<u8> {
    let mut bytes = binary_ply_header(3).into_bytes();
    bytes.extend(TRIANGLE.iter().flat_map(|c| c.to_le_bytes()));
    bytes.push(3);
    bytes.extend(indices.iter().flat_map(|i| i.to_le_bytes()));
    bytes
}

/// `info` and `render` on the model alone and on a scene holding it refuse it: exit code 2,
/// one `error:` line naming the file and containing each of `needles`, no panic.
fn refused(name: &str, bytes: &[u8], needles: &[&str]) {
    let dir = tempfile::tempdir().expect("tempdir");
    std::fs::write(dir.path().join(name), bytes).expect("write");
    std::fs::write(
        dir.path().join("scene.toml"),
        format!("[[object]]\ntype = \"mesh\"\npath = \"{name}\"\n"),
    )
    .expect("scene");
    for args in [
        &["info", name][..],
        &["render", name, "-s", "16x16", "-o", "out.png"],
        &["info", "scene.toml"],
        &["render", "scene.toml", "-s", "16x16", "-o", "out.png"],
    ] {
        let o = rastray(dir.path(), args);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(!stderr.contains("panicked"), "{stderr}");
        assert!(stderr.starts_with("error: "), "{stderr}");
        assert_eq!(stderr.trim_end().lines().count(), 1, "one line: {stderr}");
        assert!(stderr.contains(name), "names the file: {stderr}");
        for needle in needles {
            assert!(
                stderr.contains(needle),
                "{args:?}: expected `{needle}`: {stderr}"
            );
        }
    }
    assert!(!dir.path().join("out.png").exists());
}

#[test]
fn a_truncated_binary_stl_is_refused_at_its_end() {
    let bytes = binary_stl(b"solid part", 2, &[TRIANGLE, TRIANGLE]);
    refused(
        "cut.stl",
        &bytes[..bytes.len() - 7],
        &[
            "cut.stl at byte 177",
            "truncated",
            "triangle count (2) needs 184 bytes",
        ],
    );
}

#[test]
fn a_binary_stl_whose_count_disagrees_with_its_size_is_refused() {
    let mut bytes = binary_stl(b"CAD", 1, &[TRIANGLE]);
    bytes.extend([0; 30]);
    refused(
        "long.stl",
        &bytes,
        &["triangle count (1) disagrees with its size (164 bytes"],
    );
}

#[test]
fn an_ascii_stl_without_endloop_or_endfacet_names_the_line() {
    let facet =
        "solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n";
    refused(
        "noloop.stl",
        format!("{facet}endfacet\nendsolid a\n").as_bytes(),
        &[
            "noloop.stl:7",
            "expected `vertex` or `endloop`, found `endfacet`",
        ],
    );
    refused(
        "nofacet.stl",
        format!("{facet}endloop\n").as_bytes(),
        &[
            "nofacet.stl:7",
            "`endfacet` is missing",
            "facet begun at line 2",
        ],
    );
}

#[test]
fn coordinates_that_are_not_finite_or_too_far_are_refused_where_they_lie() {
    let mut far = TRIANGLE;
    far[4] = 3e7;
    refused(
        "far.stl",
        &binary_stl(b"", 1, &[far]),
        &["far.stl at byte 112", "coordinate 3e7"],
    );
    refused(
        "nan.ply",
        format!("{PLY_HEADER}0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n").as_bytes(),
        &[
            "nan.ply:11",
            "vertex 2 has a coordinate that is not a finite number",
        ],
    );
}

#[test]
fn ply_errors_name_the_line_or_byte() {
    refused(
        "index.ply",
        format!("{PLY_HEADER}0 0 0\n1 0 0\n0 1 0\n3 0 1 5\n").as_bytes(),
        &[
            "index.ply:13",
            "face 1 names vertex 5, out of range (the file has 3 vertices)",
        ],
    );
    // Binary data is not echoed.
    let m = "face 1 names a vertex out of range (the file has 3 vertices)";
    refused(
        "index_bin.ply",
        &binary_ply([0, 1, 7]),
        &["index_bin.ply at byte", m],
    );
    let whole = binary_ply([0, 1, 2]);
    refused(
        "short.ply",
        &whole[..whole.len() - 3],
        &["the file ends inside face 1 of 1"],
    );
    refused(
        "type.ply",
        PLY_HEADER.replace("float y", "float128 y").as_bytes(),
        &["type.ply:5", "unknown type `float128`"],
    );
    refused(
        "count.ply",
        format!("{PLY_HEADER}0.000000 0.000000 0.000000\n1.000000 0.000000 0.000000\n").as_bytes(),
        &["the file ends inside vertex 3 of 3"],
    );
    refused(
        "cloud.ply",
        b"ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n\
          property float z\nend_header\n0 0 0\n1 1 1\n",
        &["point cloud: 2 vertices and no faces"],
    );
}

#[test]
fn a_count_larger_than_the_file_is_refused_before_anything_is_allocated() {
    refused(
        "huge.ply",
        binary_ply_header(4_000_000_000).as_bytes(),
        &[
            "huge.ply:3",
            "declares 4000000000 records of at least 12 bytes",
        ],
    );
}

fn write(dir: &Path, name: &str, bytes: &[u8]) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, bytes).expect("write");
    path
}

#[test]
fn models_are_never_read_as_toml_and_binary_noise_says_what_was_expected() {
    let dir = tempfile::tempdir().expect("tempdir");
    write(
        dir.path(),
        "part.stl",
        &binary_stl(b"solid", 1, &[TRIANGLE]),
    );
    write(dir.path(), "part", &binary_stl(b"solid", 1, &[TRIANGLE]));
    write(dir.path(), "cloud", &binary_ply([0, 1, 2]));
    for name in ["part.stl", "part", "cloud"] {
        let o = rastray(dir.path(), &["info", name]);
        let stdout = String::from_utf8_lossy(&o.stdout);
        assert!(
            o.status.success(),
            "{name}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        assert!(stdout.contains("1 triangles"), "{stdout}");
    }
    let o = rastray(dir.path(), &["info", "part"]);
    assert!(String::from_utf8_lossy(&o.stdout).contains("STL binary, no vertex colours"));
    write(dir.path(), "noise.bin", &[0, 159, 146, 150, 1, 2, 3]);
    let o = rastray(dir.path(), &["render", "noise.bin", "-o", "out.png"]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("noise.bin: neither a scene file (TOML text) nor a model file"),
        "{stderr}"
    );
    assert!(!stderr.contains("UTF-8"), "{stderr}");
}

/// The bounds line of `rastray info` for `args`.
fn bounds(dir: &Path, args: &[&str]) -> String {
    let o = rastray(dir, args);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    String::from_utf8_lossy(&o.stdout)
        .lines()
        .find(|l| l.starts_with("bounds"))
        .expect("bounds")
        .to_string()
}

#[test]
fn up_turns_a_model_opened_on_its_own_and_a_mesh_object() {
    let dir = tempfile::tempdir().expect("tempdir");
    // A flat slab, 2 × 1 in X and Y and thin in Z: lying down when Z is up.
    let slab = [0.0, 0.0, 0.0, 2.0, 0.0, 0.0, 0.0, 1.0, 0.0];
    write(dir.path(), "slab.stl", &binary_stl(b"", 1, &[slab]));
    assert!(bounds(dir.path(), &["info", "slab.stl"]).contains("size [1.789, 0.894, 0.000]"));
    let turned = bounds(dir.path(), &["info", "slab.stl", "--up", "z"]);
    assert!(turned.contains("size [1.789, 0.000, 0.894]"), "{turned}");
    let minus = bounds(dir.path(), &["info", "--up=-x", "slab.stl"]);
    assert!(minus.contains("size [0.894, 1.789, 0.000]"), "{minus}");
    write(
        dir.path(),
        "scene.toml",
        b"[[object]]\ntype = \"mesh\"\npath = \"slab.stl\"\nup = \"z\"\n",
    );
    let scene = bounds(dir.path(), &["info", "scene.toml"]);
    assert!(scene.contains("size [2.000, 0.000, 1.000]"), "{scene}");
    // A scene says `up` of each object: the flag is for a model alone.
    let o = rastray(dir.path(), &["info", "scene.toml", "--up", "z"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("--up applies to a model file"));
    let o = rastray(dir.path(), &["info", "slab.stl", "--up", "w"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("x, y, z, -x, -y, -z"));
}

#[test]
fn a_bad_up_in_a_scene_names_the_line_and_key_and_a_good_one_is_saved_back() {
    let bad = rastray::scene::from_toml_str(
        "[[object]]\ntype = \"mesh\"\npath = \"a.stl\"\nup = \"w\"\n",
        Path::new("bad.toml"),
    )
    .unwrap_err()
    .to_string();
    assert!(bad.starts_with("bad.toml:4"), "{bad}");
    assert!(bad.contains("up = \"w\""), "{bad}");
    let stray = rastray::scene::from_toml_str(
        "[[object]]\ntype = \"box\"\nsize = [1.0, 1.0, 1.0]\nup = \"z\"\n",
        Path::new("stray.toml"),
    )
    .unwrap_err()
    .to_string();
    assert!(stray.contains("`up` does not apply"), "{stray}");
    let scene = rastray::scene::from_toml_str(
        "[[object]]\ntype = \"mesh\"\npath = \"a.STL\"\nup = \"-z\"\n\
         [[object]]\ntype = \"mesh\"\npath = \"b.ply\"\n",
        Path::new("good.toml"),
    )
    .expect("valid");
    assert!(
        !scene.objects[0].smooth,
        "an STL is flat unless the scene says"
    );
    assert!(scene.objects[1].smooth);
    let text = rastray::scene::to_toml_string(&scene);
    assert_eq!(
        text.matches("up = \"").count(),
        1,
        "only a non-default up is written: {text}"
    );
    assert!(text.contains("up = \"-z\""), "{text}");
    let again = rastray::scene::from_toml_str(&text, Path::new("again.toml")).expect("reads");
    assert_eq!(again, scene);
}
