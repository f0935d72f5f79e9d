//! Where in a scene file a value lives, such as `object[2].size`: the address validation reports
//! and the file reader turns into a line.

use std::fmt;

/// Where in a scene file a value lives, such as `object[2].size`.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct FieldPath(pub Vec<PathSegment>);

/// One step of a [`FieldPath`].
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum PathSegment {
    Key(String),
    Index(usize),
}

impl FieldPath {
    /// This path followed by table key `k`.
    pub fn key(mut self, k: &str) -> FieldPath {
        self.0.push(PathSegment::Key(k.to_string()));
        self
    }
    /// This path followed by array index `i`.
    pub fn index(mut self, i: usize) -> FieldPath {
        self.0.push(PathSegment::Index(i));
        self
    }
}

impl fmt::Display for FieldPath {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (n, seg) in self.0.iter().enumerate() {
            match seg {
                PathSegment::Key(k) if n == 0 => write!(f, "{k}")?,
                PathSegment::Key(k) => write!(f, ".{k}")?,
                PathSegment::Index(i) => write!(f, "[{i}]")?,
            }
        }
        Ok(())
    }
}
