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
    /// Bins in use, 2..=BINS: small nodes use fewer, which keeps their setup cheap.
    count: usize,
}

impl Binning {
    fn new(centroids: &Aabb, prims: usize) -> Binning {
        let count = prims.clamp(2, BINS);
        let extent = centroids.hi - centroids.lo;
        let scale = Vec3A::select(
            extent.cmpgt(Vec3A::ZERO),
            Vec3A::splat(count as f32) / extent,
            Vec3A::ZERO,
        );
        Binning {
            origin: centroids.lo,
            scale,
            count,
        }
    }

    /// The prim's bin on each axis.
    #[inline]
    fn bins(&self, p: &Prim) -> [usize; 3] {
        let f = (p.centroid2() - self.origin) * self.scale;
        let top = (self.count - 1) as f32;
        // f ≥ 0 by construction; clamping first makes the conversion a plain truncation.
        f.min(Vec3A::splat(top))
            .as_uvec3()
            .to_array()
            .map(|b| b as usize)
    }

    /// The prim's bin on one axis: the same arithmetic as [`Binning::bins`], one lane of it.
    #[inline]
    fn bin(&self, p: &Prim, axis: usize) -> usize {
        let f = (p.centroid2()[axis] - self.origin[axis]) * self.scale[axis];
        f.min((self.count - 1) as f32) as u32 as usize
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
fn best_split(bins: &Bins, used: usize, parent_area: f32) -> Option<Split> {
    let mut best: Option<Split> = None;
    for axis in 0..3 {
        // Sweep from the right: area × count of bins b.. for each b.
        let mut right_cost = [0f32; BINS];
        let mut right_count = [0u32; BINS];
        let (mut acc, mut count) = (Aabb::EMPTY, 0);
        for b in (1..used).rev() {
            acc = acc.union(bins.bounds[axis][b]);
            count += bins.counts[axis][b];
            right_cost[b] = acc.half_area() * count as f32;
            right_count[b] = count;
        }
        let (mut acc, mut count) = (Aabb::EMPTY, 0);
        for b in 0..used - 1 {
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
    let nodes = build_chunks(&mut prims, 0, 0).concat();
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
        depth: Bvh::measure_depth(&nodes),
        nodes,
        triangles,
        ids,
    }
}

/// The subtree over `prims` (which start at slot `first` of the final order), as node runs to
/// be concatenated: a large node is split in parallel and its children's runs follow its own, so
/// the nodes are copied once at the end rather than once per level.
fn build_chunks(prims: &mut [Prim], first: usize, depth: usize) -> Vec<Vec<Node>> {
    let n = prims.len();
    if n < PARALLEL_MIN {
        // Upper bound of a binary tree with n leaves: the run never reallocates.
        let mut out = Vec::with_capacity(2 * n);
        build_node(prims, first, depth, &mut out);
        return vec![out];
    }
    let mut me = Vec::new();
    let Some((node, mid)) = split_node(prims, first, depth, &mut me) else {
        return vec![me];
    };
    let (left, right) = prims.split_at_mut(mid);
    let (l, r) = rayon::join(
        || build_chunks(left, first, depth + 1),
        || build_chunks(right, first + mid, depth + 1),
    );
    me[node].set_start(1 + l.iter().map(Vec::len).sum::<usize>() as u32);
    let mut chunks = vec![me];
    chunks.extend(l);
    chunks.extend(r);
    chunks
}

/// Appends the subtree over `prims` to `out`, depth first.
fn build_node(prims: &mut [Prim], first: usize, depth: usize, out: &mut Vec<Node>) {
    let Some((me, mid)) = split_node(prims, first, depth, out) else {
        return;
    };
    let (left, right) = prims.split_at_mut(mid);
    build_node(left, first, depth + 1, out);
    let offset = (out.len() - me) as u32;
    out[me].set_start(offset);
    build_node(right, first + mid, depth + 1, out);
}

/// Pushes the node over `prims` to `out`. A leaf returns `None`; an inner node partitions
/// `prims` and returns its index in `out` and the size of the left part (its `start` is set by
/// the caller once the left subtree is built).
fn split_node(
    prims: &mut [Prim],
    first: usize,
    depth: usize,
    out: &mut Vec<Node>,
) -> Option<(usize, usize)> {
    let extent = Extent::of(prims);
    let me = out.len();
    let n = prims.len();
    out.push(Node::new(
        Vec3::from(extent.bounds.lo),
        Vec3::from(extent.bounds.hi),
        first as u32,
        n as u32,
    ));
    if n <= 2 || depth + 1 >= MAX_TREE_DEPTH {
        return None;
    }
    let binning = Binning::new(&extent.centroids, n);
    let split = best_split(
        &binning.fill(prims),
        binning.count,
        extent.bounds.half_area(),
    );
    let mid = match split {
        Some(s) if n > MAX_LEAF || s.cost < n as f32 => {
            partition(prims, |p| binning.bin(p, s.axis) <= s.bin)
        }
        // All centroids coincide: any halving is as good as another.
        None if n > MAX_LEAF => n / 2,
        _ => return None,
    };
    out[me].set_count(0);
    Some((me, mid))
}
