//! The BVH build's partition without branches against the swapping scan it replaces: the same
//! order of prims (the order of a leaf's triangles), the same count and centroid boxes.

use glam::Vec3A;
use proptest::prelude::*;

use crate::render::ray::bvh_prims::{
    Aabb, PartitionScratch, Prim, Side, partition, partition_scan,
};

/// Prims with centroids on a coarse grid (so many share a coordinate), mesh index = position.
fn prims() -> impl Strategy<Value = Vec<Prim>> {
    prop::collection::vec((0u8..8, 0u8..8, 0u8..8, 0u8..3), 0..200).prop_map(|cells| {
        cells
            .iter()
            .enumerate()
            .map(|(k, &(x, y, z, size))| {
                let lo = Vec3A::new(x as f32, y as f32, z as f32);
                Prim::new(lo, lo + Vec3A::splat(size as f32 * 0.5), k as u32)
            })
            .collect()
    })
}

fn boxes_equal(a: &Aabb, b: &Aabb) -> bool {
    a.lo.to_array()[..3] == b.lo.to_array()[..3] && a.hi.to_array()[..3] == b.hi.to_array()[..3]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 500, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn the_partition_leaves_the_order_of_the_swapping_scan(
        prims in prims(),
        axis in 0usize..3,
        limit in 0u8..18,
    ) {
        // Sides from all left to all right, through every mix.
        let side = Side { axis, origin: 0.0, scale: 1.0, limit: limit as f32 };
        let mut scanned = prims.clone();
        let mut fast = prims;
        let (n_scan, l_scan, r_scan) = partition_scan(&mut scanned, side);
        // One scratch for several calls, as a thread keeps it.
        let mut scratch = PartitionScratch::default();
        let (n_fast, l_fast, r_fast) = partition(&mut fast.clone(), side, &mut scratch);
        let (n_again, l_fast_again, r_fast_again) = partition(&mut fast, side, &mut scratch);
        prop_assert_eq!(n_fast, n_scan);
        prop_assert_eq!(n_again, n_scan);
        let order = |ps: &[Prim]| ps.iter().map(Prim::index).collect::<Vec<_>>();
        prop_assert_eq!(order(&fast), order(&scanned));
        prop_assert!(boxes_equal(&l_fast, &l_scan) && boxes_equal(&r_fast, &r_scan));
        prop_assert!(boxes_equal(&l_fast_again, &l_scan) && boxes_equal(&r_fast_again, &r_scan));
    }
}
