//! Building a [`Bvh`] top-down with the binned surface-area heuristic.
//!
//! Each node sorts its triangles' centroids into [`BINS`] bins per axis, prices every split
//! between bins by the surface-area heuristic (expected cost of a random ray through the node),
//! and partitions in place at the cheapest one. Large nodes bin in parallel and build their two
//! children with `rayon::join`; the result is the same for any number of threads because every
//! split depends only on the triangles, never on scheduling.

use glam::{Vec3, Vec3A};
use rayon::prelude::*;

use super::bvh::{Bvh, MAX_TREE_DEPTH, Node};
use super::intersect::Triangle;
use crate::mesh::Mesh;

/// Centroid bins per axis.
const BINS: usize = 16;
/// A node with at most this many triangles may become a leaf when the heuristic says so.
const MAX_LEAF: usize = 8;
/// Cost of visiting a node, relative to one ray/triangle test.
const TRAVERSAL_COST: f32 = 1.0;
/// Nodes with at least this many triangles bin in parallel and build their children in parallel.
const PARALLEL_MIN: usize = 16 * 1024;
/// Triangles per parallel binning task.
const CHUNK: usize = 8 * 1024;

/// A triangle during the build: its box and mesh index.
#[derive(Debug, Clone, Copy)]
struct Prim {
    lo: Vec3A,
    hi: Vec3A,
    index: u32,
}

impl Prim {
    /// Twice the box centre: binning only needs positions relative to each other.
    #[inline]
    fn centroid2(&self) -> Vec3A {
        self.lo + self.hi
    }
}

/// An axis-aligned box; empty when lo > hi.
#[derive(Debug, Clone, Copy)]
struct Aabb {
    lo: Vec3A,
    hi: Vec3A,
}

impl Aabb {
    const EMPTY: Aabb = Aabb {
        lo: Vec3A::INFINITY,
        hi: Vec3A::NEG_INFINITY,
    };

    #[inline]
    fn grow(&mut self, lo: Vec3A, hi: Vec3A) {
        self.lo = self.lo.min(lo);
        self.hi = self.hi.max(hi);
    }

    #[inline]
    fn union(self, other: Aabb) -> Aabb {
        Aabb {
            lo: self.lo.min(other.lo),
            hi: self.hi.max(other.hi),
        }
    }

    /// Half the surface area (the heuristic only compares ratios); 0 when empty.
    #[inline]
    fn half_area(&self) -> f32 {
        let d = (self.hi - self.lo).max(Vec3A::ZERO);
        d.x * d.y + d.y * d.z + d.z * d.x
    }
}

/// Triangle boxes and centroid box of a run of prims.
#[derive(Debug, Clone, Copy)]
struct Extent {
    bounds: Aabb,
    centroids: Aabb,
}

impl Extent {
    const EMPTY: Extent = Extent {
        bounds: Aabb::EMPTY,
        centroids: Aabb::EMPTY,
    };

    fn of(prims: &[Prim]) -> Extent {
        let seq = |prims: &[Prim]| {
            prims.iter().fold(Extent::EMPTY, |mut e, p| {
                e.bounds.grow(p.lo, p.hi);
                let c = p.centroid2();
                e.centroids.grow(c, c);
                e
            })
        };
        if prims.len() < PARALLEL_MIN {
            return seq(prims);
        }
        prims.par_chunks(CHUNK).map(seq).reduce(
            || Extent::EMPTY,
            |a, b| Extent {
                bounds: a.bounds.union(b.bounds),
                centroids: a.centroids.union(b.centroids),
            },
        )
    }
}

/// Centroid counts and boxes of one axis' bins.
#[derive(Debug, Clone, Copy)]
struct Bins {
    bounds: [[Aabb; BINS]; 3],
    counts: [[u32; BINS]; 3],
}

impl Bins {
    fn empty() -> Bins {
        Bins {
            bounds: [[Aabb::EMPTY; BINS]; 3],
            counts: [[0; BINS]; 3],
        }
    }

    fn merge(mut self, other: Bins) -> Bins {
        for axis in 0..3 {
            for b in 0..BINS {
                self.bounds[axis][b] = self.bounds[axis][b].union(other.bounds[axis][b]);
                self.counts[axis][b] += other.counts[axis][b];
            }
        }
        self
    }
}

/// Maps a centroid to its bin on each axis. Axes without extent put everything in bin 0.
#[derive(Debug, Clone, Copy)]
struct Binning {
    origin: Vec3A,
    scale: Vec3A,
}

impl Binning {
    fn new(centroids: &Aabb) -> Binning {
        let extent = centroids.hi - centroids.lo;
        let scale = Vec3A::select(
            extent.cmpgt(Vec3A::ZERO),
            Vec3A::splat(BINS as f32) / extent,
            Vec3A::ZERO,
        );
        Binning {
            origin: centroids.lo,
            scale,
        }
    }

    #[inline]
    fn bins(&self, p: &Prim) -> [usize; 3] {
        let f = (p.centroid2() - self.origin) * self.scale;
        f.to_array().map(|x| (x as usize).min(BINS - 1))
    }

    fn fill(&self, prims: &[Prim]) -> Bins {
        let seq = |prims: &[Prim]| {
            let mut bins = Bins::empty();
            for p in prims {
                for (axis, b) in self.bins(p).into_iter().enumerate() {
                    bins.bounds[axis][b].grow(p.lo, p.hi);
                    bins.counts[axis][b] += 1;
                }
            }
            bins
        };
        if prims.len() < PARALLEL_MIN {
            return seq(prims);
        }
        prims
            .par_chunks(CHUNK)
            .map(seq)
            .reduce(Bins::empty, Bins::merge)
    }
}

/// A split: triangles whose centroid falls in bins `0..=bin` of `axis` go left.
#[derive(Debug, Clone, Copy)]
struct Split {
    axis: usize,
    bin: usize,
    /// Heuristic cost, in triangle tests.
    cost: f32,
}

/// The cheapest split that leaves both sides non-empty, if any.
fn best_split(bins: &Bins, parent_area: f32) -> Option<Split> {
    let mut best: Option<Split> = None;
    for axis in 0..3 {
        // Sweep from the right: area × count of bins b.. for each b.
        let mut right_cost = [0f32; BINS];
        let mut right_count = [0u32; BINS];
        let (mut acc, mut count) = (Aabb::EMPTY, 0);
        for b in (1..BINS).rev() {
            acc = acc.union(bins.bounds[axis][b]);
            count += bins.counts[axis][b];
            right_cost[b] = acc.half_area() * count as f32;
            right_count[b] = count;
        }
        let (mut acc, mut count) = (Aabb::EMPTY, 0);
        for b in 0..BINS - 1 {
            acc = acc.union(bins.bounds[axis][b]);
            count += bins.counts[axis][b];
            if count == 0 || right_count[b + 1] == 0 {
                continue;
            }
            let cost = TRAVERSAL_COST
                + (acc.half_area() * count as f32 + right_cost[b + 1])
                    / parent_area.max(f32::MIN_POSITIVE);
            if best.is_none_or(|s| cost < s.cost) {
                best = Some(Split { axis, bin: b, cost });
            }
        }
    }
    best
}

/// Moves the prims satisfying `left` to the front; returns how many there are.
fn partition(prims: &mut [Prim], left: impl Fn(&Prim) -> bool) -> usize {
    let (mut i, mut j) = (0, prims.len());
    while i < j {
        if left(&prims[i]) {
            i += 1;
        } else {
            j -= 1;
            prims.swap(i, j);
        }
    }
    i
}

/// Builds the hierarchy over `mesh`.
pub fn build(mesh: &Mesh) -> Bvh {
    let mut prims: Vec<Prim> = (0..mesh.triangles.len())
        .into_par_iter()
        .with_min_len(4096)
        .map(|t| {
            let [a, b, c] = mesh.corners(t).map(Vec3A::from);
            Prim {
                lo: a.min(b).min(c),
                hi: a.max(b).max(c),
                index: t as u32,
            }
        })
        .collect();
    if prims.is_empty() {
        return Bvh::default();
    }
    let mut nodes = Vec::with_capacity(prims.len() / 2);
    build_node(&mut prims, 0, 0, &mut nodes);
    let triangles = prims
        .par_iter()
        .with_min_len(4096)
        .map(|p| {
            let [a, b, c] = mesh.corners(p.index as usize);
            Triangle::new(a, b, c)
        })
        .collect();
    let ids = prims.iter().map(|p| p.index).collect();
    Bvh {
        nodes,
        triangles,
        ids,
    }
}

/// Appends the subtree over `prims` (which start at slot `first` of the final order) to `out`.
fn build_node(prims: &mut [Prim], first: usize, depth: usize, out: &mut Vec<Node>) {
    let extent = Extent::of(prims);
    let me = out.len();
    out.push(Node {
        lo: Vec3::from(extent.bounds.lo),
        start: first as u32,
        hi: Vec3::from(extent.bounds.hi),
        count: prims.len() as u32,
    });
    let n = prims.len();
    if n <= 2 || depth + 1 >= MAX_TREE_DEPTH {
        return;
    }
    let binning = Binning::new(&extent.centroids);
    let split = best_split(&binning.fill(prims), extent.bounds.half_area());
    let mid = match split {
        Some(s) if n > MAX_LEAF || s.cost < n as f32 => {
            partition(prims, |p| binning.bins(p)[s.axis] <= s.bin)
        }
        // All centroids coincide: any halving is as good as another.
        None if n > MAX_LEAF => n / 2,
        _ => return,
    };
    out[me].count = 0;
    let (left, right) = prims.split_at_mut(mid);
    if n >= PARALLEL_MIN {
        let (l, r) = rayon::join(
            || subtree(left, first, depth + 1),
            || subtree(right, first + mid, depth + 1),
        );
        out[me].start = 1 + l.len() as u32;
        out.extend_from_slice(&l);
        out.extend_from_slice(&r);
    } else {
        build_node(left, first, depth + 1, out);
        out[me].start = (out.len() - me) as u32;
        build_node(right, first + mid, depth + 1, out);
    }
}

/// The subtree over `prims` as its own node list (child links are relative, so it can be
/// appended anywhere).
fn subtree(prims: &mut [Prim], first: usize, depth: usize) -> Vec<Node> {
    let mut out = Vec::with_capacity(prims.len() / 2);
    build_node(prims, first, depth, &mut out);
    out
}
