//! PLY's scalar type names, with their sizes in bytes, for tests that write PLY files.

/// Every PLY scalar type name and its size in bytes.
pub const TYPES: [(&str, usize); 8] = [
    ("char", 1),
    ("uchar", 1),
    ("short", 2),
    ("ushort", 2),
    ("int", 4),
    ("uint", 4),
    ("float", 4),
    ("double", 8),
];
