//! The binned surface-area heuristic: a node's triangles are sorted by centroid into at most
//! [`BINS`] bins per axis, and every split between two bins is priced by the expected cost of a
//! random ray through the node. Only counts, minima and maxima are gathered, so the bins (and the
//! split chosen) do not depend on the order of the triangles or on how the work is divided.

use glam::Vec3A;
use rayon::prelude::*;
use wide::f32x4;

use super::bvh_prims::{Aabb, Prim, Side};
#[cfg(target_arch = "x86_64")]
use super::bvh_sah_avx2::{self, WideBins};

/// Centroid bins per axis.
pub const BINS: usize = 16;
/// Cost of visiting a node, relative to one ray/triangle test. A visit is a dependent load that
/// often misses the cache, while a leaf's triangles are prefetched together and tested on all
/// eight lanes of a packet: 4 rather than 2 makes shallower trees with fuller leaves, which
/// build 10–15% faster (1.31M-triangle icosphere: 225–250 → 196–220 ms on 2 threads) and trace
/// as fast or faster (icosphere 640×360: 25.3–25.6 → 22.5–25.3 ms), with the same images.
const TRAVERSAL_COST: f32 = 4.0;
/// Whether a node of `prims` triangles (at most a leaf's size) is a leaf whatever its best
/// split, so that binning it would be wasted: a split costs at least [`TRAVERSAL_COST`], and a
/// leaf of `prims` costs `prims`, which wins ties. (Of the icosphere's 400,000 nodes of 3 to
/// 31 triangles, 191,000 hold fewer than 8.)
pub fn always_leaf(prims: usize) -> bool {
    prims as f32 <= TRAVERSAL_COST
}

/// Nodes with fewer triangles bin along their longest centroid axis only: the lower levels
/// cost a third as much, and the tree's quality is decided mostly near the top.
const ALL_AXES_MIN: usize = 4 * 1024;
/// Nodes with at least this many triangles bin in parallel.
const PARALLEL_MIN: usize = 16 * 1024;
/// Triangles per parallel binning task.
const CHUNK: usize = 8 * 1024;
/// Runs of fewer prims, binned on one axis, use one set of bins: clearing and joining a second
/// set costs them more than it saves (with [`always_leaf`], icosphere on 1 thread, min of 5,
/// three alternations: 256–263 → 244–247 ms; at 128 prims half the gain, at 1,024 a loss).
const ONE_SET_MAX: usize = 32;

const _: () = assert!(
    BINS.is_power_of_two(),
    "bin indices are masked with BINS − 1"
);

/// A bin's box while a run of prims is binned, with the bin's count in a lane of its own: one
/// vector operation counts a prim instead of a second read-modify-write in memory. A run holds
/// fewer than 2²⁴ prims, so the float count is exact.
///
/// Two layouts: [`LaneBox`], two four-lane registers, on any CPU; and one AVX register in
/// `bvh_sah_avx2`. Both add a prim with the same IEEE operations, and [`Binning::fill_sets`]
/// gives them the prims, and joins their sets, in the same order, so their bins are the same
/// bits and so is the tree.
pub(super) trait BinBox: Copy {
    /// A prim as this layout adds it.
    type Prim: Copy;
    /// The box that holds nothing, count 0.
    fn empty() -> Self;
    fn prim(p: &Prim) -> Self::Prim;
    /// Grows the box to hold the prim `p` and counts it.
    fn add(&mut self, p: Self::Prim);
    /// The box and its count.
    fn settle(self) -> (Aabb, u32);
}

/// [`BinBox`] on two four-lane registers: the count rides in the fourth lane of `hi` (a prim's
/// `hi` has 0 there, and the empty box −∞).
#[derive(Debug, Clone, Copy)]
pub(super) struct LaneBox(Aabb);

/// Added to a bin's `hi` after each prim: the fourth lane counts the prim, and −0 leaves every
/// coordinate bit for bit as it is (x + −0 = x for every x, ±0 included).
const COUNT_ONE: f32x4 = f32x4::new([-0.0, -0.0, -0.0, 1.0]);

impl BinBox for LaneBox {
    type Prim = Prim;

    #[inline(always)]
    fn empty() -> LaneBox {
        LaneBox(Aabb::EMPTY)
    }

    #[inline(always)]
    fn prim(p: &Prim) -> Prim {
        *p
    }

    #[inline(always)]
    fn add(&mut self, p: Prim) {
        let bin = &mut self.0;
        bin.lo = bin.lo.fast_min(p.lo());
        bin.hi = bin.hi.fast_max(p.hi()) + COUNT_ONE;
    }

    #[inline(always)]
    fn settle(self) -> (Aabb, u32) {
        // An empty bin's lane is −∞, which the saturating cast turns into 0.
        (self.0, self.0.hi.as_array_ref()[3] as u32)
    }
}

/// Two sets of bins of each axis while a run is binned: even prims go to the first, odd ones to
/// the second, so that consecutive prims falling into the same bin do not wait on each other's
/// stores.
pub(super) type BinSets<B> = [[[B; BINS]; 3]; 2];

/// The triangle boxes and centroid counts of one axis' bins.
#[derive(Debug, Clone, Copy)]
pub(super) struct AxisBins {
    pub(super) boxes: [Aabb; BINS],
    pub(super) counts: [u32; BINS],
}

impl AxisBins {
    const EMPTY: AxisBins = AxisBins {
        boxes: [Aabb::EMPTY; BINS],
        counts: [0; BINS],
    };

    fn merge(&mut self, other: &AxisBins, used: usize) {
        for b in 0..used {
            self.boxes[b] = self.boxes[b].union(other.boxes[b]);
            self.counts[b] += other.counts[b];
        }
    }
}

/// The bins of the three axes; only the axes binned are filled.
#[derive(Debug, Clone, Copy)]
pub struct Bins(pub(super) [AxisBins; 3]);

/// Working memory for binning, kept by a thread from node to node: the bins of the last run,
/// and the sets they were binned in, of which a node clears only the bins it uses.
#[derive(Debug, Clone)]
pub struct BinScratch {
    bins: Bins,
    /// The sets on four-lane registers.
    lanes: Box<BinSets<LaneBox>>,
    /// The sets as AVX registers, where the CPU has AVX2.
    #[cfg(target_arch = "x86_64")]
    wide: Box<WideBins>,
}

impl BinScratch {
    /// The bins of the last run binned.
    #[cfg(test)]
    pub(super) fn bins(&self) -> &Bins {
        &self.bins
    }

    pub fn new() -> BinScratch {
        BinScratch {
            bins: Bins([AxisBins::EMPTY; 3]),
            lanes: Box::new([[[LaneBox::empty(); BINS]; 3]; 2]),
            #[cfg(target_arch = "x86_64")]
            wide: Box::new(WideBins::new()),
        }
    }
}

/// Maps a centroid to its bin on each axis. Axes without extent put everything in bin 0.
#[derive(Debug, Clone)]
pub struct Binning {
    origin: f32x4,
    scale: f32x4,
    /// The last bin, as a float: bin indices are clamped to it.
    top: f32x4,
    /// Bins in use, 2..=BINS: small nodes use fewer, which keeps their setup cheap.
    count: usize,
    /// The axes binned.
    axes: std::ops::Range<usize>,
}

impl Binning {
    /// The binning of a node of `prims` triangles whose centroids span `centroids`.
    pub fn new(centroids: &Aabb, prims: usize) -> Binning {
        let count = prims.clamp(2, BINS);
        let extent = centroids.size();
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
        let mut origin = centroids.lo.to_array();
        origin[3] = 0.0;
        Binning {
            origin: f32x4::from(origin),
            scale: f32x4::from([scale.x, scale.y, scale.z, 0.0]),
            top: f32x4::splat((count - 1) as f32),
            count,
            axes,
        }
    }

    /// Bins in use, 2..=[`BINS`].
    #[cfg(test)]
    pub(super) fn count(&self) -> usize {
        self.count
    }

    /// The axes binned.
    #[cfg(test)]
    pub(super) fn axes(&self) -> std::ops::Range<usize> {
        self.axes.clone()
    }

    /// The prim's bin on each axis (lane 3 is 0).
    #[inline(always)]
    pub(super) fn bins(&self, p: &Prim) -> [i32; 4] {
        let f = (p.centroid2() - self.origin) * self.scale;
        // f ≥ 0 by construction; clamped to the last bin, the truncation is in range.
        f.fast_min(self.top).fast_trunc_int().to_array()
    }

    /// The bins of `prims`, left in `scratch`.
    pub fn fill<'s>(&self, prims: &[Prim], scratch: &'s mut BinScratch) -> &'s Bins {
        if prims.len() < PARALLEL_MIN {
            self.fill_run(prims, scratch);
            return &scratch.bins;
        }
        let merged = prims
            .par_chunks(CHUNK)
            .map(|run| {
                let mut scratch = Box::new(BinScratch::new());
                self.fill_run(run, &mut scratch);
                scratch
            })
            .reduce_with(|mut a, b| {
                for axis in self.axes.clone() {
                    a.bins.0[axis].merge(&b.bins.0[axis], self.count);
                }
                a
            })
            .expect("a large node has prims");
        scratch.bins = merged.bins;
        &scratch.bins
    }

    /// The bins of `prims`, in this thread, into `scratch.bins`: on AVX registers where the
    /// CPU has AVX2, else on four-lane ones.
    fn fill_run(&self, prims: &[Prim], scratch: &mut BinScratch) {
        #[cfg(target_arch = "x86_64")]
        if bvh_sah_avx2::fill_run(self, prims, &mut scratch.wide, &mut scratch.bins) {
            return;
        }
        self.fill_run_lanes(prims, scratch);
    }

    /// [`Binning::fill_run`] on four-lane registers, whatever the CPU.
    pub(super) fn fill_run_lanes(&self, prims: &[Prim], scratch: &mut BinScratch) {
        self.fill_sets(prims, &mut scratch.lanes, &mut scratch.bins);
    }

    /// The bins of `prims` into `out`, binned in `sets` of layout `B`: short runs on one axis
    /// in the first set alone ([`ONE_SET_MAX`]), longer ones alternating between both. Only
    /// the bins in use of the axes binned are cleared and joined.
    #[inline(always)]
    pub(super) fn fill_sets<B: BinBox>(
        &self,
        prims: &[Prim],
        sets: &mut BinSets<B>,
        out: &mut Bins,
    ) {
        let used = self.count;
        let one_set = prims.len() < ONE_SET_MAX && self.axes.len() == 1;
        let [even, odd] = sets;
        for axis in self.axes.clone() {
            even[axis][..used].fill(B::empty());
            if !one_set {
                odd[axis][..used].fill(B::empty());
            }
        }
        let bin = |b: i32| b as usize & (BINS - 1);
        if one_set {
            let axis = self.axes.start;
            for p in prims {
                even[axis][bin(self.bins(p)[axis])].add(B::prim(p));
            }
        } else if self.axes.len() == 1 {
            // One loop per axis: the bin is then a fixed lane, not a trip through memory.
            let axis = self.axes.start;
            let (even, odd) = (&mut even[axis], &mut odd[axis]);
            match axis {
                0 => self.fill_axis::<0, B>(prims, even, odd),
                1 => self.fill_axis::<1, B>(prims, even, odd),
                _ => self.fill_axis::<2, B>(prims, even, odd),
            }
        } else {
            let pairs = prims.chunks_exact(2);
            let rest = pairs.remainder();
            for pair in pairs {
                let (a, b) = (&pair[0], &pair[1]);
                let (ba, bb) = (self.bins(a), self.bins(b));
                let (pa, pb) = (B::prim(a), B::prim(b));
                for axis in 0..3 {
                    even[axis][bin(ba[axis])].add(pa);
                    odd[axis][bin(bb[axis])].add(pb);
                }
            }
            for p in rest {
                let (bp, pp) = (self.bins(p), B::prim(p));
                for (axis, bins) in even.iter_mut().enumerate() {
                    bins[bin(bp[axis])].add(pp);
                }
            }
        }
        for axis in self.axes.clone() {
            let out = &mut out.0[axis];
            for b in 0..used {
                let (first, count) = even[axis][b].settle();
                (out.boxes[b], out.counts[b]) = if one_set {
                    (first, count)
                } else {
                    let (second, more) = odd[axis][b].settle();
                    (first.union(second), count + more)
                };
            }
        }
    }

    /// The loop of [`Binning::fill_sets`] over two sets on axis `AXIS` alone: even prims into
    /// `even`, odd ones into `odd`.
    #[inline(always)]
    fn fill_axis<const AXIS: usize, B: BinBox>(
        &self,
        prims: &[Prim],
        even: &mut [B; BINS],
        odd: &mut [B; BINS],
    ) {
        let bin = |p: &Prim| self.bins(p)[AXIS] as usize & (BINS - 1);
        let pairs = prims.chunks_exact(2);
        let rest = pairs.remainder();
        for pair in pairs {
            let (a, b) = (&pair[0], &pair[1]);
            even[bin(a)].add(B::prim(a));
            odd[bin(b)].add(B::prim(b));
        }
        for p in rest {
            even[bin(p)].add(B::prim(p));
        }
    }

    /// The cheapest split that leaves both sides non-empty, if any. `parent_area` is the
    /// node's [`Aabb::half_area`].
    pub fn best_split(&self, bins: &Bins, parent_area: f32) -> Option<Split> {
        let used = self.count;
        let mut best: Option<(usize, usize, f32)> = None;
        for axis in self.axes.clone() {
            let bins = &bins.0[axis];
            // Sweep from the right: area × count of bins b.. for each b.
            let mut right_cost = [0f32; BINS];
            let mut right_count = [0u32; BINS];
            let (mut acc, mut count) = (Aabb::EMPTY, 0);
            for b in (1..used).rev() {
                acc = acc.union(bins.boxes[b]);
                count += bins.counts[b];
                right_cost[b] = acc.half_area() * count as f32;
                right_count[b] = count;
            }
            let (mut acc, mut count) = (Aabb::EMPTY, 0);
            for b in 0..used - 1 {
                acc = acc.union(bins.boxes[b]);
                count += bins.counts[b];
                if count == 0 || right_count[b + 1] == 0 {
                    continue;
                }
                let cost = TRAVERSAL_COST
                    + (acc.half_area() * count as f32 + right_cost[b + 1])
                        / parent_area.max(f32::MIN_POSITIVE);
                if best.is_none_or(|(_, _, c)| cost < c) {
                    best = Some((axis, b, cost));
                }
            }
        }
        let (axis, bin, cost) = best?;
        let boxes = &bins.0[axis].boxes[..used];
        let union = |bs: &[Aabb]| bs.iter().fold(Aabb::EMPTY, |a, &b| a.union(b));
        Some(Split {
            side: Side {
                axis,
                origin: self.origin.as_array_ref()[axis],
                scale: self.scale.as_array_ref()[axis],
                limit: (bin + 1) as f32,
            },
            cost,
            left: union(&boxes[..=bin]),
            right: union(&boxes[bin + 1..]),
        })
    }
}

/// A split: the prims on the left of `side` (those whose centroid falls in the bins up to the
/// split) go left.
#[derive(Debug, Clone, Copy)]
pub struct Split {
    pub side: Side,
    /// Heuristic cost, in triangle tests.
    pub cost: f32,
    /// The triangle boxes of the two sides, from their bins.
    pub left: Aabb,
    pub right: Aabb,
}
