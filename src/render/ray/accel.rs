//! The scene's acceleration structure, Embree's two levels: a tree over the objects' boxes
//! (`top_level`) whose leaves are objects, each with its bounding sphere as the first cull (the
//! study's test) and then the BVH over its triangles. A scene of at most [`FLAT_OBJECTS`]
//! objects skips the tree and tests every object's sphere in world order, as it always did.
//!
//! Every query gives the answer of that flat loop: the nearest hit, and between hits of two
//! objects at the same t, the object that comes first in the world (the loop kept the first,
//! since a later object had to be strictly nearer). The tree visits objects nearer first
//! instead, so an object that comes before the nearest so far is searched up to the next float
//! after its t, and its hit at the same t replaces the later object's.

use std::collections::HashMap;
use std::collections::hash_map::Entry;
use std::sync::Arc;
use std::time::{Duration, Instant};

use glam::{Affine3A, Vec3};
use rayon::prelude::*;
use wide::{CmpGt, CmpLt};

use super::bvh::{Bvh, BvhHit};
use super::half_line::Ray;
use super::intersect::segment_meets_sphere;
use super::packet::{PacketHits, RayPacket};
use super::top_level::{ObjectBox, TopLevel};
use crate::mesh::Sphere;
use crate::render::progress::{Cancelled, Progress};
use crate::render::simd::{F32x8, V3};
use crate::world::World;

/// Self-hit offset as a fraction of the scene's bounding radius.
const EPSILON_SCALE: f32 = 1.0e-4;

/// Most objects a scene may have and still be searched by the flat loop over all objects
/// rather than the tree over them: for so few, a sphere test each costs no more than a walk
/// through the tree, and their images stay bit for bit what they were.
pub const FLAT_OBJECTS: usize = 8;

/// One object ready for ray queries.
#[derive(Debug, Clone)]
pub struct ObjectAccel {
    /// The object's bounding sphere, grown by the scene epsilon so that rays grazing a vertex on
    /// the sphere are not culled by rounding.
    pub bounds: Sphere,
    /// BVH over the object's triangles; for an instance, over its shared mesh's, in the mesh's
    /// own space, and the same allocation for every instance of that mesh.
    pub bvh: Arc<Bvh>,
    /// For an instance, the map from the world into its mesh's space: a ray is moved by it,
    /// direction not renormalised, so that t along it stays the world ray's t.
    pub to_object: Option<Affine3A>,
}

impl ObjectAccel {
    /// `ray` in the space of this object's BVH.
    #[inline]
    fn local_ray(&self, ray: &Ray) -> Ray {
        match &self.to_object {
            Some(m) => Ray::new(
                m.transform_point3(Vec3::from(ray.origin)),
                m.transform_vector3(Vec3::from(ray.dir)),
            ),
            None => *ray,
        }
    }

    /// The nearest hit of `ray` (world space) in (t_min, t_max), t the world ray's.
    #[inline]
    fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<BvhHit> {
        match self.to_object {
            Some(_) => self.bvh.intersect(&self.local_ray(ray), t_min, t_max),
            None => self.bvh.intersect(ray, t_min, t_max),
        }
    }

    /// Whether `ray` (world space) meets a triangle in (t_min, t_max).
    #[inline]
    fn occluded(&self, ray: &Ray, t_min: f32, t_max: f32) -> bool {
        match self.to_object {
            Some(_) => self.bvh.occluded(&self.local_ray(ray), t_min, t_max),
            None => self.bvh.occluded(ray, t_min, t_max),
        }
    }

    /// `packet` in the space of this object's BVH; `None` when it is the world's.
    #[inline]
    fn local_packet(&self, packet: &RayPacket) -> Option<RayPacket> {
        let m = self.to_object.as_ref()?;
        Some(RayPacket::new(
            affine_points(m, packet.origin),
            affine_vectors(m, packet.dir),
            packet.t_min,
        ))
    }

    /// [`Bvh::intersect_packet`] with the packet moved into the BVH's space.
    #[inline]
    fn intersect_packet(&self, packet: &RayPacket, object: u32, hits: &mut PacketHits) {
        match self.local_packet(packet) {
            Some(local) => self.bvh.intersect_packet(&local, object, hits),
            None => self.bvh.intersect_packet(packet, object, hits),
        }
    }

    /// [`Bvh::occluded_packet`] with the packet moved into the BVH's space.
    #[inline]
    fn occluded_packet(&self, packet: &RayPacket, t_max: F32x8, pending: F32x8) -> F32x8 {
        match self.local_packet(packet) {
            Some(local) => self.bvh.occluded_packet(&local, t_max, pending),
            None => self.bvh.occluded_packet(packet, t_max, pending),
        }
    }
}

/// Eight points moved by `m`.
#[inline]
fn affine_points(m: &Affine3A, p: V3<F32x8>) -> V3<F32x8> {
    let moved = affine_vectors(m, p);
    let t = m.translation;
    V3::new(
        moved.x + F32x8::splat(t.x),
        moved.y + F32x8::splat(t.y),
        moved.z + F32x8::splat(t.z),
    )
}

/// Eight directions moved by `m`'s linear part.
#[inline]
fn affine_vectors(m: &Affine3A, d: V3<F32x8>) -> V3<F32x8> {
    let (a, b, c) = (m.matrix3.x_axis, m.matrix3.y_axis, m.matrix3.z_axis);
    let row =
        |k: usize| d.x * F32x8::splat(a[k]) + d.y * F32x8::splat(b[k]) + d.z * F32x8::splat(c[k]);
    V3::new(row(0), row(1), row(2))
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
    /// The tree over the objects; `None` when the flat loop searches them.
    top: Option<TopLevel>,
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
        Self::build_with(world, progress, FLAT_OBJECTS)
    }

    /// [`SceneAccel::build`], with the tree over the objects built when there are more than
    /// `flat_objects` (0: always; `usize::MAX`: never, the flat loop).
    pub fn build_with(
        world: &World,
        progress: &Progress,
        flat_objects: usize,
    ) -> Result<SceneAccel, Cancelled> {
        let started = Instant::now();
        // An instance's BVH is its shared mesh's, built once: the first instance of each
        // shared mesh builds it, the others take it from that one (`Some(first)`).
        let mut first_of = HashMap::new();
        let built_by: Vec<Option<usize>> = world
            .objects
            .iter()
            .enumerate()
            .map(|(i, o)| {
                let shared = Arc::as_ptr(&o.instance.as_ref()?.shared);
                match first_of.entry(shared) {
                    Entry::Occupied(first) => Some(*first.get()),
                    Entry::Vacant(slot) => {
                        slot.insert(i);
                        None
                    }
                }
            })
            .collect();
        let own = world
            .objects
            .par_iter()
            .zip(&built_by)
            .map(|(o, by)| match by {
                Some(_) => Ok(None),
                None => Bvh::build_cancellable(o.local_mesh(), progress).map(|b| Some(Arc::new(b))),
            })
            .collect::<Result<Vec<_>, Cancelled>>()?;
        let radius = world
            .bounds()
            .map_or(1.0, |(lo, hi)| 0.5 * (hi - lo).length());
        let epsilon = EPSILON_SCALE * radius.max(f32::MIN_POSITIVE);
        let objects: Vec<ObjectAccel> = world
            .objects
            .iter()
            .enumerate()
            .map(|(i, o)| ObjectAccel {
                bounds: Sphere {
                    center: o.bounds.center,
                    radius: o.bounds.radius + epsilon,
                },
                bvh: match built_by[i] {
                    Some(first) => own[first].clone().expect("the first instance builds it"),
                    None => own[i].clone().expect("built above"),
                },
                to_object: o.instance.as_ref().map(|instance| instance.to_object),
            })
            .collect();
        let top = (objects.len() > flat_objects).then(|| {
            // Each object's triangle box, grown by epsilon as its sphere is, so that the
            // tree's box tests never cull a ray the object's own BVH would let in.
            let boxes: Vec<ObjectBox> = objects
                .iter()
                .zip(&world.objects)
                .map(|(o, w)| {
                    let grow = glam::Vec3A::splat(epsilon);
                    match o.to_object {
                        // An instance's box is its placed mesh's, in the world.
                        Some(_) => w.extent.map(|(lo, hi)| {
                            (glam::Vec3A::from(lo) - grow, glam::Vec3A::from(hi) + grow)
                        }),
                        None => o.bvh.root.map(|r| (r.lo() - grow, r.hi() + grow)),
                    }
                })
                .collect();
            TopLevel::build(&boxes)
        });
        Ok(SceneAccel {
            objects,
            top,
            epsilon,
            build_time: started.elapsed(),
        })
    }

    /// The nearest hit with t in (t_min, t_max) over all objects; of hits at the same t, the
    /// one of the object that comes first in the world.
    pub fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<Hit> {
        let Some(top) = &self.top else {
            return self.intersect_flat(ray, t_min, t_max);
        };
        let mut best: Option<Hit> = None;
        let mut t_max = t_max;
        top.walk_ray(ray, t_min, &mut t_max, |i, t_max| {
            let o = &self.objects[i as usize];
            // A tie is searched for past the next float (see `tie_reach`), and taken below it.
            let (limit, reach) = match best {
                Some(b) if b.object > i => (b.t.next_up(), tie_reach_of(b.t, self.epsilon)),
                _ => (*t_max, *t_max),
            };
            if segment_meets_sphere(ray, o.bounds.center, o.bounds.radius, t_min, reach)
                && let Some(h) = o.intersect(ray, t_min, reach)
                && h.t < limit
            {
                *t_max = h.t;
                best = Some(Hit {
                    t: h.t,
                    u: h.u,
                    v: h.v,
                    object: i,
                    triangle: h.triangle,
                    slot: h.slot,
                });
            }
            false
        });
        best
    }

    /// [`SceneAccel::intersect`] by the flat loop: every object's sphere in world order.
    fn intersect_flat(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<Hit> {
        let mut best = None;
        let mut t_max = t_max;
        for (i, o) in self.objects.iter().enumerate() {
            if !segment_meets_sphere(ray, o.bounds.center, o.bounds.radius, t_min, t_max) {
                continue;
            }
            if let Some(h) = o.intersect(ray, t_min, t_max) {
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

    /// The nearest hit of each ray of `packet` over all objects; lane by lane the answer of
    /// [`SceneAccel::intersect_packet_flat`], ties between objects included.
    pub fn intersect_packet(&self, packet: &RayPacket) -> PacketHits {
        let Some(top) = &self.top else {
            return self.intersect_packet_flat(packet);
        };
        let hits = std::cell::Cell::new(PacketHits::none());
        top.walk_packet(
            packet,
            || hits.get().t,
            |i| {
                let o = &self.objects[i as usize];
                let mut found = hits.get();
                let limit = tie_limits(&found, i);
                let reach = tie_reach(&found, i, self.epsilon);
                if packet
                    .meets_sphere(o.bounds.center, o.bounds.radius, reach)
                    .any()
                {
                    found.t = reach;
                    o.intersect_packet(packet, i, &mut found);
                    hits.set(take_where(found.t.cmp_lt(limit), &found, &hits.get()));
                }
                false
            },
        );
        hits.get()
    }

    /// The nearest hit of each ray of `packet` by the flat loop: every object's sphere in world
    /// order, each lane keeping the first object's hit of those at the same t.
    fn intersect_packet_flat(&self, packet: &RayPacket) -> PacketHits {
        let mut hits = PacketHits::none();
        for (i, o) in self.objects.iter().enumerate() {
            let (center, radius) = (o.bounds.center, o.bounds.radius);
            if packet.meets_sphere(center, radius, hits.t).any() {
                o.intersect_packet(packet, i as u32, &mut hits);
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
        if let Some(top) = &self.top {
            let mut t_max = dist;
            return top.walk_ray(&ray, 0.0, &mut t_max, |i, _| {
                let o = &self.objects[i as usize];
                segment_meets_sphere(&ray, o.bounds.center, o.bounds.radius, 0.0, dist)
                    && o.occluded(&ray, 0.0, dist)
            });
        }
        self.objects.iter().any(|o| {
            segment_meets_sphere(&ray, o.bounds.center, o.bounds.radius, 0.0, dist)
                && o.occluded(&ray, 0.0, dist)
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
        if let Some(top) = &self.top {
            let state = std::cell::Cell::new((pending, blocked));
            let finished = F32x8::splat(f32::NEG_INFINITY);
            top.walk_packet(
                &packet,
                || state.get().0.blend(dist, finished),
                |i| {
                    let o = &self.objects[i as usize];
                    let (mut pending, mut blocked) = state.get();
                    let lanes =
                        pending & packet.meets_sphere(o.bounds.center, o.bounds.radius, dist);
                    if lanes.any() {
                        let hit = o.occluded_packet(&packet, dist, lanes);
                        blocked |= hit;
                        pending &= !hit;
                        state.set((pending, blocked));
                    }
                    !pending.any()
                },
            );
            return state.get().1;
        }
        for o in &self.objects {
            let lanes = pending & packet.meets_sphere(o.bounds.center, o.bounds.radius, dist);
            if !lanes.any() {
                continue;
            }
            let hit = o.occluded_packet(&packet, dist, lanes);
            blocked |= hit;
            pending &= !hit;
            if !pending.any() {
                break;
            }
        }
        blocked
    }
}

/// Per lane, how far `object` must be searched to match the flat loop: up to the nearest hit so
/// far, or, where that hit is of a later object, up to the next float after it, so that a hit
/// of `object` at the same t is found (and then wins, as it did when objects came in order).
#[inline]
fn tie_limits(hits: &PacketHits, object: u32) -> F32x8 {
    let t = hits.t.to_array();
    let owner = hits.object.to_array();
    F32x8::from(std::array::from_fn::<f32, 8, _>(|k| {
        if owner[k] > object && t[k] < f32::INFINITY {
            t[k].next_up()
        } else {
            t[k]
        }
    }))
}

/// Per lane, how far `object` is searched where [`tie_limits`] lets a tie in: see
/// [`tie_reach_of`]. Hits found past the tie limit are not taken.
#[inline]
fn tie_reach(hits: &PacketHits, object: u32, epsilon: f32) -> F32x8 {
    let t = hits.t.to_array();
    let owner = hits.object.to_array();
    F32x8::from(std::array::from_fn::<f32, 8, _>(|k| {
        if owner[k] > object && t[k] < f32::INFINITY {
            tie_reach_of(t[k], epsilon)
        } else {
            t[k]
        }
    }))
}

/// How far an earlier object is searched for a tie with a later object's hit at `t`: `epsilon`
/// (world units) past it, not just the next float. A search bounded by the next float can miss
/// the tie where the flat loop, whose bound lies further out, finds it: a hit on a face of a box
/// of the object's BVH can come out a few floats before that box's computed entry, and an edge
/// hit's fast f32 distance can lie a float past the exact one it gets.
#[inline]
fn tie_reach_of(t: f32, epsilon: f32) -> f32 {
    (t + epsilon).max(t.next_up())
}

/// `new` in the lanes of `mask` (all bits set), `old` elsewhere.
#[inline]
fn take_where(mask: F32x8, new: &PacketHits, old: &PacketHits) -> PacketHits {
    let pick = |a: wide::u32x8, b: wide::u32x8| -> wide::u32x8 {
        let (a, b): (F32x8, F32x8) = (bytemuck::cast(a), bytemuck::cast(b));
        bytemuck::cast(mask.blend(a, b))
    };
    PacketHits {
        t: mask.blend(new.t, old.t),
        u: mask.blend(new.u, old.u),
        v: mask.blend(new.v, old.v),
        object: pick(new.object, old.object),
        triangle: pick(new.triangle, old.triangle),
        slot: pick(new.slot, old.slot),
    }
}
