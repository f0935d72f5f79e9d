//! Building a [`Bvh`] top-down with the binned surface-area heuristic (`bvh_sah`).
//!
//! Each node bins its triangles' centroids, splits at the cheapest split between bins, and
//! partitions its run of prims in place (`bvh_prims`); a side's triangle box comes from its
//! bins and its centroid box from the partition, so no node needs a pass of its own to measure
//! itself. Large nodes bin in parallel and build their two children with `rayon::join`; the
//! tree is the same for any number of threads because every split depends only on the
//! triangles, never on scheduling.
//!
//! Inner nodes are written once, in depth-first order, into runs (one per subtree built in one
//! thread) that are joined at the end; leaves copy nothing while building, and the triangles
//! are laid out in leaf order once the tree is done, over the prims they come from
//! (`bvh_buffer`).

use rayon::prelude::*;

use super::bvh::{Bvh, Inner, MAX_TREE_DEPTH, Node};
use super::bvh_buffer::BuildBuffer;
use super::bvh_prims::{Extent, PartitionScratch, Prim, partition, partition_scan};
use super::bvh_sah::{BinScratch, Binning, always_leaf};
use crate::huge_pages;
use crate::mesh::Mesh;
use crate::render::progress::{Cancelled, Progress};

/// A node with at most this many triangles may become a leaf when the heuristic says so.
const MAX_LEAF: usize = 8;
/// Nodes with at least this many triangles build their children in parallel. Low enough that
/// a mesh of a thousand triangles uses both cores: at 16·1024 a mesh of a few thousand was built
/// on one thread, and Embree built it faster (spot, 5,856 triangles: 1.03–1.8 → 0.5–1.25 ms;
/// cow, teapot and the bunny 15–25% faster, the 1.31M-triangle icosphere 3–5%), and at 2·1024
/// suzanne's 968 triangles were (0.12 → 0.06 ms at 512, median of 1,000 builds, two threads;
/// teapot 0.52 → 0.44 ms; the bunny and the icosphere unchanged; at 256 no faster). The trees
/// are the same whatever this is.
const PARALLEL_MIN: usize = 512;
/// Nodes with at least this many triangles partition with the swapping scan, which needs no
/// memory, rather than with working memory of their own.
const SCAN_MIN: usize = 16 * 1024;
/// Items per parallel task in the passes over all triangles or nodes.
const PASS_CHUNK: usize = 4096;

/// Builds the hierarchy over `mesh`, or stops early once `progress` is cancelled (checked at
/// every node of at least [`PARALLEL_MIN`] triangles, so within milliseconds).
pub fn build(mesh: &Mesh, progress: &Progress) -> Result<Bvh, Cancelled> {
    if mesh.triangles.is_empty() {
        return Ok(Bvh::default());
    }
    let mut buffer = BuildBuffer::new(mesh);
    let prims = buffer.prims();
    let extent = Extent::of(prims);
    let top = build_runs(prims, extent, 0, 0, progress);
    progress.check()?;
    let (triangles, ids) = buffer.into_triangles(mesh);
    Ok(Bvh {
        root: Some(top.node),
        inner: join_runs(&top.runs),
        triangles,
        ids,
        depth: top.depth,
    })
}

/// A subtree: its root and the runs of its inner nodes, depth first.
struct Subtree {
    /// The root: a leaf, or an inner node linking to its position among the subtree's inner
    /// nodes (0: the first of the first run).
    node: Node,
    /// The inner nodes in depth-first order, in runs to be joined. Each run links to its own
    /// nodes and to the runs after it by position relative to the run's start.
    runs: Vec<Vec<Inner>>,
    /// Levels of the subtree: 1 for a leaf.
    depth: usize,
}

/// The inner nodes of `runs` in one array, their links made absolute.
fn join_runs(runs: &[Vec<Inner>]) -> Vec<Inner> {
    let mut starts = Vec::with_capacity(runs.len() + 1);
    let mut total = 0;
    for run in runs {
        starts.push(total);
        total += run.len();
    }
    starts.push(total);
    let mut joined = huge_pages::with_capacity(total);
    (0..total)
        .into_par_iter()
        .with_min_len(PASS_CHUNK)
        .map_init(
            || usize::MAX,
            |run, i| {
                // Each task walks consecutive nodes: find the run once, then step along.
                if *run == usize::MAX || i >= starts[*run + 1] {
                    *run = starts.partition_point(|&s| s <= i) - 1;
                }
                let start = starts[*run];
                let mut inner = runs[*run][i - start];
                for child in &mut inner.children {
                    if !child.is_leaf() {
                        child.set_start(child.start() + start as u32);
                    }
                }
                inner
            },
        )
        .collect_into_vec(&mut joined);
    joined
}

/// The subtree over `prims` (which start at slot `first` of the final order), at `depth`
/// below the root. A large node builds its children in parallel, each into runs of its own,
/// so that nodes are copied once at the end rather than once per level. Once `progress` is
/// cancelled it returns at once, leaving an unusable tree that the caller drops.
fn build_runs(
    prims: &mut [Prim],
    extent: Extent,
    first: usize,
    depth: usize,
    progress: &Progress,
) -> Subtree {
    let n = prims.len();
    if progress.is_cancelled() {
        return Subtree {
            node: leaf(&extent, first, n),
            runs: Vec::new(),
            depth: 1,
        };
    }
    if n < PARALLEL_MIN {
        // At most n − 1 inner nodes: the run never reallocates.
        let mut run = Vec::with_capacity(n.saturating_sub(1));
        let mut scratch = Scratch::new();
        let (node, depth) = build_node(prims, extent, first, depth, &mut run, &mut scratch);
        // Leaves of several triangles leave most of that room unused: returned at once, so the
        // runs hold what their nodes take (the 9M-triangle scan's runs took 255 MiB resident
        // with the room, 120 MiB without, beside 106 MiB of nodes once joined).
        run.shrink_to_fit();
        return Subtree {
            node,
            runs: vec![run],
            depth,
        };
    }
    let mut scratch = if n >= SCAN_MIN {
        Scratch::large()
    } else {
        Scratch::new()
    };
    let Some(split) = split_node(prims, &extent, depth, &mut scratch) else {
        return Subtree {
            node: leaf(&extent, first, n),
            runs: Vec::new(),
            depth: 1,
        };
    };
    let (left, right) = prims.split_at_mut(split.mid);
    let (l, r) = rayon::join(
        || build_runs(left, split.left, first, depth + 1, progress),
        || build_runs(right, split.right, first + split.mid, depth + 1, progress),
    );
    let left_nodes: usize = l.runs.iter().map(Vec::len).sum();
    let link = |mut node: Node, offset: usize| {
        if !node.is_leaf() {
            node.set_start(node.start() + offset as u32);
        }
        node
    };
    let mut runs = Vec::with_capacity(1 + l.runs.len() + r.runs.len());
    runs.push(vec![Inner {
        children: [link(l.node, 1), link(r.node, 1 + left_nodes)],
    }]);
    runs.extend(l.runs);
    runs.extend(r.runs);
    Subtree {
        node: inner(&extent, 0),
        runs,
        depth: 1 + l.depth.max(r.depth),
    }
}

/// Appends the inner nodes of the subtree over `prims` to `run`, depth first; returns the
/// subtree's root (linking to its position in `run`) and its levels.
fn build_node(
    prims: &mut [Prim],
    extent: Extent,
    first: usize,
    depth: usize,
    run: &mut Vec<Inner>,
    scratch: &mut Scratch,
) -> (Node, usize) {
    let n = prims.len();
    let Some(split) = split_node(prims, &extent, depth, scratch) else {
        return (leaf(&extent, first, n), 1);
    };
    let at = run.len();
    run.push(Inner {
        children: [Node::new(glam::Vec3::ZERO, glam::Vec3::ZERO, 0, 0); 2],
    });
    let (left, right) = prims.split_at_mut(split.mid);
    let (l, l_depth) = build_node(left, split.left, first, depth + 1, run, scratch);
    let (r, r_depth) = build_node(
        right,
        split.right,
        first + split.mid,
        depth + 1,
        run,
        scratch,
    );
    run[at] = Inner { children: [l, r] };
    (inner(&extent, at), 1 + l_depth.max(r_depth))
}

fn leaf(extent: &Extent, first: usize, count: usize) -> Node {
    let b = &extent.bounds;
    Node::new(b.lo3(), b.hi3(), first as u32, count as u32)
}

fn inner(extent: &Extent, index: usize) -> Node {
    let b = &extent.bounds;
    Node::new(b.lo3(), b.hi3(), index as u32, 0)
}

/// Working memory a thread keeps from node to node.
struct Scratch {
    bins: BinScratch,
    /// For the partition without branches; `None` for the few nodes at the top, which are
    /// too large to give each its own (they partition with the swapping scan).
    partition: Option<PartitionScratch>,
}

impl Scratch {
    fn new() -> Scratch {
        Scratch {
            bins: BinScratch::new(),
            partition: Some(PartitionScratch::default()),
        }
    }

    fn large() -> Scratch {
        Scratch {
            bins: BinScratch::new(),
            partition: None,
        }
    }
}

/// A node split in two: the size of its left part and the parts' extents.
struct Parted {
    mid: usize,
    left: Extent,
    right: Extent,
}

/// Splits the node over `prims` (whose extent is `extent`, at `depth`), partitioning `prims`;
/// `None` when it should be a leaf.
fn split_node(
    prims: &mut [Prim],
    extent: &Extent,
    depth: usize,
    scratch: &mut Scratch,
) -> Option<Parted> {
    let n = prims.len();
    if n <= 2 || (n <= MAX_LEAF && always_leaf(n)) || depth + 1 >= MAX_TREE_DEPTH {
        return None;
    }
    let binning = Binning::new(&extent.centroids, n);
    let split = binning.best_split(
        binning.fill(prims, &mut scratch.bins),
        extent.bounds.half_area(),
    );
    match split {
        Some(s) if n > MAX_LEAF || s.cost < n as f32 => {
            let (mid, left, right) = match &mut scratch.partition {
                Some(memory) => partition(prims, s.side, memory),
                None => partition_scan(prims, s.side),
            };
            Some(Parted {
                mid,
                left: Extent {
                    bounds: s.left,
                    centroids: left,
                },
                right: Extent {
                    bounds: s.right,
                    centroids: right,
                },
            })
        }
        // All centroids coincide: any halving is as good as another.
        None if n > MAX_LEAF => {
            let mid = n / 2;
            Some(Parted {
                mid,
                left: Extent::of(&prims[..mid]),
                right: Extent::of(&prims[mid..]),
            })
        }
        _ => None,
    }
}
