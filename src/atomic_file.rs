//! Atomic file writes: a temporary file in the same directory, synced, then renamed over the
//! target, so a crash leaves either the old file or the new one.
//!
//! Only a regular file, or a path where nothing exists yet, is replaced this way. A symlink is
//! followed and its target replaced in the target's own folder, so the link stays a link. A
//! device, FIFO or directory is refused: renaming over `/dev/null` would replace the device
//! with a plain file (export writes such paths as streams, `export::Destination`).

use std::io::Write;
use std::path::{Path, PathBuf};

use crate::input_file::kind_of;

/// Most symlinks followed from a path to its target (as Linux's `MAXSYMLINKS`).
const MAX_LINKS: usize = 40;

/// Writes `bytes` to `path` atomically. A replaced file keeps its permissions; a new file gets
/// mode 0666 less the umask.
pub fn write_atomically(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let mut file = AtomicFile::create(path)?;
    file.write_all(bytes)?;
    file.commit()
}

/// A file written in pieces, atomically: the pieces go to a temporary file beside the target,
/// which [`AtomicFile::commit`] syncs and renames over it. Dropped without a commit, the
/// temporary file is removed and the target is left as it was.
#[derive(Debug)]
pub struct AtomicFile {
    /// The file replaced: `path` itself, or the file its symlinks lead to.
    target: PathBuf,
    tmp: tempfile::NamedTempFile,
}

impl AtomicFile {
    /// Starts writing `path`: refused unless it is a regular file, a symlink to one, or names
    /// nothing yet.
    pub fn create(path: &Path) -> std::io::Result<AtomicFile> {
        let target = final_target(path)?;
        if let Ok(meta) = std::fs::metadata(&target)
            && !meta.is_file()
        {
            return Err(std::io::Error::new(
                std::io::ErrorKind::InvalidInput,
                format!(
                    "{} is {}, not a regular file: not replaced",
                    target.display(),
                    kind_of(&meta)
                ),
            ));
        }
        let dir = match target.parent() {
            Some(d) if !d.as_os_str().is_empty() => d,
            _ => Path::new("."),
        };
        let mut builder = tempfile::Builder::new();
        builder.prefix(".rastray-").suffix(".tmp");
        // Mode 0666 for a new file: `open` takes the umask off, as for any program's new file
        // (tempfile's own default is 0600).
        #[cfg(unix)]
        builder.permissions(std::os::unix::fs::PermissionsExt::from_mode(0o666));
        let tmp = builder.tempfile_in(dir)?;
        Ok(AtomicFile { target, tmp })
    }

    /// The temporary file being written, which [`AtomicFile::commit`] renames.
    pub fn temporary_path(&self) -> &Path {
        self.tmp.path()
    }

    /// Replaces the target with what was written. A replaced file keeps its permissions; a new
    /// file has mode 0666 less the umask, as the temporary file was created.
    pub fn commit(self) -> std::io::Result<()> {
        if let Ok(meta) = std::fs::metadata(&self.target) {
            self.tmp.as_file().set_permissions(meta.permissions())?;
        }
        self.tmp.as_file().sync_all()?;
        self.tmp.persist(&self.target).map_err(|e| e.error)?;
        Ok(())
    }
}

impl Write for AtomicFile {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        self.tmp.write(buf)
    }

    fn flush(&mut self) -> std::io::Result<()> {
        self.tmp.flush()
    }
}

/// The file `path` leads to: `path` itself unless it is a symlink, else the symlink's target,
/// followed link by link (a relative target is relative to the link's folder). The target may
/// not exist yet (a dangling link names the file to create).
pub fn final_target(path: &Path) -> std::io::Result<PathBuf> {
    let mut current = path.to_path_buf();
    for _ in 0..MAX_LINKS {
        match std::fs::symlink_metadata(&current) {
            Ok(meta) if meta.file_type().is_symlink() => {
                let link = std::fs::read_link(&current)?;
                current = match current.parent() {
                    Some(folder) => folder.join(link),
                    None => link,
                };
            }
            _ => return Ok(current),
        }
    }
    Err(std::io::Error::new(
        std::io::ErrorKind::InvalidInput,
        format!("{}: more than {MAX_LINKS} symlinks", path.display()),
    ))
}
