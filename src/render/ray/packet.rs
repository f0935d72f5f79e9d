//! Packets: eight coherent rays (neighbouring primary rays) traced through a BVH together.
//!
//! A node is fetched and its branch taken once for all eight rays, and the box and triangle
//! tests run on SIMD lanes, one ray per lane: the single-ray tests of [`super::intersect`], lane
//! by lane, so each lane finds the hit its ray would find alone. A subtree is entered when any
//! lane's ray reaches it before that lane's nearest hit so far.

use glam::Vec3A;
use wide::{CmpGe, CmpGt, CmpLe, CmpLt, u32x8};

use super::bvh::{Bvh, MAX_TREE_DEPTH, Node};
use super::half_line::TINY;
use super::intersect::{PARALLEL_COS, Triangle};
use crate::render::simd::{F32x8, V3};

/// Eight rays `origin + t·dir`, t > `t_min`, one per lane.
#[derive(Debug, Clone, Copy)]
pub struct RayPacket {
    /// Start points, world units.
    pub origin: V3<F32x8>,
    /// Unit directions.
    pub dir: V3<F32x8>,
    /// Per-component 1/dir, finite (components smaller than [`TINY`] are nudged to it).
    inv_dir: V3<F32x8>,
    /// Hits count only beyond this ray parameter.
    pub t_min: F32x8,
}

/// The nearest hit of each ray of a packet.
#[derive(Debug, Clone, Copy)]
pub struct PacketHits {
    /// Ray parameter of the hit; +∞ where nothing was hit.
    pub t: F32x8,
    /// Barycentric weight of the triangle's second vertex.
    pub u: F32x8,
    /// Barycentric weight of the triangle's third vertex.
    pub v: F32x8,
    /// Object index in the world (meaningless where nothing was hit).
    pub object: u32x8,
    /// Triangle index in the object's mesh (meaningless where nothing was hit).
    pub triangle: u32x8,
}

impl PacketHits {
    /// No hits yet.
    pub fn none() -> PacketHits {
        PacketHits {
            t: F32x8::splat(f32::INFINITY),
            u: F32x8::ZERO,
            v: F32x8::ZERO,
            object: u32x8::ZERO,
            triangle: u32x8::ZERO,
        }
    }

    /// Lanes whose ray hit something.
    #[inline]
    pub fn hit(&self) -> F32x8 {
        self.t.cmp_lt(F32x8::splat(f32::INFINITY))
    }
}

impl RayPacket {
    /// The rays from `origin` along unit `dir`, beyond `t_min`.
    #[inline]
    pub fn new(origin: V3<F32x8>, dir: V3<F32x8>, t_min: F32x8) -> RayPacket {
        let safe = |d: F32x8| {
            let tiny = F32x8::splat(TINY);
            d.abs().cmp_lt(tiny).blend(tiny.copysign(d), d)
        };
        let one = F32x8::splat(1.0);
        RayPacket {
            origin,
            dir,
            inv_dir: V3::new(one / safe(dir.x), one / safe(dir.y), one / safe(dir.z)),
            t_min,
        }
    }

    /// Lanes whose segment (t_min, `t_max`) touches the ball: the packet form of
    /// [`super::intersect::segment_meets_sphere`], the study's per-object cull.
    #[inline]
    pub fn meets_sphere(&self, center: glam::Vec3, radius: f32, t_max: F32x8) -> F32x8 {
        let to_center = V3::splat(center) - self.origin;
        let along = to_center.dot(self.dir);
        let t = along.fast_max(self.t_min).fast_min(t_max);
        let nearest = self.origin + self.dir * t;
        let gap = V3::splat(center) - nearest;
        gap.length_squared().cmp_le(F32x8::splat(radius * radius))
    }

    /// Where each ray enters the box [lo, hi] within (t_min, `t_max`): the lanes that do, and
    /// their entry distances (the slab test of [`super::intersect::ray_box`]).
    #[inline(always)]
    fn enter(&self, lo: Vec3A, hi: Vec3A, t_max: F32x8) -> (F32x8, F32x8) {
        let slab = |lo: f32, hi: f32, o: F32x8, inv: F32x8| {
            let (t1, t2) = ((F32x8::splat(lo) - o) * inv, (F32x8::splat(hi) - o) * inv);
            (t1.fast_min(t2), t1.fast_max(t2))
        };
        let (nx, fx) = slab(lo.x, hi.x, self.origin.x, self.inv_dir.x);
        let (ny, fy) = slab(lo.y, hi.y, self.origin.y, self.inv_dir.y);
        let (nz, fz) = slab(lo.z, hi.z, self.origin.z, self.inv_dir.z);
        let near = nx.fast_max(ny).fast_max(nz).fast_max(self.t_min);
        let far = fx.fast_min(fy).fast_min(fz).fast_min(t_max);
        (near.cmp_le(far), near)
    }

    /// Where each lane's ray meets the triangle within (t_min, `t_max`): the lanes that do, and
    /// their t, u and v. Möller–Trumbore as [`Triangle::intersect`] does it, lane by lane.
    #[inline(always)]
    fn meet_triangle(&self, tri: &Triangle, t_max: F32x8) -> (F32x8, F32x8, F32x8, F32x8) {
        let n = V3::splat(tri.n.into());
        let det = -self.dir.dot(n);
        let limit = PARALLEL_COS * PARALLEL_COS * tri.n.length_squared();
        let not_parallel = (det * det).cmp_gt(F32x8::splat(limit) * self.dir.length_squared());
        let inv_det = F32x8::splat(1.0) / det;
        let to_origin = self.origin - V3::splat(tri.v0.into());
        let t = to_origin.dot(n) * inv_det;
        let q = to_origin.cross(self.dir);
        let u = V3::splat(tri.e2.into()).dot(q) * inv_det;
        let v = -V3::splat(tri.e1.into()).dot(q) * inv_det;
        let inside =
            u.cmp_ge(F32x8::ZERO) & v.cmp_ge(F32x8::ZERO) & (u + v).cmp_le(F32x8::splat(1.0));
        let nearer = t.cmp_gt(self.t_min) & t.cmp_lt(t_max);
        (not_parallel & nearer & inside, t, u, v)
    }

    /// Updates `hits` with this triangle (mesh index `id` of object `object`) where it is nearer.
    #[inline(always)]
    fn hit_triangle(&self, tri: &Triangle, id: u32, object: u32, hits: &mut PacketHits) {
        let (found, t, u, v) = self.meet_triangle(tri, hits.t);
        if found.any() {
            let lanes: u32x8 = bytemuck::cast(found);
            hits.t = found.blend(t, hits.t);
            hits.u = found.blend(u, hits.u);
            hits.v = found.blend(v, hits.v);
            hits.triangle = lanes.blend(u32x8::splat(id), hits.triangle);
            hits.object = lanes.blend(u32x8::splat(object), hits.object);
        }
    }
}

/// The smallest lane of `values` where `mask` holds (+∞ when none does).
#[inline(always)]
fn min_where(mask: F32x8, values: F32x8) -> f32 {
    mask.blend(values, F32x8::splat(f32::INFINITY))
        .to_array()
        .into_iter()
        .fold(f32::INFINITY, f32::min)
}

/// The largest lane of `values`.
#[inline(always)]
fn max_lane(values: F32x8) -> f32 {
    values
        .to_array()
        .into_iter()
        .fold(f32::NEG_INFINITY, f32::max)
}

/// What a packet walk through a BVH asks: how far each lane's ray still matters, and what to
/// do at a leaf.
trait PacketQuery {
    /// Whether the answer depends on the order leaves are visited in, so the walk goes nearer
    /// child first and skips subtrees beyond every lane's limit (a nearest hit). An any-hit
    /// answer does not: its walk saves finding the nearer child.
    const ORDERED: bool;
    /// Per lane, the ray parameter beyond which nothing matters any more; −∞ for a lane that
    /// is finished (it then enters no box).
    fn limit(&self) -> F32x8;
    /// Tests the triangles in slots `first..end`; returns true when every lane is finished.
    fn leaf(&mut self, bvh: &Bvh, first: usize, end: usize) -> bool;
}

/// The nearest hit of each lane: the leaf test keeps the nearest triangle so far.
struct Nearest<'a> {
    packet: &'a RayPacket,
    object: u32,
    hits: &'a mut PacketHits,
}

impl PacketQuery for Nearest<'_> {
    const ORDERED: bool = true;

    #[inline(always)]
    fn limit(&self) -> F32x8 {
        self.hits.t
    }

    #[inline(always)]
    fn leaf(&mut self, bvh: &Bvh, first: usize, end: usize) -> bool {
        for k in first..end {
            self.packet
                .hit_triangle(&bvh.triangles[k], bvh.ids[k], self.object, self.hits);
        }
        false
    }
}

/// Any hit before each lane's `t_max`: a lane is finished once one triangle blocks it.
struct AnyHit<'a> {
    packet: &'a RayPacket,
    /// Segment ends, per lane.
    t_max: F32x8,
    /// Lanes still looking (all bits set) or finished (zero).
    pending: F32x8,
}

impl PacketQuery for AnyHit<'_> {
    const ORDERED: bool = false;

    #[inline(always)]
    fn limit(&self) -> F32x8 {
        self.pending
            .blend(self.t_max, F32x8::splat(f32::NEG_INFINITY))
    }

    #[inline(always)]
    fn leaf(&mut self, bvh: &Bvh, first: usize, end: usize) -> bool {
        for tri in &bvh.triangles[first..end] {
            let (found, _, _, _) = self.packet.meet_triangle(tri, self.t_max);
            self.pending &= !found;
            if !self.pending.any() {
                return true;
            }
        }
        false
    }
}

impl Bvh {
    /// Updates `hits` with the nearest triangle hits of `packet` in this BVH, the triangles
    /// belonging to object `object`. Children are visited nearer first (by the nearest entry of
    /// any lane), and a pending subtree is skipped once every lane has a hit before it.
    pub fn intersect_packet(&self, packet: &RayPacket, object: u32, hits: &mut PacketHits) {
        self.walk(
            packet,
            &mut Nearest {
                packet,
                object,
                hits,
            },
        );
    }

    /// The lanes of `pending` whose segment (t_min, `t_max`) meets a triangle: the shadow-ray
    /// test of eight rays at once, each lane stopping at its first blocker. Each lane's answer
    /// is [`Bvh::occluded`]'s for its ray alone.
    pub fn occluded_packet(&self, packet: &RayPacket, t_max: F32x8, pending: F32x8) -> F32x8 {
        let mut query = AnyHit {
            packet,
            t_max,
            pending,
        };
        self.walk(packet, &mut query);
        pending & !query.pending
    }

    /// Visits the leaves some lane of `packet` reaches within the query's limit, nearer child
    /// first (by the nearest entry of any lane), until the query says every lane is finished.
    #[inline(always)]
    fn walk<Q: PacketQuery>(&self, packet: &RayPacket, query: &mut Q) {
        let Some(root) = &self.root else {
            return;
        };
        if !packet.enter(root.lo(), root.hi(), query.limit()).0.any() {
            return;
        }
        // Pending far children: link (start, count) and the nearest entry of any lane.
        let mut stack = [(0u32, 0u32, 0f32); MAX_TREE_DEPTH];
        let mut top = 0;
        let mut current = (root.start(), root.count());
        loop {
            let (start, count) = current;
            if count > 0 {
                let first = start as usize;
                if query.leaf(self, first, first + count as usize) {
                    return;
                }
            } else {
                let [a, b] = &self.inner[start as usize].children;
                let limit = query.limit();
                let (hit_a, entry_a) = packet.enter(a.lo(), a.hi(), limit);
                let (hit_b, entry_b) = packet.enter(b.lo(), b.hi(), limit);
                match (hit_a.any(), hit_b.any()) {
                    (true, true) if !Q::ORDERED => {
                        stack[top] = (b.start(), b.count(), f32::NEG_INFINITY);
                        top += 1;
                        current = link(a);
                        continue;
                    }
                    (true, true) => {
                        let (near_a, near_b) =
                            (min_where(hit_a, entry_a), min_where(hit_b, entry_b));
                        let ((near, _), (far, far_entry)) = if near_a <= near_b {
                            ((a, near_a), (b, near_b))
                        } else {
                            ((b, near_b), (a, near_a))
                        };
                        stack[top] = (far.start(), far.count(), far_entry);
                        top += 1;
                        current = link(near);
                        continue;
                    }
                    (true, false) => {
                        current = link(a);
                        continue;
                    }
                    (false, true) => {
                        current = link(b);
                        continue;
                    }
                    (false, false) => {}
                }
            }
            // Next pending subtree that some lane can still reach before its limit.
            let farthest = if Q::ORDERED {
                max_lane(query.limit())
            } else {
                f32::INFINITY
            };
            loop {
                if top == 0 {
                    return;
                }
                top -= 1;
                let (start, count, entry) = stack[top];
                if entry <= farthest {
                    current = (start, count);
                    break;
                }
            }
        }
    }
}

/// A node's link: (start, count).
#[inline(always)]
fn link(node: &Node) -> (u32, u32) {
    (node.start(), node.count())
}
