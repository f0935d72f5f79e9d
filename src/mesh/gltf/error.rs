//! Why a glTF file could not be loaded. The caller adds the file's path.

/// A glTF or GLB file that cannot be turned into triangles.
#[derive(Debug, thiserror::Error)]
pub enum GltfError {
    /// The file itself could not be read.
    #[error("cannot be read: {0}")]
    Io(std::io::Error),
    /// The file has no bytes at all.
    #[error("the file is empty")]
    Empty,
    /// A GLB whose header or chunks promise more bytes than the file holds.
    #[error("the GLB file is truncated: {0}")]
    TruncatedGlb(String),
    /// A GLB container that is malformed in another way (wrong version, unknown chunk).
    #[error("not a valid GLB file: {0}")]
    BadGlb(String),
    /// JSON that does not parse as a glTF document.
    #[error("not a glTF 2.0 file: {0}")]
    NotGltf(String),
    /// A glTF document of another major version.
    #[error("glTF version {0} is not supported (2.x only)")]
    Version(String),
    /// The document breaks the glTF schema: `at` is the JSON path of the first problem.
    #[error("invalid glTF at {at}: {problem}")]
    Invalid { at: String, problem: String },
    /// A buffer whose bytes could not be had.
    #[error("buffer {index} ({source_name}) cannot be read: {reason}")]
    Buffer {
        index: usize,
        /// The buffer's URI, or "the GLB binary chunk".
        source_name: String,
        reason: String,
    },
    /// A buffer with fewer bytes than its `byteLength` declares.
    #[error("buffer {index} holds {actual} bytes but declares {declared}")]
    ShortBuffer {
        index: usize,
        declared: usize,
        actual: usize,
    },
    /// An accessor that cannot be read safely as the attribute it serves.
    #[error("{primitive}: accessor {accessor} ({role}): {reason}")]
    Accessor {
        /// Which primitive uses it, as "mesh 0 (\"Name\") primitive 1".
        primitive: String,
        accessor: usize,
        /// "POSITION", "NORMAL" or "indices".
        role: &'static str,
        reason: String,
    },
    /// A triangle corner that names a vertex the primitive does not have. The index's value is
    /// not shown: a buffer may hold any bytes, and a message must not echo them.
    #[error("{primitive}: index out of range in {place} (the primitive has {vertices} vertices)")]
    IndexOutOfRange {
        primitive: String,
        /// Where the index lies: "accessor 3 (buffer 1, offset 24)".
        place: String,
        vertices: usize,
    },
    /// A vertex position that is NaN or infinite (after the node transforms).
    #[error("{primitive}: a vertex position is not a finite number")]
    NonFinite { primitive: String },
    /// The node hierarchy loops back on itself.
    #[error("node {0} is its own ancestor")]
    NodeCycle(usize),
    /// More triangles than a world may hold, counting every node instance.
    #[error("the file instances more than {limit} triangles")]
    TooManyTriangles { limit: u64 },
    /// The primitive instances would take more memory than the bound allows (counted before
    /// any is read).
    #[error("{}", .0.figures())]
    OverBudget(crate::memory_budget::OverBudget),
    /// A node hierarchy that expands to more node instances than rastray accepts.
    #[error("the node hierarchy expands to more than {limit} node instances")]
    TooManyNodes { limit: usize },
    /// Nothing drawable was left: no scene, no mesh, or every primitive skipped.
    #[error("the file holds no triangles{}", if *skipped > 0 { format!(" that rastray can read ({skipped} primitive(s) skipped)") } else { String::new() })]
    NoTriangles { skipped: usize },
}
