//! Reading and writing scene files, with errors that point at the file, line and key.

use std::path::{Path, PathBuf};

use toml::de::{DeTable, DeValue};

use super::error::SceneError;
use super::field_path::{FieldPath, PathSegment};
use super::model::Scene;
use super::validate::validate;
use crate::atomic_file::write_atomically;
use crate::input_file::{MAX_SCENE_BYTES, read_bounded_text};

/// The built-in default scene, the same text as `scenes/default.toml`.
pub const DEFAULT_SCENE_TOML: &str = include_str!("../../scenes/default.toml");

/// The built-in default scene, parsed.
pub fn default_scene() -> Scene {
    from_toml_str(DEFAULT_SCENE_TOML, Path::new("scenes/default.toml"))
        .expect("the built-in default scene is valid (checked by a test)")
}

/// Reads and checks the scene at `path`: a regular file of at most [`MAX_SCENE_BYTES`].
pub fn load(path: &Path) -> Result<Scene, SceneError> {
    let text = read_bounded_text(path, MAX_SCENE_BYTES, "a scene file").map_err(|error| {
        SceneError::Io {
            path: path.to_path_buf(),
            error,
        }
    })?;
    from_toml_str(&text, path)
}

/// Parses and checks scene `text`; `path` is only used to name the file in errors.
pub fn from_toml_str(text: &str, path: &Path) -> Result<Scene, SceneError> {
    let scene: Scene = toml::from_str(text).map_err(|e| parse_error(text, path, e))?;
    if let Err(invalid) = validate(&scene) {
        let line = DeTable::parse(text)
            .ok()
            .and_then(|doc| span_of(&doc, &invalid.path))
            .map(|span| line_of(text, span.start));
        return Err(SceneError::Invalid {
            path: path.to_path_buf(),
            line,
            error: invalid,
        });
    }
    Ok(scene)
}

/// The scene as TOML text.
pub fn to_toml_string(scene: &Scene) -> String {
    toml::to_string_pretty(scene).expect("a scene always serialises: all keys are strings")
}

/// Writes `scene` to `path` atomically: readers see the old file or the new one, never a mix.
pub fn save(scene: &Scene, path: &Path) -> Result<(), SceneError> {
    write_atomically(path, to_toml_string(scene).as_bytes()).map_err(|error| SceneError::Io {
        path: path.to_path_buf(),
        error,
    })
}

fn parse_error(text: &str, path: &Path, error: toml::de::Error) -> SceneError {
    let line = error.span().map(|s| line_of(text, s.start));
    let source_line = line
        .and_then(|l| text.lines().nth(l - 1))
        .map(str::trim)
        .filter(|t| !t.is_empty())
        .map(str::to_string);
    SceneError::Parse {
        path: PathBuf::from(path),
        line,
        source_line,
        error: Box::new(error),
    }
}

/// 1-based line number of byte `offset` in `text`.
fn line_of(text: &str, offset: usize) -> usize {
    text[..offset.min(text.len())]
        .bytes()
        .filter(|&b| b == b'\n')
        .count()
        + 1
}

/// Span of the value at `path` in the parsed document, or of the nearest enclosing value that
/// the file spells out (a defaulted key has no span of its own).
fn span_of(doc: &toml::Spanned<DeTable<'_>>, path: &FieldPath) -> Option<std::ops::Range<usize>> {
    let mut best = None;
    let mut table: Option<&DeTable<'_>> = Some(doc.get_ref());
    let mut array: Option<&[toml::Spanned<DeValue<'_>>]> = None;
    for seg in &path.0 {
        let value = match seg {
            PathSegment::Key(k) => table.and_then(|t| t.get(k.as_str())),
            PathSegment::Index(i) => array.and_then(|a| a.get(*i)),
        };
        let Some(value) = value else { break };
        best = Some(value.span());
        table = None;
        array = None;
        match value.get_ref() {
            DeValue::Table(t) => table = Some(t),
            DeValue::Array(a) => array = Some(a.as_ref()),
            _ => {}
        }
    }
    best
}
