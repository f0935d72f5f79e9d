//! The recovery file: where unsaved edits wait, so that neither a lost terminal, a signal, a
//! crash nor `kill -9` loses them. The editor keeps it up to date in the background
//! ([`super::autosave`]), writes it at once when a signal ends it, and removes it when the
//! edits are saved or the user quits.

use std::io::Write;
use std::path::{Path, PathBuf};

use crate::atomic_file::write_atomically_no_follow;
use crate::scene::{Scene, SceneError, to_toml_string};

/// `<scene>.recovered.toml` next to the scene file, or `rastray-recovered.toml` in the current
/// directory for the built-in scene.
pub fn path_for(scene_path: Option<&Path>) -> PathBuf {
    match scene_path {
        Some(p) => p.with_file_name(format!("{}.recovered.toml", stem(p))),
        None => PathBuf::from("rastray-recovered.toml"),
    }
}

/// The name of earlier recovery file number `n` moved aside from `path`: `<stem>-<n>.toml`.
fn aside_name(path: &Path, n: u32) -> PathBuf {
    path.with_file_name(format!("{}-{n}.toml", stem(path)))
}

/// The file name of `path` without its extension.
fn stem(path: &Path) -> String {
    path.file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default()
}

/// Earlier recovery files moved aside from `path` (see [`RecoveryFile::write`]), by number.
pub fn moved_aside(path: &Path) -> Vec<PathBuf> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let stem = stem(path);
    let number = |name: &str| -> Option<u32> {
        let digits = name
            .strip_prefix(&stem)?
            .strip_prefix('-')?
            .strip_suffix(".toml")?;
        digits
            .parse()
            .ok()
            .filter(|_| digits.bytes().all(|b| b.is_ascii_digit()))
    };
    let mut found: Vec<u32> = std::fs::read_dir(dir)
        .into_iter()
        .flatten()
        .flatten()
        .filter_map(|entry| number(&entry.file_name().to_string_lossy()))
        .collect();
    found.sort_unstable();
    found.into_iter().map(|n| aside_name(path, n)).collect()
}

/// The message to show at start when recovery files exist for the scene at `scene_path`.
pub fn notice(scene_path: Option<&Path>) -> Option<String> {
    let path = path_for(scene_path);
    let aside = moved_aside(&path);
    let list = |paths: &[PathBuf]| {
        paths
            .iter()
            .map(|p| p.display().to_string())
            .collect::<Vec<_>>()
            .join(", ")
    };
    match (path.is_file(), aside.is_empty()) {
        (true, true) => Some(format!(
            "earlier unsaved edits are in {} (o opens it)",
            path.display()
        )),
        (true, false) => Some(format!(
            "earlier unsaved edits are in {} (o opens it), older ones in {}",
            path.display(),
            list(&aside)
        )),
        (false, false) => Some(format!("earlier unsaved edits are in {}", list(&aside))),
        (false, true) => None,
    }
}

/// Tells the shell, once the terminal is restored, where unsaved edits went or what went wrong
/// with the recovery file. A closed stderr is ignored.
pub fn report(outcome: &Result<Option<PathBuf>, SceneError>) {
    let mut err = std::io::stderr();
    let _ = match outcome {
        Ok(None) => Ok(()),
        Ok(Some(path)) => writeln!(err, "rastray: unsaved edits written to {}", path.display()),
        Err(e) => writeln!(err, "rastray: recovery file {e}"),
    };
}

/// The recovery file one editor writes. It never overwrites nor removes a file it did not
/// write itself (an earlier session's edits, or another editor's on the same scene).
#[derive(Debug, Default)]
pub struct RecoveryFile {
    /// Where this editor last wrote, and the text it wrote there.
    written: Option<(PathBuf, String)>,
}

impl RecoveryFile {
    /// Writes `scene` to `path` atomically. A file already there that this editor did not
    /// write is first moved aside to `<stem>-<n>.toml`, the first free `n` from 1.
    pub fn write(&mut self, scene: &Scene, path: &Path) -> Result<(), SceneError> {
        let io = |error| SceneError::Io {
            path: path.to_path_buf(),
            error,
        };
        let text = to_toml_string(scene);
        if std::fs::symlink_metadata(path).is_ok_and(|m| m.file_type().is_symlink()) {
            // A link planted where the recovery file goes is neither followed nor moved aside.
            return Err(io(std::io::Error::new(
                std::io::ErrorKind::InvalidInput,
                "a symlink is in the recovery file's place: not followed, not written",
            )));
        }
        let on_disk = std::fs::read_to_string(path).ok();
        if on_disk.as_ref() == Some(&text) {
            self.written = Some((path.to_path_buf(), text));
            return Ok(());
        }
        if on_disk.is_some() && on_disk.as_ref() != self.text_at(path) {
            let aside = (1..)
                .map(|n| aside_name(path, n))
                .find(|p| !p.exists())
                .expect("some number is free");
            std::fs::rename(path, aside).map_err(io)?;
        }
        write_atomically_no_follow(path, text.as_bytes()).map_err(io)?;
        self.written = Some((path.to_path_buf(), text));
        Ok(())
    }

    /// Removes the file this editor wrote, unless something else has replaced it since.
    pub fn remove(&mut self) -> Result<(), SceneError> {
        let Some((path, text)) = self.written.take() else {
            return Ok(());
        };
        if std::fs::read_to_string(&path).is_ok_and(|t| t == text) {
            std::fs::remove_file(&path).map_err(|error| SceneError::Io { path, error })?;
        }
        Ok(())
    }

    /// Leaves the file written where it is, for the user to open later, and stops tracking it.
    pub fn keep(&mut self) {
        self.written = None;
    }

    /// The text this editor last wrote to `path`.
    fn text_at(&self, path: &Path) -> Option<&String> {
        self.written
            .as_ref()
            .filter(|(p, _)| p == path)
            .map(|(_, text)| text)
    }
}
