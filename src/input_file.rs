//! Reading the files a scene is made of (the scene itself, its OBJ and glTF models, their
//! buffers), bounded: only a regular file is read, and only when it is no larger than a cap
//! stated here. A device, FIFO or directory is refused before it is opened, so `/dev/zero`
//! cannot grow a read until the machine runs out of memory, nor a FIFO block it.

use std::fs::File;
use std::io::{Error, ErrorKind, Read, Take};
use std::path::Path;

/// Largest scene file read, bytes (16 MiB: a scene with thousands of objects is far below it).
pub const MAX_SCENE_BYTES: u64 = 16 << 20;

/// Largest model file read (an OBJ, a glTF or GLB, or one glTF buffer), bytes: 1 GiB, about
/// the OBJ text of the 20-million-triangle cap.
pub const MAX_MODEL_BYTES: u64 = 1 << 30;

/// The whole of the regular file at `path` (symlinks followed), if it holds at most `cap` bytes.
/// `what` names the kind of file in the refusal ("a scene file").
pub fn read_bounded(path: &Path, cap: u64, what: &str) -> std::io::Result<Vec<u8>> {
    let mut file = open_bounded(path, cap, what)?;
    let mut bytes = Vec::with_capacity(file.get_ref().metadata()?.len() as usize);
    file.read_to_end(&mut bytes)?;
    if bytes.len() as u64 > cap {
        return Err(too_large(bytes.len() as u64, cap, what));
    }
    Ok(bytes)
}

/// The regular file at `path` (symlinks followed), if it holds at most `cap` bytes, open for
/// reading at most `cap + 1` bytes: a file that grows while it is read stops one byte past the
/// cap, and a reader that sees that byte (the limit left is 0) knows it grew.
pub fn open_bounded(path: &Path, cap: u64, what: &str) -> std::io::Result<Take<File>> {
    let file = open_regular(path)?;
    let size = file.metadata()?.len();
    if size > cap {
        return Err(too_large(size, cap, what));
    }
    Ok(file.take(cap + 1))
}

/// [`read_bounded`] as UTF-8 text.
pub fn read_bounded_text(path: &Path, cap: u64, what: &str) -> std::io::Result<String> {
    String::from_utf8(read_bounded(path, cap, what)?)
        .map_err(|_| Error::new(ErrorKind::InvalidData, "the file is not valid UTF-8 text"))
}

/// Opens `path` for reading when it is a regular file (symlinks followed); anything else is
/// refused before it is opened, naming what it is.
pub fn open_regular(path: &Path) -> std::io::Result<File> {
    refuse_unless_regular(&std::fs::metadata(path)?)?;
    let file = File::open(path)?;
    // The path may have been replaced between the check and the open.
    refuse_unless_regular(&file.metadata()?)?;
    Ok(file)
}

/// The refusal of a file of `size` bytes above `cap`.
pub fn too_large(size: u64, cap: u64, what: &str) -> Error {
    Error::new(
        ErrorKind::InvalidData,
        format!(
            "the file is {}; {what} may be at most {}",
            exact(size),
            human(cap)
        ),
    )
}

/// `1.5 GiB (1610612736 bytes)`, or `11 bytes`.
fn exact(bytes: u64) -> String {
    if bytes < 1024 {
        format!("{bytes} bytes")
    } else {
        format!("{} ({bytes} bytes)", human(bytes))
    }
}

/// `16 MiB`, `1.5 GiB`: binary units, one decimal when not whole.
pub fn human(bytes: u64) -> String {
    const UNITS: [&str; 4] = ["bytes", "KiB", "MiB", "GiB"];
    let mut value = bytes as f64;
    let mut unit = 0;
    while value >= 1024.0 && unit + 1 < UNITS.len() {
        value /= 1024.0;
        unit += 1;
    }
    if unit == 0 {
        format!("{bytes} bytes")
    } else if value.fract() == 0.0 {
        format!("{value} {}", UNITS[unit])
    } else {
        format!("{value:.1} {}", UNITS[unit])
    }
}

fn refuse_unless_regular(meta: &std::fs::Metadata) -> std::io::Result<()> {
    if meta.is_file() {
        return Ok(());
    }
    Err(Error::new(
        ErrorKind::InvalidInput,
        format!("{}, not a regular file: refused", kind_of(meta)),
    ))
}

/// What a file that is not a regular one is, in words: "a character device".
pub fn kind_of(meta: &std::fs::Metadata) -> &'static str {
    let kind = meta.file_type();
    if kind.is_dir() {
        return "a directory";
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if kind.is_char_device() {
            return "a character device";
        } else if kind.is_block_device() {
            return "a block device";
        } else if kind.is_fifo() {
            return "a FIFO";
        } else if kind.is_socket() {
            return "a socket";
        }
    }
    if kind.is_file() {
        "a regular file"
    } else {
        "a special file"
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_read_as_words() {
        assert_eq!(human(512), "512 bytes");
        assert_eq!(human(16 << 20), "16 MiB");
        assert_eq!(human(3 << 29), "1.5 GiB");
        assert_eq!(exact(3 << 29), "1.5 GiB (1610612736 bytes)");
    }

    #[test]
    fn a_device_and_a_directory_are_refused_and_a_file_above_the_cap_too() {
        let dev = read_bounded(Path::new("/dev/zero"), 10, "a scene file").unwrap_err();
        assert!(dev.to_string().contains("a character device"), "{dev}");
        let dir = std::env::temp_dir();
        let refused = read_bounded(&dir, 10, "a scene file").unwrap_err();
        assert!(refused.to_string().contains("a directory"), "{refused}");
        let file = tempfile::NamedTempFile::new().unwrap();
        std::fs::write(file.path(), [b'x'; 11]).unwrap();
        let big = read_bounded(file.path(), 10, "a scene file").unwrap_err();
        assert!(
            big.to_string()
                .contains("the file is 11 bytes; a scene file may be at most 10 bytes"),
            "{big}"
        );
        assert_eq!(
            read_bounded(file.path(), 11, "a scene file").unwrap().len(),
            11
        );
    }
}
