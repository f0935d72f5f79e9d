//! What is wrong with an STL file. The file and the place (line or byte) are added by
//! [`crate::mesh::ModelError`].

use crate::mesh::ModelError;

/// An STL file that could not be loaded.
pub type StlError = ModelError<StlProblem>;

/// What is wrong with an STL file.
#[derive(Debug, thiserror::Error)]
pub enum StlProblem {
    /// The file could not be read.
    #[error("{0}")]
    Io(std::io::Error),
    /// Neither text beginning with `solid` nor long enough for a binary STL's header.
    #[error(
        "not an STL file: {size} bytes, too short for a binary STL's 84-byte header, and not \
         text beginning with `solid`"
    )]
    TooShort { size: u64 },
    /// A binary STL whose size is not the 84 + 50 × count its count asks for.
    #[error(
        "a binary STL whose triangle count ({count}) disagrees with its size ({size} bytes; \
         {count} triangles take {} bytes), and not an ASCII STL (text beginning with `solid`)",
        84 + 50 * *count as u64
    )]
    CountDisagrees { count: u32, size: u64 },
    /// A binary STL shorter than its triangle count asks for.
    #[error(
        "the binary STL is truncated: its triangle count ({count}) needs {} bytes, the file \
         has {size}",
        84 + 50 * *count as u64
    )]
    CutShort { count: u32, size: u64 },
    /// The file ended inside a triangle of a binary STL (it shrank while it was read).
    #[error("the binary STL is truncated: it ends inside triangle {triangle} of {count}")]
    Truncated { triangle: u64, count: u32 },
    /// More triangles than a scene may hold.
    #[error("the file holds more than {limit} triangles, the most a scene may hold")]
    TooManyTriangles { limit: u64 },
    /// A vertex coordinate that is NaN or infinite; `triangle` counts from 1.
    #[error("triangle {triangle} has a coordinate that is not a finite number")]
    NonFinite { triangle: u64 },
    /// A vertex coordinate beyond the scene's coordinate limits; `triangle` counts from 1.
    #[error(
        "triangle {triangle} has coordinate {value:e}; coordinates must be {}",
        crate::scene::limits::COORDINATE
    )]
    OutOfRange { triangle: u64, value: f32 },
    /// An ASCII STL line that is not what the grammar allows there.
    #[error("expected {expected}, found `{found}`")]
    Expected {
        expected: &'static str,
        /// The line as written, shortened.
        found: String,
    },
    /// The text ended where the grammar wanted more.
    #[error("the file ends inside the facet begun at line {facet_line}: {expected} is missing")]
    Unfinished {
        expected: &'static str,
        facet_line: usize,
    },
    /// A `vertex` line whose numbers are not three numbers.
    #[error("a vertex is `vertex x y z`, three numbers")]
    BadVertex,
    /// A loop with fewer than three vertices.
    #[error("a facet's loop has {0} vertices; a triangle needs 3")]
    ShortLoop(usize),
    /// No triangle in the whole file.
    #[error("the file holds no triangles")]
    NoTriangles,
}

/// Why a coordinate is refused, if it is: `triangle` counts from 1.
#[inline]
pub fn coordinate_problem(value: f32, triangle: u64) -> Option<StlProblem> {
    if crate::scene::limits::COORDINATE.accepts(value) {
        None
    } else if value.is_finite() {
        Some(StlProblem::OutOfRange { triangle, value })
    } else {
        Some(StlProblem::NonFinite { triangle })
    }
}
