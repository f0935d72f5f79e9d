//! STL import, binary and ASCII. A file is binary when its size is exactly the 84 + 50 × count
//! that the triangle count at byte 80 asks for, whatever its header says (binary exporters
//! often begin the header with `solid`); otherwise it is ASCII when it is text beginning with
//! `solid`. Corners at bit-identical positions are welded into one vertex (−0 meets 0), so
//! that smooth normals and crease angles work; the file's facet normals are not read: normals
//! come from the faces.
//!
//! Memory: the result (12 bytes a distinct position, 12 a triangle) and, while welding, a binary
//! file's body (50 bytes a triangle) and its corners sorted into buckets (18 bytes a corner)
//! or an ASCII file's corners (12 bytes each); an ASCII file streams through a 64 KiB buffer.

mod ascii;
mod binary;
mod error;

use std::fmt;
use std::io::BufReader;
use std::path::Path;

pub use error::{StlError, StlProblem};

use super::byte_source::ByteSource;
use super::geometry::ModelGeometry;
use super::model_error::{Place, grew};
use super::model_format::{binary_stl_size, is_ascii_stl};
use super::weld::{Repeats, positions_of, weld_where};
use crate::memory_budget::triangle_cap;

/// How an STL file was written.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StlEncoding {
    Binary,
    Ascii,
}

impl fmt::Display for StlEncoding {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            StlEncoding::Binary => "binary",
            StlEncoding::Ascii => "ASCII",
        })
    }
}

/// An STL file's triangles, welded.
#[derive(Debug, Clone, PartialEq)]
pub struct StlModel {
    /// Positions and triangles; no normals, colours or texture coordinates (STL has none that
    /// rastray reads).
    pub geometry: ModelGeometry,
    pub encoding: StlEncoding,
}

/// Reads the STL file at `path`: a regular file of at most [`MAX_MODEL_BYTES`](crate::input_file::MAX_MODEL_BYTES) holding at most
/// [`triangle_cap`] triangles, every coordinate within the scene's coordinate limits. Errors
/// name the file and the line (ASCII) or byte offset (binary).
pub fn load_stl(path: &Path) -> Result<StlModel, StlError> {
    let fail = |(place, problem)| StlError {
        path: path.to_path_buf(),
        place,
        problem,
    };
    let io = |e| fail((Place::File, StlProblem::Io(e)));
    let (mut source, size) = ByteSource::open_model(path).map_err(io)?;
    let head = source.ahead(512).map_err(io)?;
    let (positions, triangles, encoding) = if binary_stl_size(head) == Some(size) {
        let count = u32::from_le_bytes([head[80], head[81], head[82], head[83]]);
        if count as u64 > triangle_cap() {
            return Err(fail((
                Place::Byte(80),
                StlProblem::TooManyTriangles {
                    limit: triangle_cap(),
                },
            )));
        }
        source.consume(84);
        let (positions, triangles) = binary::read_triangles(&mut source, count).map_err(fail)?;
        (positions, triangles, StlEncoding::Binary)
    } else if is_ascii_stl(head) {
        let mut reader = BufReader::with_capacity(1 << 16, &mut source);
        let (corners, triangles) = ascii::read_solids(&mut reader, triangle_cap()).map_err(fail)?;
        // Every corner read is a triangle's: all are used.
        let (keys, triangles) = weld_where(corners, |k| *k, triangles, Repeats::Near, |_| true);
        (positions_of(&keys), triangles, StlEncoding::Ascii)
    } else if size < 84 {
        return Err(fail((Place::File, StlProblem::TooShort { size })));
    } else {
        let count = u32::from_le_bytes([head[80], head[81], head[82], head[83]]);
        return Err(fail(if size < 84 + 50 * count as u64 {
            (Place::Byte(size), StlProblem::CutShort { count, size })
        } else {
            (Place::File, StlProblem::CountDisagrees { count, size })
        }));
    };
    if source.get_ref().limit() == 0 {
        return Err(io(grew()));
    }
    if triangles.is_empty() {
        return Err(fail((Place::File, StlProblem::NoTriangles)));
    }
    Ok(StlModel {
        geometry: ModelGeometry {
            positions,
            triangles,
            corner_normals: None,
            colors: None,
            corner_uvs: None,
        },
        encoding,
    })
}
