//! Preset views: the camera placed on one side of the scene's bounds, looking at their centre,
//! at the distance (or, orthographic, the height) that fits them with a small margin.
//!
//! The world is +Y up (a model's up axis is turned to +Y when it is loaded), so the presets
//! follow the up axis: `front` looks along −Z from the +Z side, `top` looks down with −Z up on
//! the screen, `iso` looks from (+1, +1, +1).

use std::fmt;

use glam::{Quat, Vec3};

use crate::scene::{Camera, Projection};

/// Room left around the fitted bounds: their extent times this.
pub const MARGIN: f32 = 1.08;

/// A side the camera looks from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum PresetView {
    Front,
    Back,
    Left,
    Right,
    Top,
    Bottom,
    Iso,
}

impl PresetView {
    /// Every preset, in the order the editor steps through them.
    pub const ALL: [PresetView; 7] = [
        PresetView::Front,
        PresetView::Right,
        PresetView::Back,
        PresetView::Left,
        PresetView::Top,
        PresetView::Bottom,
        PresetView::Iso,
    ];

    /// The spelling on the command line and in file names: `front`, `iso`.
    pub fn name(self) -> &'static str {
        match self {
            PresetView::Front => "front",
            PresetView::Back => "back",
            PresetView::Left => "left",
            PresetView::Right => "right",
            PresetView::Top => "top",
            PresetView::Bottom => "bottom",
            PresetView::Iso => "iso",
        }
    }

    /// The preset spelled `name` (any case).
    pub fn from_name(name: &str) -> Option<PresetView> {
        PresetView::ALL
            .into_iter()
            .find(|v| v.name().eq_ignore_ascii_case(name))
    }

    /// Unit direction from the target toward the camera.
    pub fn toward_camera(self) -> Vec3 {
        match self {
            PresetView::Front => Vec3::Z,
            PresetView::Back => Vec3::NEG_Z,
            PresetView::Left => Vec3::NEG_X,
            PresetView::Right => Vec3::X,
            PresetView::Top => Vec3::Y,
            PresetView::Bottom => Vec3::NEG_Y,
            PresetView::Iso => Vec3::ONE.normalize(),
        }
    }

    /// The world direction shown upward on the screen.
    pub fn screen_up(self) -> Vec3 {
        match self {
            PresetView::Top => Vec3::NEG_Z,
            PresetView::Bottom => Vec3::Z,
            _ => Vec3::Y,
        }
    }

    /// The next preset in [`PresetView::ALL`] (`step` 1) or the previous (−1), wrapping.
    pub fn step(self, step: i32) -> PresetView {
        let n = PresetView::ALL.len() as i32;
        let at = PresetView::ALL.iter().position(|&v| v == self).unwrap_or(0) as i32;
        PresetView::ALL[(at + step).rem_euclid(n) as usize]
    }
}

impl fmt::Display for PresetView {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// `camera` looking from `view`'s side, turned by `azimuth` degrees about +Y and raised by
/// `elevation` degrees, at the centre of `bounds` (min, max, world units), fitting them in an
/// image of `aspect` (width / height). Keeps the field of view and the projection; an
/// orthographic camera gets a fitting height.
pub fn place(
    camera: &Camera,
    view: PresetView,
    azimuth: f32,
    elevation: f32,
    bounds: (Vec3, Vec3),
    aspect: f32,
) -> Camera {
    let turn = Quat::from_rotation_y(azimuth.to_radians());
    let (back, up) = (turn * view.toward_camera(), turn * view.screen_up());
    let right = (-back).cross(up).normalize();
    let raise = Quat::from_axis_angle(right, -elevation.to_radians());
    let (back, up) = ((raise * back).normalize(), (raise * up).normalize());
    fit(camera, back, up, bounds, aspect)
}

/// `camera` looking along −`back` with `up` on the screen at the centre of `bounds`, at the
/// distance that fits them (perspective) or with the height that does (orthographic).
pub fn fit(camera: &Camera, back: Vec3, up: Vec3, bounds: (Vec3, Vec3), aspect: f32) -> Camera {
    let (lo, hi) = bounds;
    let centre = (lo + hi) * 0.5;
    let right = (-back).cross(up).normalize();
    let up = right.cross(-back);
    let corners = (0..8).map(|k| {
        let pick = |bit: u32, a: f32, b: f32| if k >> bit & 1 == 0 { a } else { b };
        Vec3::new(
            pick(0, lo.x, hi.x),
            pick(1, lo.y, hi.y),
            pick(2, lo.z, hi.z),
        ) - centre
    });
    let tan_v = (camera.fov.to_radians() * 0.5).tan();
    let tan_h = tan_v * aspect;
    // Perspective: the eye at distance d along `back` sees corner c when its offset across the
    // view is within tan·(d − c·back), with the margin; the least such d over the corners.
    let (mut distance, mut half_x, mut half_y, mut depth) = (0.0_f32, 0.0_f32, 0.0_f32, 0.0_f32);
    for c in corners {
        let (x, y, z) = (c.dot(right).abs(), c.dot(up).abs(), c.dot(back));
        distance = distance
            .max(z + x * MARGIN / tan_h)
            .max(z + y * MARGIN / tan_v);
        (half_x, half_y, depth) = (half_x.max(x), half_y.max(y), depth.max(z.abs()));
    }
    let extent = (hi - lo).length().max(1e-3);
    let distance = distance.max(depth + 0.05 * extent);
    let mut placed = Camera {
        position: centre + back * distance,
        target: centre,
        up,
        ..*camera
    };
    if camera.projection == Projection::Orthographic {
        // Ortho rays start on the plane through the eye: keep it outside the bounds.
        let height = (half_y.max(half_x / aspect) * 2.0 * MARGIN).max(1e-3);
        placed.height = Some(height);
        placed.position = centre + back * (depth + 0.5 * extent).max(distance);
    }
    placed
}

#[cfg(test)]
mod tests {
    use super::*;

    const CUBE: (Vec3, Vec3) = (Vec3::splat(-0.5), Vec3::splat(0.5));

    #[test]
    fn front_stands_on_plus_z_looking_along_minus_z_with_y_up() {
        let camera = place(&Camera::default(), PresetView::Front, 0.0, 0.0, CUBE, 1.0);
        let forward = (camera.target - camera.position).normalize();
        assert!(forward.distance(Vec3::NEG_Z) < 1e-6);
        assert!(camera.up.distance(Vec3::Y) < 1e-6);
        assert_eq!(camera.target, Vec3::ZERO);
    }

    #[test]
    fn top_has_minus_z_up_on_screen() {
        let camera = place(&Camera::default(), PresetView::Top, 0.0, 0.0, CUBE, 1.0);
        assert!(camera.position.normalize().distance(Vec3::Y) < 1e-6);
        assert!(camera.up.distance(Vec3::NEG_Z) < 1e-6);
    }

    #[test]
    fn azimuth_and_elevation_orbit_from_the_preset() {
        // Front turned 90° about +Y is the right view; raised 90° it is the top view.
        let right = place(&Camera::default(), PresetView::Front, 90.0, 0.0, CUBE, 1.0);
        assert!(right.position.normalize().distance(Vec3::X) < 1e-5);
        let top = place(&Camera::default(), PresetView::Front, 0.0, 90.0, CUBE, 1.0);
        assert!(top.position.normalize().distance(Vec3::Y) < 1e-5);
        assert!(top.up.distance(Vec3::NEG_Z) < 1e-5);
    }

    #[test]
    fn orthographic_fit_is_the_bounds_with_the_margin() {
        let ortho = Camera::default().to_orthographic();
        let camera = place(&ortho, PresetView::Front, 0.0, 0.0, CUBE, 2.0);
        assert!((camera.height.expect("a height") - MARGIN).abs() < 1e-5);
        // The eye plane stands outside the cube.
        assert!(camera.position.z > 0.5);
    }

    #[test]
    fn names_round_trip_and_steps_wrap() {
        for view in PresetView::ALL {
            assert_eq!(PresetView::from_name(view.name()), Some(view));
        }
        assert_eq!(PresetView::Iso.step(1), PresetView::Front);
        assert_eq!(PresetView::Front.step(-1), PresetView::Iso);
    }
}
