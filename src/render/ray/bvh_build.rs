//! Building a [`Bvh`] top-down with the binned surface-area heuristic.
//!
//! Each node sorts its triangles' centroids into [`BINS`] bins per axis, prices every split
//! between bins by the surface-area heuristic (expected cost of a random ray through the node),
//! and partitions in place at the cheapest one. Large nodes bin in parallel and build their two
//! children with `rayon::join`; the result is the same for any number of threads because every
//! split depends only on the triangles, never on scheduling.

use glam::{Vec3, Vec3A, Vec4};
use rayon::prelude::*;

use super::bvh::{Bvh, MAX_TREE_DEPTH, Node};
use super::intersect::Triangle;
use crate::mesh::Mesh;
use crate::render::progress::{Cancelled, Progress};

/// Centroid bins per axis.
const BINS: usize = 16;
/// A node with at most this many triangles may become a leaf when the heuristic says so.
const MAX_LEAF: usize = 8;
/// Cost of visiting a node, relative to one ray/triangle test.
const TRAVERSAL_COST: f32 = 2.0;
/// Nodes with at least this many triangles bin in parallel and build their children in parallel.
const PARALLEL_MIN: usize = 16 * 1024;
/// Nodes with fewer triangles bin along their longest centroid axis only: the lower levels
/// cost a third as much, and the tree's quality is decided mostly near the top.
const ALL_AXES_MIN: usize = 4 * 1024;
/// Triangles per parallel binning task.
const CHUNK: usize = 8 * 1024;

/// A triangle during the build: its box, with the mesh index in the fourth lane of `lo` (32
/// bytes, so the array that is partitioned over and over stays small).
#[derive(Debug, Clone, Copy)]
struct Prim {
    lo: Vec4,
    hi: Vec3A,
}

impl Prim {
    fn new(lo: Vec3A, hi: Vec3A, index: u32) -> Prim {
        Prim {
            lo: lo.extend(f32::from_bits(index)),
            hi,
        }
    }

    #[inline]
    fn lo(&self) -> Vec3A {
        Vec3A::from_vec4(self.lo)
    }

    /// The triangle's index in the mesh.
    #[inline]
    fn index(&self) -> u32 {
        self.lo.w.to_bits()
    }

    /// Twice the box centre: binning only needs positions relative to each other.
    #[inline]
    fn centroid2(&self) -> Vec3A {
        self.lo() + self.hi
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

    #[inline]
    fn grow(&mut self, p: &Prim) {
        self.bounds.grow(p.lo(), p.hi);
        let c = p.centroid2();
        self.centroids.grow(c, c);
    }

    fn union(self, other: Extent) -> Extent {
        Extent {
            bounds: self.bounds.union(other.bounds),
            centroids: self.centroids.union(other.centroids),
        }
    }

    fn of(prims: &[Prim]) -> Extent {
        let seq = |prims: &[Prim]| {
            prims.iter().fold(Extent::EMPTY, |mut e, p| {
                e.grow(p);
                e
            })
        };
        if prims.len() < PARALLEL_MIN {
            return seq(prims);
        }
        prims
            .par_chunks(CHUNK)
            .map(seq)
            .reduce(|| Extent::EMPTY, Extent::union)
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
#[derive(Debug, Clone)]
struct Binning {
    origin: Vec3A,
    scale: Vec3A,
    /// Bins in use, 2..=BINS: small nodes use fewer, which keeps their setup cheap.
    count: usize,
    /// The axes binned.
    axes: std::ops::Range<usize>,
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
        let axes = if prims >= ALL_AXES_MIN {
            0..3
        } else {
            let longest = extent.max_position();
            longest..longest + 1
        };
        Binning {
            origin: centroids.lo,
            scale,
            count,
            axes,
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
            if self.axes.len() == 1 {
                let axis = self.axes.start;
                for p in prims {
                    let b = self.bin(p, axis);
                    bins.bounds[axis][b].grow(p.lo(), p.hi);
                    bins.counts[axis][b] += 1;
                }
            } else {
                for p in prims {
                    for (axis, b) in self.bins(p).into_iter().enumerate() {
                        bins.bounds[axis][b].grow(p.lo(), p.hi);
                        bins.counts[axis][b] += 1;
                    }
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
fn best_split(bins: &Bins, binning: &Binning, parent_area: f32) -> Option<Split> {
    let used = binning.count;
    let mut best: Option<Split> = None;
    for axis in binning.axes.clone() {
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

/// Moves the prims satisfying `left` to the front; returns how many there are and the extents
/// of the two parts, gathered on the way so the children need no pass of their own.
fn partition(prims: &mut [Prim], left: impl Fn(&Prim) -> bool) -> (usize, Extent, Extent) {
    let (mut i, mut j) = (0, prims.len());
    let (mut l, mut r) = (Extent::EMPTY, Extent::EMPTY);
    while i < j {
        if left(&prims[i]) {
            l.grow(&prims[i]);
            i += 1;
        } else {
            j -= 1;
            r.grow(&prims[i]);
            prims.swap(i, j);
        }
    }
    (i, l, r)
}

/// Builds the hierarchy over `mesh`, or stops early once `progress` is cancelled (checked at
/// every node of at least [`PARALLEL_MIN`] triangles, so within milliseconds).
pub fn build(mesh: &Mesh, progress: &Progress) -> Result<Bvh, Cancelled> {
    let mut prims: Vec<Prim> = (0..mesh.triangles.len())
        .into_par_iter()
        .with_min_len(4096)
        .map(|t| {
            let [a, b, c] = mesh.corners(t).map(Vec3A::from);
            Prim::new(a.min(b).min(c), a.max(b).max(c), t as u32)
        })
        .collect();
    if prims.is_empty() {
        return Ok(Bvh::default());
    }
    let extent = Extent::of(&prims);
    let nodes = build_chunks(&mut prims, extent, 0, 0, progress).concat();
    progress.check()?;
    let triangles = prims
        .par_iter()
        .with_min_len(4096)
        .map(|p| {
            let [a, b, c] = mesh.corners(p.index() as usize);
            Triangle::new(a, b, c)
        })
        .collect();
    let ids = prims
        .par_iter()
        .with_min_len(4096)
        .map(Prim::index)
        .collect();
    let (root, inner) = Bvh::pack(&nodes);
    let mut bvh = Bvh {
        root,
        inner,
        triangles,
        ids,
        depth: 0,
    };
    bvh.depth = bvh.measure_depth();
    Ok(bvh)
}

/// The subtree over `prims` (which start at slot `first` of the final order), as node runs to
/// be concatenated: a large node is split in parallel and its children's runs follow its own, so
/// the nodes are copied once at the end rather than once per level. Once `progress` is
/// cancelled it returns at once, leaving an unusable tree that the caller drops.
fn build_chunks(
    prims: &mut [Prim],
    extent: Extent,
    first: usize,
    depth: usize,
    progress: &Progress,
) -> Vec<Vec<Node>> {
    if progress.is_cancelled() {
        return Vec::new();
    }
    let n = prims.len();
    if n < PARALLEL_MIN {
        // Upper bound of a binary tree with n leaves: the run never reallocates.
        let mut out = Vec::with_capacity(2 * n);
        build_node(prims, extent, first, depth, &mut out);
        return vec![out];
    }
    let mut me = Vec::new();
    let Some(split) = split_node(prims, extent, first, depth, &mut me) else {
        return vec![me];
    };
    let (left, right) = prims.split_at_mut(split.mid);
    let (l, r) = rayon::join(
        || build_chunks(left, split.left, first, depth + 1, progress),
        || build_chunks(right, split.right, first + split.mid, depth + 1, progress),
    );
    me[split.node].set_start(1 + l.iter().map(Vec::len).sum::<usize>() as u32);
    let mut chunks = vec![me];
    chunks.extend(l);
    chunks.extend(r);
    chunks
}

/// Appends the subtree over `prims` to `out`, depth first.
fn build_node(prims: &mut [Prim], extent: Extent, first: usize, depth: usize, out: &mut Vec<Node>) {
    let Some(split) = split_node(prims, extent, first, depth, out) else {
        return;
    };
    let (left, right) = prims.split_at_mut(split.mid);
    build_node(left, split.left, first, depth + 1, out);
    let offset = (out.len() - split.node) as u32;
    out[split.node].set_start(offset);
    build_node(right, split.right, first + split.mid, depth + 1, out);
}

/// An inner node just pushed: its index, the size of its left part and the parts' extents.
struct Parted {
    node: usize,
    mid: usize,
    left: Extent,
    right: Extent,
}

/// Pushes the node over `prims` (whose extent is `extent`) to `out`. A leaf returns `None`; an
/// inner node partitions `prims` (its `start` is set by the caller once the left subtree is
/// built).
fn split_node(
    prims: &mut [Prim],
    extent: Extent,
    first: usize,
    depth: usize,
    out: &mut Vec<Node>,
) -> Option<Parted> {
    let node = out.len();
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
    let split = best_split(&binning.fill(prims), &binning, extent.bounds.half_area());
    let (mid, left, right) = match split {
        Some(s) if n > MAX_LEAF || s.cost < n as f32 => {
            partition(prims, |p| binning.bin(p, s.axis) <= s.bin)
        }
        // All centroids coincide: any halving is as good as another.
        None if n > MAX_LEAF => {
            let mid = n / 2;
            (mid, Extent::of(&prims[..mid]), Extent::of(&prims[mid..]))
        }
        _ => return None,
    };
    out[node].set_count(0);
    Some(Parted {
        node,
        mid,
        left,
        right,
    })
}
