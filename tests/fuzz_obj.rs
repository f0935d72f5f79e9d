//! Fuzzing the OBJ reader: files made of valid, edge-valued and broken statements. Loading
//! never panics; a loaded model keeps its invariants (indices in range, every vertex used and
//! within the coordinate limits, one unit normal triple per triangle) and has the triangles its
//! faces fan into; a refusal names the file.
//!
//! CI runs proptest's default 256 cases; `PROPTEST_CASES=250000` runs a long session (see the
//! README, "Fuzzing").

mod common;

use std::path::Path;

use proptest::prelude::*;
use rastray::mesh::{load_obj, read_obj, read_obj_in_blocks, tessellate};
use rastray::scene::limits::COORDINATE;
use rastray::scene::{Object, Shape};

/// A number as an OBJ file might spell it: ordinary, at or past the limits, or not a number.
fn number() -> impl Strategy<Value = String> {
    prop_oneof![
        6 => (-10.0f32..10.0).prop_map(|x| x.to_string()),
        1 => Just("1e6".to_string()),
        1 => Just("-1000000".to_string()),
        1 => Just("1000000.1".to_string()),
        1 => Just("3.4e38".to_string()),
        1 => Just("-3.4e38".to_string()),
        1 => Just("nan".to_string()),
        1 => Just("inf".to_string()),
        1 => Just("1e-45".to_string()),
        1 => Just("-0".to_string()),
        1 => Just("x".to_string()),
        1 => Just(String::new()),
    ]
}

/// A face corner index as written: small positive and negative ones mostly, and edge values.
fn index() -> impl Strategy<Value = String> {
    prop_oneof![
        8 => (1i64..12).prop_map(|i| i.to_string()),
        3 => (-12i64..0).prop_map(|i| i.to_string()),
        1 => Just("0".to_string()),
        1 => Just("4294967296".to_string()),
        1 => Just("-9223372036854775808".to_string()),
        1 => Just("a".to_string()),
    ]
}

/// One face corner: `v`, `v/vt`, `v//vn` or `v/vt/vn`.
fn corner() -> impl Strategy<Value = String> {
    (index(), index(), index(), 0..5u8).prop_map(|(v, t, n, form)| match form {
        0 | 1 => v,
        2 => format!("{v}/{t}"),
        3 => format!("{v}//{n}"),
        _ => format!("{v}/{t}/{n}"),
    })
}

/// One line of an OBJ file.
fn line() -> impl Strategy<Value = String> {
    prop_oneof![
        8 => prop::collection::vec(number(), 2..5).prop_map(|xs| format!("v {}", xs.join(" "))),
        2 => prop::collection::vec(number(), 2..4).prop_map(|xs| format!("vn {}", xs.join(" "))),
        1 => prop::collection::vec(number(), 2..3).prop_map(|xs| format!("vt {}", xs.join(" "))),
        6 => prop::collection::vec(corner(), 0..7).prop_map(|cs| format!("f {}", cs.join(" "))),
        1 => prop::collection::vec(corner(), 0..4).prop_map(|cs| format!("l {}", cs.join(" "))),
        1 => prop::sample::select(vec![
            "# comment", "", "o part", "g group", "s 1", "usemtl red", "mtllib x.mtl", "p 1",
            "\t  ", "f", "v", "\\",
        ])
        .prop_map(str::to_string),
        1 => "[ -~]{0,20}",
    ]
}

/// A file that should load: ordinary vertices, then faces whose corners name them (from the
/// start or back from the end), all with normals or none.
fn valid_file() -> impl Strategy<Value = Vec<String>> {
    (3usize..12, any::<bool>()).prop_flat_map(|(vertices, normals)| {
        let vertex = prop::collection::vec(-100.0f32..100.0, 3)
            .prop_map(|xyz| format!("v {} {} {}", xyz[0], xyz[1], xyz[2]));
        let n = vertices as i64;
        let corner = (prop_oneof![1..=n, -n..=-1], 0..3u8).prop_map(move |(i, form)| {
            match (normals, form) {
                (true, 0) => format!("{i}//1"),
                (true, _) => format!("{i}/1/-1"),
                (false, 0) => format!("{i}"),
                (false, _) => format!("{i}/1"),
            }
        });
        let face = prop::collection::vec(corner, 3..7).prop_map(|cs| format!("f {}", cs.join(" ")));
        (
            prop::collection::vec(vertex, vertices),
            prop::collection::vec(face, 1..10),
        )
            .prop_map(move |(mut lines, faces)| {
                lines.push("vt 0 0".to_string());
                if normals {
                    lines.push("vn 0 0.5 0.5".to_string());
                }
                lines.extend(faces);
                lines
            })
    })
}

/// A whole file, random or valid (with a few random lines mixed in), joined by LF or CRLF.
fn file() -> impl Strategy<Value = String> {
    let lines = prop_oneof![
        prop::collection::vec(line(), 0..40),
        (
            valid_file(),
            prop::collection::vec((any::<prop::sample::Index>(), line()), 0..3)
        )
            .prop_map(|(mut lines, extra)| {
                for (at, line) in extra {
                    let at = at.index(lines.len() + 1);
                    lines.insert(at, line);
                }
                lines
            }),
    ];
    (lines, any::<bool>()).prop_map(|(lines, crlf)| lines.join(if crlf { "\r\n" } else { "\n" }))
}

proptest! {
    #![proptest_config(ProptestConfig::default())]

    #[test]
    fn obj_files_load_or_are_refused_with_their_name(text in file()) {
        let path = common::scratch().join("fuzz.obj");
        std::fs::write(&path, &text).unwrap();
        match load_obj(&path) {
            Err(error) => {
                let message = error.to_string();
                prop_assert!(message.starts_with(&path.display().to_string()), "{message}");
            }
            Ok(model) => {
                prop_assert!(!model.triangles.is_empty());
                let mut used = vec![false; model.positions.len()];
                for &i in model.triangles.iter().flatten() {
                    prop_assert!((i as usize) < model.positions.len());
                    used[i as usize] = true;
                }
                prop_assert!(used.iter().all(|&u| u), "an unused vertex was kept");
                for p in &model.positions {
                    prop_assert!(p.to_array().iter().all(|&x| COORDINATE.accepts(x)), "{p}");
                }
                if let Some(normals) = &model.corner_normals {
                    prop_assert_eq!(normals.len(), model.triangles.len());
                    for n in normals.iter().flatten() {
                        prop_assert!(n.is_finite() && (n.length() - 1.0).abs() < 1e-4, "{n}");
                    }
                }
                prop_assert_eq!(model.triangles.len(), fanned_triangles(&text));
                let object = Object::new(Shape::Mesh {
                    path: Path::new("fuzz.obj").to_path_buf(),
                    position: glam::Vec3::ZERO,
                    scale: 1.0,
                    up: Default::default(),
                    materials: rastray::scene::MaterialSource::File,
                });
                let mesh = tessellate(&object, Some(&model));
                prop_assert_eq!(mesh.triangle_count(), model.triangles.len());
                prop_assert!(mesh.positions.iter().all(|p| p.is_finite()));
                prop_assert!(mesh.normals.iter().all(|n| n.is_finite()));
                prop_assert!(mesh.surface_area().is_finite());
            }
        }
    }

    /// The file read in pieces of a few bytes (statements fall across blocks and pieces, read
    /// on several threads and joined) gives what it gives read whole, or the same refusal.
    #[test]
    fn obj_files_read_in_small_pieces_read_as_whole(text in file(), block in 1usize..64) {
        let path = common::scratch().join("pieces.obj");
        std::fs::write(&path, &text).unwrap();
        let whole = read_obj_in_blocks(&path, 1 << 30);
        match (read_obj_in_blocks(&path, block), whole) {
            (Ok(pieces), Ok(whole)) => prop_assert_eq!(pieces, whole),
            (Err(a), Err(b)) => prop_assert_eq!(a.to_string(), b.to_string()),
            (a, b) => prop_assert!(false, "pieces {:?}, whole {:?}", a.map(drop), b.map(drop)),
        }
        prop_assert_eq!(read_obj(&path).map_err(|e| e.to_string()), read_obj_in_blocks(&path, 1 << 30).map_err(|e| e.to_string()));
    }
}

/// The triangles the `f` statements of a file that loaded fan into: a face of n ≥ 3 corners
/// makes n − 2.
fn fanned_triangles(text: &str) -> usize {
    text.lines()
        .filter_map(|line| {
            let mut words = line.split_whitespace();
            (words.next() == Some("f")).then(|| words.count())
        })
        .map(|corners| corners.saturating_sub(2))
        .sum()
}

/// Files the fuzz target found that made tobj 4.0.5 panic or misread a vertex: rastray's reader
/// loads each with the triangles its faces give, within the coordinate limits.
#[test]
fn files_that_broke_tobj_load() {
    for text in [
        "v 0 0 0\nv 0 0 0\nv 0 0 0\nv 1e-45 0 7.7368727 1e-45\nvt 0 0\nf 1 1 -1",
        "f 1 1/-2 1\nv 0 0 0\nv 0 0 0\nv 0 0 0\nv 0 0 0\nv 0 0 0\nv 0 0 0\nv 0 0 0\nv 0 0 0\nv 0 0 0\nv 0 0 0\nvt 0 0\nf 1 1 1",
        "v 0 0 0\nv 0 0 0\nv 0 0 0\nv 0 0 0\nv 0 0 0\nl 1 -2 1\nvt 0 0\nf 1 1 1",
    ] {
        let path = common::scratch().join("tobj.obj");
        std::fs::write(&path, text).unwrap();
        match load_obj(&path) {
            Ok(model) => {
                assert_eq!(model.triangles.len(), fanned_triangles(text), "{text:?}");
                for p in &model.positions {
                    assert!(p.to_array().iter().all(|&x| COORDINATE.accepts(x)), "{p}");
                }
            }
            Err(error) => assert!(error.to_string().contains("tobj.obj"), "{error}"),
        }
    }
}
