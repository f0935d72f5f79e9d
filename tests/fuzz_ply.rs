//! Fuzzing the PLY reader: files whose headers declare elements in any order, of every
//! scalar type, with lists and unknown elements, written in ASCII or binary of either byte
//! order with ordinary and edge values; then perhaps cut short or with bytes overwritten; and
//! headers made of random lines. Loading never panics; a loaded model keeps its invariants; a
//! refusal names the file.
//!
//! CI runs proptest's default 256 cases; `scripts/fuzz.sh` runs a long session.

mod common;

use common::ply_types::TYPES;
use proptest::prelude::*;
use rastray::mesh::load_ply;

/// A value of type `ty` (an index into [`TYPES`]) in the encoding: its text and its bytes.
fn encode(ty: usize, value: f64, big: bool) -> (String, Vec<u8>) {
    let mut bytes = match ty {
        0 => vec![value as i8 as u8],
        1 => vec![value as u8],
        2 => (value as i16).to_le_bytes().to_vec(),
        3 => (value as u16).to_le_bytes().to_vec(),
        4 => (value as i32).to_le_bytes().to_vec(),
        5 => (value as u32).to_le_bytes().to_vec(),
        6 => (value as f32).to_le_bytes().to_vec(),
        _ => value.to_le_bytes().to_vec(),
    };
    if big {
        bytes.reverse();
    }
    let text = if ty >= 6 {
        format!("{value:?}")
    } else {
        format!("{}", value as i64)
    };
    (text, bytes)
}

/// A value as a file may hold it.
fn value() -> impl Strategy<Value = f64> {
    prop_oneof![
        8 => -10.0f64..10.0,
        4 => 0.0f64..8.0,
        1 => Just(1e6),
        1 => Just(3e7),
        1 => Just(f64::NAN),
        1 => Just(f64::INFINITY),
        1 => Just(-1.0),
        1 => Just(4e9),
    ]
}

/// A property: a name (a vertex attribute or another), a scalar type, or a list.
#[derive(Debug, Clone)]
struct Property {
    name: &'static str,
    ty: usize,
    /// The list's length type, for a list.
    list: Option<usize>,
}

fn property() -> impl Strategy<Value = Property> {
    (
        prop::sample::select(vec![
            "x",
            "y",
            "z",
            "nx",
            "ny",
            "nz",
            "red",
            "green",
            "blue",
            "s",
            "t",
            "u",
            "v",
            "vertex_indices",
            "vertex_index",
            "texcoord",
            "other",
        ]),
        0..8usize,
        prop_oneof![4 => Just(None), 1 => (0..6usize).prop_map(Some)],
    )
        .prop_map(|(name, ty, list)| Property { name, ty, list })
}

/// An element: its name, its properties, and the values of its records.
type ElementSpec = (&'static str, Vec<Property>, Vec<Vec<f64>>);

/// An element: a name, a count, properties, and the values of its records.
fn element() -> impl Strategy<Value = ElementSpec> {
    (
        prop::sample::select(vec!["vertex", "vertex", "face", "face", "edge"]),
        prop::collection::vec(property(), 0..6),
        0..8usize,
    )
        .prop_flat_map(|(name, properties, count)| {
            let width = properties.len() * 5;
            (
                Just(name),
                Just(properties),
                prop::collection::vec(prop::collection::vec(value(), width), count),
            )
        })
}

/// A vertex element with x y z (and perhaps colours and texture coordinates) of `types`, and
/// a face element of triangles and quads naming them: a file that should load.
fn valid_elements() -> impl Strategy<Value = Vec<ElementSpec>> {
    (3usize..9, 0..8usize, 0..8usize, any::<bool>(), 1usize..6).prop_flat_map(
        |(vertices, ty, color_ty, extras, faces)| {
            let mut properties: Vec<Property> = ["x", "y", "z"]
                .into_iter()
                .map(|name| Property {
                    name,
                    ty: ty.max(2),
                    list: None,
                })
                .collect();
            if extras {
                for name in ["red", "green", "blue"] {
                    properties.push(Property {
                        name,
                        ty: color_ty,
                        list: None,
                    });
                }
                for name in ["s", "t"] {
                    properties.push(Property {
                        name,
                        ty: 6,
                        list: None,
                    });
                }
            }
            let width = properties.len();
            let vertex =
                prop::collection::vec(prop::collection::vec(0.0f64..100.0, width), vertices);
            let face = prop::collection::vec(
                prop::collection::vec(0..vertices as u64, 3..5).prop_map(|c| {
                    std::iter::once(c.len() as f64)
                        .chain(c.into_iter().map(|i| i as f64))
                        .collect::<Vec<f64>>()
                }),
                faces,
            );
            (Just(properties), vertex, face).prop_map(|(properties, vertex, face)| {
                vec![
                    ("vertex", properties, vertex),
                    (
                        "face",
                        vec![Property {
                            name: "vertex_indices",
                            ty: 5,
                            list: Some(1),
                        }],
                        face,
                    ),
                ]
            })
        },
    )
}

/// The file of `elements` in `format` (0 ascii, 1 little-endian, 2 big-endian). A record's
/// values are taken in turn: a scalar takes one, a list one for its length (taken modulo 5)
/// and then that many.
fn write(format: u8, elements: &[ElementSpec]) -> Vec<u8> {
    let name = ["ascii", "binary_little_endian", "binary_big_endian"][format as usize];
    let mut text = format!("ply\nformat {name} 1.0\ncomment TextureFile t.png\n");
    for (element, properties, records) in elements {
        text += &format!("element {element} {}\n", records.len());
        for p in properties {
            text += &match p.list {
                Some(count) => format!(
                    "property list {} {} {}\n",
                    TYPES[count].0, TYPES[p.ty].0, p.name
                ),
                None => format!("property {} {}\n", TYPES[p.ty].0, p.name),
            };
        }
    }
    text += "end_header\n";
    let mut bytes = text.into_bytes();
    let big = format == 2;
    for (_, properties, records) in elements {
        for record in records {
            let mut values = record.iter().copied().chain(std::iter::repeat(0.0));
            let mut words = Vec::new();
            for p in properties {
                let mut put = |ty, value| {
                    let (text, raw) = encode(ty, value, big);
                    if format == 0 {
                        words.push(text);
                    } else {
                        bytes.extend(raw);
                    }
                };
                match p.list {
                    None => put(p.ty, values.next().unwrap_or(0.0)),
                    Some(count) => {
                        let n = values.next().unwrap_or(0.0).abs() as usize % 5;
                        put(count, n as f64);
                        for _ in 0..n {
                            put(p.ty, values.next().unwrap_or(0.0));
                        }
                    }
                }
            }
            if format == 0 {
                bytes.extend(words.join(" ").into_bytes());
                bytes.push(b'\n');
            }
        }
    }
    bytes
}

/// A whole file: valid or random elements in any format, then perhaps cut or overwritten; or
/// a header of random lines.
fn file() -> impl Strategy<Value = Vec<u8>> {
    let elements = prop_oneof![valid_elements(), prop::collection::vec(element(), 0..4),];
    prop_oneof![
        4 => (
            0u8..3,
            elements,
            prop_oneof![4 => Just(None), 1 => any::<prop::sample::Index>().prop_map(Some)],
            prop::collection::vec((any::<prop::sample::Index>(), any::<u8>()), 0..2),
        )
            .prop_map(|(format, elements, cut, flips)| {
                let mut bytes = write(format, &elements);
                if let Some(cut) = cut {
                    bytes.truncate(cut.index(bytes.len() + 1));
                }
                for (at, value) in flips {
                    if !bytes.is_empty() {
                        let i = at.index(bytes.len());
                        bytes[i] = value;
                    }
                }
                bytes
            }),
        1 => prop::collection::vec(
            prop_oneof![
                prop::sample::select(vec![
                    "ply", "format ascii 1.0", "format binary_big_endian 1.0", "element vertex 3",
                    "element face 1", "property float x", "property list uchar int vertex_indices",
                    "property list float int vertex_indices", "end_header", "comment x",
                    "element vertex 99999999999", "property", "element",
                ])
                .prop_map(str::to_string),
                "[ -~]{0,20}",
            ],
            0..12,
        )
        .prop_map(|lines| format!("ply\n{}\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", lines.join("\n")).into_bytes()),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::default())]

    #[test]
    fn ply_files_load_or_are_refused_with_their_name(bytes in file()) {
        let path = common::scratch().join("fuzz.ply");
        std::fs::write(&path, &bytes).unwrap();
        let outcome = load_ply(&path);
        let wrong = common::model_invariants::wrong_outcome(&path, outcome.as_ref().map(|m| &m.geometry));
        prop_assert!(wrong.is_none(), "{wrong:?}");
    }
}

/// The valid generator does make files that load: the target tests the reader, not only its
/// refusals.
#[test]
fn the_valid_files_load() {
    use proptest::strategy::ValueTree;
    let mut runner = proptest::test_runner::TestRunner::deterministic();
    let mut loaded = 0;
    for format in 0..3 {
        for _ in 0..20 {
            let elements = valid_elements().new_tree(&mut runner).unwrap().current();
            let path = common::scratch().join(format!("valid{format}.ply"));
            std::fs::write(&path, write(format, &elements)).unwrap();
            match load_ply(&path) {
                Ok(model) => {
                    assert_eq!(common::model_invariants::broken(&model.geometry), None);
                    loaded += 1;
                }
                Err(error) => panic!("{error}"),
            }
        }
    }
    assert_eq!(loaded, 60);
}
