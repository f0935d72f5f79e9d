//! The top level of the scene's two-level BVH (Embree's instances over meshes): a binary tree
//! over the objects' boxes whose leaves name objects, each of which has its own triangle BVH.
//! A ray visits only the objects whose boxes it enters, nearer first, so the cost grows with the
//! logarithm of the object count rather than with the count.
//!
//! The walks only choose which objects to visit and in what order; what happens at an object
//! (its bounding-sphere cull, its triangle BVH, the rule that breaks ties) is the caller's
//! closure, so the answers stay those of the flat loop over all objects.

use std::cell::Cell;

use glam::Vec3A;
use wide::{CmpGe, CmpLe};

use super::half_line::Ray;
use super::intersect::ray_box;
use super::packet::RayPacket;
use crate::render::simd::{F32x8, V3};

/// Most objects in a leaf.
const LEAF_OBJECTS: usize = 2;
/// Stack entries of a walk: the tree splits at the median, so its depth is at most
/// log2(objects) + 1, and u32 object indices bound that by 33.
const STACK: usize = 64;

/// A box and what it holds: objects `order[start..start + count]` (a leaf), or, when `count`
/// is 0, two children at `nodes[start]` and `nodes[start + 1]`.
#[derive(Debug, Clone, Copy)]
struct TopNode {
    /// Box minimum corner, world units.
    lo: Vec3A,
    /// Box maximum corner, world units.
    hi: Vec3A,
    start: u32,
    count: u32,
}

/// A box per object, as the tree is built from: `None` for an object without triangles, which
/// no ray can hit and the tree leaves out.
pub type ObjectBox = Option<(Vec3A, Vec3A)>;

/// The tree over the objects. Invariant: every object with a box is in exactly one leaf, and
/// every node's box holds its objects' boxes.
#[derive(Debug, Clone, Default)]
pub struct TopLevel {
    /// The root first; children in adjacent pairs.
    nodes: Vec<TopNode>,
    /// Object indices in leaf order.
    order: Vec<u32>,
}

impl TopLevel {
    /// Builds the tree over `boxes` (one per object, in world order): each node splits its
    /// objects at the median of their box centres along the widest axis of those centres.
    /// O(n log n) in the object count.
    pub fn build(boxes: &[ObjectBox]) -> TopLevel {
        let mut order: Vec<u32> = (0..boxes.len() as u32)
            .filter(|&i| boxes[i as usize].is_some())
            .collect();
        let mut top = TopLevel {
            nodes: Vec::with_capacity(2 * order.len() / LEAF_OBJECTS + 1),
            order: Vec::new(),
        };
        if order.is_empty() {
            return top;
        }
        let boxes: Vec<(Vec3A, Vec3A)> = boxes.iter().map(|b| b.unwrap_or_default()).collect();
        top.nodes.push(TopNode {
            lo: Vec3A::ZERO,
            hi: Vec3A::ZERO,
            start: 0,
            count: 0,
        });
        // (node index, objects order[first..end]) still to fill in.
        let mut pending = vec![(0usize, 0usize, order.len())];
        while let Some((node, first, end)) = pending.pop() {
            let objects = &mut order[first..end];
            let (lo, hi) =
                objects
                    .iter()
                    .fold((Vec3A::INFINITY, Vec3A::NEG_INFINITY), |(lo, hi), &i| {
                        let (a, b) = boxes[i as usize];
                        (lo.min(a), hi.max(b))
                    });
            if objects.len() <= LEAF_OBJECTS {
                // Leaves keep world order, as the flat loop had it.
                objects.sort_unstable();
                top.nodes[node] = TopNode {
                    lo,
                    hi,
                    start: first as u32,
                    count: objects.len() as u32,
                };
                continue;
            }
            let centre = |i: u32| {
                let (a, b) = boxes[i as usize];
                a + b
            };
            let (c_lo, c_hi) = objects
                .iter()
                .fold((Vec3A::INFINITY, Vec3A::NEG_INFINITY), |(lo, hi), &i| {
                    (lo.min(centre(i)), hi.max(centre(i)))
                });
            let extent = c_hi - c_lo;
            let axis = if extent.x >= extent.y && extent.x >= extent.z {
                0
            } else if extent.y >= extent.z {
                1
            } else {
                2
            };
            let half = objects.len() / 2;
            objects.select_nth_unstable_by(half, |&a, &b| {
                centre(a)[axis].total_cmp(&centre(b)[axis]).then(a.cmp(&b))
            });
            let children = top.nodes.len();
            let blank = top.nodes[node];
            top.nodes.push(blank);
            top.nodes.push(blank);
            top.nodes[node] = TopNode {
                lo,
                hi,
                start: children as u32,
                count: 0,
            };
            pending.push((children, first, first + half));
            pending.push((children + 1, first + half, end));
        }
        top.order = order;
        top
    }

    /// Visits the objects whose boxes the segment (t_min, `t_max`) of `ray` enters, nearer box
    /// first, skipping boxes that start beyond `t_max`; `visit(object, t_max)` may shrink
    /// `t_max` (a nearer hit) and returns true to stop. Returns whether it was stopped.
    #[inline]
    pub fn walk_ray(
        &self,
        ray: &Ray,
        t_min: f32,
        t_max: &mut f32,
        mut visit: impl FnMut(u32, &mut f32) -> bool,
    ) -> bool {
        let limit = Cell::new(*t_max);
        let stopped = self.walk(
            |node| ray_box(ray, node.lo, node.hi, t_min, limit.get()),
            |entry| entry <= limit.get(),
            |object| {
                let mut t = limit.get();
                let stop = visit(object, &mut t);
                limit.set(t);
                stop
            },
        );
        *t_max = limit.get();
        stopped
    }

    /// Visits the objects whose boxes some lane of `packet` enters before its `limit()` (−∞ for
    /// a finished lane), nearer box first by the nearest entry of any lane, skipping boxes every
    /// lane enters beyond its limit; `visit(object)` returns true to stop. The limits are read
    /// again at every box, so a hit found in one object prunes the rest.
    #[inline]
    pub fn walk_packet(
        &self,
        packet: &RayPacket,
        limit: impl Fn() -> F32x8,
        visit: impl FnMut(u32) -> bool,
    ) {
        self.walk(
            |node| enter_lanes(packet, node, limit()),
            |entry| limit().cmp_ge(F32x8::splat(entry)).any(),
            visit,
        );
    }

    /// The walk both queries share: from the root, each inner node's children that `enter`
    /// gives an entry distance for, nearer first, the farther one kept on a stack; a node taken
    /// from the stack is skipped unless `wanted(entry)` still holds (the hits found since may
    /// lie before it). Leaves' objects go to `visit` in world order; true stops the walk, and
    /// is returned.
    #[inline(always)]
    fn walk(
        &self,
        enter: impl Fn(&TopNode) -> Option<f32>,
        wanted: impl Fn(f32) -> bool,
        mut visit: impl FnMut(u32) -> bool,
    ) -> bool {
        let Some(root) = self.nodes.first() else {
            return false;
        };
        let Some(entry) = enter(root) else {
            return false;
        };
        let mut stack = [(0u32, 0f32); STACK];
        let mut top = 0;
        let mut current = (0u32, entry);
        loop {
            let (index, entry) = current;
            let node = &self.nodes[index as usize];
            if wanted(entry) {
                if node.count > 0 {
                    let first = node.start as usize;
                    for &object in &self.order[first..first + node.count as usize] {
                        if visit(object) {
                            return true;
                        }
                    }
                } else {
                    let (a, b) = (node.start, node.start + 1);
                    let ta = enter(&self.nodes[a as usize]).map(|t| (a, t));
                    let tb = enter(&self.nodes[b as usize]).map(|t| (b, t));
                    let (near, far) = match (ta, tb) {
                        (Some(ta), Some(tb)) if tb.1 < ta.1 => (Some(tb), Some(ta)),
                        (Some(ta), tb) => (Some(ta), tb),
                        (None, tb) => (tb, None),
                    };
                    if let Some(far) = far {
                        stack[top] = far;
                        top += 1;
                    }
                    if let Some(near) = near {
                        current = near;
                        continue;
                    }
                }
            }
            if top == 0 {
                return false;
            }
            top -= 1;
            current = stack[top];
        }
    }
}

/// The nearest entry, over the lanes that enter `node`'s box within (t_min, `t_max`), or
/// `None` when no lane does (slab test, eight rays at once).
#[inline(always)]
fn enter_lanes(packet: &RayPacket, node: &TopNode, t_max: F32x8) -> Option<f32> {
    let slab = |corner: Vec3A| {
        let d = V3::splat(glam::Vec3::from(corner)) - packet.origin;
        V3::new(
            d.x * packet.inv_dir.x,
            d.y * packet.inv_dir.y,
            d.z * packet.inv_dir.z,
        )
    };
    let (t1, t2) = (slab(node.lo), slab(node.hi));
    let near =
        t1.x.fast_min(t2.x)
            .fast_max(t1.y.fast_min(t2.y))
            .fast_max(t1.z.fast_min(t2.z))
            .fast_max(packet.t_min);
    let far =
        t1.x.fast_max(t2.x)
            .fast_min(t1.y.fast_max(t2.y))
            .fast_min(t1.z.fast_max(t2.z))
            .fast_min(t_max);
    let entered = near.cmp_le(far);
    if !entered.any() {
        return None;
    }
    Some(
        entered
            .blend(near, F32x8::splat(f32::INFINITY))
            .to_array()
            .into_iter()
            .fold(f32::INFINITY, f32::min),
    )
}
