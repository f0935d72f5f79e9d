//! glTF's `KHR_texture_transform`: texture coordinates offset, rotated and scaled before the
//! texture is read. Affine, so a loader applies it to the corner coordinates once, and the
//! interpolated coordinates are transformed alike.

use glam::{Affine2, Mat2, Vec2};

/// `offset`, `rotation` (radians, counter-clockwise in the image as seen with v downward, as
/// the extension states) and `scale` of texture coordinates.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UvTransform {
    pub offset: Vec2,
    pub rotation: f32,
    pub scale: Vec2,
}

impl Default for UvTransform {
    fn default() -> UvTransform {
        UvTransform {
            offset: Vec2::ZERO,
            rotation: 0.0,
            scale: Vec2::ONE,
        }
    }
}

impl UvTransform {
    /// The extension's matrix: translation × rotation × scale, with its rotation
    /// `[cos, sin; −sin, cos]` (rows).
    pub fn matrix(&self) -> Affine2 {
        let (sin, cos) = self.rotation.sin_cos();
        let rotation = Mat2::from_cols(Vec2::new(cos, -sin), Vec2::new(sin, cos));
        Affine2::from_mat2_translation(rotation * Mat2::from_diagonal(self.scale), self.offset)
    }

    /// `uv` transformed.
    pub fn apply(&self, uv: Vec2) -> Vec2 {
        self.matrix().transform_point2(uv)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_extension_example_rotates_a_quarter_turn() {
        // Offset, then rotate, then scale, as the specification's example orders them.
        let t = UvTransform {
            offset: Vec2::new(0.5, 0.0),
            rotation: std::f32::consts::FRAC_PI_2,
            scale: Vec2::new(2.0, 1.0),
        };
        // (1, 0) scaled to (2, 0), rotated to (0·2, −1·2) = (0, −2), offset to (0.5, −2).
        let p = t.apply(Vec2::new(1.0, 0.0));
        assert!((p - Vec2::new(0.5, -2.0)).length() < 1e-6, "{p}");
        assert_eq!(
            UvTransform::default().apply(Vec2::new(0.3, 0.7)),
            Vec2::new(0.3, 0.7)
        );
    }
}
