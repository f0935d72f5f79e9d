//! Why an OBJ file could not be loaded: the file, the line where it is known, and the problem.

use std::fmt;
use std::path::PathBuf;

/// An OBJ file that could not be loaded.
#[derive(Debug, thiserror::Error)]
#[error("{}: {problem}", self.location())]
pub struct ObjError {
    /// The file as it was opened.
    pub path: PathBuf,
    /// 1-based line of the offending statement, when the problem has one.
    pub line: Option<usize>,
    pub problem: ObjProblem,
}

/// What is wrong with an OBJ file.
#[derive(Debug, thiserror::Error)]
pub enum ObjProblem {
    /// The file could not be read.
    #[error("{0}")]
    Io(std::io::Error),
    /// A statement that is not OBJ as rastray reads it: what was expected.
    #[error("malformed OBJ: {0}")]
    Malformed(&'static str),
    /// A `v` statement with a NaN or infinite coordinate; `vertex` counts from 1.
    #[error("vertex {vertex} is not a finite number")]
    NonFiniteVertex { vertex: usize },
    /// A `v` statement with a coordinate beyond the scene's coordinate limits; `vertex` counts
    /// from 1.
    #[error(
        "vertex {vertex} has coordinate {value:e}; coordinates must be {}",
        crate::scene::limits::COORDINATE
    )]
    VertexOutOfRange { vertex: usize, value: f32 },
    /// A face refers to a vertex the file does not define; `index` is as written.
    #[error("a face names vertex {index}, but the file has {count} vertices")]
    MissingVertex { index: i64, count: usize },
    /// More triangles than a scene may hold, found before the file was read to its end.
    #[error("the file holds more than {limit} triangles, the most a scene may hold")]
    TooManyTriangles { limit: u64 },
    /// The model's textures would take it past the memory bound: the figures, counted from the
    /// textures' headers before they were decoded.
    #[error("{0}")]
    OverBudget(String),
    /// Nothing to draw: no face with three or more corners.
    #[error("the file holds no faces")]
    NoFaces,
}

impl ObjError {
    /// The file, and the line when known: `models/cube.obj:12`.
    pub fn location(&self) -> impl fmt::Display + '_ {
        Location(self)
    }
}

struct Location<'a>(&'a ObjError);

impl fmt::Display for Location<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.0.path.display())?;
        match self.0.line {
            Some(line) => write!(f, ":{line}"),
            None => Ok(()),
        }
    }
}

/// The problem and line without the file name, for callers that keep errors as text and name
/// the file themselves.
impl From<ObjError> for String {
    fn from(error: ObjError) -> String {
        match error.line {
            Some(line) => format!("line {line}: {}", error.problem),
            None => error.problem.to_string(),
        }
    }
}
