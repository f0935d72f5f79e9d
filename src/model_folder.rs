//! The files a model pulls in (glTF buffers and images, MTL files, textures), confined to the
//! model's own folder. A model is data from anyone: a reference it holds may name a file in its
//! folder or below it, and nothing else. `..`, absolute paths, percent-encoded escapes and
//! symlinks that lead out are refused before anything outside is opened (the checks use only
//! `lstat`-like look-ups, which never open a file, so not even a FIFO outside is touched).
//!
//! A scene file is the user's own and may name models anywhere; this confinement applies to what
//! those models name in turn.

use std::fs::File;
use std::io::Read;
use std::path::{Component, Path, PathBuf};

use crate::input_file::{kind_of, too_large};
use crate::mesh::texture::TextureLedger;

/// The folder a model file lives in, resolved (every symlink followed), within which all the
/// model's references must stay.
#[derive(Debug, Clone)]
pub struct ModelFolder {
    /// The canonical folder: absolute, no symlinks, no `.` or `..`.
    root: PathBuf,
    /// The memory the model's textures will take, committed before each is decoded.
    textures: TextureLedger,
}

/// How a reference is spelled in its file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ReferenceKind {
    /// A URI reference (glTF): `%XX` escapes are decoded first.
    Uri,
    /// A plain path (MTL, PLY comments): taken literally, `\` read as a folder separator as
    /// Windows exporters write it.
    Path,
}

/// Why a reference was not read. The caller names the model and the reference.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum ReferenceError {
    /// The reference leads outside the model's folder (by `..`, an absolute path or a symlink).
    #[error("refused: it leads outside the model's folder {0}")]
    Outside(String),
    /// A malformed reference (a bad `%`-escape, a NUL, an empty name).
    #[error("refused: {0}")]
    Malformed(&'static str),
    /// The file is missing or could not be read.
    #[error("{0}")]
    Unreadable(String),
}

impl ModelFolder {
    /// The folder of the model file at `model` (the folder of its resolved path, when the model
    /// itself is reached through a symlink).
    pub fn of(model: &Path) -> std::io::Result<ModelFolder> {
        let resolved = std::fs::canonicalize(model)?;
        let root = resolved
            .parent()
            .map(Path::to_path_buf)
            .unwrap_or_else(|| PathBuf::from("/"));
        Ok(ModelFolder {
            root,
            textures: TextureLedger::new(model),
        })
    }

    /// The account of the model's textures against the memory bound: every texture read for
    /// this model is committed to it from its header before it is decoded.
    pub fn textures(&self) -> &TextureLedger {
        &self.textures
    }

    /// The folder, canonical.
    pub fn root(&self) -> &Path {
        &self.root
    }

    /// The canonical path `reference` names, when it stays inside the folder. Nothing is opened:
    /// the reference is checked by its spelling first (`..` that climbs out, absolute paths),
    /// then resolved through its symlinks and checked again.
    pub fn resolve(&self, reference: &str, kind: ReferenceKind) -> Result<PathBuf, ReferenceError> {
        let decoded = match kind {
            ReferenceKind::Uri => percent_decode(reference).ok_or(ReferenceError::Malformed(
                "the URI has a malformed %-escape",
            ))?,
            ReferenceKind::Path => reference.to_string(),
        };
        if decoded.contains('\0') {
            return Err(ReferenceError::Malformed("the name holds a NUL character"));
        }
        let relative = decoded.replace('\\', "/");
        if relative.trim().is_empty() {
            return Err(ReferenceError::Malformed("the name is empty"));
        }
        let lexical = self.lexically_inside(&relative)?;
        let resolved = std::fs::canonicalize(&lexical).map_err(|e| {
            ReferenceError::Unreadable(format!("{}: {}", lexical.display(), plain(&e)))
        })?;
        if !resolved.starts_with(&self.root) {
            return Err(self.outside());
        }
        Ok(resolved)
    }

    /// Reads the regular file `reference` names, at most `cap` bytes (`what` names the kind of
    /// file in a refusal). The file is opened without following a final symlink and without
    /// blocking, and where `/proc` tells, the opened file is checked to be the one resolved.
    pub fn read(
        &self,
        reference: &str,
        kind: ReferenceKind,
        cap: u64,
        what: &str,
    ) -> Result<Vec<u8>, ReferenceError> {
        let path = self.resolve(reference, kind)?;
        let unreadable = |e: std::io::Error| {
            ReferenceError::Unreadable(format!("{}: {}", path.display(), plain(&e)))
        };
        let meta = std::fs::symlink_metadata(&path).map_err(unreadable)?;
        if !meta.is_file() {
            return Err(ReferenceError::Unreadable(format!(
                "{}: {}, not a regular file: refused",
                path.display(),
                kind_of(&meta)
            )));
        }
        let file = open_no_follow(&path).map_err(unreadable)?;
        self.check_opened(&file, &path)?;
        let opened = file.metadata().map_err(unreadable)?;
        if !opened.is_file() {
            return Err(ReferenceError::Unreadable(format!(
                "{}: not a regular file: refused",
                path.display()
            )));
        }
        let size = opened.len();
        if size > cap {
            return Err(unreadable(too_large(size, cap, what)));
        }
        let mut bytes = Vec::with_capacity(size as usize);
        file.take(cap + 1)
            .read_to_end(&mut bytes)
            .map_err(unreadable)?;
        if bytes.len() as u64 > cap {
            return Err(unreadable(too_large(bytes.len() as u64, cap, what)));
        }
        Ok(bytes)
    }

    /// `relative` joined to the folder with `.` and `..` resolved by spelling alone; refused when
    /// it is absolute or climbs above the folder.
    fn lexically_inside(&self, relative: &str) -> Result<PathBuf, ReferenceError> {
        if relative.starts_with('/') || has_drive_letter(relative) {
            return Err(self.outside());
        }
        let mut path = self.root.clone();
        let mut depth = 0usize;
        for component in Path::new(relative).components() {
            match component {
                Component::Normal(name) => {
                    path.push(name);
                    depth += 1;
                }
                Component::CurDir => {}
                Component::ParentDir => {
                    if depth == 0 {
                        return Err(self.outside());
                    }
                    path.pop();
                    depth -= 1;
                }
                Component::RootDir | Component::Prefix(_) => return Err(self.outside()),
            }
        }
        if depth == 0 {
            return Err(ReferenceError::Malformed(
                "the name is the model's folder itself",
            ));
        }
        Ok(path)
    }

    /// Where the kernel says which file a descriptor holds (Linux's `/proc/self/fd`), checks it is
    /// `expected`: a folder swapped for a symlink between the check and the open is caught.
    fn check_opened(&self, file: &File, expected: &Path) -> Result<(), ReferenceError> {
        #[cfg(target_os = "linux")]
        {
            use std::os::fd::AsRawFd;
            let link = format!("/proc/self/fd/{}", file.as_raw_fd());
            if let Ok(actual) = std::fs::read_link(link)
                && (actual != expected || !actual.starts_with(&self.root))
            {
                return Err(self.outside());
            }
        }
        #[cfg(not(target_os = "linux"))]
        let _ = (file, expected);
        Ok(())
    }

    fn outside(&self) -> ReferenceError {
        ReferenceError::Outside(self.root.display().to_string())
    }
}

/// Opens `path` for reading, refusing a final symlink and never waiting on a FIFO or device.
fn open_no_follow(path: &Path) -> std::io::Result<File> {
    let mut options = std::fs::OpenOptions::new();
    options.read(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        options.custom_flags(
            (rustix::fs::OFlags::NOFOLLOW | rustix::fs::OFlags::NONBLOCK).bits() as i32,
        );
    }
    options.open(path)
}

/// Whether `text` starts with a Windows drive such as `C:`.
fn has_drive_letter(text: &str) -> bool {
    let bytes = text.as_bytes();
    bytes.len() >= 2 && bytes[0].is_ascii_alphabetic() && bytes[1] == b':'
}

/// An I/O error's message without the "(os error 2)" tail.
fn plain(error: &std::io::Error) -> String {
    let text = error.to_string();
    match text.find(" (os error") {
        Some(end) => text[..end].to_string(),
        None => text,
    }
}

/// `text` with its `%XX` escapes decoded as UTF-8; `None` when an escape or the result is malformed.
pub fn percent_decode(text: &str) -> Option<String> {
    let bytes = text.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%' {
            let hex = std::str::from_utf8(bytes.get(i + 1..i + 3)?).ok()?;
            out.push(u8::from_str_radix(hex, 16).ok()?);
            i += 3;
        } else {
            out.push(bytes[i]);
            i += 1;
        }
    }
    String::from_utf8(out).ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn folder() -> (tempfile::TempDir, ModelFolder) {
        let dir = tempfile::tempdir().expect("tempdir");
        std::fs::create_dir(dir.path().join("model")).unwrap();
        std::fs::create_dir(dir.path().join("model/sub")).unwrap();
        std::fs::write(dir.path().join("model/model.gltf"), b"{}").unwrap();
        std::fs::write(dir.path().join("model/a b.bin"), b"inside").unwrap();
        std::fs::write(dir.path().join("model/sub/c.bin"), b"below").unwrap();
        std::fs::write(dir.path().join("secret.bin"), b"outside").unwrap();
        let folder = ModelFolder::of(&dir.path().join("model/model.gltf")).unwrap();
        (dir, folder)
    }

    fn read(
        folder: &ModelFolder,
        reference: &str,
        kind: ReferenceKind,
    ) -> Result<Vec<u8>, ReferenceError> {
        folder.read(reference, kind, 1 << 20, "a test file")
    }

    #[test]
    fn files_in_the_folder_and_below_are_read() {
        let (_dir, folder) = folder();
        assert_eq!(
            read(&folder, "a%20b.bin", ReferenceKind::Uri).unwrap(),
            b"inside"
        );
        assert_eq!(
            read(&folder, "a b.bin", ReferenceKind::Path).unwrap(),
            b"inside"
        );
        assert_eq!(
            read(&folder, "sub/c.bin", ReferenceKind::Uri).unwrap(),
            b"below"
        );
        assert_eq!(
            read(&folder, "sub\\c.bin", ReferenceKind::Path).unwrap(),
            b"below"
        );
        assert_eq!(
            read(&folder, "./sub/../a b.bin", ReferenceKind::Path).unwrap(),
            b"inside"
        );
    }

    #[test]
    fn every_way_out_is_refused() {
        let (dir, folder) = folder();
        let secret = dir.path().join("secret.bin");
        let outside = [
            ("../secret.bin", ReferenceKind::Uri),
            ("sub/../../secret.bin", ReferenceKind::Uri),
            ("%2e%2e/secret.bin", ReferenceKind::Uri),
            ("%2E%2E%2Fsecret.bin", ReferenceKind::Uri),
            ("..\\secret.bin", ReferenceKind::Path),
            ("/etc/passwd", ReferenceKind::Uri),
            ("%2Fetc%2Fpasswd", ReferenceKind::Uri),
            ("C:/Windows/win.ini", ReferenceKind::Path),
        ];
        for (reference, kind) in outside {
            let error = read(&folder, reference, kind).expect_err(reference);
            assert!(
                matches!(error, ReferenceError::Outside(_)),
                "{reference}: {error}"
            );
        }
        // An absolute path spelled out in full is refused too, though it exists.
        let absolute = secret.to_str().unwrap();
        assert!(matches!(
            read(&folder, absolute, ReferenceKind::Path),
            Err(ReferenceError::Outside(_))
        ));
    }

    #[cfg(unix)]
    #[test]
    fn symlinks_out_are_refused_and_symlinks_within_are_followed() {
        let (dir, folder) = folder();
        let model = dir.path().join("model");
        std::os::unix::fs::symlink(dir.path().join("secret.bin"), model.join("out.bin")).unwrap();
        std::os::unix::fs::symlink(dir.path(), model.join("up")).unwrap();
        std::os::unix::fs::symlink(model.join("sub/c.bin"), model.join("in.bin")).unwrap();
        for reference in ["out.bin", "up/secret.bin", "up/model/../secret.bin"] {
            let error = read(&folder, reference, ReferenceKind::Uri).expect_err(reference);
            assert!(
                matches!(error, ReferenceError::Outside(_)),
                "{reference}: {error}"
            );
        }
        assert_eq!(
            read(&folder, "in.bin", ReferenceKind::Uri).unwrap(),
            b"below"
        );
        // Through the link into the parent and back down into the folder is inside.
        assert_eq!(
            read(&folder, "up/model/sub/c.bin", ReferenceKind::Uri).unwrap(),
            b"below"
        );
    }

    #[cfg(unix)]
    #[test]
    fn a_fifo_inside_is_refused_without_being_opened() {
        let (dir, folder) = folder();
        let fifo = dir.path().join("model/pipe.bin");
        rustix::fs::mkfifoat(
            rustix::fs::CWD,
            &fifo,
            rustix::fs::Mode::from_raw_mode(0o600),
        )
        .unwrap();
        let error = read(&folder, "pipe.bin", ReferenceKind::Uri).expect_err("fifo");
        assert!(error.to_string().contains("FIFO"), "{error}");
    }

    #[test]
    fn malformed_references_are_refused() {
        let (_dir, folder) = folder();
        for reference in ["bad%2", "%zz", "", ".", "a%00b"] {
            let error = read(&folder, reference, ReferenceKind::Uri).expect_err(reference);
            assert!(
                matches!(error, ReferenceError::Malformed(_)),
                "{reference:?}: {error}"
            );
        }
        let missing = read(&folder, "missing.bin", ReferenceKind::Uri).expect_err("missing");
        assert!(
            matches!(missing, ReferenceError::Unreadable(_)),
            "{missing}"
        );
    }

    #[test]
    fn percent_escapes_decode_and_malformed_ones_are_refused() {
        assert_eq!(
            percent_decode("box%20data.bin").as_deref(),
            Some("box data.bin")
        );
        assert_eq!(percent_decode("a%C3%A9.bin").as_deref(), Some("aé.bin"));
        assert_eq!(percent_decode("plain.bin").as_deref(), Some("plain.bin"));
        assert_eq!(percent_decode("bad%2"), None);
        assert_eq!(percent_decode("bad%zz.bin"), None);
        assert_eq!(percent_decode("%ff"), None, "not UTF-8");
    }
}
