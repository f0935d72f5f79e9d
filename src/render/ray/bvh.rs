//! A bounding volume hierarchy over one mesh's triangles: inner nodes in depth-first order, each
//! holding the boxes of both its children in one 64-byte cache line (a visit tests both boxes
//! with one memory access), and the triangles copied in leaf order, so a leaf's triangles sit
//! side by side in memory.
//!
//! The tree is built by `bvh_build` (binned surface-area heuristic). Traversal visits the nearer
//! child first and skips any node that starts beyond the nearest hit found so far.

use glam::{Vec3, Vec3A, Vec4};

use super::bvh_build;
use super::half_line::Ray;
use super::intersect::{Triangle, ray_box};
use crate::mesh::Mesh;
use crate::render::progress::{Cancelled, Progress};

/// The deepest tree the builder makes; a node at this depth becomes a leaf whatever its size.
/// It bounds the traversal stack.
pub const MAX_TREE_DEPTH: usize = 60;
/// Stack entries for trees of at most this depth (meshes up to thousands of triangles).
const SMALL_STACK: usize = 16;

/// A box and what it holds: a run of triangles (a leaf) or an inner node. 32 bytes; the link
/// rides in the otherwise unused fourth lanes so the box loads as whole SIMD registers.
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C, align(32))]
pub struct Node {
    /// Box minimum corner (world units) in x, y, z; `start` as bits in w.
    lo: Vec4,
    /// Box maximum corner (world units) in x, y, z; `count` as bits in w.
    hi: Vec4,
}

/// An inner node: its two children, boxes included. One cache line.
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C, align(64))]
pub struct Inner {
    pub children: [Node; 2],
}

impl Node {
    /// A node over the box [lo, hi]; see [`Node::start`] and [`Node::count`].
    #[inline]
    pub fn new(lo: Vec3, hi: Vec3, start: u32, count: u32) -> Node {
        Node {
            lo: lo.extend(f32::from_bits(start)),
            hi: hi.extend(f32::from_bits(count)),
        }
    }

    /// Box minimum corner, world units.
    #[inline]
    pub fn lo(&self) -> Vec3A {
        Vec3A::from_vec4(self.lo)
    }

    /// Box maximum corner, world units.
    #[inline]
    pub fn hi(&self) -> Vec3A {
        Vec3A::from_vec4(self.hi)
    }

    /// Leaf: index of its first triangle. Inner node: its index in [`Bvh::inner`] (while
    /// building: the offset from this node to its second child in the depth-first node list,
    /// the first child following its parent).
    #[inline]
    pub fn start(&self) -> u32 {
        self.lo.w.to_bits()
    }

    /// Number of triangles; 0 marks an inner node.
    #[inline]
    pub fn count(&self) -> u32 {
        self.hi.w.to_bits()
    }

    /// Sets [`Node::start`].
    #[inline]
    pub fn set_start(&mut self, start: u32) {
        self.lo.w = f32::from_bits(start);
    }

    /// Whether the node holds triangles rather than children.
    #[inline]
    pub fn is_leaf(&self) -> bool {
        self.count() > 0
    }

    #[inline]
    fn entry(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<f32> {
        ray_box(ray, self.lo(), self.hi(), t_min, t_max)
    }
}

/// The nearest hit in one mesh.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BvhHit {
    /// Ray parameter of the hit.
    pub t: f32,
    /// Barycentric weight of the triangle's second vertex.
    pub u: f32,
    /// Barycentric weight of the triangle's third vertex.
    pub v: f32,
    /// Index of the triangle in the mesh.
    pub triangle: u32,
    /// Index of the triangle in [`Bvh::triangles`].
    pub slot: u32,
}

/// A BVH over one mesh. Invariant: every triangle of the mesh is in exactly one leaf.
#[derive(Debug, Clone, Default)]
pub struct Bvh {
    /// The root's box and link; `None` for a mesh without triangles.
    pub root: Option<Node>,
    /// Inner nodes in depth-first order.
    pub inner: Vec<Inner>,
    /// Triangles in leaf order.
    pub triangles: Vec<Triangle>,
    /// The mesh index of each entry of `triangles`.
    pub ids: Vec<u32>,
    /// Levels of the tree: 1 for a single leaf, 0 when empty; at most [`MAX_TREE_DEPTH`].
    pub depth: usize,
}

impl Bvh {
    /// Builds the hierarchy over `mesh` (in parallel for large meshes).
    #[cfg(test)]
    pub fn build(mesh: &Mesh) -> Bvh {
        bvh_build::build(mesh, &Progress::new()).expect("a fresh progress is never cancelled")
    }

    /// [`Bvh::build`], abandoned once `progress` is cancelled.
    pub fn build_cancellable(mesh: &Mesh, progress: &Progress) -> Result<Bvh, Cancelled> {
        bvh_build::build(mesh, progress)
    }

    /// Levels of the tree walked from the root: 1 for a single leaf, 0 when empty.
    #[cfg(test)]
    pub fn measure_depth(&self) -> usize {
        fn depth_at(bvh: &Bvh, n: &Node) -> usize {
            if n.is_leaf() {
                1
            } else {
                let [a, b] = &bvh.inner[n.start() as usize].children;
                1 + depth_at(bvh, a).max(depth_at(bvh, b))
            }
        }
        self.root.as_ref().map_or(0, |r| depth_at(self, r))
    }

    /// The nearest triangle hit with t in (t_min, t_max).
    pub fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<BvhHit> {
        let mut best: Option<BvhHit> = None;
        let mut t_max = t_max;
        self.traverse(ray, t_min, &mut t_max, |k, t_max| {
            let tri = &self.triangles[k];
            if let Some(h) = tri.intersect(ray, t_min, *t_max) {
                *t_max = h.t;
                best = Some(BvhHit {
                    t: h.t,
                    u: h.u,
                    v: h.v,
                    triangle: self.ids[k],
                    slot: k as u32,
                });
            }
            false
        });
        best
    }

    /// Whether any triangle is hit with t in (t_min, t_max): the shadow-ray test.
    ///
    /// Kept out of line, a function of its own as it always was: inlined into the tracer's
    /// shadow test, the same machine code ran the default scene 8% slower or faster depending
    /// only on the address the linker gave it.
    #[inline(never)]
    pub fn occluded(&self, ray: &Ray, t_min: f32, t_max: f32) -> bool {
        let mut t_max = t_max;
        self.traverse(ray, t_min, &mut t_max, |k, t_max| {
            self.triangles[k].intersect(ray, t_min, *t_max).is_some()
        })
    }

    /// Visits the leaves the ray segment reaches, nearer child first, calling `visit(triangle
    /// slot, t_max)` for each of their triangles; `visit` may shrink `t_max` and returns true
    /// to stop. Returns whether it was stopped.
    #[inline]
    fn traverse(
        &self,
        ray: &Ray,
        t_min: f32,
        t_max: &mut f32,
        visit: impl FnMut(usize, &mut f32) -> bool,
    ) -> bool {
        // A stack just deep enough: small meshes do not pay for clearing a large one per ray.
        if self.depth <= SMALL_STACK {
            self.traverse_with::<SMALL_STACK>(ray, t_min, t_max, visit)
        } else {
            self.traverse_with::<{ MAX_TREE_DEPTH }>(ray, t_min, t_max, visit)
        }
    }

    /// [`Bvh::traverse`] with a stack of `N` ≥ depth − 1 entries.
    #[inline]
    fn traverse_with<const N: usize>(
        &self,
        ray: &Ray,
        t_min: f32,
        t_max: &mut f32,
        mut visit: impl FnMut(usize, &mut f32) -> bool,
    ) -> bool {
        let Some(root) = &self.root else {
            return false;
        };
        let Some(entry) = root.entry(ray, t_min, *t_max) else {
            return false;
        };
        // Pending far children: link (start, count) and entry distance; their boxes are tested.
        let mut stack = [(0u32, 0u32, 0f32); N];
        let mut top = 0;
        let mut current = (root.start(), root.count(), entry);
        loop {
            let (start, count, entry) = current;
            if entry <= *t_max {
                if count > 0 {
                    let first = start as usize;
                    for k in first..first + count as usize {
                        if visit(k, t_max) {
                            return true;
                        }
                    }
                } else {
                    let [a, b] = &self.inner[start as usize].children;
                    let ta = a.entry(ray, t_min, *t_max);
                    let tb = b.entry(ray, t_min, *t_max);
                    match (ta, tb) {
                        (Some(ta), Some(tb)) => {
                            let (near, far) = if ta <= tb {
                                ((a, ta), (b, tb))
                            } else {
                                ((b, tb), (a, ta))
                            };
                            stack[top] = (far.0.start(), far.0.count(), far.1);
                            top += 1;
                            current = (near.0.start(), near.0.count(), near.1);
                            continue;
                        }
                        (Some(ta), None) => {
                            current = (a.start(), a.count(), ta);
                            continue;
                        }
                        (None, Some(tb)) => {
                            current = (b.start(), b.count(), tb);
                            continue;
                        }
                        (None, None) => {}
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
