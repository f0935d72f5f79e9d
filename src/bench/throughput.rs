//! Throughput on one scene, in units other renderers report: rasterizer Mtriangles/s and
//! Mpixels/s per shading, ray tracer Mrays/s per kind of ray, and BVH build time.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use glam::Vec3;

use super::area::total_face_area;
use super::runner::{summarize, time_render};
use crate::mesh::load_obj;
use crate::render::ray::accel::SceneAccel;
use crate::render::{
    Algorithm, Cancelled, Frame, Progress, RenderError, RenderOptions, Size, View, ray::tracer,
};
use crate::scene::{Camera, Light, Object, Scene, Shape};
use crate::world::World;

/// Rays a render cast, by kind, and the time it spent building its BVH.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct RayStats {
    /// Camera rays, one per sample.
    pub primary: u64,
    /// Rays toward lights.
    pub shadow: u64,
    /// Mirror rays.
    pub reflection: u64,
    /// Time spent building the bounding volume hierarchy.
    pub bvh_build: Duration,
}

/// Renders with the ray tracer into `frame` (its buffer reused when it has the view's size),
/// building its BVH first, and returns the ray counts and the build time.
pub fn render_ray_with_stats(
    world: &World,
    view: &View,
    options: &RenderOptions,
    progress: &Progress,
    frame: &mut Frame,
) -> Result<RayStats, Cancelled> {
    let accel = SceneAccel::build(world);
    frame.reshape(view.width, view.height);
    let rays = tracer::trace_into(&accel, world, view, options, progress, &mut frame.pixels)?;
    Ok(RayStats {
        primary: rays.primary,
        shadow: rays.shadow,
        reflection: rays.reflection,
        bvh_build: accel.build_time,
    })
}

/// One Z-buffer shading on one scene.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RasterRate {
    pub algorithm: Algorithm,
    /// Median render time.
    pub time: Duration,
    /// Triangles submitted.
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

/// The ray tracer on one scene.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RayRate {
    /// Median render time, BVH build included.
    pub time: Duration,
    /// Counts of the median render.
    pub stats: RayStats,
}

impl RayRate {
    /// Tracing time: the render without the BVH build.
    pub fn trace_time(&self) -> Duration {
        self.time.saturating_sub(self.stats.bvh_build)
    }

    /// Million rays per second of tracing time for `count` rays.
    pub fn mrays_per_s(&self, count: u64) -> f64 {
        count as f64 / self.trace_time().as_secs_f64().max(1e-9) / 1e6
    }
}

/// Throughput of all three algorithms on one scene.
#[derive(Debug, Clone, PartialEq)]
pub struct Throughput {
    pub size: Size,
    pub raster: Vec<RasterRate>,
    pub ray: RayRate,
}

/// Measures `scene` (OBJ paths relative to `base`) at `size`, `reps` renders each (median kept).
pub fn measure(
    scene: &Scene,
    world: &World,
    size: Size,
    reps: u32,
) -> Result<Throughput, RenderError> {
    let view = View::new(&scene.camera, size.width, size.height);
    let face_area = total_face_area(world, &view);
    let mut raster = Vec::new();
    let mut frame = Frame::default();
    for algorithm in [Algorithm::Gouraud, Algorithm::Phong] {
        let options = RenderOptions::new(algorithm, size.width, size.height);
        let times = (0..reps.max(1))
            .map(|_| time_render(world, &scene.camera, &options, &mut frame))
            .collect::<Result<Vec<_>, _>>()?;
        let (median_ms, _, _) = summarize(&times);
        raster.push(RasterRate {
            algorithm,
            time: Duration::from_secs_f64(median_ms / 1e3),
            triangles: world.triangle_count(),
            pixels: size.width as u64 * size.height as u64,
            face_area,
        });
    }
    let options = RenderOptions::new(Algorithm::Ray, size.width, size.height);
    let mut runs = Vec::new();
    for _ in 0..reps.max(1) {
        let started = Instant::now();
        let stats = render_ray_with_stats(world, &view, &options, &Progress::new(), &mut frame)?;
        runs.push((started.elapsed(), stats));
        std::hint::black_box(&frame.pixels);
    }
    runs.sort_by_key(|r| r.0);
    let (time, stats) = runs[runs.len() / 2];
    Ok(Throughput {
        size,
        raster,
        ray: RayRate { time, stats },
    })
}

/// A scene showing the OBJ model at `path` alone: scaled to a 2-unit size, seen from the front,
/// lit by one light beside the camera. The model's path is kept as given, relative to its folder.
pub fn obj_scene(path: &Path) -> Result<Scene, String> {
    let model = load_obj(path)?;
    let (lo, hi) = model.bounds();
    let extent = (hi - lo).max_element();
    let scale = if extent > 0.0 { 2.0 / extent } else { 1.0 };
    let file_name = path.file_name().map(PathBuf::from).unwrap_or_default();
    Ok(Scene {
        camera: Camera {
            position: Vec3::new(0.0, 0.6, 3.6),
            target: Vec3::ZERO,
            up: Vec3::Y,
            fov: 45.0,
        },
        lights: vec![Light {
            position: Vec3::new(-2.0, 3.0, 4.0),
            ..Light::default()
        }],
        objects: vec![Object::new(Shape::Mesh {
            path: file_name,
            position: Vec3::ZERO,
            scale,
        })],
        ..Scene::default()
    })
}
