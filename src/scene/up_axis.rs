//! Which axis of a model file points up. rastray's world is +Y up; CAD files (and Blender's
//! own space) are usually +Z up. A mesh object turns its file so that the axis named here
//! becomes +Y, before its own rotation.

use std::fmt;

use glam::Quat;
use serde::{Deserialize, Serialize};

/// The axis of a model file that points up; `y` (no turn) by default.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize)]
pub enum UpAxis {
    #[serde(rename = "x")]
    X,
    #[default]
    #[serde(rename = "y")]
    Y,
    #[serde(rename = "z")]
    Z,
    #[serde(rename = "-x")]
    NegX,
    #[serde(rename = "-y")]
    NegY,
    #[serde(rename = "-z")]
    NegZ,
}

impl UpAxis {
    /// Every axis, in the order menus and messages list them.
    pub const ALL: [UpAxis; 6] = [
        UpAxis::X,
        UpAxis::Y,
        UpAxis::Z,
        UpAxis::NegX,
        UpAxis::NegY,
        UpAxis::NegZ,
    ];

    /// The spelling in files and on the command line: `x`, `-z`.
    pub fn name(self) -> &'static str {
        match self {
            UpAxis::X => "x",
            UpAxis::Y => "y",
            UpAxis::Z => "z",
            UpAxis::NegX => "-x",
            UpAxis::NegY => "-y",
            UpAxis::NegZ => "-z",
        }
    }

    /// The axis spelled `name` (any case); `None` for anything else.
    pub fn from_name(name: &str) -> Option<UpAxis> {
        UpAxis::ALL
            .into_iter()
            .find(|a| a.name().eq_ignore_ascii_case(name))
    }

    /// The rotation that takes this axis to +Y: a quarter turn about X for ±Z (so that a Z-up
    /// file's −Y, its front, faces +Z, toward the default camera), about Z for ±X, a half
    /// turn about X for −Y.
    pub fn rotation(self) -> Quat {
        use std::f32::consts::{FRAC_PI_2, PI};
        match self {
            UpAxis::Y => Quat::IDENTITY,
            UpAxis::Z => Quat::from_rotation_x(-FRAC_PI_2),
            UpAxis::NegZ => Quat::from_rotation_x(FRAC_PI_2),
            UpAxis::X => Quat::from_rotation_z(FRAC_PI_2),
            UpAxis::NegX => Quat::from_rotation_z(-FRAC_PI_2),
            UpAxis::NegY => Quat::from_rotation_x(PI),
        }
    }
}

impl fmt::Display for UpAxis {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::*;

    #[test]
    fn each_axis_is_turned_to_plus_y() {
        let vectors = [Vec3::X, Vec3::Y, Vec3::Z, -Vec3::X, -Vec3::Y, -Vec3::Z];
        for (axis, v) in UpAxis::ALL.into_iter().zip(vectors) {
            let turned = axis.rotation() * v;
            assert!(turned.distance(Vec3::Y) < 1e-6, "{axis}: {turned}");
            assert_eq!(UpAxis::from_name(axis.name()), Some(axis));
        }
        // A Z-up file's front (−Y) faces the default camera (+Z).
        assert!((UpAxis::Z.rotation() * -Vec3::Y).distance(Vec3::Z) < 1e-6);
        assert_eq!(UpAxis::from_name("Z"), Some(UpAxis::Z));
        assert_eq!(UpAxis::from_name("w"), None);
    }
}
