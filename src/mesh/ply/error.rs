//! What is wrong with a PLY file. The file and the place (line or byte) are added by
//! [`crate::mesh::ModelError`]. Values read from binary data are never echoed: they may be any
//! bytes.

use crate::mesh::ModelError;

/// A PLY file that could not be loaded.
pub type PlyError = ModelError<PlyProblem>;

/// What is wrong with a PLY file.
#[derive(Debug, thiserror::Error)]
pub enum PlyProblem {
    /// The file could not be read.
    #[error("{0}")]
    Io(std::io::Error),
    /// The model's texture would take it past the memory bound: the figures, counted from the
    /// texture's header before it was decoded.
    #[error("{0}")]
    OverBudget(String),
    /// The first line is not `ply`.
    #[error("not a PLY file: the first line must be `ply`")]
    NotPly,
    /// No `end_header` line within the first `limit` bytes, or before the file ends.
    #[error("the header does not end: no `end_header` line (within the first {limit} bytes)")]
    HeaderTooLong { limit: usize },
    /// A header line that is not what PLY allows there.
    #[error("expected {expected}, found `{found}`")]
    Header {
        expected: &'static str,
        /// The line as written, shortened.
        found: String,
    },
    /// A `format` other than the three PLY has.
    #[error("unknown format `{0}` (expected ascii, binary_little_endian or binary_big_endian)")]
    UnknownFormat(String),
    /// A property type PLY does not have.
    #[error(
        "unknown type `{0}` (expected char, uchar, short, ushort, int, uint, float, double, or \
         int8, uint8, int16, uint16, int32, uint32, float32, float64)"
    )]
    UnknownType(String),
    /// A list whose length type is not a whole-number type.
    #[error("a list's length must be of a whole-number type, not {0}")]
    ListLengthType(String),
    /// An element whose declared count cannot fit in what is left of the file.
    #[error(
        "element `{element}` declares {count} records of at least {record} bytes each, more \
         than the {available} bytes left in the file"
    )]
    CountTooLarge {
        element: String,
        count: u64,
        record: u64,
        available: u64,
    },
    /// More vertices than rastray reads.
    #[error("the file declares {count} vertices; at most {limit} are read")]
    TooManyVertices { count: u64, limit: u64 },
    /// No `vertex` element, or one without x, y and z.
    #[error("the file has no `vertex` element with `x`, `y` and `z` properties")]
    NoPositions,
    /// A `face` element without a list of vertex indices.
    #[error("the `face` element has no `vertex_indices` (or `vertex_index`) list")]
    NoIndexList,
    /// Vertices and no faces.
    #[error("the file is a point cloud: {vertices} vertices and no faces; rastray draws triangles")]
    PointCloud { vertices: u64 },
    /// The body ended inside a record.
    #[error("the file ends inside {element} {index} of {count}")]
    Truncated {
        element: String,
        /// Counting from 1.
        index: u64,
        count: u64,
    },
    /// An ASCII record with fewer values than its properties call for.
    #[error("{element} {index} has fewer values than its properties call for")]
    TooFewValues { element: String, index: u64 },
    /// An ASCII record with more values than its properties call for.
    #[error("{element} {index} has more values than its properties call for")]
    TooManyValues { element: String, index: u64 },
    /// An ASCII value that is not a number of its type.
    #[error("`{token}` is not a number of type {ty}")]
    BadNumber { token: String, ty: String },
    /// A list length that is negative or not whole.
    #[error("{element} {index} has a list of negative length")]
    BadListLength { element: String, index: u64 },
    /// A face naming a vertex that does not exist; `written` is the index as an ASCII file
    /// spells it (binary values are not echoed).
    #[error(
        "face {face} names {} (the file has {vertices} vertices)",
        written.map_or("a vertex out of range".to_string(), |w| format!("vertex {w}, out of range"))
    )]
    IndexOutOfRange {
        face: u64,
        written: Option<i64>,
        vertices: u64,
    },
    /// A position that is NaN or infinite; `vertex` counts from 1.
    #[error("vertex {vertex} has a coordinate that is not a finite number")]
    NonFinite { vertex: u64 },
    /// A position beyond the scene's coordinate limits; `vertex` counts from 1.
    #[error(
        "vertex {vertex} has coordinate {value:e}; coordinates must be {}",
        crate::scene::limits::COORDINATE
    )]
    OutOfRange { vertex: u64, value: f32 },
    /// A texture coordinate that is NaN or infinite; `vertex` counts from 1.
    #[error("vertex {vertex} has a texture coordinate that is not a finite number")]
    NonFiniteUv { vertex: u64 },
    /// More triangles than a scene may hold.
    #[error("the file holds more than {limit} triangles, the most a scene may hold")]
    TooManyTriangles { limit: u64 },
    /// Faces, but none with three or more corners.
    #[error("the file holds no triangles (no face has three corners)")]
    NoTriangles,
}
