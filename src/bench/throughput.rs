//! Throughput on one scene, in units other renderers report: rasterizer Mtriangles/s and
//! Mpixels/s per shading, ray tracer Mrays/s per kind of ray, and BVH build time.

use std::sync::Arc;
use std::time::{Duration, Instant};

use super::area::total_face_area;
use super::runner::{summarize, time_render};
use crate::render::{
    Algorithm, Frame, Progress, RenderError, RenderOptions, RenderStats, Renderer, Size, View,
};
use crate::scene::{Camera, Scene};
use crate::world::World;

/// One Z-buffer shading on one scene.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RasterRate {
    pub algorithm: Algorithm,
    /// Median render time by one renderer kept from render to render, as the editor's preview
    /// keeps it: its working memory (band buffers, setup vectors) is reused.
    pub time: Duration,
    /// Median render time by a new renderer each time, as a one-off `rastray render` does: it
    /// also allocates and faults in that working memory.
    pub one_off: Duration,
    /// Triangles drawn.
    pub triangles: usize,
    /// Image pixels.
    pub pixels: u64,
    /// Total projected face area, square pixels, overdraw included.
    pub face_area: f64,
}

impl RasterRate {
    /// Million triangles per second.
    pub fn mtriangles_per_s(&self) -> f64 {
        self.triangles as f64 / self.time.as_secs_f64() / 1e6
    }

    /// Million image pixels per second.
    pub fn mpixels_per_s(&self) -> f64 {
        self.pixels as f64 / self.time.as_secs_f64() / 1e6
    }

    /// Million pixels of face area (overdraw included) per second.
    pub fn mfragments_per_s(&self) -> f64 {
        self.face_area / self.time.as_secs_f64() / 1e6
    }
}

/// The ray tracer on one scene: its median render, BVH build included, and the medians of
/// renders that cast fewer kinds of ray, so that each kind is timed on its own: primary rays
/// alone (no shadows, no reflections), then with their shadow rays, then everything.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RayRate {
    /// The median full render's figures (shadows on, the scene's reflection depth).
    pub stats: RenderStats,
    /// The median render with primary rays only.
    pub primary_only: RenderStats,
    /// The median render with primary rays and their shadow rays, no reflections.
    pub with_shadows: RenderStats,
    /// The median BVH build of all these renders, each of which built its own (one sample,
    /// the median render's, drifts with the page faults of that one build).
    pub build: Duration,
}

/// One kind of ray timed on its own.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RayKind {
    /// "primary", "shadow" or "reflection".
    pub name: &'static str,
    /// Rays of this kind in one render.
    pub rays: u64,
    /// Tracing time they add to a render (shading of their hits included).
    pub time: Duration,
}

impl RayKind {
    /// Million rays per second of this kind's own time.
    pub fn mrays_per_s(&self) -> f64 {
        self.rays as f64 / self.time.as_secs_f64().max(1e-9) / 1e6
    }
}

impl RayRate {
    /// Render time, BVH build included.
    pub fn time(&self) -> Duration {
        self.stats.total()
    }

    /// Tracing time: the render without the BVH build.
    pub fn trace_time(&self) -> Duration {
        self.stats.draw
    }

    /// Million rays per second of tracing time for `count` rays.
    pub fn mrays_per_s(&self, count: u64) -> f64 {
        count as f64 / self.trace_time().as_secs_f64().max(1e-9) / 1e6
    }

    /// Each kind of ray with the time it adds: primary rays the time of a render casting
    /// nothing else; shadow rays what casting them adds to that; reflection rays what the
    /// full render adds to that, the shadow rays from reflected hits counted with them.
    pub fn kinds(&self) -> [RayKind; 3] {
        let (primary, shadowed, full) = (&self.primary_only, &self.with_shadows, &self.stats);
        [
            RayKind {
                name: "primary",
                rays: primary.rays.primary,
                time: primary.draw,
            },
            RayKind {
                name: "shadow",
                rays: shadowed.rays.shadow,
                time: shadowed.draw.saturating_sub(primary.draw),
            },
            RayKind {
                name: "reflection",
                rays: full.rays.reflection + full.rays.shadow.saturating_sub(shadowed.rays.shadow),
                time: full.draw.saturating_sub(shadowed.draw),
            },
        ]
    }
}

/// Throughput of all three algorithms on one scene.
#[derive(Debug, Clone, PartialEq)]
pub struct Throughput {
    pub size: Size,
    pub raster: Vec<RasterRate>,
    pub ray: RayRate,
}

/// Measures `world`, built from `scene`, at `size`, `reps` renders each (median kept). The
/// Z-buffer is timed twice: by one renderer kept for all its renders (the editor's steady state)
/// and by a new renderer per render. Every ray-traced render is a one-off: the ray tracer builds
/// its BVH each time (timed apart from tracing).
pub fn measure(
    scene: &Scene,
    world: &Arc<World>,
    size: Size,
    reps: u32,
) -> Result<Throughput, RenderError> {
    let view = View::new(&scene.camera, size.width, size.height);
    let face_area = total_face_area(world, &view);
    let mut raster = Vec::new();
    let mut frame = Frame::default();
    for algorithm in [Algorithm::Gouraud, Algorithm::Phong] {
        let options = RenderOptions::new(algorithm, size.width, size.height);
        let mut kept = Renderer::new(options);
        warm_up(&mut kept, world, &scene.camera, &mut frame)?;
        let kept_runs = (0..reps.max(1))
            .map(|_| time_kept_render(&mut kept, world, &scene.camera, &mut frame))
            .collect::<Result<Vec<_>, _>>()?;
        let one_off_runs = (0..reps.max(1))
            .map(|_| time_render(world, &scene.camera, &options, &mut frame))
            .collect::<Result<Vec<_>, _>>()?;
        raster.push(RasterRate {
            algorithm,
            time: median_total(&kept_runs),
            one_off: median_total(&one_off_runs),
            triangles: kept_runs[0].triangles,
            pixels: size.width as u64 * size.height as u64,
            face_area,
        });
    }
    let full = RenderOptions::new(Algorithm::Ray, size.width, size.height);
    let mut builds = Vec::new();
    let mut median = |options: RenderOptions| -> Result<RenderStats, RenderError> {
        let mut runs = (0..reps.max(1))
            .map(|_| time_render(world, &scene.camera, &options, &mut frame))
            .collect::<Result<Vec<_>, _>>()?;
        builds.extend(runs.iter().map(|r| r.bvh_build));
        runs.sort_by_key(|r| r.draw);
        Ok(runs[runs.len() / 2])
    };
    let primary_only = median(RenderOptions {
        shadows: false,
        max_depth: Some(0),
        ..full
    })?;
    let with_shadows = median(RenderOptions {
        max_depth: Some(0),
        ..full
    })?;
    // Without reflections the full render is the one just timed.
    let stats = if world.max_depth == 0 {
        with_shadows
    } else {
        median(full)?
    };
    builds.sort();
    let ray = RayRate {
        stats,
        primary_only,
        with_shadows,
        build: builds[builds.len() / 2],
    };
    Ok(Throughput { size, raster, ray })
}

/// The median of the renders' total times. `runs` must not be empty.
fn median_total(runs: &[RenderStats]) -> Duration {
    let times: Vec<Duration> = runs.iter().map(RenderStats::total).collect();
    let (median_ms, _, _) = summarize(&times);
    Duration::from_secs_f64(median_ms / 1e3)
}

/// How long a kept renderer draws untimed frames before it is timed (at least one frame).
///
/// A live preview has been drawing for a while when a key is pressed; a fresh process has not.
/// On a two-core virtual machine the first tens of milliseconds of 2-thread frames ran up to
/// twice as slow as the rest (bunny, 160×96, Gouraud, median of 7 frames, 20 fresh processes
/// each: after 1 untimed frame, 0.49–1.05 ms, half of them near 1 ms; after 30 frames,
/// 0.48–0.91 ms; after 100 frames, about 60 ms, all 0.48–0.54 ms).
const WARM_UP: Duration = Duration::from_millis(200);

/// Renders untimed frames with `renderer` until [`WARM_UP`] has passed, at least one.
fn warm_up(
    renderer: &mut Renderer,
    world: &Arc<World>,
    camera: &Camera,
    frame: &mut Frame,
) -> Result<(), RenderError> {
    let started = Instant::now();
    loop {
        time_kept_render(renderer, world, camera, frame)?;
        if started.elapsed() >= WARM_UP {
            return Ok(());
        }
    }
}

/// One render by `renderer`, kept from render to render, into `frame`.
fn time_kept_render(
    renderer: &mut Renderer,
    world: &Arc<World>,
    camera: &Camera,
    frame: &mut Frame,
) -> Result<RenderStats, RenderError> {
    let stats = renderer.render(world, camera, &Progress::new(), frame)?;
    std::hint::black_box(&frame.pixels);
    Ok(stats)
}
