//! How a camera maps the world onto the image: through a point (perspective) or along parallel
//! lines (orthographic).

use serde::{Deserialize, Serialize};

use super::model::Camera;

/// The camera's projection, as the scene file names it (`projection = "orthographic"`).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Projection {
    /// Rays from the eye through each pixel; the view widens with distance by `fov`.
    #[default]
    Perspective,
    /// Parallel rays along the view direction, starting on the plane through the eye; the view
    /// is the camera's `height` tall at every distance.
    Orthographic,
}

impl Projection {
    /// Whether this is the default, which a saved scene leaves unwritten.
    pub fn is_perspective(&self) -> bool {
        *self == Projection::Perspective
    }
}

/// The orthographic height that shows what a perspective camera of vertical field of view
/// `fov_degrees` shows at distance `distance`: 2·distance·tan(fov/2), world units.
pub fn framing_height(fov_degrees: f32, distance: f32) -> f32 {
    2.0 * distance * (fov_degrees.to_radians() * 0.5).tan()
}

/// The field of view (degrees) at which a perspective camera shows `height` world units at
/// `distance`: the inverse of [`framing_height`].
pub fn framing_fov(height: f32, distance: f32) -> f32 {
    (2.0 * (0.5 * height / distance).atan()).to_degrees()
}

impl Camera {
    /// This camera made orthographic, showing at its target what it shows there now: a
    /// perspective camera's height is [`framing_height`] at the target distance.
    pub fn to_orthographic(&self) -> Camera {
        let height = match (self.projection, self.height) {
            (Projection::Orthographic, Some(height)) => height,
            _ => framing_height(self.fov, self.position.distance(self.target)),
        };
        Camera {
            projection: Projection::Orthographic,
            height: Some(height),
            ..*self
        }
    }

    /// This camera made perspective, keeping its field of view and its height for switching
    /// back; the framing at the target is kept by moving the eye along the view direction.
    pub fn to_perspective(&self) -> Camera {
        let mut camera = Camera {
            projection: Projection::Perspective,
            ..*self
        };
        if let (Projection::Orthographic, Some(height)) = (self.projection, self.height) {
            let distance = 0.5 * height / (self.fov.to_radians() * 0.5).tan();
            let back = (self.position - self.target).normalize_or(glam::Vec3::Z);
            camera.position = self.target + back * distance;
        }
        camera
    }

    /// The other projection, keeping the framing at the target.
    pub fn toggled_projection(&self) -> Camera {
        match self.projection {
            Projection::Perspective => self.to_orthographic(),
            Projection::Orthographic => self.to_perspective(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{Camera, Projection, framing_fov, framing_height};

    #[test]
    fn toggling_keeps_the_framing_at_the_target() {
        let camera = Camera::default();
        let distance = camera.position.distance(camera.target);
        let ortho = camera.to_orthographic();
        assert_eq!(ortho.projection, Projection::Orthographic);
        let height = ortho.height.expect("a height");
        assert!((height - framing_height(camera.fov, distance)).abs() < 1e-5);
        let back = ortho.to_perspective();
        assert!(back.position.distance(camera.position) < 1e-4);
        assert_eq!(back.projection, Projection::Perspective);
    }

    #[test]
    fn framing_height_and_fov_are_inverse() {
        // 90° shows twice the distance.
        assert!((framing_height(90.0, 3.0) - 6.0).abs() < 1e-5);
        assert!((framing_fov(6.0, 3.0) - 90.0).abs() < 1e-4);
    }
}
