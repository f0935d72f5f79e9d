//! Turntables: the camera orbits its target through a full turn and every view becomes a
//! frame of an animation.
//!
//! Frames render in parallel, a batch at a time, each by its own [`Renderer`] (which keeps the
//! world prepared from one frame to the next), and are made ready for the encoder on the same
//! threads; one writer thread writes them in order while the next batch renders. Memory stays
//! bounded whatever the length: a batch of frames, one fewer ready frames waiting, and the one
//! being written. The batch holds as many frames as the memory bound leaves room for beside the
//! world ([`frames_in_flight`]), one at least and one a render thread at most.

use std::f32::consts::TAU;
use std::io::BufWriter;
use std::path::Path;
use std::sync::Arc;
use std::sync::mpsc::sync_channel;
use std::time::{Duration, Instant};

use glam::{Quat, Vec3};
use rayon::prelude::*;

use super::animation::{Animation, ReadyFrame};
use super::destination::{Destination, Sink};
use super::error::ExportError;
use super::format::{AnimationFormat, PngDepth};
use crate::memory_budget::{Estimate, frames_in_flight};
use crate::render::{Frame, Progress, RenderError, RenderOptions, Renderer};
use crate::scene::Camera;
use crate::world::World;

/// Most frames a turntable may have.
pub const MAX_FRAMES: u32 = 3600;
/// Highest frame rate, frames per second: GIF delays are whole hundredths of a second, and
/// viewers slow down anything shorter than two.
pub const MAX_FPS: u32 = 50;
/// The frame rate unless asked otherwise, frames per second.
pub const DEFAULT_FPS: u32 = 25;

/// A full turn of the camera about the axis through its target along its up vector:
/// `frames` views at equal angles, right-handed about the up vector (counter-clockwise seen
/// from above), played at `fps`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Turntable {
    /// Views in the turn, 1..=[`MAX_FRAMES`]; the first is the camera itself.
    pub frames: u32,
    /// Frames per second, 1..=[`MAX_FPS`].
    pub fps: u32,
}

/// A turntable's frame count or rate out of range.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum TurntableError {
    #[error("a turntable has 1 to {MAX_FRAMES} frames, not {0}")]
    Frames(u32),
    #[error("a turntable plays at 1 to {MAX_FPS} frames per second, not {0}")]
    Fps(u32),
}

/// What a turntable render did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TurntableStats {
    pub frames: u32,
    /// Triangles in the world.
    pub triangles: usize,
    /// Wall-clock time from the first render to the file written.
    pub elapsed: Duration,
}

impl Turntable {
    /// `frames` views at the default rate.
    pub fn new(frames: u32) -> Turntable {
        Turntable {
            frames,
            fps: DEFAULT_FPS,
        }
    }

    /// Checks the frame count and rate.
    pub fn check(&self) -> Result<(), TurntableError> {
        if !(1..=MAX_FRAMES).contains(&self.frames) {
            return Err(TurntableError::Frames(self.frames));
        }
        if !(1..=MAX_FPS).contains(&self.fps) {
            return Err(TurntableError::Fps(self.fps));
        }
        Ok(())
    }

    /// The most bytes the turntable's file can take, `width`×`height` pixels a frame in `format`
    /// with or without `alpha`: every frame's pixels uncompressed (GIF one byte a pixel, APNG
    /// three or four channels of one or two bytes), which compression only lowers.
    pub fn largest_size(
        &self,
        width: u32,
        height: u32,
        alpha: bool,
        format: AnimationFormat,
    ) -> u64 {
        let bytes_per_pixel = match format {
            AnimationFormat::Gif => 1,
            AnimationFormat::Apng(depth) => {
                let channels = if alpha { 4 } else { 3 };
                let bytes = if depth == PngDepth::Sixteen { 2 } else { 1 };
                channels * bytes
            }
        };
        u64::from(self.frames) * u64::from(width) * u64::from(height) * bytes_per_pixel
    }

    /// The camera of frame `k`: `camera` turned about its target by k/frames of a full turn,
    /// about its up vector; the target, up vector and field of view stay.
    pub fn camera(&self, camera: &Camera, k: u32) -> Camera {
        let angle = TAU * (k % self.frames) as f32 / self.frames as f32;
        let turn = Quat::from_axis_angle(camera.up.normalize_or(Vec3::Y), angle);
        Camera {
            position: camera.target + turn * (camera.position - camera.target),
            ..*camera
        }
    }
}

/// The renderers, frames and thread pool that turntables render with, kept from one turntable
/// to the next: a batch of many turntables starts its threads and allocates its frames once.
#[derive(Default)]
pub struct TurntableWorkers {
    /// The pool asked for by `--threads`, with its thread count.
    pool: Option<(usize, rayon::ThreadPool)>,
    /// One renderer and frame for each frame in flight.
    slots: Vec<(Renderer, Frame)>,
}

/// Renders the turntable of `world` around `camera` with `options` and writes it to
/// `destination` in `format` (a file atomically). `progress` counts frames written; cancelling
/// it stops the turntable after the frames rendering at the time, and leaves a file untouched.
pub fn render_turntable(
    world: &Arc<World>,
    camera: &Camera,
    options: &RenderOptions,
    turntable: Turntable,
    format: AnimationFormat,
    destination: &Destination,
    progress: &Progress,
) -> Result<TurntableStats, ExportError> {
    let mut workers = TurntableWorkers::default();
    let job = TurntableJob {
        world,
        camera,
        options,
        turntable,
        format,
    };
    render_turntable_with(&mut workers, &job, destination, progress)
}

/// What one turntable shows and how.
pub struct TurntableJob<'a> {
    pub world: &'a Arc<World>,
    pub camera: &'a Camera,
    pub options: &'a RenderOptions,
    pub turntable: Turntable,
    pub format: AnimationFormat,
}

/// As [`render_turntable`], with the renderers, frames and thread pool of `workers`, which keep
/// them for the next turntable.
pub fn render_turntable_with(
    workers: &mut TurntableWorkers,
    job: &TurntableJob,
    destination: &Destination,
    progress: &Progress,
) -> Result<TurntableStats, ExportError> {
    let TurntableJob {
        world,
        camera,
        options,
        turntable,
        format,
    } = *job;
    let path = destination.path();
    turntable.check()?;
    options.check().map_err(RenderError::from)?;
    let started = Instant::now();
    let animation = Animation {
        format,
        width: options.width,
        height: options.height,
        alpha: options.alpha,
        frames: turntable.frames,
        fps: turntable.fps,
    };
    let mut out = BufWriter::new(destination.open(progress)?);
    progress.start(turntable.frames as u64);
    let orbit = Orbit {
        world,
        camera,
        // The frames of a batch share the render threads: each renderer uses the pool it runs on.
        options: RenderOptions {
            threads: None,
            ..*options
        },
        turntable,
    };
    let TurntableWorkers { pool, slots } = workers;
    let mut render_all =
        |out: &mut BufWriter<Sink>| render_frames(&orbit, &animation, slots, out, path, progress);
    match options.threads.map(|n| n.get()) {
        None => render_all(&mut out)?,
        Some(threads) => {
            if pool.as_ref().is_none_or(|(n, _)| *n != threads) {
                let started = rayon::ThreadPoolBuilder::new()
                    .num_threads(threads)
                    .build()
                    .map_err(|e| RenderError::Threads {
                        threads,
                        message: e.to_string(),
                    })?;
                *pool = Some((threads, started));
            }
            let (_, pool) = pool.as_ref().expect("started above");
            pool.install(|| render_all(&mut out))?
        }
    }
    let file = out
        .into_inner()
        .map_err(|e| ExportError::io(path, e.into_error()))?;
    file.commit(progress).map_err(|e| e.at(path))?;
    Ok(TurntableStats {
        frames: turntable.frames,
        triangles: world.triangle_count(),
        elapsed: started.elapsed(),
    })
}

/// What every frame of one turntable shares.
struct Orbit<'a> {
    world: &'a Arc<World>,
    /// The camera of frame 0.
    camera: &'a Camera,
    /// The options of each frame's render.
    options: RenderOptions,
    turntable: Turntable,
}

impl Orbit<'_> {
    /// Renders frame `k` into `frame` with `renderer`.
    fn render(
        &self,
        k: u32,
        renderer: &mut Renderer,
        frame: &mut Frame,
    ) -> Result<(), RenderError> {
        let camera = self.turntable.camera(self.camera, k);
        renderer.render(self.world, &camera, &Progress::new(), frame)?;
        Ok(())
    }
}

/// Renders every frame of `orbit`, as many at once as the current pool has threads and the
/// memory bound allows, and writes them in order to `out` on a thread of their own.
fn render_frames(
    orbit: &Orbit,
    animation: &Animation,
    slots: &mut Vec<(Renderer, Frame)>,
    out: &mut BufWriter<Sink>,
    path: &Path,
    progress: &Progress,
) -> Result<(), ExportError> {
    let frames = orbit.turntable.frames;
    let pixels = u64::from(animation.width) * u64::from(animation.height);
    let batch = frames_in_flight(
        &Estimate::of_world(orbit.world),
        pixels,
        rayon::current_num_threads(),
    );
    // The slots of the last turntable, as many as this one has in flight, each renderer made
    // again only when the options changed.
    slots.truncate(batch);
    for (renderer, _) in slots.iter_mut() {
        if *renderer.options() != orbit.options {
            *renderer = Renderer::new(orbit.options);
        }
    }
    slots.resize_with(batch, || (Renderer::new(orbit.options), Frame::default()));
    let encode_error = |message: String| ExportError::encode(path, animation.format, message);
    std::thread::scope(|s| {
        // With one frame in flight the renderer hands each frame straight to the writer.
        let (send, receive) = sync_channel::<ReadyFrame>(batch - 1);
        let writer = s.spawn(move || {
            let mut writer = animation.start(out).map_err(encode_error)?;
            for frame in receive {
                writer.write(&frame).map_err(encode_error)?;
                progress.advance(1);
            }
            writer.finish().map_err(encode_error)
        });
        let rendered = (|| {
            for first in (0..frames).step_by(batch) {
                progress.check().map_err(RenderError::from)?;
                let last = (first + batch as u32).min(frames);
                let ready: Vec<Result<ReadyFrame, RenderError>> = slots
                    .par_iter_mut()
                    .zip(first..last)
                    .map(|((renderer, frame), k)| {
                        orbit.render(k, renderer, frame)?;
                        Ok(animation.ready(frame))
                    })
                    .collect();
                for frame in ready {
                    if send.send(frame?).is_err() {
                        // The writer stopped; its error says why.
                        return Ok(());
                    }
                }
            }
            Ok::<(), ExportError>(())
        })();
        drop(send);
        let written = writer.join().expect("the animation writer does not panic");
        rendered.and(written)
    })
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::{Turntable, TurntableError};
    use crate::scene::Camera;

    fn close(a: Vec3, b: Vec3) -> bool {
        // Tolerance: f32 rotation of a vector of length 5.
        (a - b).abs().max_element() < 1e-5
    }

    #[test]
    fn a_turntable_turns_the_camera_once_about_its_up_vector() {
        let camera = Camera {
            position: Vec3::new(1.0, 3.0, 5.0),
            target: Vec3::new(1.0, 1.0, 0.0),
            up: Vec3::new(0.0, 2.0, 0.0),
            fov: 30.0,
            ..Camera::default()
        };
        let turn = Turntable::new(4);
        assert_eq!(turn.camera(&camera, 0), camera);
        // A quarter turn, right-handed about +Y: +Z goes to +X; the height stays.
        let quarter = turn.camera(&camera, 1);
        assert!(
            close(quarter.position, Vec3::new(6.0, 3.0, 0.0)),
            "{quarter:?}"
        );
        assert_eq!(
            (quarter.target, quarter.up, quarter.fov),
            (camera.target, camera.up, camera.fov)
        );
        let half = turn.camera(&camera, 2);
        assert!(close(half.position, Vec3::new(1.0, 3.0, -5.0)), "{half:?}");
        assert!(close(turn.camera(&camera, 4).position, camera.position));
        // A Z-up scene turns about Z.
        let z_up = Camera {
            position: Vec3::new(0.0, -4.0, 2.0),
            target: Vec3::ZERO,
            up: Vec3::Z,
            fov: 40.0,
            ..Camera::default()
        };
        let quarter = turn.camera(&z_up, 1);
        assert!(
            close(quarter.position, Vec3::new(4.0, 0.0, 2.0)),
            "{quarter:?}"
        );
    }

    #[test]
    fn frame_counts_and_rates_out_of_range_are_refused() {
        assert_eq!(Turntable::new(0).check(), Err(TurntableError::Frames(0)));
        assert_eq!(
            Turntable::new(super::MAX_FRAMES + 1).check(),
            Err(TurntableError::Frames(super::MAX_FRAMES + 1))
        );
        let too_fast = Turntable {
            frames: 10,
            fps: super::MAX_FPS + 1,
        };
        assert_eq!(
            too_fast.check(),
            Err(TurntableError::Fps(super::MAX_FPS + 1))
        );
        assert_eq!(Turntable::new(1).check(), Ok(()));
    }
}
