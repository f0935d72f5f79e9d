//! Distance attenuation of point lights. A scene without it holds `None`: the one way to say
//! att(d) = 1, whether the file leaves `falloff` out or spells both coefficients as 0.

use serde::{Deserialize, Deserializer, Serialize};

/// att(d) = 1 / (1 + linear·d + quadratic·d²). Invariant: the coefficients are not both zero
/// (that is no falloff, `None`; see [`Falloff::new`]); their ranges are in [`super::limits`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Falloff {
    /// Linear coefficient, per world unit, ≥ 0.
    pub linear: f32,
    /// Quadratic coefficient, per square world unit, ≥ 0.
    pub quadratic: f32,
}

impl Falloff {
    /// The falloff with these coefficients; `None` when both are zero (att(d) = 1).
    pub fn new(linear: f32, quadratic: f32) -> Option<Falloff> {
        (linear != 0.0 || quadratic != 0.0).then_some(Falloff { linear, quadratic })
    }

    /// Attenuation factor at distance `d` (world units), in (0, 1].
    #[inline]
    pub fn attenuation(&self, d: f32) -> f32 {
        1.0 / (1.0 + self.linear * d + self.quadratic * d * d)
    }
}

/// The `falloff` table as a file writes it: each coefficient defaults to 0.
#[derive(Default, Deserialize)]
#[serde(deny_unknown_fields, default)]
struct FalloffTable {
    linear: f32,
    quadratic: f32,
}

/// Reads a `falloff` table into the scene's one representation (see [`Falloff::new`]).
pub(super) fn falloff_table<'de, D: Deserializer<'de>>(
    deserializer: D,
) -> Result<Option<Falloff>, D::Error> {
    let table = FalloffTable::deserialize(deserializer)?;
    Ok(Falloff::new(table.linear, table.quadratic))
}
