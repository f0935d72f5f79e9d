//! Experiment 3, who wins where: the fastest algorithm over image size × face count.
//!
//! The study's two experiments use one image size, so they cannot show what the editor's
//! preview shows: at a small image the ray tracer, its BVH kept from frame to frame, can beat
//! the Z-buffer, whose cost grows with the triangles whatever the image. This sweep renders the
//! experiment 2 scene (constant total face area, as a fraction of the image) at every pair of
//! size and face count, and counts the ray tracer's BVH build two ways:
//! - **kept**: built once per scene, as the editor keeps it (the render's time less its
//!   preparation);
//! - **per frame**: built for every render, as a one-off `rastray render` does.

use std::path::Path;
use std::sync::Arc;
use std::time::Duration;

use indicatif::ProgressBar;

use super::area::face_count;
use super::error::BenchError;
use super::experiments::faces_point;
use super::runner::{summarize, time_render};
use crate::render::{Algorithm, Frame, RenderOptions, Size};
use crate::world::World;

/// Image sizes of the full sweep, from the editor's preview up to 4K.
pub const SIZES: [Size; 5] = [
    Size::new(160, 96),
    Size::new(480, 270),
    Size::new(960, 540),
    Size::new(1920, 1080),
    Size::new(3840, 2160),
];
/// Image sizes in quick mode.
pub const SIZES_QUICK: [Size; 2] = [Size::new(160, 96), Size::new(640, 360)];
/// Experiment 2 steps (icosahedron subdivisions, box and prism segments) of the full sweep:
/// 1,600 to 1.39 million faces, four times more at each step.
pub const STEPS: [(u32, u32); 6] = [(3, 4), (4, 8), (5, 16), (6, 32), (7, 64), (8, 64)];
/// Steps in quick mode.
pub const STEPS_QUICK: [(u32, u32); 2] = [(3, 4), (5, 16)];

/// How the ray tracer's BVH build is counted.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BvhCount {
    /// Built once per scene and kept, as in the editor.
    Kept,
    /// Built for every frame, as in a one-off render.
    PerFrame,
}

impl BvhCount {
    /// Both, kept first.
    pub const ALL: [BvhCount; 2] = [BvhCount::Kept, BvhCount::PerFrame];

    /// A short description for titles.
    pub fn title(self) -> &'static str {
        match self {
            BvhCount::Kept => "BVH built once per scene (the editor)",
            BvhCount::PerFrame => "BVH built for every frame (a one-off render)",
        }
    }
}

/// The three algorithms' median times on one scene at one size.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cell {
    pub size: Size,
    /// Triangles in the scene.
    pub faces: usize,
    /// Median render time of the Z-buffer with Gouraud shading, ms.
    pub gouraud_ms: f64,
    /// Median render time of the Z-buffer with Phong shading, ms.
    pub phong_ms: f64,
    /// Median time of the ray tracer without its BVH build, ms.
    pub ray_trace_ms: f64,
    /// Median time of the ray tracer's BVH build, ms.
    pub ray_build_ms: f64,
}

impl Cell {
    /// The ray tracer's time with its build counted as `bvh` says, ms.
    pub fn ray_ms(&self, bvh: BvhCount) -> f64 {
        match bvh {
            BvhCount::Kept => self.ray_trace_ms,
            BvhCount::PerFrame => self.ray_trace_ms + self.ray_build_ms,
        }
    }

    /// `algorithm`'s time, ms, the BVH counted as `bvh` says.
    pub fn time_ms(&self, algorithm: Algorithm, bvh: BvhCount) -> f64 {
        match algorithm {
            Algorithm::Gouraud => self.gouraud_ms,
            Algorithm::Phong => self.phong_ms,
            Algorithm::Ray => self.ray_ms(bvh),
        }
    }

    /// The fastest algorithm, the BVH counted as `bvh` says; the earlier of
    /// [`Algorithm::ALL`] on a tie.
    pub fn winner(&self, bvh: BvhCount) -> Algorithm {
        Algorithm::ALL
            .into_iter()
            .min_by(|&a, &b| self.time_ms(a, bvh).total_cmp(&self.time_ms(b, bvh)))
            .expect("three algorithms")
    }
}

/// Runs the sweep: `reps` timed renders per algorithm and cell, the three taking turns, with one
/// line per cell on standard output and progress on `bar` (which may be hidden).
pub fn run_crossover(quick: bool, reps: u32, bar: &ProgressBar) -> Result<Vec<Cell>, BenchError> {
    let (sizes, steps): (&[Size], &[(u32, u32)]) = if quick {
        (&SIZES_QUICK, &STEPS_QUICK)
    } else {
        (&SIZES, &STEPS)
    };
    let reps = reps.max(1);
    bar.set_length((sizes.len() * steps.len() * Algorithm::ALL.len()) as u64 * reps as u64);
    // The scale that gives the constant area fraction does not depend on the image size: the
    // scenes are made once, at the first size, and drawn at every size.
    bar.set_message("experiment 3: preparing scenes");
    let worlds = steps
        .iter()
        .map(|&(k, s)| {
            let point = faces_point(k, s, sizes[0]);
            let world = Arc::new(World::build(&point.scene, Path::new("."))?);
            Ok((point.scene.camera, world))
        })
        .collect::<Result<Vec<_>, BenchError>>()?;
    let mut cells = Vec::new();
    for &size in sizes {
        // Each algorithm renders into its own frame, kept across the scenes of one size.
        let mut frames = vec![Frame::default(); Algorithm::ALL.len()];
        for (camera, world) in &worlds {
            let faces = face_count(world);
            bar.set_message(format!("experiment 3: {size}, {faces} faces"));
            let mut times: Vec<Vec<Duration>> = vec![Vec::new(); Algorithm::ALL.len() + 1];
            for _ in 0..reps {
                for (i, algorithm) in Algorithm::ALL.into_iter().enumerate() {
                    let options = RenderOptions::new(algorithm, size.width, size.height);
                    let stats = time_render(world, camera, &options, &mut frames[i])?;
                    match algorithm {
                        // A renderer of its own builds the BVH in its preparation.
                        Algorithm::Ray => {
                            times[i].push(stats.total() - stats.prepare);
                            times[i + 1].push(stats.prepare);
                        }
                        _ => times[i].push(stats.total()),
                    }
                    bar.inc(1);
                }
            }
            let median = |i: usize| summarize(&times[i]).0;
            let cell = Cell {
                size,
                faces,
                gouraud_ms: median(0),
                phong_ms: median(1),
                ray_trace_ms: median(2),
                ray_build_ms: median(3),
            };
            bar.suspend(|| {
                println!(
                    "cross {:>9} {:>8} faces: Gouraud {:.2} ms  Phong {:.2} ms  Ray {:.2} ms + build {:.2} ms",
                    size.to_string(),
                    faces,
                    cell.gouraud_ms,
                    cell.phong_ms,
                    cell.ray_trace_ms,
                    cell.ray_build_ms
                )
            });
            cells.push(cell);
        }
    }
    Ok(cells)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cell(gouraud_ms: f64, phong_ms: f64, ray_trace_ms: f64, ray_build_ms: f64) -> Cell {
        Cell {
            size: Size::new(160, 96),
            faces: 1000,
            gouraud_ms,
            phong_ms,
            ray_trace_ms,
            ray_build_ms,
        }
    }

    #[test]
    fn the_build_decides_only_when_it_is_counted() {
        let c = cell(4.0, 5.0, 3.0, 2.0);
        assert_eq!(c.winner(BvhCount::Kept), Algorithm::Ray);
        assert_eq!(c.winner(BvhCount::PerFrame), Algorithm::Gouraud);
        assert_eq!(c.ray_ms(BvhCount::PerFrame), 5.0);
    }

    #[test]
    fn a_tie_goes_to_the_earlier_algorithm() {
        assert_eq!(
            cell(2.0, 2.0, 9.0, 0.0).winner(BvhCount::Kept),
            Algorithm::Gouraud
        );
        assert_eq!(
            cell(3.0, 2.0, 2.0, 0.0).winner(BvhCount::Kept),
            Algorithm::Phong
        );
    }

    #[test]
    fn the_full_sweep_spans_the_preview_to_4k_and_1k_to_a_million_faces() {
        use crate::bench::experiments::faces_scene_face_count;
        let faces: Vec<usize> = STEPS
            .iter()
            .map(|&(k, s)| faces_scene_face_count(k, s))
            .collect();
        assert!(faces[0] >= 1000 && faces[0] < 2000, "{faces:?}");
        assert!(*faces.last().unwrap() >= 1_300_000, "{faces:?}");
        assert!(faces.windows(2).all(|w| w[1] > w[0]), "{faces:?}");
        assert_eq!(SIZES[0], Size::new(160, 96));
        assert_eq!(SIZES[4], Size::new(3840, 2160));
    }
}
