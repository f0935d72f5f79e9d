//! Surface material: the coefficients of the Phong lighting formula plus mirror reflection.

use glam::Vec3;
use serde::{Deserialize, Serialize};

/// How a surface answers light. Colour is linear RGB in [0, 1]; coefficients are in [0, 1]
/// except `shininess`, the Phong exponent p ≥ 0.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Material {
    /// Linear RGB albedo, each channel in [0, 1].
    #[serde(deserialize_with = "super::vector::vec3")]
    pub color: Vec3,
    /// Diffuse coefficient Kd in [0, 1].
    pub diffuse: f32,
    /// Specular coefficient Ks in [0, 1].
    pub specular: f32,
    /// Phong exponent p, ≥ 0 (larger is a tighter highlight).
    pub shininess: f32,
    /// Mirror reflection coefficient Kr in [0, 1]; only the ray tracer shows it.
    pub reflection: f32,
}

impl Default for Material {
    fn default() -> Self {
        Material {
            color: Vec3::splat(0.8),
            diffuse: 0.8,
            specular: 0.3,
            shininess: 32.0,
            reflection: 0.0,
        }
    }
}
