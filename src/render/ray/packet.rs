//! Packets: eight coherent rays (neighbouring primary rays) traced through a BVH together.
//!
//! A node is fetched and its branch taken once for all eight rays, and the box and triangle
//! tests run on SIMD lanes, one ray per lane: the single-ray tests of [`super::intersect`], lane
//! by lane, so each lane finds the hit its ray would find alone. A subtree is entered when any
//! lane's ray reaches it before that lane's nearest hit so far.
//!
//! Deep in the tree of a dense mesh the rays of a packet part ways, and a leaf is often entered
//! by one or two of them. Such a leaf turns the test around: each ray that entered it meets up
//! to eight of its triangles at once (`super::triangle_lanes`), with the same bits.

use glam::Vec3A;
use std::ops::{Add, BitAnd, Div, Mul, Sub};

use wide::{CmpGe, CmpGt, CmpLe, CmpLt, u32x8};

use super::bvh::{Bvh, MAX_TREE_DEPTH, Node};
use super::half_line::TINY;
use super::intersect::Triangle;
use super::triangle_lanes::{RayLanes, TriangleLanes, meet};
use crate::render::prefetch;
use crate::render::simd::{F32x8, V3};

/// Eight rays `origin + t·dir`, t > `t_min`, one per lane.
#[derive(Debug, Clone, Copy)]
pub struct RayPacket {
    /// Start points, world units.
    pub origin: V3<F32x8>,
    /// Unit directions.
    pub dir: V3<F32x8>,
    /// Per-component 1/dir, finite (components smaller than [`TINY`] are nudged to it).
    pub(super) inv_dir: V3<F32x8>,
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
    /// Index of the triangle in the object's [`Bvh::triangles`] (meaningless where nothing was
    /// hit). Carried beside `triangle`, which `Bvh::ids[slot]` would give, so that neither the
    /// tracer's flat-mesh path (the BVH's triangle, by slot) nor its smooth-mesh path (the
    /// mesh's corners, by index) waits on a load the other needs.
    pub slot: u32x8,
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
            slot: u32x8::ZERO,
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
}

/// Whether a leaf of `triangles` triangles entered by the lanes of `lanes` tests each of those
/// rays against up to eight of its triangles at once, rather than each triangle against all
/// eight rays: when few lanes entered (at most 3), fewer than half as many as it has triangles.
/// 1 thread, median of 15, three alternations: the 1.31M-triangle icosphere at 640×360, whose
/// leaves are entered by 1.3–1.6 lanes on average, 33.2–34.3 → 29.5–30.1 ms; the bunny at
/// 1920×1080, 3.2–3.5 lanes per leaf, 81.5–82.3 → 81.5–83.7 ms (83.8–84.9 ms with the lane
/// count alone deciding). Criterion `ray_perf`, 2 threads, two alternations: icosphere 640×360
/// 16.8–17.8 → 14.8–15.1 ms, bunny 1920×1080 41.2–43.7 → 43.5–44.9 ms (the one loss: its
/// packets stay together, and one lane's test of a leaf is a longer chain of dependent steps
/// than several triangles' tests side by side).
#[inline(always)]
fn lanes_apart(lanes: u32, triangles: usize) -> bool {
    let entered = lanes.count_ones() as usize;
    entered <= 3 && 2 * entered < triangles
}

/// Eight `f32` lanes as the packet walk needs them: the `wide` type everywhere, and AVX2
/// registers where the CPU has them (`super::packet_avx2`). Both give the same bits: every
/// operation is one correctly rounded IEEE operation (no fused multiply-add), and the
/// comparisons, min and max behave alike on NaN (`minps`/`maxps` return the second operand).
pub(super) trait Lane8:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + BitAnd<Output = Self>
{
    /// From the `wide` lanes, bit for bit.
    fn from_wide(value: F32x8) -> Self;
    /// To the `wide` lanes, bit for bit.
    fn to_wide(self) -> F32x8;
    /// Every lane `value`.
    fn splat(value: f32) -> Self;
    /// `minps(self, other)`.
    fn min(self, other: Self) -> Self;
    /// `maxps(self, other)`.
    fn max(self, other: Self) -> Self;
    /// All bits set where `self < other` (false on NaN); likewise `le`, `gt`, `ge`.
    fn lt(self, other: Self) -> Self;
    /// See [`Lane8::lt`].
    fn le(self, other: Self) -> Self;
    /// See [`Lane8::lt`].
    fn gt(self, other: Self) -> Self;
    /// See [`Lane8::lt`].
    fn ge(self, other: Self) -> Self;
    /// `self` where `mask` is clear, zero where it is set.
    fn and_not(self, mask: Self) -> Self;
    /// `t` where `mask` (all bits set or clear per lane) is set, else `f`.
    fn select(mask: Self, t: Self, f: Self) -> Self;
    /// Whether any lane has its sign bit set.
    fn any(self) -> bool;
    /// The sign bits, lane k in bit k.
    fn bits(self) -> u32;

    /// The x, y and z of eight vectors, `rows[k]` in lane k.
    #[inline(always)]
    fn transpose(rows: [&Vec3A; 8]) -> Lanes3<Self> {
        let axis = |a: usize| Self::from_wide(F32x8::from(rows.map(|r| r[a])));
        [axis(0), axis(1), axis(2)]
    }

    /// `0 − self`, as `wide` negates.
    #[inline(always)]
    fn negate(self) -> Self {
        Self::splat(0.0) - self
    }

    /// The lanes in order.
    #[inline(always)]
    fn to_array(self) -> [f32; 8] {
        self.to_wide().to_array()
    }
}

impl Lane8 for F32x8 {
    #[inline(always)]
    fn from_wide(value: F32x8) -> F32x8 {
        value
    }
    #[inline(always)]
    fn to_wide(self) -> F32x8 {
        self
    }
    #[inline(always)]
    fn splat(value: f32) -> F32x8 {
        F32x8::splat(value)
    }
    #[inline(always)]
    fn min(self, other: F32x8) -> F32x8 {
        self.fast_min(other)
    }
    #[inline(always)]
    fn max(self, other: F32x8) -> F32x8 {
        self.fast_max(other)
    }
    #[inline(always)]
    fn lt(self, other: F32x8) -> F32x8 {
        self.cmp_lt(other)
    }
    #[inline(always)]
    fn le(self, other: F32x8) -> F32x8 {
        self.cmp_le(other)
    }
    #[inline(always)]
    fn gt(self, other: F32x8) -> F32x8 {
        self.cmp_gt(other)
    }
    #[inline(always)]
    fn ge(self, other: F32x8) -> F32x8 {
        self.cmp_ge(other)
    }
    #[inline(always)]
    fn and_not(self, mask: F32x8) -> F32x8 {
        self & !mask
    }
    #[inline(always)]
    fn select(mask: F32x8, t: F32x8, f: F32x8) -> F32x8 {
        mask.blend(t, f)
    }
    #[inline(always)]
    fn any(self) -> bool {
        F32x8::any(self)
    }
    #[inline(always)]
    fn bits(self) -> u32 {
        self.move_mask() as u32
    }
}

/// Three lane vectors: x, y, z.
pub(super) type Lanes3<L> = [L; 3];

/// `a · b`, summed x, y, z in that order (as [`V3::dot`]).
#[inline(always)]
pub(super) fn dot<L: Lane8>(a: Lanes3<L>, b: Lanes3<L>) -> L {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Every lane of each component from `v`.
#[inline(always)]
pub(super) fn splat3<L: Lane8>(v: Vec3A) -> Lanes3<L> {
    [L::splat(v.x), L::splat(v.y), L::splat(v.z)]
}

/// A [`RayPacket`] in the lanes `L` the walk runs on.
#[derive(Clone, Copy)]
struct Rays<L> {
    lanes: RayLanes<L>,
    inv_dir: Lanes3<L>,
    /// Each lane's ray on its own: origin x, y, z, direction x, y, z, |d|², t_min. A copy of
    /// `lanes` laid out for single lanes: broadcasting a lane out of the registers instead
    /// measured no faster (bunny 1920×1080, 2 threads, min of 21: 41.4–41.8 → 42.1–42.3 ms).
    each: [[f32; 8]; 8],
}

impl<L: Lane8> Rays<L> {
    /// `packet`'s rays, bit for bit.
    #[inline(always)]
    fn new(packet: &RayPacket) -> Rays<L> {
        let lanes = |v: V3<F32x8>| [L::from_wide(v.x), L::from_wide(v.y), L::from_wide(v.z)];
        let dir = lanes(packet.dir);
        let dir_len2 = dot(dir, dir);
        let [ox, oy, oz] = [packet.origin.x, packet.origin.y, packet.origin.z].map(F32x8::to_array);
        let [dx, dy, dz] = [packet.dir.x, packet.dir.y, packet.dir.z].map(F32x8::to_array);
        Rays {
            lanes: RayLanes {
                origin: lanes(packet.origin),
                dir,
                dir_len2,
                t_min: L::from_wide(packet.t_min),
            },
            inv_dir: lanes(packet.inv_dir),
            each: [
                ox,
                oy,
                oz,
                dx,
                dy,
                dz,
                dir_len2.to_array(),
                packet.t_min.to_array(),
            ],
        }
    }

    /// Lane `k`'s ray in every lane.
    #[inline(always)]
    fn one(&self, k: usize) -> RayLanes<L> {
        let e = |i: usize| L::splat(self.each[i][k]);
        RayLanes {
            origin: [e(0), e(1), e(2)],
            dir: [e(3), e(4), e(5)],
            dir_len2: e(6),
            t_min: e(7),
        }
    }

    /// Lane `k`'s ray on its own: origin, direction and t_min.
    #[inline(always)]
    fn alone(&self, k: usize) -> (Vec3A, Vec3A, f32) {
        let e = |i: usize| self.each[i][k];
        (
            Vec3A::new(e(0), e(1), e(2)),
            Vec3A::new(e(3), e(4), e(5)),
            e(7),
        )
    }

    /// Where each ray enters the box [lo, hi] within (t_min, `t_max`): the lanes that do, and
    /// their entry distances (the slab test of [`super::intersect::ray_box`]).
    #[inline(always)]
    fn enter(&self, lo: Vec3A, hi: Vec3A, t_max: L) -> (L, L) {
        let slab = |axis: usize, lo: f32, hi: f32| {
            let (o, inv) = (self.lanes.origin[axis], self.inv_dir[axis]);
            let (t1, t2) = ((L::splat(lo) - o) * inv, (L::splat(hi) - o) * inv);
            (t1.min(t2), t1.max(t2))
        };
        let (nx, fx) = slab(0, lo.x, hi.x);
        let (ny, fy) = slab(1, lo.y, hi.y);
        let (nz, fz) = slab(2, lo.z, hi.z);
        let near = nx.max(ny).max(nz).max(self.lanes.t_min);
        let far = fx.min(fy).min(fz).min(t_max);
        (near.le(far), near)
    }

    /// Where each lane's ray meets the triangle within (t_min, `t_max`): the lanes that do, and
    /// their t, u and v. Möller–Trumbore as [`Triangle::intersect`] does it, lane by lane, lanes
    /// near an edge decided again in `f64` as it decides them.
    #[inline(always)]
    fn meet_triangle(&self, tri: &Triangle, t_max: L) -> (L, L, L, L) {
        let m = meet(&self.lanes, &TriangleLanes::splat(tri), t_max);
        if m.edge.any() {
            return self.meet_near_edge(tri, t_max, m.edge, (m.found, m.t, m.u, m.v));
        }
        (m.found, m.t, m.u, m.v)
    }

    /// [`Rays::meet_triangle`]'s answer with the lanes of `edge` decided in `f64` by
    /// [`Triangle::intersect_exact`], as [`Triangle::intersect`] decides them.
    #[cold]
    #[inline(never)]
    fn meet_near_edge(
        &self,
        tri: &Triangle,
        t_max: L,
        edge: L,
        lanes: (L, L, L, L),
    ) -> (L, L, L, L) {
        let [mut found, mut t, mut u, mut v] =
            [lanes.0, lanes.1, lanes.2, lanes.3].map(L::to_array);
        let t_max = t_max.to_array();
        for k in set_bits(edge.bits()) {
            let (origin, dir, t_min) = self.alone(k);
            let hit = tri.intersect_exact(origin, dir, t_min, t_max[k]);
            found[k] = f32::from_bits(if hit.is_some() { u32::MAX } else { 0 });
            if let Some(h) = hit {
                (t[k], u[k], v[k]) = (h.t, h.u, h.v);
            }
        }
        let back = |a: [f32; 8]| L::from_wide(F32x8::from(a));
        (back(found), back(t), back(u), back(v))
    }
}

/// The indices of the set bits of `bits`, lowest first.
#[inline(always)]
fn set_bits(mut bits: u32) -> impl Iterator<Item = usize> {
    std::iter::from_fn(move || {
        (bits != 0).then(|| {
            let k = bits.trailing_zeros() as usize;
            bits &= bits - 1;
            k
        })
    })
}

/// [`PacketHits`] in the lanes `L`; the indices ride as bits in float lanes.
#[derive(Clone, Copy)]
struct LaneHits<L> {
    t: L,
    u: L,
    v: L,
    object: L,
    triangle: L,
    slot: L,
}

impl<L: Lane8> LaneHits<L> {
    /// `hits`, bit for bit.
    #[inline(always)]
    fn new(hits: &PacketHits) -> LaneHits<L> {
        LaneHits {
            t: L::from_wide(hits.t),
            u: L::from_wide(hits.u),
            v: L::from_wide(hits.v),
            object: L::from_wide(bytemuck::cast(hits.object)),
            triangle: L::from_wide(bytemuck::cast(hits.triangle)),
            slot: L::from_wide(bytemuck::cast(hits.slot)),
        }
    }

    /// Back to [`PacketHits`], bit for bit.
    #[inline(always)]
    fn store(&self, hits: &mut PacketHits) {
        hits.t = self.t.to_wide();
        hits.u = self.u.to_wide();
        hits.v = self.v.to_wide();
        hits.object = bytemuck::cast(self.object.to_wide());
        hits.triangle = bytemuck::cast(self.triangle.to_wide());
        hits.slot = bytemuck::cast(self.slot.to_wide());
    }

    /// Takes this triangle (in slot `slot`, mesh index `id` of object `object`) where it is
    /// nearer.
    #[inline(always)]
    fn add(&mut self, rays: &Rays<L>, tri: &Triangle, slot: usize, id: u32, object: u32) {
        let (found, t, u, v) = rays.meet_triangle(tri, self.t);
        if found.any() {
            self.t = L::select(found, t, self.t);
            self.u = L::select(found, u, self.u);
            self.v = L::select(found, v, self.v);
            self.triangle = L::select(found, L::splat(f32::from_bits(id)), self.triangle);
            self.object = L::select(found, L::splat(f32::from_bits(object)), self.object);
            self.slot = L::select(found, L::splat(f32::from_bits(slot as u32)), self.slot);
        }
    }
}

/// The smallest lane of `values` where `mask` holds (+∞ when none does).
#[inline(always)]
fn min_where<L: Lane8>(mask: L, values: L) -> f32 {
    L::select(mask, values, L::splat(f32::INFINITY))
        .to_array()
        .into_iter()
        .fold(f32::INFINITY, f32::min)
}

/// The largest lane of `values`.
#[inline(always)]
fn max_lane<L: Lane8>(values: L) -> f32 {
    values
        .to_array()
        .into_iter()
        .fold(f32::NEG_INFINITY, f32::max)
}

/// What a packet walk through a BVH asks: how far each lane's ray still matters, and what to
/// do at a leaf.
trait PacketQuery<L> {
    /// Whether the answer depends on the order leaves are visited in, so the walk goes nearer
    /// child first and skips subtrees beyond every lane's limit (a nearest hit). An any-hit
    /// answer does not: its walk saves finding the nearer child.
    const ORDERED: bool;
    /// Per lane, the ray parameter beyond which nothing matters any more; −∞ for a lane that
    /// is finished (it then enters no box).
    fn limit(&self) -> L;
    /// Tests the triangles in slots `first..end` for the lanes of `lanes` (bit k: lane k; the
    /// lanes that entered the leaf's box); returns true when every lane is finished.
    fn leaf(&mut self, bvh: &Bvh, first: usize, end: usize, lanes: u32) -> bool;
}

/// The nearest hit of each lane: the leaf test keeps the nearest triangle so far.
struct Nearest<'a, L> {
    rays: &'a Rays<L>,
    object: u32,
    hits: LaneHits<L>,
}

impl<L: Lane8> PacketQuery<L> for Nearest<'_, L> {
    const ORDERED: bool = true;

    #[inline(always)]
    fn limit(&self) -> L {
        self.hits.t
    }

    #[inline(always)]
    fn leaf(&mut self, bvh: &Bvh, first: usize, end: usize, lanes: u32) -> bool {
        if !lanes_apart(lanes, end - first) {
            for k in first..end {
                self.hits
                    .add(self.rays, &bvh.triangles[k], k, bvh.ids[k], self.object);
            }
            return false;
        }
        for start in (first..end).step_by(8) {
            let tris = TriangleLanes::gather(&bvh.triangles[start..end.min(start + 8)]);
            for k in set_bits(lanes) {
                self.lane_nearest(bvh, k, start, &tris);
            }
        }
        false
    }
}

impl<L: Lane8> Nearest<'_, L> {
    /// Lane `k`'s ray against the triangles of `tris` (slots `start..`, at most eight), the
    /// nearest kept: what testing them one by one in slot order gives, bit for bit.
    #[inline(always)]
    fn lane_nearest(&mut self, bvh: &Bvh, k: usize, start: usize, tris: &TriangleLanes<L>) {
        let ray = self.rays.one(k);
        let t_max = self.hits.t.to_array()[k];
        let m = meet(&ray, tris, L::splat(t_max));
        let edge = m.edge.bits();
        let candidates = m.found.bits() | edge;
        if candidates == 0 {
            return;
        }
        let (t, u, v) = (m.t.to_array(), m.u.to_array(), m.v.to_array());
        // One by one, each against the nearest so far: a triangle whose f32 t is not nearer
        // is neither a hit nor an edge case, as the test of that triangle alone finds.
        let mut nearest = t_max;
        let mut best = None;
        for j in set_bits(candidates) {
            // (t is not NaN: a candidate is not parallel, so det ≠ 0.)
            if t[j] >= nearest {
                continue;
            }
            let hit = if edge & (1 << j) != 0 {
                let (origin, dir, t_min) = self.rays.alone(k);
                bvh.triangles[start + j]
                    .intersect_exact(origin, dir, t_min, nearest)
                    .map(|h| (h.t, h.u, h.v))
            } else {
                Some((t[j], u[j], v[j]))
            };
            if let Some(h) = hit {
                nearest = h.0;
                best = Some((start + j, h));
            }
        }
        if let Some((slot, (t, u, v))) = best {
            let lane = lane_mask::<L>(1 << k);
            let set = |lanes: L, value: f32| L::select(lane, L::splat(value), lanes);
            let hits = &mut self.hits;
            hits.t = set(hits.t, t);
            hits.u = set(hits.u, u);
            hits.v = set(hits.v, v);
            hits.triangle = set(hits.triangle, f32::from_bits(bvh.ids[slot]));
            hits.object = set(hits.object, f32::from_bits(self.object));
            hits.slot = set(hits.slot, f32::from_bits(slot as u32));
        }
    }
}

/// All bits set in the lanes of `bits` (bit k: lane k), clear elsewhere.
#[inline(always)]
fn lane_mask<L: Lane8>(bits: u32) -> L {
    let lane_bits = u32x8::from([1, 2, 4, 8, 16, 32, 64, 128]);
    let set = (u32x8::splat(bits) & lane_bits).cmp_eq(lane_bits);
    L::from_wide(bytemuck::cast(set))
}

/// Any hit before each lane's `t_max`: a lane is finished once one triangle blocks it.
struct AnyHit<'a, L> {
    rays: &'a Rays<L>,
    /// Segment ends, per lane.
    t_max: L,
    /// Lanes still looking (all bits set) or finished (zero).
    pending: L,
}

impl<L: Lane8> PacketQuery<L> for AnyHit<'_, L> {
    const ORDERED: bool = false;

    #[inline(always)]
    fn limit(&self) -> L {
        L::select(self.pending, self.t_max, L::splat(f32::NEG_INFINITY))
    }

    #[inline(always)]
    fn leaf(&mut self, bvh: &Bvh, first: usize, end: usize, lanes: u32) -> bool {
        let lanes = lanes & self.pending.bits();
        if !lanes_apart(lanes, end - first) {
            for tri in &bvh.triangles[first..end] {
                let (found, _, _, _) = self.rays.meet_triangle(tri, self.t_max);
                self.pending = self.pending.and_not(found);
                if !self.pending.any() {
                    return true;
                }
            }
            return false;
        }
        for start in (first..end).step_by(8) {
            let tris = &bvh.triangles[start..end.min(start + 8)];
            let blocked = self.lanes_blocked(tris, lanes);
            if blocked != 0 {
                self.pending = self.pending.and_not(lane_mask::<L>(blocked));
                if !self.pending.any() {
                    return true;
                }
            }
        }
        false
    }
}

impl<L: Lane8> AnyHit<'_, L> {
    /// The lanes of `lanes` whose segment meets one of `tris` (at most eight), each lane's ray
    /// tested against all of them at once; bit k: lane k.
    #[inline(always)]
    fn lanes_blocked(&self, tris: &[Triangle], lanes: u32) -> u32 {
        let each = TriangleLanes::gather(tris);
        let t_max = self.t_max.to_array();
        let mut blocked = 0;
        for k in set_bits(lanes) {
            let m = meet(&self.rays.one(k), &each, L::splat(t_max[k]));
            // Lanes near an edge are decided in f64, whatever f32 found.
            let edge = m.edge.bits();
            let hit = m.found.bits() & !edge != 0
                || set_bits(edge).any(|j| {
                    let (origin, dir, t_min) = self.rays.alone(k);
                    tris[j]
                        .intersect_exact(origin, dir, t_min, t_max[k])
                        .is_some()
                });
            if hit {
                blocked |= 1 << k;
            }
        }
        blocked
    }
}

impl Bvh {
    /// Updates `hits` with the nearest triangle hits of `packet` in this BVH, the triangles
    /// belonging to object `object`. Children are visited nearer first (by the nearest entry of
    /// any lane), and a pending subtree is skipped once every lane has a hit before it.
    pub fn intersect_packet(&self, packet: &RayPacket, object: u32, hits: &mut PacketHits) {
        #[cfg(target_arch = "x86_64")]
        if super::packet_avx2::intersect_packet(self, packet, object, hits) {
            return;
        }
        self.nearest_in::<F32x8>(packet, object, hits);
    }

    /// The lanes of `pending` whose segment (t_min, `t_max`) meets a triangle: the shadow-ray
    /// test of eight rays at once, each lane stopping at its first blocker. Each lane's answer
    /// is [`Bvh::occluded`]'s for its ray alone.
    pub fn occluded_packet(&self, packet: &RayPacket, t_max: F32x8, pending: F32x8) -> F32x8 {
        #[cfg(target_arch = "x86_64")]
        if let Some(blocked) = super::packet_avx2::occluded_packet(self, packet, t_max, pending) {
            return blocked;
        }
        self.any_hit_in::<F32x8>(packet, t_max, pending)
    }

    /// [`Bvh::intersect_packet`] on lanes `L`.
    #[inline(always)]
    pub(super) fn nearest_in<L: Lane8>(
        &self,
        packet: &RayPacket,
        object: u32,
        hits: &mut PacketHits,
    ) {
        let rays = Rays::<L>::new(packet);
        let mut query = Nearest {
            rays: &rays,
            object,
            hits: LaneHits::new(hits),
        };
        self.walk(&rays, &mut query);
        query.hits.store(hits);
    }

    /// [`Bvh::occluded_packet`] on lanes `L`.
    #[inline(always)]
    pub(super) fn any_hit_in<L: Lane8>(
        &self,
        packet: &RayPacket,
        t_max: F32x8,
        pending: F32x8,
    ) -> F32x8 {
        let rays = Rays::<L>::new(packet);
        let mut query = AnyHit {
            rays: &rays,
            t_max: L::from_wide(t_max),
            pending: L::from_wide(pending),
        };
        self.walk(&rays, &mut query);
        pending & !query.pending.to_wide()
    }

    /// Visits the leaves some lane of `rays` reaches within the query's limit, nearer child
    /// first (by the nearest entry of any lane), until the query says every lane is finished.
    #[inline(always)]
    fn walk<L: Lane8, Q: PacketQuery<L>>(&self, rays: &Rays<L>, query: &mut Q) {
        let Some(root) = &self.root else {
            return;
        };
        let entered = rays.enter(root.lo(), root.hi(), query.limit()).0.bits();
        if entered == 0 {
            return;
        }
        // Pending far children: link (start, count), the nearest entry of any lane, and the
        // lanes that entered.
        let mut stack = [(0u32, 0u32, 0f32, 0u32); MAX_TREE_DEPTH];
        let mut top = 0;
        let mut current = (root.start(), root.count());
        let mut lanes = entered;
        loop {
            let (start, count) = current;
            if count > 0 {
                let first = start as usize;
                if query.leaf(self, first, first + count as usize, lanes) {
                    return;
                }
            } else {
                let [a, b] = &self.inner[start as usize].children;
                self.prefetch(a);
                self.prefetch(b);
                let limit = query.limit();
                let (hit_a, entry_a) = rays.enter(a.lo(), a.hi(), limit);
                let (hit_b, entry_b) = rays.enter(b.lo(), b.hi(), limit);
                let (lanes_a, lanes_b) = (hit_a.bits(), hit_b.bits());
                match (lanes_a != 0, lanes_b != 0) {
                    (true, true) if !Q::ORDERED => {
                        stack[top] = (b.start(), b.count(), f32::NEG_INFINITY, lanes_b);
                        top += 1;
                        (current, lanes) = (link(a), lanes_a);
                        continue;
                    }
                    (true, true) => {
                        let (near_a, near_b) =
                            (min_where(hit_a, entry_a), min_where(hit_b, entry_b));
                        let ((near, near_lanes), (far, far_entry, far_lanes)) = if near_a <= near_b
                        {
                            ((a, lanes_a), (b, near_b, lanes_b))
                        } else {
                            ((b, lanes_b), (a, near_a, lanes_a))
                        };
                        stack[top] = (far.start(), far.count(), far_entry, far_lanes);
                        top += 1;
                        (current, lanes) = (link(near), near_lanes);
                        continue;
                    }
                    (true, false) => {
                        (current, lanes) = (link(a), lanes_a);
                        continue;
                    }
                    (false, true) => {
                        (current, lanes) = (link(b), lanes_b);
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
                let (start, count, entry, entered) = stack[top];
                if entry <= farthest {
                    (current, lanes) = ((start, count), entered);
                    break;
                }
            }
        }
    }
}

impl Bvh {
    /// Hints that what `node` links to, its children or its first triangles, is read soon.
    #[inline(always)]
    fn prefetch(&self, node: &Node) {
        let start = node.start() as usize;
        if node.is_leaf() {
            // A triangle is one cache line.
            for tri in self
                .triangles
                .iter()
                .skip(start)
                .take(node.count() as usize)
            {
                prefetch::ahead(tri);
            }
            if let Some(id) = self.ids.get(start) {
                prefetch::ahead(id);
            }
        } else if let Some(inner) = self.inner.get(start) {
            prefetch::ahead(inner);
        }
    }
}

/// A node's link: (start, count).
#[inline(always)]
fn link(node: &Node) -> (u32, u32) {
    (node.start(), node.count())
}
