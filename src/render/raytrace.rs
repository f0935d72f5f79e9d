//! Backward (Whitted) ray tracing: one primary ray per pixel centre, the shared lighting function
//! at the nearest hit with shadow rays deciding which lights count, and mirror reflection
//! recursing to a maximum depth. Rows are traced in parallel; every pixel depends only on its own
//! rays, so the image is the same for any number of threads.

use std::ops::Add;

use glam::Vec3;
use rayon::prelude::*;

use super::accel::SceneAccel;
use super::camera::{NEAR, View};
use super::frame::Frame;
use super::materials::ObjectMaterials;
use super::options::RenderOptions;
use super::progress::{Cancelled, Progress};
use super::ray::Ray;
use super::shading::Lighting;
use crate::world::World;

/// Deepest reflection recursion traced, whatever the options ask: the limit scene files
/// already have, which also bounds the recursion's stack use.
pub const MAX_REFLECTION_DEPTH: u32 = crate::scene::MAX_DEPTH;

/// How many rays of each kind a render cast.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct RayStats {
    /// Rays from the eye, one per pixel (sample).
    pub primary: u64,
    /// Rays toward lights from lit points.
    pub shadow: u64,
    /// Mirror rays from reflective surfaces.
    pub reflection: u64,
}

impl RayStats {
    /// All rays cast.
    pub fn total(&self) -> u64 {
        self.primary + self.shadow + self.reflection
    }
}

impl Add for RayStats {
    type Output = RayStats;

    fn add(self, o: RayStats) -> RayStats {
        RayStats {
            primary: self.primary + o.primary,
            shadow: self.shadow + o.shadow,
            reflection: self.reflection + o.reflection,
        }
    }
}

/// Renders `world` through `view` (one ray per pixel centre), building the acceleration
/// structure first.
pub fn render(
    world: &World,
    view: &View,
    options: &RenderOptions,
    progress: &Progress,
) -> Result<Frame, Cancelled> {
    let accel = SceneAccel::build(world);
    render_with(&accel, world, view, options, progress)
}

/// As [`render`], with an acceleration structure already built from `world`.
pub fn render_with(
    accel: &SceneAccel,
    world: &World,
    view: &View,
    options: &RenderOptions,
    progress: &Progress,
) -> Result<Frame, Cancelled> {
    render_with_stats(accel, world, view, options, progress).map(|(frame, _)| frame)
}

/// As [`render_with`], also counting the rays cast.
pub fn render_with_stats(
    accel: &SceneAccel,
    world: &World,
    view: &View,
    options: &RenderOptions,
    progress: &Progress,
) -> Result<(Frame, RayStats), Cancelled> {
    debug_assert_eq!(accel.objects.len(), world.objects.len());
    let tracer = Tracer {
        world,
        accel,
        lighting: Lighting::new(world),
        materials: ObjectMaterials::new(world),
        shadows: options.shadows,
        max_depth: options
            .max_depth
            .unwrap_or(world.max_depth)
            .min(MAX_REFLECTION_DEPTH),
    };
    let width = view.width as usize;
    let mut pixels = vec![Vec3::ZERO; width * view.height as usize];
    let stats = pixels
        .par_chunks_mut(width)
        .enumerate()
        .map(|(j, row)| {
            progress.check()?;
            let mut stats = RayStats::default();
            for (i, pixel) in row.iter_mut().enumerate() {
                let dir = view.ray_direction(i as f32 + 0.5, j as f32 + 0.5);
                // Start where the rasterizer's near plane cuts the ray, so both see the same.
                let t_min = NEAR / dir.dot(view.forward);
                stats.primary += 1;
                *pixel = tracer.trace(&Ray::new(view.eye, dir), t_min, 0, &mut stats);
            }
            progress.advance(1);
            Ok(stats)
        })
        .try_reduce(RayStats::default, |a, b| Ok(a + b))?;
    let frame = Frame {
        width: view.width,
        height: view.height,
        pixels,
    };
    Ok((frame, stats))
}

/// What every ray of one render shares.
struct Tracer<'a> {
    world: &'a World,
    accel: &'a SceneAccel,
    lighting: Lighting<'a>,
    materials: ObjectMaterials,
    shadows: bool,
    max_depth: u32,
}

impl Tracer<'_> {
    /// Colour seen along `ray` beyond `t_min`; `depth` counts reflections so far.
    fn trace(&self, ray: &Ray, t_min: f32, depth: u32, stats: &mut RayStats) -> Vec3 {
        let Some(hit) = self.accel.intersect(ray, t_min, f32::INFINITY) else {
            return self.world.background;
        };
        let object = &self.world.objects[hit.object as usize];
        let mesh = &object.mesh;
        let [a, b, c] = mesh.triangles[hit.triangle as usize].map(|k| k as usize);
        let w = [1.0 - hit.u - hit.v, hit.u, hit.v];
        // Interpolate position and normal exactly as the Phong fragment stage does.
        let p = mesh.positions[a] * w[0] + mesh.positions[b] * w[1] + mesh.positions[c] * w[2];
        let n = (mesh.normals[a] * w[0] + mesh.normals[b] * w[1] + mesh.normals[c] * w[2])
            .normalize_or_zero();
        let d = Vec3::from(ray.dir);
        let v = -d;
        // Secondary rays leave from a point lifted off the surface, on the side the ray came
        // from, by an offset scaled to the scene.
        let mut ng = Vec3::from(hit.normal.normalize_or_zero());
        if ng.dot(d) > 0.0 {
            ng = -ng;
        }
        let origin = p + ng * self.accel.epsilon;
        let material = &object.material;
        let coefficients = &self.materials.one[hit.object as usize];
        let mut color = self.lighting.shade(p, n, v, coefficients, |_, light| {
            if !self.shadows {
                return true;
            }
            stats.shadow += 1;
            !self.accel.occluded(origin, light.position)
        });
        if depth < self.max_depth && material.reflection > 0.0 {
            // The shading normal, turned toward the viewer as the lighting function does.
            let n = if n.dot(v) < 0.0 { -n } else { n };
            let r = d - 2.0 * n * d.dot(n);
            stats.reflection += 1;
            let reflected = Ray::new(origin, r.normalize_or(d));
            color += material.reflection * self.trace(&reflected, 0.0, depth + 1, stats);
        }
        color
    }
}
