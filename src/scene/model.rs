//! Scene-wide settings: camera, lights, ambient light, background, recursion depth.

use glam::Vec3;
use serde::{Deserialize, Serialize};

use super::falloff::{Falloff, falloff_table};
use super::object::Object;
use super::projection::Projection;
use super::vector::vec3;

/// A whole scene as stored in a `.toml` file. Invariant after [`super::validate`]: every number
/// is finite and within the range its doc states.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scene {
    /// The viewpoint.
    #[serde(default)]
    pub camera: Camera,
    /// Ambient intensity Ia in [0, 1], multiplied by each object's colour.
    #[serde(default = "default_ambient")]
    pub ambient: f32,
    /// Linear RGB returned by rays that hit nothing and drawn behind rasterized objects.
    #[serde(default = "default_background", deserialize_with = "vec3")]
    pub background: Vec3,
    /// Maximum reflection recursion depth for the ray tracer (0 = no reflections), ≤ 16.
    #[serde(default = "default_max_depth")]
    pub max_depth: u32,
    /// Distance attenuation of point lights; `None` (the key absent, or both coefficients 0)
    /// means att(d) = 1.
    #[serde(
        default,
        deserialize_with = "falloff_table",
        skip_serializing_if = "Option::is_none"
    )]
    pub falloff: Option<Falloff>,
    /// Point lights, in file order.
    #[serde(default, rename = "light", skip_serializing_if = "Vec::is_empty")]
    pub lights: Vec<Light>,
    /// Objects, in file order.
    #[serde(default, rename = "object", skip_serializing_if = "Vec::is_empty")]
    pub objects: Vec<Object>,
}

fn default_ambient() -> f32 {
    0.1
}
fn default_background() -> Vec3 {
    Vec3::new(0.05, 0.06, 0.08)
}
fn default_max_depth() -> u32 {
    4
}

impl Default for Scene {
    fn default() -> Self {
        Scene {
            camera: Camera::default(),
            ambient: default_ambient(),
            background: default_background(),
            max_depth: default_max_depth(),
            falloff: None,
            lights: Vec::new(),
            objects: Vec::new(),
        }
    }
}

impl Scene {
    /// Total triangle count is computed by the world; this counts objects and lights only.
    pub fn is_empty(&self) -> bool {
        self.objects.is_empty() && self.lights.is_empty()
    }
}

/// A pinhole camera. Right-handed world, +Y up.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Camera {
    /// Eye position in world units.
    #[serde(deserialize_with = "vec3")]
    pub position: Vec3,
    /// Point the camera looks at; must differ from `position`.
    #[serde(deserialize_with = "vec3")]
    pub target: Vec3,
    /// Approximate up direction; must not be parallel to the view direction.
    #[serde(deserialize_with = "vec3")]
    pub up: Vec3,
    /// Vertical field of view in degrees, in (0, 180); perspective only.
    pub fov: f32,
    /// Perspective (the default) or orthographic.
    #[serde(skip_serializing_if = "Projection::is_perspective")]
    pub projection: Projection,
    /// World-space height of an orthographic view, world units, > 0; an orthographic camera
    /// needs it, a perspective one keeps it for switching.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub height: Option<f32>,
}

impl Default for Camera {
    fn default() -> Self {
        Camera {
            position: Vec3::new(0.0, 2.0, 8.0),
            target: Vec3::ZERO,
            up: Vec3::Y,
            fov: 45.0,
            projection: Projection::Perspective,
            height: None,
        }
    }
}

/// A point light.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Light {
    /// Optional label shown in the editor.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// Position in world units.
    #[serde(deserialize_with = "vec3")]
    pub position: Vec3,
    /// Intensity I ≥ 0 (1 is a full-strength light).
    #[serde(default = "default_intensity")]
    pub intensity: f32,
    /// Linear RGB colour of the light, each channel in [0, 1].
    #[serde(default = "default_light_color", deserialize_with = "vec3")]
    pub color: Vec3,
}

fn default_intensity() -> f32 {
    1.0
}
fn default_light_color() -> Vec3 {
    Vec3::ONE
}

impl Default for Light {
    fn default() -> Self {
        Light {
            name: None,
            position: Vec3::new(4.0, 6.0, 4.0),
            intensity: default_intensity(),
            color: default_light_color(),
        }
    }
}
