//! The temporary file an atomic write fills before it takes the target's name. Where the file
//! system allows it (Linux's `O_TMPFILE`: ext4, xfs, btrfs, tmpfs), the file has no name at all
//! until it is complete, so a process killed with SIGKILL leaves nothing behind. Elsewhere it is
//! named `.rastray-<pid>-<random>.tmp`, and each later write into that folder removes the ones
//! whose process is gone.

use std::fs::File;
use std::io::Write;
use std::path::{Path, PathBuf};

use rustix::fs::{AtFlags, CWD, Mode, OFlags};
use rustix::io::Errno;

/// How every temporary name starts and ends.
const PREFIX: &str = ".rastray-";
const SUFFIX: &str = ".tmp";

/// A file being written in `folder`, removed (or never named) unless [`TemporaryFile::persist`]
/// moves it over its target.
#[derive(Debug)]
pub struct TemporaryFile {
    file: File,
    folder: PathBuf,
    /// The file's name while it has one (the fallback); `None` for an anonymous file.
    named: Option<PathBuf>,
}

impl TemporaryFile {
    /// A new empty file in `folder` with mode `mode` less the umask.
    pub fn new_in(folder: &Path, mode: u32) -> std::io::Result<TemporaryFile> {
        let mode = Mode::from_raw_mode(mode);
        #[cfg(target_os = "linux")]
        match rustix::fs::open(
            folder,
            OFlags::TMPFILE | OFlags::WRONLY | OFlags::CLOEXEC,
            mode,
        ) {
            Ok(fd) => {
                return Ok(TemporaryFile {
                    file: File::from(fd),
                    folder: folder.to_path_buf(),
                    named: None,
                });
            }
            // The file system (or kernel) has no anonymous files: fall back to a name.
            Err(Errno::OPNOTSUPP | Errno::ISDIR | Errno::INVAL | Errno::NOENT)
                if folder.is_dir() => {}
            Err(error) => return Err(error.into()),
        }
        remove_stale(folder);
        let (fd, path) = create_named(folder, mode)?;
        Ok(TemporaryFile {
            file: File::from(fd),
            folder: folder.to_path_buf(),
            named: Some(path),
        })
    }

    /// The open file.
    pub fn as_file(&self) -> &File {
        &self.file
    }

    /// Gives the file the name `target`, replacing what is there in one rename. An anonymous
    /// file is first linked under a temporary name (a link cannot replace a file), then renamed.
    pub fn persist(mut self, target: &Path) -> std::io::Result<()> {
        let named = match self.named.take() {
            Some(path) => path,
            None => self.link_anonymous()?,
        };
        std::fs::rename(&named, target).inspect_err(|_| {
            let _ = std::fs::remove_file(&named);
        })
    }

    /// Links the anonymous file into its folder under a fresh temporary name.
    fn link_anonymous(&self) -> std::io::Result<PathBuf> {
        use std::os::fd::AsRawFd;
        let proc_path = format!("/proc/self/fd/{}", self.file.as_raw_fd());
        loop {
            let path = self.folder.join(temporary_name());
            let linked = rustix::fs::linkat(CWD, &proc_path, CWD, &path, AtFlags::SYMLINK_FOLLOW)
                .or_else(|_| {
                    // Without /proc, the descriptor itself (needs CAP_DAC_READ_SEARCH).
                    rustix::fs::linkat(&self.file, "", CWD, &path, AtFlags::EMPTY_PATH)
                });
            match linked {
                Ok(()) => return Ok(path),
                Err(Errno::EXIST) => continue,
                Err(error) => return Err(error.into()),
            }
        }
    }
}

impl Write for TemporaryFile {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        self.file.write(buf)
    }

    fn flush(&mut self) -> std::io::Result<()> {
        self.file.flush()
    }
}

impl Drop for TemporaryFile {
    fn drop(&mut self) {
        if let Some(path) = self.named.take() {
            let _ = std::fs::remove_file(path);
        }
    }
}

/// Creates `.rastray-<pid>-<random>.tmp` in `folder`, exclusively.
fn create_named(folder: &Path, mode: Mode) -> std::io::Result<(rustix::fd::OwnedFd, PathBuf)> {
    loop {
        let path = folder.join(temporary_name());
        let flags =
            OFlags::CREATE | OFlags::EXCL | OFlags::WRONLY | OFlags::CLOEXEC | OFlags::NOFOLLOW;
        match rustix::fs::open(&path, flags, mode) {
            Ok(fd) => return Ok((fd, path)),
            Err(Errno::EXIST) => continue,
            Err(error) => return Err(error.into()),
        }
    }
}

/// `.rastray-<pid>-<random>.tmp`.
fn temporary_name() -> String {
    use std::hash::{BuildHasher, Hasher};
    let mut hasher = std::collections::hash_map::RandomState::new().build_hasher();
    hasher.write_u128(
        std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map_or(0, |d| d.as_nanos()),
    );
    format!(
        "{PREFIX}{}-{:012x}{SUFFIX}",
        std::process::id(),
        hasher.finish() & 0xffff_ffff_ffff
    )
}

/// The process id in a temporary file's name, when the name is one of ours.
fn pid_of(name: &str) -> Option<i32> {
    let middle = name.strip_prefix(PREFIX)?.strip_suffix(SUFFIX)?;
    let (pid, random) = middle.split_once('-')?;
    (random.len() == 12 && random.bytes().all(|b| b.is_ascii_hexdigit()))
        .then(|| pid.parse().ok())
        .flatten()
}

/// Removes the temporary files in `folder` whose process no longer runs (it was killed before it
/// could remove them). A process that runs, or that the check cannot see, keeps its files.
fn remove_stale(folder: &Path) {
    let Ok(entries) = std::fs::read_dir(folder) else {
        return;
    };
    for entry in entries.flatten() {
        let name = entry.file_name();
        let Some(pid) = name.to_str().and_then(pid_of) else {
            continue;
        };
        let gone = rustix::process::Pid::from_raw(pid)
            .is_some_and(|pid| rustix::process::test_kill_process(pid) == Err(Errno::SRCH));
        if gone && entry.file_type().is_ok_and(|t| t.is_file()) {
            let _ = std::fs::remove_file(entry.path());
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names(folder: &Path) -> Vec<String> {
        let mut names: Vec<String> = std::fs::read_dir(folder)
            .unwrap()
            .flatten()
            .map(|e| e.file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        names
    }

    #[test]
    fn an_unpersisted_file_leaves_nothing() {
        let dir = tempfile::tempdir().unwrap();
        let mut file = TemporaryFile::new_in(dir.path(), 0o666).unwrap();
        file.write_all(b"half").unwrap();
        drop(file);
        assert!(names(dir.path()).is_empty());
    }

    #[test]
    fn a_persisted_file_takes_the_name_and_nothing_else_is_left() {
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("out.png");
        std::fs::write(&target, b"old").unwrap();
        let mut file = TemporaryFile::new_in(dir.path(), 0o666).unwrap();
        file.write_all(b"new").unwrap();
        file.persist(&target).unwrap();
        assert_eq!(std::fs::read(&target).unwrap(), b"new");
        assert_eq!(names(dir.path()), ["out.png"]);
    }

    #[cfg(target_os = "linux")]
    #[test]
    fn on_linux_file_systems_the_file_has_no_name_while_it_is_written() {
        let dir = tempfile::tempdir().unwrap();
        let _file = TemporaryFile::new_in(dir.path(), 0o666).unwrap();
        assert!(names(dir.path()).is_empty(), "anonymous (O_TMPFILE)");
    }

    #[test]
    fn stale_files_of_processes_that_are_gone_are_removed() {
        let dir = tempfile::tempdir().unwrap();
        // A process that has ended: a child that exited and was waited for.
        let gone = std::process::Command::new("true").spawn().unwrap();
        let gone_pid = gone.id();
        let mut gone = gone;
        gone.wait().unwrap();
        let stale = format!("{PREFIX}{gone_pid}-0123456789ab{SUFFIX}");
        let running = format!("{PREFIX}{}-0123456789ab{SUFFIX}", std::process::id());
        let foreign = ".rastray-notours.tmp".to_string();
        for name in [&stale, &running, &foreign] {
            std::fs::write(dir.path().join(name), b"x").unwrap();
        }
        remove_stale(dir.path());
        let mut expected = vec![foreign, running];
        expected.sort();
        assert_eq!(names(dir.path()), expected);
    }

    #[test]
    fn names_are_parsed_strictly() {
        assert_eq!(pid_of(".rastray-42-0123456789ab.tmp"), Some(42));
        assert_eq!(pid_of(".rastray-42-0123456789.tmp"), None);
        assert_eq!(pid_of(".rastray-x-0123456789ab.tmp"), None);
        assert_eq!(pid_of("rastray-42-0123456789ab.tmp"), None);
        assert!(pid_of(&temporary_name()).is_some());
    }
}
