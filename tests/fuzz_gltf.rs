//! Fuzzing the glTF reader: the test models' JSON with values replaced anywhere in the tree,
//! their external buffer and GLB container with bytes changed, cut or grown. Loading never
//! panics; a loaded model keeps its invariants (parts with triangles, indices in range, finite
//! positions and unit normals) and tessellates into a finite mesh.
//!
//! CI runs proptest's default 256 cases; `PROPTEST_CASES=250000` runs a long session (see the
//! README, "Fuzzing").

mod common;

use std::path::{Path, PathBuf};

use proptest::prelude::*;
use rastray::mesh::gltf::load_gltf;
use rastray::mesh::tessellate_part;
use rastray::scene::{Object, Shape};
use serde_json::{Value, json};

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/gltf")
        .join(name)
}

/// The seeds, read once: the two JSON models, the GLB and the external buffer.
struct Seeds {
    json: Vec<Value>,
    glb: Vec<u8>,
    buffer: Vec<u8>,
}

fn seeds() -> &'static Seeds {
    static SEEDS: std::sync::OnceLock<Seeds> = std::sync::OnceLock::new();
    SEEDS.get_or_init(|| Seeds {
        json: ["box.gltf", "scene.gltf"]
            .iter()
            .map(|name| serde_json::from_slice(&std::fs::read(data(name)).unwrap()).unwrap())
            .collect(),
        glb: std::fs::read(data("box.glb")).unwrap(),
        buffer: std::fs::read(data("box data.bin")).unwrap(),
    })
}

/// A value spliced into the JSON: edge numbers, wrong types, indices just out of range.
fn value() -> impl Strategy<Value = Value> {
    prop_oneof![
        (-3i64..30).prop_map(|i| json!(i)),
        prop::sample::select(vec![
            json!(0),
            json!(-1),
            json!(4294967295u64),
            json!(1e30),
            json!(-0.0),
            json!(1.5),
            json!(5120),
            json!(5121),
            json!(5123),
            json!(5125),
            json!(5126),
            json!("SCALAR"),
            json!("VEC2"),
            json!("VEC3"),
            json!("MAT4"),
            json!("data:application/octet-stream;base64,AAAA"),
            json!("../box data.bin"),
            json!("https://example.com/x.bin"),
            json!("missing.bin"),
            json!(null),
            json!(true),
            json!([]),
            json!({}),
            json!([0, 1, 2]),
            json!([1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0]),
            json!([1e30, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]),
        ]),
    ]
}

/// One edit of the JSON tree: the n-th value in document order (objects and arrays included)
/// replaced, or removed from its parent.
#[derive(Debug, Clone)]
enum Edit {
    Replace(prop::sample::Index, Value),
    Remove(prop::sample::Index),
}

fn edit() -> impl Strategy<Value = Edit> {
    prop_oneof![
        4 => (any::<prop::sample::Index>(), value()).prop_map(|(i, v)| Edit::Replace(i, v)),
        1 => any::<prop::sample::Index>().prop_map(Edit::Remove),
    ]
}

fn count(v: &Value) -> usize {
    1 + match v {
        Value::Array(items) => items.iter().map(count).sum(),
        Value::Object(map) => map.values().map(count).sum(),
        _ => 0,
    }
}

/// Applies `edit` to the `n`-th value below `v` (0 is `v` itself, never removed).
fn apply(v: &mut Value, n: &mut usize, edit: &Edit) -> bool {
    let children: Vec<&mut Value> = match v {
        Value::Array(items) => items.iter_mut().collect(),
        Value::Object(map) => map.values_mut().collect(),
        _ => return false,
    };
    let mut remove = None;
    for (k, child) in children.into_iter().enumerate() {
        *n -= 1;
        if *n == 0 {
            match edit {
                Edit::Replace(_, value) => *child = value.clone(),
                Edit::Remove(_) => remove = Some(k),
            }
            break;
        }
        if apply(child, n, edit) {
            return true;
        }
    }
    match (remove, v) {
        (Some(k), Value::Array(items)) => {
            items.remove(k);
        }
        (Some(k), Value::Object(map)) => {
            let key = map.keys().nth(k).cloned().expect("the k-th key");
            map.remove(&key);
        }
        _ => {}
    }
    *n == 0
}

/// A byte-level change: flip bytes, cut the end, or append.
#[derive(Debug, Clone)]
enum Bytes {
    Set(Vec<(prop::sample::Index, u8)>),
    Truncate(prop::sample::Index),
    Append(Vec<u8>),
}

fn bytes_edit() -> impl Strategy<Value = Bytes> {
    prop_oneof![
        4 => prop::collection::vec((any::<prop::sample::Index>(), any::<u8>()), 1..6).prop_map(Bytes::Set),
        1 => any::<prop::sample::Index>().prop_map(Bytes::Truncate),
        1 => prop::collection::vec(any::<u8>(), 1..16).prop_map(Bytes::Append),
    ]
}

fn change(bytes: &mut Vec<u8>, edit: &Bytes) {
    match edit {
        Bytes::Set(sets) => {
            for (at, b) in sets {
                if !bytes.is_empty() {
                    let i = at.index(bytes.len());
                    bytes[i] = *b;
                }
            }
        }
        Bytes::Truncate(at) => bytes.truncate(at.index(bytes.len() + 1)),
        Bytes::Append(more) => bytes.extend_from_slice(more),
    }
}

/// A model folder's files: the model's name and bytes, and the external buffer's bytes.
#[derive(Debug, Clone)]
struct Case {
    name: &'static str,
    model: Vec<u8>,
    buffer: Vec<u8>,
}

fn case() -> impl Strategy<Value = Case> {
    let json_case = (
        any::<prop::sample::Index>(),
        prop::collection::vec(edit(), 0..5),
        prop::option::of(bytes_edit()),
    )
        .prop_map(|(seed, edits, buffer_edit)| {
            let seeds = seeds();
            let mut document = seeds.json[seed.index(seeds.json.len())].clone();
            for edit in &edits {
                let at = match edit {
                    Edit::Replace(i, _) | Edit::Remove(i) => i,
                };
                let mut n = at.index(count(&document));
                if n > 0 {
                    apply(&mut document, &mut n, edit);
                }
            }
            let mut buffer = seeds.buffer.clone();
            if let Some(e) = &buffer_edit {
                change(&mut buffer, e);
            }
            Case {
                name: "fuzz.gltf",
                model: document.to_string().into_bytes(),
                buffer,
            }
        });
    let glb_case = prop::collection::vec(bytes_edit(), 1..4).prop_map(|edits| {
        let mut glb = seeds().glb.clone();
        for e in &edits {
            change(&mut glb, e);
        }
        Case {
            name: "fuzz.glb",
            model: glb,
            buffer: seeds().buffer.clone(),
        }
    });
    prop_oneof![3 => json_case, 1 => glb_case]
}

proptest! {
    #![proptest_config(ProptestConfig::default())]

    #[test]
    fn gltf_files_load_or_are_refused(case in case()) {
        let dir = common::scratch();
        let path = dir.join(case.name);
        std::fs::write(&path, &case.model).unwrap();
        std::fs::write(dir.join("box data.bin"), &case.buffer).unwrap();
        let Ok(model) = load_gltf(&path) else {
            return Ok(());
        };
        prop_assert!(!model.parts.is_empty());
        prop_assert!(model.triangle_count() > 0);
        let (lo, hi) = model.bounds();
        let centre = (lo + hi) * 0.5;
        let object = Object::new(Shape::Mesh {
            path: path.clone(),
            position: glam::Vec3::ZERO,
            scale: 1.0,
            up: Default::default(),
            materials: rastray::scene::MaterialSource::File,
        });
        for part in &model.parts {
            let g = &part.geometry;
            for &i in g.triangles.iter().flatten() {
                prop_assert!((i as usize) < g.positions.len());
            }
            prop_assert!(g.positions.iter().all(|p| p.is_finite()), "{}", part.label);
            if let Some(normals) = &g.corner_normals {
                prop_assert_eq!(normals.len(), g.triangles.len());
                for n in normals.iter().flatten() {
                    prop_assert!(n.is_finite() && (n.length() - 1.0).abs() < 1e-3, "{n}");
                }
            }
            if centre.is_finite() {
                let mesh = tessellate_part(&object, g, centre);
                prop_assert_eq!(mesh.triangle_count(), g.triangles.len());
                prop_assert!(mesh.normals.iter().all(|n| n.is_finite()));
            }
        }
    }
}

/// Found by the fuzzer: a primitive with fewer than three indices became a part with no
/// triangles, and a file of only such primitives loaded as a model that draws nothing.
#[test]
fn a_primitive_with_fewer_than_three_indices_draws_nothing_and_is_refused() {
    let seeds = seeds();
    let mut document = seeds.json[0].clone();
    document["accessors"][2]["count"] = json!(1);
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("one index.gltf");
    std::fs::write(&path, document.to_string()).unwrap();
    std::fs::write(dir.path().join("box data.bin"), &seeds.buffer).unwrap();
    let error = load_gltf(&path).expect_err("no triangles").to_string();
    assert_eq!(error, "the file holds no triangles");
}
