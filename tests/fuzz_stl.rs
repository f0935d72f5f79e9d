//! Fuzzing the STL reader: binary files with edge-valued coordinates and counts that agree or
//! disagree with their size, cut short or with bytes flipped; ASCII files made of valid,
//! edge-valued and broken lines. Loading never panics; a loaded model keeps its invariants;
//! a refusal names the file.
//!
//! CI runs proptest's default 256 cases; `scripts/fuzz.sh` runs a long session.

mod common;

use proptest::prelude::*;
use rastray::mesh::load_stl;

/// A coordinate: ordinary, at or past the limits, or not a number.
fn coordinate() -> impl Strategy<Value = f32> {
    prop_oneof![
        8 => -10.0f32..10.0,
        1 => Just(1e6f32),
        1 => Just(-1e6f32),
        1 => Just(1.000_001e6f32),
        1 => Just(f32::MAX),
        1 => Just(f32::NAN),
        1 => Just(f32::INFINITY),
        1 => Just(f32::MIN_POSITIVE / 2.0),
        1 => Just(-0.0f32),
    ]
}

/// A binary STL: a header (sometimes beginning with `solid`), a count, the triangles, then
/// perhaps cut short, lengthened, or with a few bytes overwritten.
fn binary() -> impl Strategy<Value = Vec<u8>> {
    (
        any::<bool>(),
        prop::collection::vec(prop::collection::vec(coordinate(), 9), 0..12),
        prop_oneof![6 => Just(None), 1 => any::<u32>().prop_map(Some), 1 => (0u32..20).prop_map(Some)],
        prop_oneof![6 => Just(0isize), 1 => -60isize..60],
        prop::collection::vec((any::<prop::sample::Index>(), any::<u8>()), 0..3),
    )
        .prop_map(|(solid, triangles, count, resize, flips)| {
            let mut bytes = if solid { b"solid part".to_vec() } else { Vec::new() };
            bytes.resize(80, b' ');
            let count = count.unwrap_or(triangles.len() as u32);
            bytes.extend(count.to_le_bytes());
            for t in &triangles {
                bytes.extend([0u8; 12]);
                bytes.extend(t.iter().flat_map(|c| c.to_le_bytes()));
                bytes.extend([0, 0]);
            }
            let len = (bytes.len() as isize + resize).max(0) as usize;
            bytes.resize(len, 0);
            for (at, value) in flips {
                if !bytes.is_empty() {
                    let i = at.index(bytes.len());
                    bytes[i] = value;
                }
            }
            bytes
        })
}

/// One line of an ASCII STL.
fn line() -> impl Strategy<Value = String> {
    let number = prop_oneof![
        6 => (-10.0f32..10.0).prop_map(|x| x.to_string()),
        1 => Just("1e6".to_string()),
        1 => Just("1e7".to_string()),
        1 => Just("nan".to_string()),
        1 => Just("-inf".to_string()),
        1 => Just("x".to_string()),
    ];
    prop_oneof![
        4 => prop::collection::vec(number, 2..5).prop_map(|xs| format!("vertex {}", xs.join(" "))),
        1 => prop::sample::select(vec![
            "solid a", "endsolid a", "facet normal 0 0 1", "outer loop", "endloop",
            "endfacet", "", "  ", "FACET", "outer", "solid", "endsolid",
        ])
        .prop_map(str::to_string),
        1 => "[ -~]{0,20}",
    ]
}

/// An ASCII STL: valid facets with a few random lines mixed in, or random lines.
fn ascii() -> impl Strategy<Value = Vec<u8>> {
    let facet = prop::collection::vec((-10.0f32..10.0, -10.0f32..10.0, -10.0f32..10.0), 3..5)
        .prop_map(|corners| {
            let mut text = "facet normal 0 0 1\nouter loop\n".to_string();
            for (x, y, z) in corners {
                text += &format!("vertex {x} {y} {z}\n");
            }
            text + "endloop\nendfacet\n"
        });
    prop_oneof![
        (
            prop::collection::vec(facet, 1..6),
            prop::collection::vec((any::<prop::sample::Index>(), line()), 0..3),
            any::<bool>(),
        )
            .prop_map(|(facets, extra, crlf)| {
                let mut lines: Vec<String> = vec!["solid fuzz".into()];
                lines.extend(facets.join("").lines().map(str::to_string));
                lines.push("endsolid fuzz".into());
                for (at, line) in extra {
                    let at = at.index(lines.len() + 1);
                    lines.insert(at, line);
                }
                lines.join(if crlf { "\r\n" } else { "\n" }).into_bytes()
            }),
        prop::collection::vec(line(), 0..30).prop_map(|lines| format!(
            "solid x\n{}",
            lines.join("\n")
        )
        .into_bytes()),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::default())]

    #[test]
    fn stl_files_load_or_are_refused_with_their_name(
        bytes in prop_oneof![binary(), ascii()]
    ) {
        let path = common::scratch().join("fuzz.stl");
        std::fs::write(&path, &bytes).unwrap();
        let outcome = load_stl(&path);
        let wrong = common::model_invariants::wrong_outcome(&path, outcome.as_ref().map(|m| &m.geometry));
        prop_assert!(wrong.is_none(), "{wrong:?}");
    }
}
