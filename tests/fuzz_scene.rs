//! Fuzzing the scene reader: the shipped scenes mutated line by line and token by token, with
//! edge values and stray bytes. Parsing never panics; a refusal names the file (and the line,
//! when it points at one that exists); an accepted scene is valid, and writes back to TOML that
//! reads as the same scene.
//!
//! CI runs proptest's default 256 cases; `PROPTEST_CASES=250000` runs a long session (see the
//! README, "Fuzzing").

use std::path::Path;

use proptest::prelude::*;
use rastray::scene::{from_toml_str, to_toml_string, validate};

/// The scenes the mutations start from, read once.
fn seeds() -> &'static [String] {
    static SEEDS: std::sync::OnceLock<Vec<String>> = std::sync::OnceLock::new();
    SEEDS.get_or_init(read_seeds)
}

fn read_seeds() -> Vec<String> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
    let mut seeds: Vec<String> = ["default.toml", "ico8.toml", "suzanne.toml", "teapot.toml"]
        .iter()
        .map(|name| std::fs::read_to_string(dir.join(name)).expect("a shipped scene"))
        .collect();
    seeds.push(rastray::scene::DEFAULT_SCENE_TOML.to_string());
    seeds
}

/// Words and values a mutation splices in: keys, edge numbers, broken syntax, control bytes.
const TOKENS: &[&str] = &[
    "0",
    "-0.0",
    "1",
    "1e6",
    "1000001",
    "-1e6",
    "3.4e38",
    "1e39",
    "nan",
    "inf",
    "-inf",
    "1e-45",
    "180",
    "0.0",
    "8",
    "9",
    "512",
    "513",
    "16",
    "17",
    "4294967296",
    "-1",
    "true",
    "\"x\"",
    "[",
    "]",
    "[1, 2]",
    "[1, 2, 3]",
    "[1, 2, 3, 4]",
    "[0, 0, 0, 1e30, \"junk?\"]",
    "{}",
    "=",
    ",",
    "\n",
    "\"",
    "'",
    "#",
    "[[object]]",
    "[[light]]",
    "[camera]",
    "[falloff]",
    "type = \"box\"",
    "type = \"mesh\"",
    "type = \"prism\"",
    "type = \"icosahedron\"",
    "type = \"cube\"",
    "size",
    "center",
    "radius",
    "rotation",
    "segments",
    "subdivisions",
    "smooth",
    "path",
    "position",
    "scale",
    "material",
    "color",
    "diffuse",
    "specular",
    "shininess",
    "reflection",
    "intensity",
    "name",
    "fov",
    "up",
    "target",
    "ambient",
    "background",
    "max_depth",
    "linear",
    "quadratic",
    "\u{1b}]0;pwned\u{7}",
    "\u{0}",
    "é",
    "\r",
];

/// One edit of a scene's text.
#[derive(Debug, Clone)]
enum Mutation {
    /// Put a token at a byte position.
    Insert(prop::sample::Index, usize),
    /// Replace the token at a position, up to the next space or line end.
    Replace(prop::sample::Index, usize),
    /// Remove a span of bytes.
    Delete(prop::sample::Index, usize),
    /// Repeat a line.
    DuplicateLine(prop::sample::Index),
    /// Swap two lines.
    SwapLines(prop::sample::Index, prop::sample::Index),
}

fn mutation() -> impl Strategy<Value = Mutation> {
    let token = 0..TOKENS.len();
    prop_oneof![
        3 => (any::<prop::sample::Index>(), token.clone()).prop_map(|(i, t)| Mutation::Insert(i, t)),
        4 => (any::<prop::sample::Index>(), token).prop_map(|(i, t)| Mutation::Replace(i, t)),
        2 => (any::<prop::sample::Index>(), 1usize..12).prop_map(|(i, n)| Mutation::Delete(i, n)),
        1 => any::<prop::sample::Index>().prop_map(Mutation::DuplicateLine),
        1 => (any::<prop::sample::Index>(), any::<prop::sample::Index>())
            .prop_map(|(a, b)| Mutation::SwapLines(a, b)),
    ]
}

/// The nearest char boundary at or before byte `at`.
fn boundary(text: &str, mut at: usize) -> usize {
    at = at.min(text.len());
    while !text.is_char_boundary(at) {
        at -= 1;
    }
    at
}

fn apply(text: &mut String, mutation: &Mutation) {
    match mutation {
        Mutation::Insert(at, token) => {
            let at = boundary(text, at.index(text.len() + 1));
            text.insert_str(at, TOKENS[*token]);
        }
        Mutation::Replace(at, token) => {
            let start = boundary(text, at.index(text.len() + 1));
            let end = text[start..]
                .find([' ', '\n', ',', ']'])
                .map_or(text.len(), |n| start + n);
            text.replace_range(start..end, TOKENS[*token]);
        }
        Mutation::Delete(at, n) => {
            let start = boundary(text, at.index(text.len() + 1));
            let end = boundary(text, start + n);
            text.replace_range(start..end, "");
        }
        Mutation::DuplicateLine(at) | Mutation::SwapLines(at, _) => {
            let mut lines: Vec<&str> = text.lines().collect();
            if lines.is_empty() {
                return;
            }
            let i = at.index(lines.len());
            match mutation {
                Mutation::SwapLines(_, other) => {
                    let j = other.index(lines.len());
                    lines.swap(i, j);
                }
                _ => lines.insert(i, lines[i]),
            }
            *text = lines.join("\n");
        }
    }
}

fn mutated_scene() -> impl Strategy<Value = String> {
    (
        any::<prop::sample::Index>(),
        prop::collection::vec(mutation(), 0..6),
    )
        .prop_map(|(seed, mutations)| {
            let seeds = seeds();
            let mut text = seeds[seed.index(seeds.len())].clone();
            for m in &mutations {
                apply(&mut text, m);
            }
            text
        })
}

proptest! {
    #![proptest_config(ProptestConfig::default())]

    #[test]
    fn scenes_parse_or_are_refused_with_their_name(text in mutated_scene()) {
        let path = Path::new("fuzz.toml");
        match from_toml_str(&text, path) {
            Err(error) => {
                let message = error.to_string();
                prop_assert!(message.starts_with("fuzz.toml"), "{message}");
                if let Some(line) = message
                    .strip_prefix("fuzz.toml:")
                    .and_then(|rest| rest.split(':').next())
                    .and_then(|n| n.parse::<usize>().ok())
                {
                    prop_assert!(line >= 1 && line <= text.split('\n').count(), "{message}");
                }
            }
            Ok(scene) => {
                prop_assert!(validate(&scene).is_ok(), "{:?}", validate(&scene));
                let written = to_toml_string(&scene);
                let again = from_toml_str(&written, path);
                prop_assert!(again.is_ok(), "{written}\n{again:?}");
                prop_assert_eq!(again.unwrap(), scene);
            }
        }
    }
}
