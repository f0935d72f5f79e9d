//! The bytes behind a glTF document's buffers: the GLB binary chunk, `data:` URIs, and files
//! in the model's folder or below it (`model_folder` refuses every other path). Nothing is
//! fetched from the network.

use std::path::PathBuf;

use base64::Engine;
use base64::engine::general_purpose::STANDARD;

use super::error::GltfError;
use crate::input_file::MAX_MODEL_BYTES;
use crate::model_folder::{ModelFolder, ReferenceKind};

/// Loads every buffer of `document` in order. `blob` is the GLB binary chunk, when there is one;
/// relative URIs are resolved inside `folder` (the model file's folder). Each file read is
/// added to `files`.
pub fn load_buffers(
    document: &::gltf::Document,
    blob: Option<Vec<u8>>,
    folder: &ModelFolder,
    files: &mut Vec<PathBuf>,
) -> Result<Vec<Vec<u8>>, GltfError> {
    let mut blob = blob;
    document
        .buffers()
        .map(|buffer| {
            let index = buffer.index();
            let (source_name, data) = match buffer.source() {
                ::gltf::buffer::Source::Bin => (
                    "the GLB binary chunk".to_string(),
                    blob.take().ok_or_else(|| {
                        "the file has no binary chunk (or it serves another buffer)".to_string()
                    }),
                ),
                ::gltf::buffer::Source::Uri(uri) => {
                    (format!("`{uri}`"), read_uri(uri, folder, files))
                }
            };
            let data = data.map_err(|reason| GltfError::Buffer {
                index,
                source_name,
                reason,
            })?;
            if data.len() < buffer.length() {
                return Err(GltfError::ShortBuffer {
                    index,
                    declared: buffer.length(),
                    actual: data.len(),
                });
            }
            Ok(data)
        })
        .collect()
}

/// The bytes a buffer URI names: a base64 `data:` URI, or a file inside `folder`.
pub fn read_uri(
    uri: &str,
    folder: &ModelFolder,
    files: &mut Vec<PathBuf>,
) -> Result<Vec<u8>, String> {
    if let Some(rest) = uri.strip_prefix("data:") {
        let (_, payload) = rest
            .split_once(";base64,")
            .ok_or("a data URI that is not base64")?;
        return STANDARD
            .decode(payload)
            .map_err(|e| format!("bad base64: {e}"));
    }
    if has_scheme(uri) {
        return Err("only files in the model's folder and data URIs are read".into());
    }
    let path = folder
        .resolve(uri, ReferenceKind::Uri)
        .map_err(|e| e.to_string())?;
    files.push(path);
    folder
        .read(uri, ReferenceKind::Uri, MAX_MODEL_BYTES, "a glTF buffer")
        .map_err(|e| e.to_string())
}

/// Whether `uri` starts with a scheme such as `https:` (RFC 3986: a letter, then letters,
/// digits, `+`, `-` or `.`, then `:`).
fn has_scheme(uri: &str) -> bool {
    match uri.split_once(':') {
        Some((scheme, _)) => {
            let mut chars = scheme.chars();
            chars.next().is_some_and(|c| c.is_ascii_alphabetic())
                && chars.all(|c| c.is_ascii_alphanumeric() || "+-.".contains(c))
                // A Windows drive letter such as `C:` is a path, not a scheme.
                && scheme.len() > 1
        }
        None => false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn schemes_are_told_from_paths() {
        assert!(has_scheme("https://example.com/a.bin"));
        assert!(has_scheme("file:///tmp/a.bin"));
        assert!(!has_scheme("a.bin"));
        assert!(!has_scheme("sub/dir/a.bin"));
        assert!(!has_scheme("C:/models/a.bin"));
        assert!(!has_scheme("1abc:def"));
    }

    #[test]
    fn data_uris_decode_and_remote_ones_are_refused() {
        let folder = ModelFolder::of(std::path::Path::new("Cargo.toml")).expect("folder");
        let folder = &folder;
        let mut files = Vec::new();
        assert_eq!(
            read_uri(
                "data:application/octet-stream;base64,AAEC",
                folder,
                &mut files
            ),
            Ok(vec![0, 1, 2])
        );
        assert!(read_uri("data:text/plain,hello", folder, &mut files).is_err());
        assert!(
            read_uri(
                "data:application/octet-stream;base64,!!",
                folder,
                &mut files
            )
            .is_err()
        );
        let remote = read_uri("https://example.com/a.bin", folder, &mut files).expect_err("remote");
        assert!(remote.contains("only files"), "{remote}");
        let outside = read_uri("../x.bin", folder, &mut files).expect_err("outside");
        assert!(outside.contains("outside the model's folder"), "{outside}");
        assert!(files.is_empty(), "no file was read: {files:?}");
    }
}
