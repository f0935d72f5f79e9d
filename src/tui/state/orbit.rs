//! Camera moves for the editor: orbit around the target, pan, zoom. World +Y is up.

use glam::Vec3;

use crate::render::View;
use crate::scene::{Camera, Projection};

/// Steepest pitch allowed, degrees: the view never lines up with the up vector.
const MAX_PITCH: f32 = 89.0;
/// Closest the camera may come to its target, world units.
const MIN_DISTANCE: f32 = 0.05;

/// `camera` turned about its target by `yaw` degrees around +Y and `pitch` degrees upward.
pub fn orbit(camera: &Camera, yaw: f32, pitch: f32) -> Camera {
    let offset = camera.position - camera.target;
    let r = offset.length().max(MIN_DISTANCE);
    // Spherical angles of the eye seen from the target: yaw from +Z toward +X, pitch above XZ.
    let old_yaw = offset.x.atan2(offset.z);
    let old_pitch = (offset.y / r).clamp(-1.0, 1.0).asin();
    let yaw = old_yaw + yaw.to_radians();
    let pitch =
        (old_pitch + pitch.to_radians()).clamp(-MAX_PITCH.to_radians(), MAX_PITCH.to_radians());
    let dir = Vec3::new(
        pitch.cos() * yaw.sin(),
        pitch.sin(),
        pitch.cos() * yaw.cos(),
    );
    Camera {
        position: camera.target + dir * r,
        up: Vec3::Y,
        ..*camera
    }
}

/// `camera` and its target moved by `right` and `up` times the viewing distance.
pub fn pan(camera: &Camera, right: f32, up: f32) -> Camera {
    let view = View::new(camera, 1, 1);
    let r = (camera.position - camera.target).length();
    let shift = (view.right * right + view.up * up) * r;
    Camera {
        position: camera.position + shift,
        target: camera.target + shift,
        ..*camera
    }
}

/// `camera` with its distance to the target multiplied by `factor` (> 0), and an
/// orthographic camera's height with it (its distance alone changes nothing on screen).
pub fn zoom(camera: &Camera, factor: f32) -> Camera {
    let offset = camera.position - camera.target;
    let r = (offset.length() * factor).max(MIN_DISTANCE);
    let height = match camera.projection {
        Projection::Orthographic => camera.height.map(|h| h * factor),
        Projection::Perspective => camera.height,
    };
    Camera {
        position: camera.target + offset.normalize_or(Vec3::Z) * r,
        height,
        ..*camera
    }
}
