//! Broken glTF input as a user meets it: `rastray info` and `render` refuse it with one message
//! that names the file and exit code 2, never a panic; skipped parts are `warning:` lines.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use serde_json::{Value, json};

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/gltf")
        .join(name)
}

/// The JSON of box.gltf, to be broken by each test.
fn box_json() -> Value {
    serde_json::from_slice(&std::fs::read(data("box.gltf")).expect("box.gltf")).expect("JSON")
}

/// A folder holding `model_name` with `bytes`, the box's external buffer unless told otherwise,
/// and a scene showing the model.
struct Case {
    dir: tempfile::TempDir,
    model_name: String,
}

impl Case {
    fn new(model_name: &str, bytes: &[u8]) -> Case {
        let dir = tempfile::tempdir().expect("tempdir");
        std::fs::write(dir.path().join(model_name), bytes).expect("write model");
        std::fs::copy(data("box data.bin"), dir.path().join("box data.bin")).expect("buffer");
        std::fs::write(
            dir.path().join("scene.toml"),
            format!(
                "[camera]\nposition = [0.0, 0.0, 6.0]\n[[light]]\nposition = [0.0, 3.0, 6.0]\n\
                 [[object]]\ntype = \"mesh\"\npath = \"{model_name}\"\n"
            ),
        )
        .expect("write scene");
        Case {
            dir,
            model_name: model_name.to_string(),
        }
    }

    fn json(model_name: &str, document: &Value) -> Case {
        Case::new(model_name, document.to_string().as_bytes())
    }

    fn run(&self, args: &[&str]) -> Output {
        Command::new(env!("CARGO_BIN_EXE_rastray"))
            .args(args)
            .current_dir(self.dir.path())
            .output()
            .expect("runs")
    }

    /// `info` and `render` both refuse the model: exit code 2, one error naming the model file
    /// and containing `needle`, no panic. Returns the message.
    fn refused(&self, needle: &str) -> String {
        let mut message = String::new();
        for args in [
            &["info", "scene.toml"][..],
            &["render", "scene.toml", "-s", "16x16", "-o", "out.png"],
        ] {
            let o = self.run(args);
            let stderr = String::from_utf8_lossy(&o.stderr).into_owned();
            assert_eq!(o.status.code(), Some(2), "{args:?}: {stderr}");
            assert!(!stderr.contains("panicked"), "{stderr}");
            assert!(stderr.starts_with("error: "), "{stderr}");
            assert_eq!(stderr.trim_end().lines().count(), 1, "one line: {stderr}");
            assert!(
                stderr.contains(&self.model_name),
                "names the file: {stderr}"
            );
            assert!(stderr.contains(needle), "expected `{needle}`: {stderr}");
            message = stderr;
        }
        assert!(
            !self.dir.path().join("out.png").exists(),
            "no image is written"
        );
        message
    }
}

#[test]
fn a_missing_buffer_names_the_model_and_the_buffer() {
    let case = Case::json("box.gltf", &box_json());
    std::fs::remove_file(case.dir.path().join("box data.bin")).expect("remove");
    let m = case.refused("buffer 0 (`box%20data.bin`) cannot be read");
    assert!(m.contains("box data.bin"), "the path tried: {m}");
}

#[test]
fn a_short_buffer_is_refused_with_both_lengths() {
    let case = Case::json("box.gltf", &box_json());
    std::fs::write(case.dir.path().join("box data.bin"), [0u8; 100]).expect("write");
    case.refused("buffer 0 holds 100 bytes but declares 648");
}

#[test]
fn an_accessor_index_out_of_range_is_refused_at_its_json_path() {
    let mut doc = box_json();
    doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = json!(99);
    Case::json("box.gltf", &doc)
        .refused("invalid glTF at meshes[0].primitives[0].attributes.POSITION");
    let mut doc = box_json();
    doc["meshes"][0]["primitives"][0]["indices"] = json!(42);
    Case::json("box.gltf", &doc).refused("invalid glTF at meshes[0].primitives[0].indices");
}

#[test]
fn a_vertex_index_out_of_range_is_refused() {
    let doc = box_json();
    let case = Case::json("box.gltf", &doc);
    // Overwrite the first 16-bit index with 999.
    let view = doc["accessors"][2]["bufferView"].as_u64().expect("view") as usize;
    let offset = doc["bufferViews"][view]["byteOffset"]
        .as_u64()
        .expect("offset") as usize;
    let path = case.dir.path().join("box data.bin");
    let mut bytes = std::fs::read(&path).expect("read");
    bytes[offset..offset + 2].copy_from_slice(&999u16.to_le_bytes());
    std::fs::write(&path, bytes).expect("write");
    // The message says where the index lies, never its value (a buffer may hold any bytes).
    let message = case.refused(&format!(
        "index out of range in accessor 2 (buffer 0, offset {offset}) (the primitive has 24 vertices)"
    ));
    assert!(!message.contains("999"), "{message}");
}

#[test]
fn an_accessor_running_past_its_buffer_view_is_refused() {
    let mut doc = box_json();
    doc["accessors"][0]["count"] = json!(1000);
    Case::json("box.gltf", &doc).refused("accessor 0 (POSITION): 1000 elements");
    let mut doc = box_json();
    doc["accessors"][2]["componentType"] = json!(5126);
    Case::json("box.gltf", &doc).refused("accessor 2 (indices)");
}

#[test]
fn truncated_and_malformed_glb_containers_are_refused() {
    let glb = std::fs::read(data("box.glb")).expect("box.glb");
    Case::new("cut.glb", &glb[..glb.len() / 2]).refused("the GLB file is truncated");
    Case::new("header.glb", &glb[..7]).refused("truncated");
    let mut short = glb.clone();
    short[8..12].copy_from_slice(&4u32.to_le_bytes());
    Case::new("short.glb", &short).refused("not a valid GLB file");
    let mut chunk = glb.clone();
    chunk[12..16].copy_from_slice(&u32::MAX.to_le_bytes());
    Case::new("chunk.glb", &chunk).refused("truncated");
}

#[test]
fn an_empty_file_and_files_that_are_not_gltf_are_refused() {
    Case::new("empty.glb", b"").refused("the file is empty");
    Case::new("empty.gltf", b"").refused("the file is empty");
    Case::new("other.gltf", br#"{"name": "not a model"}"#).refused("not a glTF 2.0 file");
    Case::new("text.gltf", b"hello").refused("not a glTF 2.0 file");
    let mut doc = box_json();
    doc["asset"]["version"] = json!("1.0");
    Case::json("old.gltf", &doc).refused("glTF version 1.0 is not supported");
}

#[test]
fn a_node_cycle_and_a_remote_buffer_are_refused() {
    let mut doc = box_json();
    doc["nodes"][1]["children"] = json!([0]);
    Case::json("loop.gltf", &doc).refused("node 0 is its own ancestor");
    let mut doc = box_json();
    doc["buffers"][0]["uri"] = json!("https://example.com/box.bin");
    Case::json("remote.gltf", &doc)
        .refused("only files in the model's folder and data URIs are read");
}

/// box.gltf declaring a required compression extension, with a second primitive whose
/// positions live in no buffer view (as compressed primitives do).
fn box_with_compressed_primitive() -> Value {
    let mut doc = box_json();
    doc["extensionsUsed"] = json!(["KHR_draco_mesh_compression"]);
    doc["extensionsRequired"] = json!(["KHR_draco_mesh_compression"]);
    let compressed = doc["accessors"].as_array().expect("accessors").len();
    doc["accessors"]
        .as_array_mut()
        .expect("accessors")
        .push(json!({
            "componentType": 5126, "count": 3, "type": "VEC3",
            "min": [0.0, 0.0, 0.0], "max": [1.0, 1.0, 0.0]
        }));
    doc["meshes"][0]["primitives"]
        .as_array_mut()
        .expect("primitives")
        .push(json!({ "attributes": { "POSITION": compressed } }));
    doc
}

#[test]
fn unsupported_required_extensions_are_warnings_and_the_rest_still_draws() {
    let case = Case::json("draco.gltf", &box_with_compressed_primitive());
    let o = case.run(&["info", "scene.toml"]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{stderr}");
    let warnings: Vec<&str> = stderr.lines().collect();
    assert_eq!(warnings.len(), 2, "{stderr}");
    assert!(
        warnings
            .iter()
            .all(|w| w.starts_with("warning: ") && w.contains("draco.gltf"))
    );
    assert!(warnings[0].contains("requires extension KHR_draco_mesh_compression"));
    assert!(warnings[1].contains("mesh 0 \"Box\" primitive 1 skipped"));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains("triangles 12"), "{stdout}");

    // With nothing left to draw, the file is refused, and the message says why.
    let mut doc = box_with_compressed_primitive();
    doc["meshes"][0]["primitives"]
        .as_array_mut()
        .expect("primitives")
        .remove(0);
    Case::json("all_draco.gltf", &doc)
        .refused("the file holds no triangles that rastray can read (1 primitive(s) skipped)");
}

#[test]
fn info_lists_each_primitive_with_its_triangles_and_colour() {
    let case = Case::new(
        "scene.gltf",
        &std::fs::read(data("scene.gltf")).expect("scene.gltf"),
    );
    let o = case.run(&["info", "scene.toml"]);
    assert!(o.status.success());
    let stdout = String::from_utf8_lossy(&o.stdout);
    for line in [
        "node 1 \"Left\", mesh 0 \"Tri\" primitive 0: 1 triangles  colour [0.100, 0.600, 0.200]",
        "node 2 \"Right\", mesh 1 \"Strip\" primitive 0: 2 triangles  colour [0.900, 0.900, 0.900]",
        "node 4 \"Fan\", mesh 2 \"Fan\" primitive 0: 6 triangles  colour [0.800, 0.800, 0.800]",
    ] {
        assert!(stdout.contains(line), "missing `{line}` in:\n{stdout}");
    }
    assert!(stdout.contains(" 11 triangles"), "{stdout}");
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(stderr.matches("warning: ").count(), 3, "{stderr}");
}

mod corrupted {
    use proptest::prelude::*;

    use super::data;

    /// `bytes` with `flips` bytes replaced and cut to `keep` of its length (in [0, 1]).
    fn corrupt(mut bytes: Vec<u8>, flips: &[(usize, u8)], keep: f64) -> Vec<u8> {
        let len = bytes.len();
        for &(at, value) in flips {
            bytes[at % len] = value;
        }
        bytes.truncate((len as f64 * keep) as usize);
        bytes
    }

    /// JSON pointers of every number in `value`.
    fn numbers(value: &serde_json::Value, at: String, out: &mut Vec<String>) {
        match value {
            serde_json::Value::Number(_) => out.push(at),
            serde_json::Value::Array(items) => {
                for (i, v) in items.iter().enumerate() {
                    numbers(v, format!("{at}/{i}"), out);
                }
            }
            serde_json::Value::Object(map) => {
                for (k, v) in map {
                    numbers(v, format!("{at}/{k}"), out);
                }
            }
            _ => {}
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(300))]

        /// Counts, offsets, strides, indices and types set to edge values: still no panic.
        #[test]
        fn models_with_wrong_numbers_never_panic(
            file in prop::sample::select(vec!["scene.gltf", "box.gltf"]),
            edits in prop::collection::vec(
                (any::<usize>(), prop::sample::select(vec![
                    0u64, 1, 2, 3, 4, 7, 12, 99, 255, 5121, 5123, 5125, 5126,
                    65_535, 4_294_967_295, 1 << 40,
                ])),
                1..4,
            ),
        ) {
            let dir = tempfile::tempdir().expect("tempdir");
            let mut doc: serde_json::Value =
                serde_json::from_slice(&std::fs::read(data(file)).expect("model")).expect("JSON");
            let mut leaves = Vec::new();
            numbers(&doc, String::new(), &mut leaves);
            for (pick, value) in edits {
                let at = &leaves[pick % leaves.len()];
                *doc.pointer_mut(at).expect("leaf") = serde_json::json!(value);
            }
            let path = dir.path().join(file);
            std::fs::write(&path, doc.to_string()).expect("write");
            std::fs::copy(data("box data.bin"), dir.path().join("box data.bin")).expect("copy");
            let _ = rastray::mesh::gltf::load_gltf(&path);
        }

        /// Whatever bytes a damaged model holds, loading it returns a model or an error: it
        /// never panics.
        #[test]
        fn damaged_models_never_panic(
            file in prop::sample::select(vec!["box.glb", "scene.gltf", "box.gltf"]),
            flips in prop::collection::vec((any::<usize>(), any::<u8>()), 0..6),
            keep in prop_oneof![Just(1.0), 0.0..1.0f64],
        ) {
            let dir = tempfile::tempdir().expect("tempdir");
            let bytes = corrupt(std::fs::read(data(file)).expect("model"), &flips, keep);
            let path = dir.path().join(file);
            std::fs::write(&path, bytes).expect("write");
            std::fs::copy(data("box data.bin"), dir.path().join("box data.bin")).expect("copy");
            let _ = rastray::mesh::gltf::load_gltf(&path);
        }
    }
}
