//! Atomic file writes: a temporary file in the same directory (`temporary_file`: nameless until
//! complete where the file system allows), synced, then renamed over the target, so a crash leaves
//! either the old file or the new one, and no half-written file.
//!
//! Only a regular file, or a path where nothing exists yet, is replaced this way. A symlink is
//! followed and its target replaced in the target's own folder, so the link stays a link. A
//! device, FIFO or directory is refused: renaming over `/dev/null` would replace the device
//! with a plain file (export writes such paths as streams, `export::Destination`).

use std::io::Write;
use std::path::{Path, PathBuf};

use crate::input_file::kind_of;
use crate::temporary_file::TemporaryFile;

/// Most symlinks followed from a path to its target (as Linux's `MAXSYMLINKS`).
const MAX_LINKS: usize = 40;

/// Writes `bytes` to `path` atomically. A replaced file keeps its permission bits (never its
/// setuid, setgid or sticky bits); a new file gets mode 0666 less the umask.
pub fn write_atomically(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let mut file = AtomicFile::create(path)?;
    file.write_all(bytes)?;
    file.commit()
}

/// As [`write_atomically`], for a file rastray names itself in a folder others may share (the
/// recovery file): a symlink at `path`, even a dangling one, is refused rather than followed, so
/// a link planted there cannot make rastray create or replace the file it points to. The
/// temporary file is created with `O_EXCL` and the rename replaces the name, never a link's target.
pub fn write_atomically_no_follow(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    if let Ok(meta) = std::fs::symlink_metadata(path)
        && meta.file_type().is_symlink()
    {
        return Err(std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            format!("{} is a symlink: not followed, not written", path.display()),
        ));
    }
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
    tmp: TemporaryFile,
}

impl AtomicFile {
    /// Starts writing `path`: refused unless it is a regular file, a symlink to one, or names
    /// nothing yet.
    pub fn create(path: &Path) -> std::io::Result<AtomicFile> {
        let target = final_target(path)?;
        if let Ok(meta) = std::fs::metadata(&target) {
            if !meta.is_file() {
                return Err(std::io::Error::new(
                    std::io::ErrorKind::InvalidInput,
                    format!(
                        "{} is {}, not a regular file: not replaced",
                        target.display(),
                        kind_of(&meta)
                    ),
                ));
            }
            refuse_unless_writable(&target, &meta)?;
        }
        let dir = match target.parent() {
            Some(d) if !d.as_os_str().is_empty() => d,
            _ => Path::new("."),
        };
        // Mode 0666 for a new file: `open` takes the umask off, as for any program's new file.
        let tmp = TemporaryFile::new_in(dir, 0o666)?;
        Ok(AtomicFile { target, tmp })
    }

    /// Replaces the target with what was written. A replaced file keeps its permission bits
    /// (not setuid, setgid or sticky: an image is no program); a new file has mode 0666 less the
    /// umask, as the temporary file was created.
    pub fn commit(self) -> std::io::Result<()> {
        self.commit_unless(|| false).map(|_| ())
    }

    /// As [`AtomicFile::commit`], unless `cancelled` says so once the data is on disk, just
    /// before the rename: then the temporary file is removed, the target is left as it was and
    /// the result is `Ok(false)`. A signal that arrives before the rename thus wins.
    pub fn commit_unless(self, cancelled: impl FnOnce() -> bool) -> std::io::Result<bool> {
        if let Ok(meta) = std::fs::metadata(&self.target) {
            self.tmp
                .as_file()
                .set_permissions(permission_bits(meta.permissions()))?;
        }
        self.tmp.as_file().sync_all()?;
        if cancelled() {
            return Ok(false);
        }
        self.tmp.persist(&self.target)?;
        Ok(true)
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

/// `permissions` without the setuid, setgid and sticky bits.
fn permission_bits(permissions: std::fs::Permissions) -> std::fs::Permissions {
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        std::fs::Permissions::from_mode(permissions.mode() & 0o777)
    }
    #[cfg(not(unix))]
    permissions
}

/// Refuses to replace `target` when its mode says its owner may not write it (a file made
/// read-only on purpose, such as 0444), or when the user running rastray may not write it
/// (another user's file in a folder anyone can write to). Root passes the second test but not
/// the first: a read-only mode is the owner's word, whoever runs the program.
fn refuse_unless_writable(target: &Path, meta: &std::fs::Metadata) -> std::io::Result<()> {
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        let mode = meta.permissions().mode();
        let writable =
            mode & 0o200 != 0 && rustix::fs::access(target, rustix::fs::Access::WRITE_OK).is_ok();
        if !writable {
            return Err(std::io::Error::new(
                std::io::ErrorKind::PermissionDenied,
                format!(
                    "{} is not writable (mode {:04o}): not replaced",
                    target.display(),
                    mode & 0o7777
                ),
            ));
        }
    }
    #[cfg(not(unix))]
    if meta.permissions().readonly() {
        return Err(std::io::Error::new(
            std::io::ErrorKind::PermissionDenied,
            format!("{} is read-only: not replaced", target.display()),
        ));
    }
    Ok(())
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

#[cfg(all(test, unix))]
mod tests {
    use std::os::unix::fs::PermissionsExt;

    use super::*;

    fn mode(path: &Path) -> u32 {
        std::fs::metadata(path).unwrap().permissions().mode() & 0o7777
    }

    #[test]
    fn setuid_setgid_and_sticky_bits_are_never_copied() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("image.png");
        std::fs::write(&path, b"old").unwrap();
        std::fs::set_permissions(&path, std::fs::Permissions::from_mode(0o7755)).unwrap();
        write_atomically(&path, b"new").unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), b"new");
        assert_eq!(
            mode(&path),
            0o755,
            "permission bits kept, special bits dropped"
        );
    }

    #[test]
    fn a_file_its_owner_made_read_only_is_not_replaced() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("keep.png");
        std::fs::write(&path, b"old").unwrap();
        std::fs::set_permissions(&path, std::fs::Permissions::from_mode(0o444)).unwrap();
        let error = write_atomically(&path, b"new").expect_err("read-only");
        assert_eq!(error.kind(), std::io::ErrorKind::PermissionDenied);
        assert!(error.to_string().contains("keep.png"), "{error}");
        assert!(error.to_string().contains("0444"), "{error}");
        assert_eq!(std::fs::read(&path).unwrap(), b"old");
        let leftovers = std::fs::read_dir(dir.path()).unwrap().count();
        assert_eq!(leftovers, 1, "no temporary file left");
    }

    #[test]
    fn a_commit_cancelled_before_the_rename_leaves_the_target_as_it_was() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("out.png");
        std::fs::write(&path, b"old").unwrap();
        let mut file = AtomicFile::create(&path).unwrap();
        file.write_all(b"new").unwrap();
        assert!(!file.commit_unless(|| true).unwrap());
        assert_eq!(std::fs::read(&path).unwrap(), b"old");
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
    }

    #[test]
    fn a_symlink_is_refused_by_the_no_follow_write() {
        let dir = tempfile::tempdir().unwrap();
        let link = dir.path().join("recovered.toml");
        let target = dir.path().join("elsewhere.toml");
        std::os::unix::fs::symlink(&target, &link).unwrap();
        assert!(write_atomically_no_follow(&link, b"x").is_err());
        assert!(!target.exists());
        let plain = dir.path().join("plain.toml");
        write_atomically_no_follow(&plain, b"x").unwrap();
        assert_eq!(std::fs::read(&plain).unwrap(), b"x");
    }
}
