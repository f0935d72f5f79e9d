//! Which format a model file is in: known by its extension (`.obj`, `.stl`, `.ply`, `.gltf`,
//! `.glb`, any case) or, failing that, by its first bytes.

use std::fmt;
use std::io::Read;
use std::path::Path;

use crate::input_file::open_regular;

/// The model formats rastray reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ModelFormat {
    Obj,
    /// glTF 2.0 as JSON (`.gltf`).
    Gltf,
    /// glTF 2.0 in its binary container (`.glb`).
    Glb,
    Stl,
    Ply,
}

/// Bytes read from the start of a file to recognise its format.
pub const SNIFF_BYTES: usize = 1 << 16;

/// The formats and their extensions, in the order messages list them.
const EXTENSIONS: [(&str, ModelFormat); 5] = [
    ("obj", ModelFormat::Obj),
    ("stl", ModelFormat::Stl),
    ("ply", ModelFormat::Ply),
    ("gltf", ModelFormat::Gltf),
    ("glb", ModelFormat::Glb),
];

/// What a model file was expected to be, for refusals of files that are none of them.
pub const EXPECTED_MODEL: &str = "a model file: OBJ, STL, PLY, glTF or GLB (known by the \
     extension .obj, .stl, .ply, .gltf or .glb, or by content: an STL's size or `solid`, \
     `ply` on the first line, GLB's `glTF` magic, glTF's JSON with an `asset`)";

impl ModelFormat {
    /// The format the extension of `path` names, any case; `None` for any other extension.
    pub fn of_extension(path: &Path) -> Option<ModelFormat> {
        let extension = path.extension()?.to_str()?;
        EXTENSIONS
            .iter()
            .find(|(e, _)| extension.eq_ignore_ascii_case(e))
            .map(|&(_, format)| format)
    }

    /// The format of a file from its first bytes `head` (up to [`SNIFF_BYTES`]) and its whole
    /// `size` in bytes: STL by a binary STL's exact size (84 + 50 × the count at byte 80) or
    /// text beginning with `solid`, PLY by `ply` alone on the first line, GLB by its `glTF`
    /// magic, glTF by a JSON object naming an `asset`, OBJ by text whose first statement is
    /// one of OBJ's (`v`, `vn`, `vt`, `f`, `o`, `g`, `mtllib`, `usemtl`, `s`).
    pub fn sniff(head: &[u8], size: u64) -> Option<ModelFormat> {
        if head.starts_with(b"ply\n") || head.starts_with(b"ply\r\n") {
            return Some(ModelFormat::Ply);
        }
        if head.starts_with(b"glTF") {
            return Some(ModelFormat::Glb);
        }
        if binary_stl_size(head) == Some(size) || is_ascii_stl(head) {
            return Some(ModelFormat::Stl);
        }
        let text = match std::str::from_utf8(head) {
            Ok(text) => text,
            // The head may end inside a character.
            Err(e) if e.error_len().is_none() => {
                std::str::from_utf8(&head[..e.valid_up_to()]).ok()?
            }
            Err(_) => return None,
        };
        let trimmed = text.trim_start_matches('\u{feff}').trim_start();
        if trimmed.starts_with('{') && trimmed.contains("\"asset\"") {
            return Some(ModelFormat::Gltf);
        }
        let first = trimmed
            .lines()
            .map(str::trim)
            .find(|line| !line.is_empty() && !line.starts_with('#'))?;
        let mut words = first.split_whitespace();
        let keyword = words.next()?;
        let argument = words.next()?;
        let obj = match keyword {
            "v" | "vn" | "vt" | "f" => argument.parse::<f64>().is_ok(),
            "o" | "g" | "mtllib" | "usemtl" | "s" => argument != "=",
            _ => false,
        };
        obj.then_some(ModelFormat::Obj)
    }

    /// The format of the file at `path`: by extension, else by content; `None` when neither
    /// says. Only a regular file's content is read.
    pub fn of_file(path: &Path) -> std::io::Result<Option<ModelFormat>> {
        if let Some(format) = ModelFormat::of_extension(path) {
            return Ok(Some(format));
        }
        let file = open_regular(path)?;
        let size = file.metadata()?.len();
        let mut head = Vec::with_capacity(SNIFF_BYTES);
        file.take(SNIFF_BYTES as u64).read_to_end(&mut head)?;
        Ok(ModelFormat::sniff(&head, size))
    }

    /// The format's name in messages and `rastray info`.
    pub fn name(self) -> &'static str {
        match self {
            ModelFormat::Obj => "OBJ",
            ModelFormat::Gltf => "glTF",
            ModelFormat::Glb => "GLB",
            ModelFormat::Stl => "STL",
            ModelFormat::Ply => "PLY",
        }
    }
}

impl fmt::Display for ModelFormat {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The size a binary STL with the head `head` has: 84 + 50 × the triangle count at byte 80;
/// `None` when the head is shorter than the 84-byte header.
pub fn binary_stl_size(head: &[u8]) -> Option<u64> {
    let count = head.get(80..84)?;
    Some(84 + 50 * u32::from_le_bytes([count[0], count[1], count[2], count[3]]) as u64)
}

/// Whether `head` looks like an ASCII STL: `solid` first (after blanks, any case), and text:
/// no control character but tab, line feed, vertical tab, form feed and carriage return in the
/// first 512 bytes. A binary STL's header may begin with `solid` too; the triangle count right
/// after it has a zero byte for any count below 2^24.
pub fn is_ascii_stl(head: &[u8]) -> bool {
    let start = head
        .iter()
        .position(|b| !b.is_ascii_whitespace())
        .unwrap_or(head.len());
    let word = &head[start..];
    word.len() >= 5
        && word[..5].eq_ignore_ascii_case(b"solid")
        && word.get(5).is_none_or(|b| b.is_ascii_whitespace())
        && head
            .iter()
            .take(512)
            .all(|&b| b >= 0x20 || (b'\t'..=b'\r').contains(&b))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn extensions_name_formats_in_any_case() {
        assert_eq!(
            ModelFormat::of_extension(Path::new("a.STL")),
            Some(ModelFormat::Stl)
        );
        assert_eq!(
            ModelFormat::of_extension(Path::new("d/b.Ply")),
            Some(ModelFormat::Ply)
        );
        assert_eq!(
            ModelFormat::of_extension(Path::new("c.glb")),
            Some(ModelFormat::Glb)
        );
        assert_eq!(ModelFormat::of_extension(Path::new("c.toml")), None);
        assert_eq!(ModelFormat::of_extension(Path::new("stl")), None);
    }

    #[test]
    fn content_names_formats() {
        let mut binary = b"solid exported by a CAD program".to_vec();
        binary.resize(80, b' ');
        binary.extend(1u32.to_le_bytes());
        binary.resize(134, 0);
        assert_eq!(ModelFormat::sniff(&binary, 134), Some(ModelFormat::Stl));
        assert!(!is_ascii_stl(&binary), "the count's zero bytes are no text");
        assert_eq!(
            ModelFormat::sniff(b"solid cube\nfacet normal 0 0 1\n", 30),
            Some(ModelFormat::Stl)
        );
        assert_eq!(
            ModelFormat::sniff(b"ply\nformat ascii 1.0\n", 20),
            Some(ModelFormat::Ply)
        );
        assert_eq!(
            ModelFormat::sniff(b"glTF\x02\0\0\0", 8),
            Some(ModelFormat::Glb)
        );
        assert_eq!(
            ModelFormat::sniff(b" {\"asset\": {\"version\": \"2.0\"}}", 30),
            Some(ModelFormat::Gltf)
        );
        assert_eq!(
            ModelFormat::sniff(b"# made by hand\nv 0 0 0\n", 22),
            Some(ModelFormat::Obj)
        );
        for other in [
            &b"[camera]\nfov = 40\n"[..],
            b"v = 3\n",
            b"solidarity\n",
            b"",
            b"\x89PNG\r\n",
        ] {
            assert_eq!(
                ModelFormat::sniff(other, other.len() as u64),
                None,
                "{other:?}"
            );
        }
    }
}
