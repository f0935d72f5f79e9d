//! The closed set of display modes: how a render shows the surfaces it finds.

use std::fmt;
use std::str::FromStr;

/// How the surfaces are shown. `Shaded` is the lit image each algorithm draws; the others are
/// worked out from the surface hit at each sample (object, triangle, barycentrics), which the
/// three algorithms find the same way (`render::surface_hit`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum DisplayMode {
    /// The algorithm's lit image (today's render, unchanged).
    #[default]
    Shaded,
    /// The lit image with the triangle edges drawn over it.
    Wire,
    /// Flat white faces with their visible edges.
    HiddenLine,
    /// The world-space unit normal n as the 8-bit colour (n + 1)/2, no lighting.
    Normals,
    /// Depth along the view: the nearest point of the scene's bounds white, the farthest black.
    Depth,
    /// A checker over the texture coordinates (grey where a model has none).
    Uv,
}

impl DisplayMode {
    /// All six, in the order the editor cycles them.
    pub const ALL: [DisplayMode; 6] = [
        DisplayMode::Shaded,
        DisplayMode::Wire,
        DisplayMode::HiddenLine,
        DisplayMode::Normals,
        DisplayMode::Depth,
        DisplayMode::Uv,
    ];

    /// The name the command line and the status bar use.
    pub fn name(self) -> &'static str {
        match self {
            DisplayMode::Shaded => "shaded",
            DisplayMode::Wire => "wire",
            DisplayMode::HiddenLine => "hidden-line",
            DisplayMode::Normals => "normals",
            DisplayMode::Depth => "depth",
            DisplayMode::Uv => "uv",
        }
    }

    /// The mode `steps` places on in [`DisplayMode::ALL`], wrapping around (negative: back).
    pub fn cycled(self, steps: i32) -> DisplayMode {
        let here = DisplayMode::ALL
            .iter()
            .position(|&m| m == self)
            .unwrap_or(0) as i32;
        let count = DisplayMode::ALL.len() as i32;
        DisplayMode::ALL[(here + steps).rem_euclid(count) as usize]
    }

    /// Whether the mode draws the triangle edges.
    pub fn has_edges(self) -> bool {
        matches!(self, DisplayMode::Wire | DisplayMode::HiddenLine)
    }
}

impl fmt::Display for DisplayMode {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A name that is not one of the modes.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("`{0}` is not a display mode: use shaded, wire, hidden-line, normals, depth or uv")]
pub struct UnknownMode(pub String);

impl FromStr for DisplayMode {
    type Err = UnknownMode;

    fn from_str(s: &str) -> Result<DisplayMode, UnknownMode> {
        DisplayMode::ALL
            .into_iter()
            .find(|m| m.name() == s.trim())
            .ok_or_else(|| UnknownMode(s.to_string()))
    }
}

#[cfg(test)]
mod tests {
    use super::DisplayMode;

    #[test]
    fn names_read_back_and_cycling_wraps_both_ways() {
        for mode in DisplayMode::ALL {
            assert_eq!(mode.name().parse::<DisplayMode>(), Ok(mode));
        }
        assert!("wireframe".parse::<DisplayMode>().is_err());
        assert_eq!(DisplayMode::Shaded.cycled(1), DisplayMode::Wire);
        assert_eq!(DisplayMode::Shaded.cycled(-1), DisplayMode::Uv);
        assert_eq!(DisplayMode::Uv.cycled(1), DisplayMode::Shaded);
    }
}
