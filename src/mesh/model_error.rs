//! Why an STL or PLY file could not be loaded: the file, where in it (a line of text or a byte
//! of binary data), and the problem, one type per format.

use std::fmt;
use std::path::PathBuf;

/// Where in a model file a problem lies.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Place {
    /// The file as a whole (it cannot be read, or it lacks something).
    File,
    /// 1-based line of a text file.
    Line(usize),
    /// Offset from the start of the file, bytes.
    Byte(u64),
}

/// A model file that could not be loaded, with the format's `problem`.
#[derive(Debug, thiserror::Error)]
#[error("{}{}: {problem}", path.display(), self.place)]
pub struct ModelError<P: std::error::Error> {
    /// The file as it was opened.
    pub path: PathBuf,
    pub place: Place,
    pub problem: P,
}

impl fmt::Display for Place {
    /// `:12` for a line, ` at byte 84` for an offset, nothing for the whole file.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Place::File => Ok(()),
            Place::Line(line) => write!(f, ":{line}"),
            Place::Byte(offset) => write!(f, " at byte {offset}"),
        }
    }
}

/// The refusal of a file that grew past its size limit while it was read.
pub fn grew() -> std::io::Error {
    std::io::Error::new(
        std::io::ErrorKind::InvalidData,
        "the file grew past the size limit while it was read",
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Debug, thiserror::Error)]
    #[error("broken")]
    struct Broken;

    #[test]
    fn the_place_follows_the_file_name() {
        let at = |place| {
            ModelError {
                path: "a/b.stl".into(),
                place,
                problem: Broken,
            }
            .to_string()
        };
        assert_eq!(at(Place::File), "a/b.stl: broken");
        assert_eq!(at(Place::Line(3)), "a/b.stl:3: broken");
        assert_eq!(at(Place::Byte(84)), "a/b.stl at byte 84: broken");
    }
}
