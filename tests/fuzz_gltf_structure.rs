//! Fuzzing the glTF reader's structure, where `fuzz_gltf` edits values: documents built from
//! node trees and graphs (deep, wide, shared and cyclic), accessors with huge or lying counts,
//! strides and offsets, sparse accessors, buffers from data URIs of every shape and from paths
//! that try to leave the model's folder, and GLB containers whose chunk lengths are cut short or
//! grown past the file. Loading never panics, never reads outside the folder (a file there is a
//! FIFO: opening it would block the test), and a loaded model keeps its invariants.
//!
//! CI runs proptest's default 256 cases; `scripts/fuzz.sh` runs a long session.

mod common;

use base64::Engine;
use base64::engine::general_purpose::STANDARD;
use proptest::prelude::*;
use rastray::mesh::gltf::load_gltf;
use serde_json::{Value, json};

/// A cube's 8 corners and 12 triangles: positions (96 bytes), then u16 indices (72 bytes).
fn cube_buffer() -> Vec<u8> {
    let mut bytes = Vec::new();
    for i in 0..8u32 {
        for axis in 0..3 {
            let v: f32 = if i >> axis & 1 == 1 { 1.0 } else { -1.0 };
            bytes.extend_from_slice(&v.to_le_bytes());
        }
    }
    let faces: [u16; 36] = [
        0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4, 2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6,
        1, 3, 5, 3, 7, 5,
    ];
    for i in faces {
        bytes.extend_from_slice(&i.to_le_bytes());
    }
    bytes
}

/// Where the buffer's bytes come from.
#[derive(Debug, Clone)]
enum BufferSource {
    /// A base64 data URI, possibly mangled.
    DataUri { mangle: u8 },
    /// A file beside the model.
    Beside,
    /// A path that tries to leave the folder (the target is a FIFO outside).
    Outside(usize),
    /// The GLB binary chunk.
    Glb,
}

/// How the node hierarchy is shaped.
#[derive(Debug, Clone)]
enum Nodes {
    /// A full tree of `depth` levels, each node `branching` children, all naming mesh 0.
    Tree { depth: u32, branching: u32 },
    /// A chain whose last node points back at `back`.
    Cycle { length: usize, back: usize },
    /// Nodes that name children that do not exist, or themselves.
    Broken { children: Vec<i64> },
}

#[derive(Debug, Clone)]
struct Case {
    nodes: Nodes,
    source: BufferSource,
    /// Overrides of the index accessor: count, byteOffset, and the view's byteStride.
    index_count: u64,
    index_offset: u64,
    stride: Option<u64>,
    /// A sparse block on the positions, with this many entries.
    sparse: Option<u64>,
    /// The buffer's declared byteLength, as a multiple of the real one (0 = the real one).
    declared_scale: u64,
    /// For GLB: changes to the JSON and BIN chunk length fields.
    json_chunk_delta: i64,
    bin_chunk_delta: i64,
}

const OUTSIDE: [&str; 6] = [
    "../outside/secret.bin",
    "%2e%2e/outside/secret.bin",
    "..%2Foutside%2Fsecret.bin",
    "sub/../../outside/secret.bin",
    "link/secret.bin",
    "..\\outside\\secret.bin",
];

fn nodes() -> impl Strategy<Value = Nodes> {
    prop_oneof![
        (0u32..9, 1u32..4).prop_map(|(depth, branching)| Nodes::Tree { depth, branching }),
        (1usize..6, 0usize..6).prop_map(|(length, back)| Nodes::Cycle { length, back }),
        prop::collection::vec(-2i64..8, 0..6).prop_map(|children| Nodes::Broken { children }),
    ]
}

fn source() -> impl Strategy<Value = BufferSource> {
    prop_oneof![
        2 => any::<u8>().prop_map(|mangle| BufferSource::DataUri { mangle }),
        2 => Just(BufferSource::Beside),
        2 => (0..OUTSIDE.len()).prop_map(BufferSource::Outside),
        2 => Just(BufferSource::Glb),
    ]
}

/// A chunk length field's change: mostly none, sometimes a little, sometimes far past the file.
fn chunk_delta() -> impl Strategy<Value = i64> {
    prop_oneof![4 => Just(0i64), 1 => -64i64..64, 1 => Just(i32::MAX as i64)]
}

prop_compose! {
    fn case()(
        nodes in nodes(),
        source in source(),
        index_count in prop_oneof![
            4 => Just(36u64),
            1 => 0u64..40,
            1 => prop::sample::select(vec![u32::MAX as u64, 1 << 40, 1_000_000_000]),
        ],
        index_offset in prop_oneof![4 => Just(0u64), 1 => 0u64..200, 1 => Just(u32::MAX as u64)],
        stride in prop::option::of(prop_oneof![Just(2u64), Just(1), Just(4), Just(255), Just(1 << 31)]),
        sparse in prop::option::of(prop_oneof![0u64..10, Just(u32::MAX as u64)]),
        declared_scale in prop_oneof![4 => Just(0u64), 1 => 1u64..4, 1 => Just(1 << 30)],
        json_chunk_delta in chunk_delta(),
        bin_chunk_delta in chunk_delta(),
    ) -> Case {
        Case {
            nodes, source, index_count, index_offset, stride, sparse, declared_scale,
            json_chunk_delta, bin_chunk_delta,
        }
    }
}

/// The nodes array and the scene's root list for `shape`.
fn nodes_of(shape: &Nodes) -> (Vec<Value>, Vec<usize>) {
    match shape {
        Nodes::Tree { depth, branching } => {
            let mut nodes: Vec<Value> = Vec::new();
            let mut level = vec![0usize];
            nodes.push(json!({ "mesh": 0 }));
            for _ in 0..*depth {
                let mut next = Vec::new();
                for &parent in &level {
                    let mut children = Vec::new();
                    for _ in 0..*branching {
                        children.push(nodes.len());
                        next.push(nodes.len());
                        nodes.push(json!({ "mesh": 0, "translation": [0.5, 0.0, 0.0] }));
                    }
                    nodes[parent]["children"] = json!(children);
                }
                level = next;
            }
            (nodes, vec![0])
        }
        Nodes::Cycle { length, back } => {
            let nodes = (0..*length)
                .map(|i| {
                    let child = if i + 1 < *length {
                        i + 1
                    } else {
                        back % length
                    };
                    json!({ "mesh": 0, "children": [child] })
                })
                .collect();
            (nodes, vec![0])
        }
        Nodes::Broken { children } => {
            let nodes = vec![
                json!({ "mesh": 0, "children": children }),
                json!({ "mesh": 0 }),
            ];
            (nodes, vec![0, 1])
        }
    }
}

/// The model's files: its name, its bytes, and the buffer file beside it (when it has one).
fn build(case: &Case, buffer: &[u8]) -> (&'static str, Vec<u8>, Option<Vec<u8>>) {
    let (nodes, roots) = nodes_of(&case.nodes);
    let declared = if case.declared_scale == 0 {
        buffer.len() as u64
    } else {
        buffer.len() as u64 * case.declared_scale
    };
    let uri = match &case.source {
        BufferSource::DataUri { mangle } => {
            let mut text = format!(
                "data:application/octet-stream;base64,{}",
                STANDARD.encode(buffer)
            );
            match mangle % 5 {
                0 => {}
                1 => text.truncate(text.len() / 2),
                2 => text = text.replace(";base64,", ","),
                3 => text.push_str("!!"),
                _ => text = "data:".into(),
            }
            Some(text)
        }
        BufferSource::Beside => Some("cube%20data.bin".to_string()),
        BufferSource::Outside(i) => Some(OUTSIDE[*i].to_string()),
        BufferSource::Glb => None,
    };
    let mut buffer_json = json!({ "byteLength": declared });
    if let Some(uri) = &uri {
        buffer_json["uri"] = json!(uri);
    }
    let mut index_view = json!({ "buffer": 0, "byteOffset": 96, "byteLength": 72 });
    if let Some(stride) = case.stride {
        index_view["byteStride"] = json!(stride);
    }
    let mut positions = json!({
        "bufferView": 0, "componentType": 5126, "count": 8, "type": "VEC3",
        "min": [-1.0, -1.0, -1.0], "max": [1.0, 1.0, 1.0]
    });
    if let Some(count) = case.sparse {
        positions["sparse"] = json!({
            "count": count,
            "indices": { "bufferView": 1, "componentType": 5123 },
            "values": { "bufferView": 0 }
        });
    }
    let document = json!({
        "asset": { "version": "2.0" },
        "scene": 0,
        "scenes": [{ "nodes": roots }],
        "nodes": nodes,
        "meshes": [{ "primitives": [{ "attributes": { "POSITION": 0 }, "indices": 1 }] }],
        "buffers": [buffer_json],
        "bufferViews": [
            { "buffer": 0, "byteOffset": 0, "byteLength": 96 },
            index_view
        ],
        "accessors": [
            positions,
            {
                "bufferView": 1, "byteOffset": case.index_offset,
                "componentType": 5123, "count": case.index_count, "type": "SCALAR"
            }
        ]
    });
    let text = document.to_string().into_bytes();
    match case.source {
        BufferSource::Glb => ("cube.glb", glb(case, &text, buffer), None),
        BufferSource::Beside => ("cube.gltf", text, Some(buffer.to_vec())),
        _ => ("cube.gltf", text, None),
    }
}

/// A GLB container of `json` and `bin`, with its chunk length fields moved by the case's deltas.
fn glb(case: &Case, json: &[u8], bin: &[u8]) -> Vec<u8> {
    let pad = |bytes: &[u8], fill: u8| {
        let mut v = bytes.to_vec();
        while !v.len().is_multiple_of(4) {
            v.push(fill);
        }
        v
    };
    let (json, bin) = (pad(json, b' '), pad(bin, 0));
    let field = |len: usize, delta: i64| {
        (len as i64).saturating_add(delta).clamp(0, u32::MAX as i64) as u32
    };
    let mut out = Vec::new();
    let total = 12 + 8 + json.len() + 8 + bin.len();
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&field(json.len(), case.json_chunk_delta).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&json);
    out.extend_from_slice(&field(bin.len(), case.bin_chunk_delta).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(&bin);
    out
}

/// A fresh folder `model/` beside `outside/` (holding the FIFO `secret.bin`), with `model/link`
/// a symlink to `outside/`.
fn layout() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir_all(dir.path().join("outside")).unwrap();
    std::fs::create_dir_all(dir.path().join("model/sub")).unwrap();
    common::mkfifo(&dir.path().join("outside/secret.bin"));
    std::os::unix::fs::symlink(dir.path().join("outside"), dir.path().join("model/link")).unwrap();
    dir
}

/// The case's files written into a fresh [`layout`]: the folder, and the model's path.
fn written(case: &Case) -> (tempfile::TempDir, std::path::PathBuf) {
    let dir = layout();
    let (name, model, beside) = build(case, &cube_buffer());
    let path = dir.path().join("model").join(name);
    std::fs::write(&path, model).unwrap();
    if let Some(bytes) = beside {
        std::fs::write(dir.path().join("model/cube data.bin"), bytes).unwrap();
    }
    (dir, path)
}

proptest! {
    #![proptest_config(ProptestConfig::default())]

    #[test]
    fn structured_gltf_files_load_or_are_refused(case in case()) {
        let (_dir, path) = written(&case);
        // Returning at all shows the FIFO outside was never opened for reading.
        let result = load_gltf(&path);
        if let BufferSource::Outside(_) = case.source {
            // Refused: by the buffer's path, or by an earlier check of the document.
            let error = result.as_ref().err().map(|e| e.to_string());
            prop_assert!(error.is_some(), "a buffer outside the folder loaded");
            let error = error.unwrap_or_default();
            if error.starts_with("buffer 0") {
                prop_assert!(error.contains("outside the model's folder"), "{error}");
            }
        }
        let Ok(model) = result else { return Ok(()) };
        prop_assert!(!model.parts.is_empty());
        for part in &model.parts {
            let g = &part.geometry;
            for &i in g.triangles.iter().flatten() {
                prop_assert!((i as usize) < g.positions.len());
            }
            prop_assert!(g.positions.iter().all(|p| p.is_finite()));
        }
        if let Nodes::Tree { depth, branching } = case.nodes {
            // Every node of the tree draws the cube once (when nothing else was refused): the
            // cube is read once and placed at each node.
            let nodes: u32 = (0..=depth).map(|d| branching.pow(d)).sum();
            let drawn: usize = model.parts.iter().map(|p| p.instances.len().max(1)).sum();
            prop_assert_eq!(drawn as u32, nodes);
        }
    }
}

#[test]
fn the_plain_case_loads_from_every_source() {
    for source in [
        BufferSource::DataUri { mangle: 0 },
        BufferSource::Beside,
        BufferSource::Glb,
    ] {
        let case = Case {
            nodes: Nodes::Tree {
                depth: 2,
                branching: 2,
            },
            source,
            index_count: 36,
            index_offset: 0,
            stride: None,
            sparse: None,
            declared_scale: 0,
            json_chunk_delta: 0,
            bin_chunk_delta: 0,
        };
        let (_dir, path) = written(&case);
        let model = load_gltf(&path).unwrap_or_else(|e| panic!("{case:?}: {e}"));
        // The cube is read once, its mesh named by all 1 + 2 + 4 nodes.
        assert_eq!(model.parts.len(), 1);
        assert_eq!(model.parts[0].instances.len(), 7, "1 + 2 + 4 nodes");
        assert_eq!(model.triangle_count(), 7 * 12);
    }
}
