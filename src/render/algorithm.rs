//! The closed set of rendering algorithms the user can switch between.

use std::fmt;

/// Which of the three classic algorithms draws the image.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Hash, Default, serde::Serialize, serde::Deserialize,
)]
#[serde(rename_all = "lowercase")]
pub enum Algorithm {
    /// Z-buffer, lighting at the vertices, colour interpolated across faces.
    #[default]
    Gouraud,
    /// Z-buffer, normal interpolated across faces, lighting at every pixel.
    Phong,
    /// Backward (Whitted) ray tracing with shadows and reflections.
    Ray,
}

impl Algorithm {
    /// All three, in key order (1, 2, 3).
    pub const ALL: [Algorithm; 3] = [Algorithm::Gouraud, Algorithm::Phong, Algorithm::Ray];

    /// Short display name.
    pub fn name(self) -> &'static str {
        match self {
            Algorithm::Gouraud => "Gouraud",
            Algorithm::Phong => "Phong",
            Algorithm::Ray => "Ray",
        }
    }
}

impl fmt::Display for Algorithm {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}
