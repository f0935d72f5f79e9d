//! The BVH build's binning on AVX registers against the four-lane binning it stands in for:
//! the same boxes, bit for bit (signed zeros included), and the same counts, in every bin of
//! every axis binned, so that the tree is the same whichever the CPU runs.

use glam::Vec3A;
use proptest::prelude::*;

use crate::render::ray::bvh_prims::{Aabb, Extent, Prim};
use crate::render::ray::bvh_sah::{BinScratch, Binning, Bins};
use crate::render::ray::bvh_sah_avx2::{self, WideBins};

/// Coordinates that tie often, signed zeros among them: −0 and +0 compare equal, so which of
/// them a bin keeps depends on the order its prims are joined in.
const COORDINATES: [f32; 6] = [-1.0, -0.0, 0.0, 0.25, 0.5, 1.0];

/// Prims with corners drawn from [`COORDINATES`] (lo ≤ hi on each axis), mesh index = position.
fn prims(len: std::ops::Range<usize>) -> impl Strategy<Value = Vec<Prim>> {
    prop::collection::vec(prop::array::uniform6(0..COORDINATES.len()), len).prop_map(|cells| {
        cells
            .iter()
            .enumerate()
            .map(|(k, c)| {
                let pick = |a: usize, b: usize| {
                    let (a, b) = (COORDINATES[c[a]], COORDINATES[c[b]]);
                    if b < a { (b, a) } else { (a, b) }
                };
                let (x, y, z) = (pick(0, 1), pick(2, 3), pick(4, 5));
                Prim::new(
                    Vec3A::new(x.0, y.0, z.0),
                    Vec3A::new(x.1, y.1, z.1),
                    k as u32,
                )
            })
            .collect()
    })
}

fn bits(b: &Aabb) -> [u32; 6] {
    let (lo, hi) = (b.lo.to_array(), b.hi.to_array());
    [lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]].map(f32::to_bits)
}

/// The bins of `prims` both ways: four lanes, then AVX (`None` where the CPU lacks AVX2).
fn both(prims: &[Prim]) -> (Binning, Bins, Option<Bins>) {
    let binning = Binning::new(&Extent::of(prims).centroids, prims.len());
    let mut scratch = BinScratch::new();
    binning.fill_run_lanes(prims, &mut scratch);
    let lanes = *scratch.bins();
    let mut bins = *BinScratch::new().bins();
    let avx = bvh_sah_avx2::fill_run(&binning, prims, &mut WideBins::new(), &mut bins);
    (binning, lanes, avx.then_some(bins))
}

fn assert_same(prims: &[Prim]) -> Result<(), TestCaseError> {
    let (binning, lanes, avx) = both(prims);
    let Some(avx) = avx else { return Ok(()) };
    for axis in binning.axes() {
        for b in 0..binning.count() {
            let (l, a) = (&lanes.0[axis], &avx.0[axis]);
            prop_assert_eq!(l.counts[b], a.counts[b], "count, axis {} bin {}", axis, b);
            prop_assert_eq!(
                bits(&l.boxes[b]),
                bits(&a.boxes[b]),
                "box, axis {} bin {}",
                axis,
                b
            );
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 400, failure_persistence: None, ..ProptestConfig::default() })]

    /// Runs of one set and of two, binned on their longest axis.
    #[test]
    fn small_runs_bin_to_the_same_bits_on_avx(prims in prims(1..200)) {
        assert_same(&prims)?;
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 12, failure_persistence: None, ..ProptestConfig::default() })]

    /// Runs large enough to be binned on all three axes.
    #[test]
    fn large_runs_bin_to_the_same_bits_on_avx(prims in prims(4096..9000)) {
        assert_same(&prims)?;
    }
}

/// The bins of `prims` worked out one prim at a time: each bin's count and the union of its
/// prims' boxes, on each axis binned.
fn brute_force(binning: &Binning, prims: &[Prim]) -> Vec<(usize, usize, u32, Aabb)> {
    let mut bins = Vec::new();
    for axis in binning.axes() {
        for b in 0..binning.count() {
            let inside: Vec<&Prim> = prims
                .iter()
                .filter(|p| binning.bins(p)[axis] as usize == b)
                .collect();
            let mut union = Aabb::EMPTY;
            for p in &inside {
                union.grow(p.lo(), p.hi());
            }
            bins.push((axis, b, inside.len() as u32, union));
        }
    }
    bins
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, failure_persistence: None, ..ProptestConfig::default() })]

    /// Every prim is counted once, in its own bin, and each bin's box is the union of its prims'
    /// boxes (compared as values: which of ±0 a bin keeps is the order's business, checked
    /// above), for runs of one set, of two, and on three axes.
    #[test]
    fn each_bin_counts_and_bounds_its_prims(prims in prop_oneof![prims(1..200), prims(4096..4200)]) {
        let (binning, lanes, _) = both(&prims);
        for (axis, b, count, union) in brute_force(&binning, &prims) {
            let bins = &lanes.0[axis];
            prop_assert_eq!(bins.counts[b], count, "count, axis {} bin {}", axis, b);
            if count > 0 {
                let (lo, hi) = (bins.boxes[b].lo.to_array(), bins.boxes[b].hi.to_array());
                let (ulo, uhi) = (union.lo.to_array(), union.hi.to_array());
                prop_assert_eq!(&lo[..3], &ulo[..3], "lo, axis {} bin {}", axis, b);
                prop_assert_eq!(&hi[..3], &uhi[..3], "hi, axis {} bin {}", axis, b);
            }
        }
    }
}
