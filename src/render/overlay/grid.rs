//! The ground grid: lines of a round spacing on the plane under the scene.

use glam::Vec3;

use super::canvas::Canvas;
use super::colors;
use crate::world::World;

/// Grid cells across the scene's larger horizontal side, about.
const CELLS_ACROSS: f32 = 5.0;

/// Line width, output pixels.
const WIDTH: f32 = 1.0;

/// A square grid on the plane y = `level`, from `min` to `max` in x and z.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Grid {
    /// Distance between lines, world units: 1, 2 or 5 times a power of ten.
    pub spacing: f32,
    /// Height of the plane, world units: the bottom of the scene's bounds.
    pub level: f32,
    /// Smallest x and z of the grid, multiples of `spacing`.
    pub min: (f32, f32),
    /// Largest x and z of the grid, multiples of `spacing`.
    pub max: (f32, f32),
}

/// The grid under `world`: its spacing gives about five cells across the scene, and it reaches
/// half the scene's size beyond it on every side. `None` for an empty world.
pub fn ground_grid(world: &World) -> Option<Grid> {
    let (lo, hi) = world.bounds()?;
    let span = (hi.x - lo.x).max(hi.z - lo.z).max(hi.y - lo.y);
    let spacing = round_step(if span > 0.0 { span } else { 1.0 } / CELLS_ACROSS);
    let snap_down = |v: f32| (v / spacing).floor() * spacing;
    let snap_up = |v: f32| (v / spacing).ceil() * spacing;
    let margin = 0.5 * span;
    Some(Grid {
        spacing,
        level: lo.y,
        min: (snap_down(lo.x - margin), snap_down(lo.z - margin)),
        max: (snap_up(hi.x + margin), snap_up(hi.z + margin)),
    })
}

/// The smallest of 1, 2 and 5 times a power of ten that is at least `step` (> 0).
fn round_step(step: f32) -> f32 {
    // In f64 and by an integer power, so that 0.2 is the f32 nearest 0.2 and prints so.
    let exponent = (step as f64).log10().floor() as i32;
    let power = 10f64.powi(exponent);
    [1.0, 2.0, 5.0, 10.0]
        .into_iter()
        .map(|m| m * power)
        .find(|&s| s >= step as f64 * (1.0 - 1e-6))
        .unwrap_or(10.0 * power) as f32
}

impl Grid {
    /// Draws the grid's lines, hidden where a surface is in front of them.
    pub fn draw(&self, canvas: &mut Canvas) {
        let lines = |from: f32, to: f32| {
            let count = ((to - from) / self.spacing).round() as i32;
            (0..=count).map(move |k| from + k as f32 * self.spacing)
        };
        let ((x0, z0), (x1, z1)) = (self.min, self.max);
        for x in lines(x0, x1) {
            let (a, b) = (Vec3::new(x, self.level, z0), Vec3::new(x, self.level, z1));
            canvas.segment(a, b, WIDTH, colors::GRID, true);
        }
        for z in lines(z0, z1) {
            let (a, b) = (Vec3::new(x0, self.level, z), Vec3::new(x1, self.level, z));
            canvas.segment(a, b, WIDTH, colors::GRID, true);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::round_step;

    #[test]
    fn steps_round_up_to_one_two_or_five_times_a_power_of_ten() {
        for (step, round) in [(0.4, 0.5), (1.0, 1.0), (1.3, 2.0), (3.0, 5.0), (7.0, 10.0)] {
            assert!((round_step(step) - round).abs() < 1e-5, "{step}");
        }
        assert!((round_step(0.013) - 0.02).abs() < 1e-7);
    }
}
