//! Runs the sweeps: builds each point's world (not timed), records its face count and area, then
//! times a render `reps` times for each algorithm, the three taking turns, and keeps the median,
//! minimum and maximum.
//!
//! Only the render is timed (its [`RenderStats::total`]), into a frame each algorithm keeps from
//! render to render. Each timed render has a renderer of its own, as a one-off render does, so
//! for the ray tracer it includes building its BVH; for the Z-buffer it includes the vertex
//! stage, rasterization and shading. Tessellating the scene into a world happens before and is
//! not timed.

use std::path::Path;
use std::sync::Arc;
use std::time::Duration;

use indicatif::{ProgressBar, ProgressStyle};

use super::area::{face_count, total_face_area};
use super::error::BenchError;
use super::experiments::{Experiment, Point, points};
use super::format::number;
use super::measurement::{BenchConfig, Measurement};
use crate::render::{
    Algorithm, Frame, Progress, RenderError, RenderOptions, RenderStats, Renderer, View,
};
use crate::scene::Camera;
use crate::world::World;

/// Median, minimum and maximum of `samples` in milliseconds; the median of an even count is the
/// mean of the two middle values. `samples` must not be empty.
pub fn summarize(samples: &[Duration]) -> (f64, f64, f64) {
    let mut ms: Vec<f64> = samples.iter().map(|d| d.as_secs_f64() * 1e3).collect();
    ms.sort_by(f64::total_cmp);
    let n = ms.len();
    let median = if n % 2 == 1 {
        ms[n / 2]
    } else {
        0.5 * (ms[n / 2 - 1] + ms[n / 2])
    };
    (median, ms[0], ms[n - 1])
}

/// One render of `world` seen by `camera` with `options`, by a renderer of its own (so the ray
/// tracer builds its BVH, as in a one-off render), into `frame`, whose buffer is reused from
/// the previous render of the same size: the time is the render's, not that of faulting in a
/// fresh image (about 8 ms for 1920×1080 on a virtual machine).
pub fn time_render(
    world: &Arc<World>,
    camera: &Camera,
    options: &RenderOptions,
    frame: &mut Frame,
) -> Result<RenderStats, RenderError> {
    let stats = Renderer::new(*options).render(world, camera, &Progress::new(), frame)?;
    std::hint::black_box(&frame.pixels);
    Ok(stats)
}

/// Runs both experiments for the three algorithms, reporting on `bar` (which may be hidden) and
/// printing one line per point to standard output.
pub fn run(config: &BenchConfig, bar: &ProgressBar) -> Result<Vec<Measurement>, BenchError> {
    bar.set_message("preparing scenes");
    let sweeps: Vec<Point> = Experiment::ALL
        .into_iter()
        .flat_map(|e| points(e, config.size, config.quick))
        .collect();
    let reps = config.reps.max(1);
    bar.set_length((sweeps.len() * Algorithm::ALL.len()) as u64 * reps as u64);
    bar.set_style(
        ProgressStyle::with_template("{msg:32} [{bar:40}] {pos}/{len} renders ({elapsed})")
            .expect("a valid template")
            .progress_chars("=> "),
    );
    let mut results = Vec::new();
    // Each algorithm renders into its own frame, kept from point to point.
    let mut frames = vec![Frame::default(); Algorithm::ALL.len()];
    for point in &sweeps {
        bar.set_message(format!("{} {}", point.experiment, point.label));
        let world = Arc::new(World::build(&point.scene, Path::new("."))?);
        let faces = face_count(&world);
        let view = View::new(&point.scene.camera, config.size.width, config.size.height);
        let area_px = total_face_area(&world, &view);
        let mut line = format!(
            "{:5} {:18} {:>8} faces {:>11.0} px ({:.3} Mpx):",
            point.experiment.name(),
            point.label,
            faces,
            area_px,
            area_px / 1e6
        );
        // Repetitions run the three algorithms in turn, so that a change in the machine's load
        // during the point weighs on all three alike.
        let mut times = vec![Vec::new(); Algorithm::ALL.len()];
        for _ in 0..reps {
            for ((algorithm, samples), frame) in
                Algorithm::ALL.into_iter().zip(&mut times).zip(&mut frames)
            {
                let options = RenderOptions::new(algorithm, config.size.width, config.size.height);
                let stats = time_render(&world, &point.scene.camera, &options, frame)?;
                samples.push(stats.total());
                bar.inc(1);
            }
        }
        for (algorithm, samples) in Algorithm::ALL.into_iter().zip(&times) {
            let (median_ms, min_ms, max_ms) = summarize(samples);
            line.push_str(&format!(" {algorithm} {} ms", number(median_ms)));
            results.push(Measurement {
                experiment: point.experiment,
                algorithm,
                faces,
                area_px,
                median_ms,
                min_ms,
                max_ms,
            });
        }
        bar.suspend(|| println!("{line}"));
    }
    bar.finish_and_clear();
    Ok(results)
}
