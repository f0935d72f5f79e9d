//! Three-component vectors as a scene file writes them, `[x, y, z]`: exactly three numbers.
//! glam's own reader takes the first three elements of a longer array and drops the rest
//! without a word; these readers refuse it, naming the length.

use std::fmt;

use glam::Vec3;
use serde::Deserializer;
use serde::de::{Error, IgnoredAny, SeqAccess, Visitor};

/// Reads `[x, y, z]`, refusing an array of any other length.
pub fn vec3<'de, D: Deserializer<'de>>(deserializer: D) -> Result<Vec3, D::Error> {
    deserializer.deserialize_seq(Vec3Visitor)
}

/// Reads an optional `[x, y, z]` (with `#[serde(default)]`, an absent key is `None`).
pub fn optional_vec3<'de, D: Deserializer<'de>>(deserializer: D) -> Result<Option<Vec3>, D::Error> {
    vec3(deserializer).map(Some)
}

struct Vec3Visitor;

impl<'de> Visitor<'de> for Vec3Visitor {
    type Value = Vec3;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("an array of 3 numbers [x, y, z]")
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Vec3, A::Error> {
        let mut xyz = [0.0f32; 3];
        for (i, slot) in xyz.iter_mut().enumerate() {
            *slot = seq
                .next_element()?
                .ok_or_else(|| A::Error::invalid_length(i, &self))?;
        }
        let mut length = 3;
        while seq.next_element::<IgnoredAny>()?.is_some() {
            length += 1;
        }
        if length != 3 {
            return Err(A::Error::invalid_length(length, &self));
        }
        Ok(Vec3::from_array(xyz))
    }
}
