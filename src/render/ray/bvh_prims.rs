//! The triangles of a BVH build as boxes (`Prim`), the boxes and centroid boxes of runs of them
//! (`Extent`), and the in-place partition that splits a node's run in two.
//!
//! Everything is four-lane `f32x4` arithmetic: a box corner is one register, so growing a box
//! is one `min` and one `max`. The fourth lane carries no geometry (a prim's mesh index, a box's
//! padding) and is never read as a coordinate.

use glam::{Vec3, Vec3A};
use rayon::prelude::*;
use wide::{CmpLt, f32x4};

/// Runs of at least this many prims are measured in parallel.
const PARALLEL_MIN: usize = 16 * 1024;
/// Prims per parallel task.
const CHUNK: usize = 8 * 1024;

/// One triangle during the build: its box, with the mesh index in the fourth lane of `lo` (32
/// bytes, so the array that is partitioned over and over stays small).
#[derive(Debug, Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
#[repr(C)]
pub struct Prim {
    lo: f32x4,
    hi: f32x4,
}

impl Prim {
    /// The box [lo, hi] of triangle `index`.
    #[inline]
    pub fn new(lo: Vec3A, hi: Vec3A, index: u32) -> Prim {
        Prim {
            lo: f32x4::from([lo.x, lo.y, lo.z, f32::from_bits(index)]),
            hi: f32x4::from([hi.x, hi.y, hi.z, 0.0]),
        }
    }

    /// The triangle's index in the mesh.
    #[inline]
    pub fn index(&self) -> u32 {
        self.lo.as_array_ref()[3].to_bits()
    }

    /// Box minimum corner (lanes x, y, z).
    #[inline]
    pub fn lo(&self) -> f32x4 {
        self.lo
    }

    /// Box maximum corner (lanes x, y, z).
    #[inline]
    pub fn hi(&self) -> f32x4 {
        self.hi
    }

    /// Twice the box centre: binning only needs positions relative to each other.
    #[inline]
    pub fn centroid2(&self) -> f32x4 {
        self.lo + self.hi
    }
}

/// An axis-aligned box in lanes x, y, z; empty when lo > hi.
#[derive(Debug, Clone, Copy)]
pub struct Aabb {
    pub lo: f32x4,
    pub hi: f32x4,
}

impl Aabb {
    pub const EMPTY: Aabb = Aabb {
        lo: f32x4::new([f32::INFINITY; 4]),
        hi: f32x4::new([f32::NEG_INFINITY; 4]),
    };

    /// Grows the box to hold [lo, hi].
    #[inline]
    pub fn grow(&mut self, lo: f32x4, hi: f32x4) {
        self.lo = self.lo.fast_min(lo);
        self.hi = self.hi.fast_max(hi);
    }

    /// Grows the box to hold the point `p`.
    #[inline]
    pub fn grow_point(&mut self, p: f32x4) {
        self.grow(p, p);
    }

    #[inline]
    pub fn union(self, other: Aabb) -> Aabb {
        Aabb {
            lo: self.lo.fast_min(other.lo),
            hi: self.hi.fast_max(other.hi),
        }
    }

    /// The box's extent in x, y, z (negative when empty).
    #[inline]
    pub fn size(&self) -> Vec3A {
        let d = (self.hi - self.lo).to_array();
        Vec3A::new(d[0], d[1], d[2])
    }

    /// Half the surface area (the heuristic only compares ratios); 0 when empty.
    #[inline]
    pub fn half_area(&self) -> f32 {
        let d = self.size().max(Vec3A::ZERO);
        d.x * d.y + d.y * d.z + d.z * d.x
    }

    /// Minimum corner as a vector.
    pub fn lo3(&self) -> Vec3 {
        let a = self.lo.to_array();
        Vec3::new(a[0], a[1], a[2])
    }

    /// Maximum corner as a vector.
    pub fn hi3(&self) -> Vec3 {
        let a = self.hi.to_array();
        Vec3::new(a[0], a[1], a[2])
    }
}

/// Triangle boxes and centroid box of a run of prims.
#[derive(Debug, Clone, Copy)]
pub struct Extent {
    /// Union of the prims' boxes.
    pub bounds: Aabb,
    /// Box of the prims' [`Prim::centroid2`].
    pub centroids: Aabb,
}

impl Extent {
    pub const EMPTY: Extent = Extent {
        bounds: Aabb::EMPTY,
        centroids: Aabb::EMPTY,
    };

    #[inline]
    fn grow(&mut self, p: &Prim) {
        self.bounds.grow(p.lo, p.hi);
        self.centroids.grow_point(p.centroid2());
    }

    fn union(self, other: Extent) -> Extent {
        Extent {
            bounds: self.bounds.union(other.bounds),
            centroids: self.centroids.union(other.centroids),
        }
    }

    /// The extent of `prims`, measured in parallel when they are many.
    pub fn of(prims: &[Prim]) -> Extent {
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

/// Which side of a split a prim goes to: the left when `(centroid2[axis] − origin) · scale <
/// limit`, the same arithmetic the binning uses, so the sides match the bins' counts exactly.
#[derive(Debug, Clone, Copy)]
pub struct Side {
    pub axis: usize,
    pub origin: f32,
    pub scale: f32,
    pub limit: f32,
}

impl Side {
    /// `mask` (all bits) where the prim with centroid `c2` goes left, in lane `AXIS`.
    #[inline]
    fn left_lanes(&self, c2: f32x4) -> f32x4 {
        ((c2 - f32x4::splat(self.origin)) * f32x4::splat(self.scale))
            .cmp_lt(f32x4::splat(self.limit))
    }
}

/// Working memory for [`partition`], kept by a thread from node to node.
#[derive(Debug, Clone, Default)]
pub struct PartitionScratch {
    /// Each prim's side: 1 left, 0 right.
    left: Vec<u8>,
    /// Positions of the right prims among the first `lefts` (ascending), then one spare.
    fronts: Vec<u32>,
    /// Positions of the left prims among the rest (descending), then one spare.
    backs: Vec<u32>,
    /// The right prims found at the front, while they wait for their slots.
    saved: Vec<Prim>,
}

/// Moves the prims on the left of `side` to the front, in place; returns how many there are
/// and the centroid boxes of the two parts (their triangle boxes come from the bins).
///
/// The order it leaves is part of the tree (it is the order of a leaf's triangles, which decides
/// between two hits at exactly the same distance): that of a scan from the front that swaps each
/// right prim with the last unscanned one. This is that scan; it needs no memory, but branches
/// on every prim, on a side no predictor can guess. [`partition`] leaves the same order without
/// those branches.
pub fn partition_scan(prims: &mut [Prim], side: Side) -> (usize, Aabb, Aabb) {
    // One loop per axis: the coordinate is then a fixed lane.
    match side.axis {
        0 => scan::<0>(prims, side),
        1 => scan::<1>(prims, side),
        _ => scan::<2>(prims, side),
    }
}

fn scan<const AXIS: usize>(prims: &mut [Prim], side: Side) -> (usize, Aabb, Aabb) {
    let (mut i, mut j) = (0, prims.len());
    let (mut l, mut r) = (Aabb::EMPTY, Aabb::EMPTY);
    while i < j {
        let p = prims[i];
        let c2 = p.centroid2();
        if (side.left_lanes(c2).move_mask() >> AXIS) & 1 != 0 {
            l.grow_point(c2);
            i += 1;
        } else {
            j -= 1;
            r.grow_point(c2);
            prims[i] = prims[j];
            prims[j] = p;
        }
    }
    (i, l, r)
}

/// [`partition_scan`] without a branch per prim: the same order, written down once every
/// prim's side is known. With L left prims, call the first L slots the front and the rest the
/// back. The scan keeps a front left prim in place and fills each front slot that held a right
/// prim with the back's left prims, taken from the end; each back right prim moves down one
/// slot, in one block move; and the k-th right prim found at the front lands just below the
/// slot of the (k − 1)-th left prim taken from the back (the last slot for the first). If the
/// back's left prims run out before the scan reaches slot L, slot L is scanned as a front slot
/// too.
pub fn partition(
    prims: &mut [Prim],
    side: Side,
    scratch: &mut PartitionScratch,
) -> (usize, Aabb, Aabb) {
    let (lefts, l, r) = match side.axis {
        0 => sides::<0>(prims, side, &mut scratch.left),
        1 => sides::<1>(prims, side, &mut scratch.left),
        _ => sides::<2>(prims, side, &mut scratch.left),
    };
    reorder(prims, lefts, scratch);
    (lefts, l, r)
}

/// Records each prim's side in `left`; returns the number of left prims and the centroid
/// boxes of both sides. No branch depends on a prim.
fn sides<const AXIS: usize>(prims: &[Prim], side: Side, left: &mut Vec<u8>) -> (usize, Aabb, Aabb) {
    left.clear();
    left.reserve(prims.len());
    let far = Aabb::EMPTY;
    let (mut l, mut r) = (Aabb::EMPTY, Aabb::EMPTY);
    let mut lefts = 0;
    for p in prims {
        let c2 = p.centroid2();
        let is_left = (side.left_lanes(c2).move_mask() >> AXIS) & 1;
        let mask = f32x4::splat(f32::from_bits(0u32.wrapping_sub(is_left as u32)));
        l.lo = l.lo.fast_min(mask.blend(c2, far.lo));
        l.hi = l.hi.fast_max(mask.blend(c2, far.hi));
        r.lo = r.lo.fast_min(mask.blend(far.lo, c2));
        r.hi = r.hi.fast_max(mask.blend(far.hi, c2));
        left.push(is_left as u8);
        lefts += is_left as usize;
    }
    (lefts, l, r)
}

/// Puts `prims` in the order the swapping scan leaves, from the sides in `scratch.left`
/// (`lefts` of them left); see [`partition`].
fn reorder(prims: &mut [Prim], lefts: usize, scratch: &mut PartitionScratch) {
    let n = prims.len();
    let left = &scratch.left;
    // Right prims at the front, in scan order; left prims at the back, from the end.
    scratch.fronts.clear();
    scratch.fronts.resize(lefts + 1, 0);
    let mut misplaced = 0;
    for (p, &is_left) in left[..lefts].iter().enumerate() {
        scratch.fronts[misplaced] = p as u32;
        misplaced += 1 - is_left as usize;
    }
    scratch.backs.clear();
    scratch.backs.resize(n - lefts + 1, 0);
    let mut taken = 0;
    for p in (lefts..n).rev() {
        scratch.backs[taken] = p as u32;
        taken += left[p] as usize;
    }
    debug_assert_eq!(misplaced, taken, "as many misplaced on each side");
    let (fronts, backs) = (&mut scratch.fronts, &scratch.backs);
    // The scan reaches slot L as a front slot when the back's left prims are all taken above it.
    let mut found = misplaced;
    let mut back_start = lefts;
    if lefts < n && (misplaced == 0 || backs[misplaced - 1] as usize > lefts) {
        fronts[found] = lefts as u32;
        found += 1;
        back_start += 1;
    }
    scratch.saved.clear();
    scratch
        .saved
        .extend(fronts[..found].iter().map(|&a| prims[a as usize]));
    for (&a, &b) in fronts.iter().zip(&backs[..misplaced]) {
        prims[a as usize] = prims[b as usize];
    }
    // Back right prims move down one slot; slots this fills from a left prim are refilled below.
    if back_start < n {
        if left[back_start] == 0 {
            prims.copy_within(back_start..n, back_start - 1);
        } else {
            prims.copy_within(back_start + 1..n, back_start);
        }
    }
    for (k, p) in scratch.saved.iter().enumerate() {
        let slot = if k == 0 { n } else { backs[k - 1] as usize };
        prims[slot - 1] = *p;
    }
}
