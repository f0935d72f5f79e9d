//! Where an export's bytes go, chosen from what the output path is: a regular file (or a path
//! where nothing exists yet, or a symlink to either) is replaced atomically; a FIFO or a
//! character device (`/dev/null`, a terminal) is written as a stream, as is standard output.
//! Nothing else is written: a directory, a block device or a socket is refused.

use std::io::Write;
use std::path::{Path, PathBuf};

use super::error::ExportError;
use super::stream::Stream;
use crate::atomic_file::{AtomicFile, final_target};
use crate::input_file::kind_of;
use crate::render::{Cancelled, Progress, RenderError};

/// Where an export writes.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Destination {
    /// A regular file, or a path where nothing exists yet: written beside it, then renamed over
    /// it. Through a symlink, the link's target is replaced.
    File(PathBuf),
    /// A FIFO or a character device, written in place as a stream.
    Stream(PathBuf),
    /// The process's standard output (`-o -` on the command line).
    Stdout,
}

impl Destination {
    /// What `path` is, and so how it is written. Refuses a directory, a block device or a
    /// socket.
    pub fn for_path(path: &Path) -> Result<Destination, ExportError> {
        let meta = match std::fs::metadata(path) {
            Ok(meta) => meta,
            // Nothing there (or a dangling symlink): a new file.
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
                return Ok(Destination::File(path.to_path_buf()));
            }
            Err(e) => return Err(ExportError::io(path, e)),
        };
        if meta.is_file() {
            return Ok(Destination::File(path.to_path_buf()));
        }
        if is_stream(&meta) {
            return Ok(Destination::Stream(path.to_path_buf()));
        }
        Err(ExportError::io(
            path,
            std::io::Error::new(
                std::io::ErrorKind::InvalidInput,
                format!(
                    "{} cannot be written; write a regular file, a FIFO, a character device or `-` (standard output)",
                    kind_of(&meta)
                ),
            ),
        ))
    }

    /// Whether the bytes are written as they come, with no file name to take a format from
    /// when the name has no extension.
    pub fn is_stream(&self) -> bool {
        !matches!(self, Destination::File(_))
    }

    /// The path as messages name it: `-` for standard output.
    pub fn path(&self) -> &Path {
        match self {
            Destination::File(path) | Destination::Stream(path) => path,
            Destination::Stdout => Path::new("-"),
        }
    }

    /// Starts writing: an atomic file, or the stream opened for writing. Waiting on a stream (for
    /// a FIFO's reader, or for a full pipe to drain) ends when `progress` is cancelled.
    pub fn open(&self, progress: &Progress) -> Result<Sink, ExportError> {
        let io = |e| ExportError::io(self.path(), e);
        Ok(match self {
            Destination::File(path) => Sink::Atomic(AtomicFile::create(path).map_err(io)?),
            Destination::Stream(path) => {
                Sink::Stream(Stream::open(path, progress.cancel_flag()).map_err(io)?)
            }
            Destination::Stdout => Sink::Stream(Stream::stdout(progress.cancel_flag())),
        })
    }

    /// Refuses to write over any of `inputs` (the scene file, its models and their buffers):
    /// a render must not overwrite what it was made from. Files are compared by identity
    /// (device and inode), whatever path or link names them.
    pub fn refuse_inputs(&self, inputs: &[PathBuf]) -> Result<(), ExportError> {
        let Destination::File(path) = self else {
            return Ok(());
        };
        let Ok(target) = final_target(path) else {
            return Ok(());
        };
        let Ok(out) = std::fs::metadata(&target) else {
            return Ok(());
        };
        for input in inputs {
            if let Ok(meta) = std::fs::metadata(input)
                && same_file(&out, &meta)
            {
                return Err(ExportError::OutputIsInput {
                    path: path.clone(),
                    input: input.clone(),
                });
            }
        }
        Ok(())
    }
}

/// Why [`Sink::commit`] did not finish.
#[derive(Debug, thiserror::Error)]
pub enum SinkCommitError {
    #[error(transparent)]
    Io(#[from] std::io::Error),
    #[error(transparent)]
    Cancelled(#[from] Cancelled),
}

impl SinkCommitError {
    /// The export error of a commit to `path`.
    pub fn at(self, path: &Path) -> ExportError {
        match self {
            SinkCommitError::Io(error) => ExportError::io(path, error),
            SinkCommitError::Cancelled(cancelled) => RenderError::from(cancelled).into(),
        }
    }
}

/// An export being written: finish it with [`Sink::commit`]. A file dropped without a commit is
/// removed and the target left as it was; a stream keeps what was written.
#[derive(Debug)]
pub enum Sink {
    Atomic(AtomicFile),
    /// A FIFO, a character device or standard output.
    Stream(Stream),
}

impl Sink {
    /// Finishes the export: renames a file over its target, flushes a stream. A write error
    /// the stream reports only now (a full disk, `/dev/full`) is returned. When `progress` is
    /// cancelled by then (a signal arrived before the rename), a file is not renamed: its
    /// temporary file is removed and the result is the cancellation.
    pub fn commit(self, progress: &Progress) -> Result<(), SinkCommitError> {
        match self {
            Sink::Atomic(file) => {
                if file.commit_unless(|| progress.is_cancelled())? {
                    Ok(())
                } else {
                    Err(SinkCommitError::Cancelled(Cancelled))
                }
            }
            Sink::Stream(mut stream) => Ok(stream.flush()?),
        }
    }
}

impl Write for Sink {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        match self {
            Sink::Atomic(file) => file.write(buf),
            Sink::Stream(stream) => stream.write(buf),
        }
    }

    fn flush(&mut self) -> std::io::Result<()> {
        match self {
            Sink::Atomic(file) => file.flush(),
            Sink::Stream(stream) => stream.flush(),
        }
    }
}

#[cfg(unix)]
fn is_stream(meta: &std::fs::Metadata) -> bool {
    use std::os::unix::fs::FileTypeExt;
    meta.file_type().is_fifo() || meta.file_type().is_char_device()
}

#[cfg(not(unix))]
fn is_stream(_meta: &std::fs::Metadata) -> bool {
    false
}

#[cfg(unix)]
fn same_file(a: &std::fs::Metadata, b: &std::fs::Metadata) -> bool {
    use std::os::unix::fs::MetadataExt;
    a.dev() == b.dev() && a.ino() == b.ino()
}

#[cfg(not(unix))]
fn same_file(_a: &std::fs::Metadata, _b: &std::fs::Metadata) -> bool {
    false
}
