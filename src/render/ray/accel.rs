//! The scene's acceleration structure: each object's bounding sphere as the first cull (the
//! study's test), then the BVH over the object's triangles.

use std::time::{Duration, Instant};

use glam::Vec3;
use rayon::prelude::*;
use wide::CmpGt;

use super::bvh::Bvh;
use super::half_line::Ray;
use super::intersect::segment_meets_sphere;
use super::packet::{PacketHits, RayPacket};
use crate::mesh::Sphere;
use crate::render::progress::{Cancelled, Progress};
use crate::render::simd::{F32x8, V3};
use crate::world::World;

/// Self-hit offset as a fraction of the scene's bounding radius.
const EPSILON_SCALE: f32 = 1.0e-4;

/// One object ready for ray queries.
#[derive(Debug, Clone)]
pub struct ObjectAccel {
    /// The object's bounding sphere, grown by the scene epsilon so that rays grazing a vertex on
    /// the sphere are not culled by rounding.
    pub bounds: Sphere,
    /// BVH over the object's triangles.
    pub bvh: Bvh,
}

/// The nearest surface along a ray.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hit {
    /// Ray parameter of the hit.
    pub t: f32,
    /// Barycentric weight of the triangle's second vertex.
    pub u: f32,
    /// Barycentric weight of the triangle's third vertex.
    pub v: f32,
    /// Object index in the world.
    pub object: u32,
    /// Triangle index in the object's mesh.
    pub triangle: u32,
    /// Index of the triangle in the object's [`Bvh::triangles`].
    pub slot: u32,
}

/// Everything the ray tracer queries, built once per world.
#[derive(Debug, Clone)]
pub struct SceneAccel {
    /// One entry per world object, in world order.
    pub objects: Vec<ObjectAccel>,
    /// Distance secondary rays start off the surface, world units: 1e-4 × the scene's
    /// bounding radius.
    pub epsilon: f32,
    /// Wall-clock time the build took.
    pub build_time: Duration,
}

impl SceneAccel {
    /// Builds every object's BVH (objects and large meshes in parallel); stops with
    /// [`Cancelled`] soon after `progress` is cancelled, so a scene edited again during a long
    /// build does not wait for it.
    pub fn build(world: &World, progress: &Progress) -> Result<SceneAccel, Cancelled> {
        let started = Instant::now();
        let bvhs = world
            .objects
            .par_iter()
            .map(|o| Bvh::build_cancellable(&o.mesh, progress))
            .collect::<Result<Vec<_>, Cancelled>>();
        let radius = world
            .bounds()
            .map_or(1.0, |(lo, hi)| 0.5 * (hi - lo).length());
        let epsilon = EPSILON_SCALE * radius.max(f32::MIN_POSITIVE);
        let objects = world
            .objects
            .iter()
            .zip(bvhs?)
            .map(|(o, bvh)| ObjectAccel {
                bounds: Sphere {
                    center: o.bounds.center,
                    radius: o.bounds.radius + epsilon,
                },
                bvh,
            })
            .collect();
        Ok(SceneAccel {
            objects,
            epsilon,
            build_time: started.elapsed(),
        })
    }

    /// The nearest hit with t in (t_min, t_max) over all objects.
    pub fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<Hit> {
        let mut best = None;
        let mut t_max = t_max;
        for (i, o) in self.objects.iter().enumerate() {
            if !segment_meets_sphere(ray, o.bounds.center, o.bounds.radius, t_min, t_max) {
                continue;
            }
            if let Some(h) = o.bvh.intersect(ray, t_min, t_max) {
                t_max = h.t;
                best = Some(Hit {
                    t: h.t,
                    u: h.u,
                    v: h.v,
                    object: i as u32,
                    triangle: h.triangle,
                    slot: h.slot,
                });
            }
        }
        best
    }

    /// The nearest hit of each ray of `packet` over all objects.
    pub fn intersect_packet(&self, packet: &RayPacket) -> PacketHits {
        let mut hits = PacketHits::none();
        for (i, o) in self.objects.iter().enumerate() {
            let (center, radius) = (o.bounds.center, o.bounds.radius);
            if packet.meets_sphere(center, radius, hits.t).any() {
                o.bvh.intersect_packet(packet, i as u32, &mut hits);
            }
        }
        hits
    }

    /// Whether anything lies on the segment from `from` to `to` (exclusive at both ends).
    pub fn occluded(&self, from: Vec3, to: Vec3) -> bool {
        let d = to - from;
        let dist = d.length();
        if dist <= 0.0 {
            return false;
        }
        let ray = Ray::new(from, d / dist);
        self.objects.iter().any(|o| {
            segment_meets_sphere(&ray, o.bounds.center, o.bounds.radius, 0.0, dist)
                && o.bvh.occluded(&ray, 0.0, dist)
        })
    }

    /// The lanes of `wanted` whose segment from `from` to `to` (exclusive at both ends) is
    /// blocked: [`SceneAccel::occluded`] for eight segments at once, lane by lane the same
    /// arithmetic, so each lane's answer is the one its segment would get alone.
    pub fn occluded_packet(&self, from: V3<F32x8>, to: Vec3, wanted: F32x8) -> F32x8 {
        let d = V3::splat(to) - from;
        let dist = d.length_squared().sqrt();
        let mut pending = wanted & dist.cmp_gt(F32x8::ZERO);
        if !pending.any() {
            return F32x8::ZERO;
        }
        let dir = V3::new(d.x / dist, d.y / dist, d.z / dist);
        let packet = RayPacket::new(from, dir, F32x8::ZERO);
        let mut blocked = F32x8::ZERO;
        for o in &self.objects {
            let lanes = pending & packet.meets_sphere(o.bounds.center, o.bounds.radius, dist);
            if !lanes.any() {
                continue;
            }
            let hit = o.bvh.occluded_packet(&packet, dist, lanes);
            blocked |= hit;
            pending &= !hit;
            if !pending.any() {
                break;
            }
        }
        blocked
    }
}
