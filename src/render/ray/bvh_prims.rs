//! The triangles of a BVH build as boxes (`Prim`), the boxes and centroid boxes of runs of them
//! (`Extent`), and the in-place partition that splits a node's run in two.
//!
//! Everything is four-lane `f32x4` arithmetic: a box corner is one register, so growing a box
//! is one `min` and one `max`. The fourth lane carries no geometry (a prim's mesh index, a box's
//! padding) and is never read as a coordinate.

use glam::{Vec3, Vec3A};
use rayon::prelude::*;
use wide::f32x4;

/// Runs of at least this many prims are measured in parallel.
const PARALLEL_MIN: usize = 16 * 1024;
/// Prims per parallel task.
const CHUNK: usize = 8 * 1024;

/// One triangle during the build: its box, with the mesh index in the fourth lane of `lo` (32
/// bytes, so the array that is partitioned over and over stays small).
#[derive(Debug, Clone, Copy)]
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
    #[inline]
    fn is_left(&self, p: &Prim) -> bool {
        let c = p.centroid2().as_array_ref()[self.axis];
        (c - self.origin) * self.scale < self.limit
    }
}

/// Moves the prims on the left of `side` to the front, in place; returns how many there are
/// and the centroid boxes of the two parts (their triangle boxes come from the bins).
///
/// The order it leaves is part of the tree (it is the order of a leaf's triangles, which decides
/// between two hits at exactly the same distance), so it is kept as it always was: a scan from
/// the front that swaps each right prim with the last unscanned one.
pub fn partition(prims: &mut [Prim], side: Side) -> (usize, Aabb, Aabb) {
    let (mut i, mut j) = (0, prims.len());
    let (mut l, mut r) = (Aabb::EMPTY, Aabb::EMPTY);
    while i < j {
        let p = prims[i];
        if side.is_left(&p) {
            l.grow_point(p.centroid2());
            i += 1;
        } else {
            j -= 1;
            r.grow_point(p.centroid2());
            prims[i] = prims[j];
            prims[j] = p;
        }
    }
    (i, l, r)
}
