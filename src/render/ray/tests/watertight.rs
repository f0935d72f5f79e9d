//! Rays through the edge two triangles share hit one of them: a closed mesh has no cracks for a
//! ray to slip through. Small, slightly folded triangles far from the ray's origin are where
//! `f32` rounding alone left a shared edge outside both (a 1.31M-triangle sphere seen from 3.7
//! radii showed pixels of its far side through its near one).

use glam::Vec3;
use proptest::prelude::*;

use super::bvh::{direction, mesh_from, packet_of};
use crate::render::ray::bvh::Bvh;
use crate::render::ray::half_line::Ray;
use crate::render::ray::intersect::Triangle;
use crate::render::ray::packet::PacketHits;

/// Two triangles folded along the edge a–b, about `size` across, on the unit sphere around
/// `centre` (a unit vector): a piece of a finely tessellated sphere.
fn fold(centre: Vec3, size: f32, jitter: [f32; 4]) -> [[Vec3; 3]; 2] {
    let side = centre.any_orthonormal_vector();
    let up = centre.cross(side);
    let at = |x: f32, y: f32| (centre + (side * x + up * y) * size).normalize();
    let (a, b) = (at(-1.0, jitter[0]), at(1.0, jitter[1]));
    let (c, d) = (at(jitter[2], 1.0), at(jitter[3], -1.0));
    // Their first vertices differ, so each works the shared edge out from another corner.
    [[a, b, c], [d, b, a]]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn a_ray_through_a_shared_edge_hits_one_of_its_triangles(
        centre in direction(),
        size in prop::sample::select(vec![0.002f32, 0.004, 0.02]),
        jitter in prop::array::uniform4(-0.3f32..0.3),
        eye_distance in 2.0f32..6.0,
        eye_offset in direction(),
        along in prop::array::uniform8(0.01f32..0.99),
    ) {
        let [first, second] = fold(centre, size, jitter);
        let (a, b) = (first[0], first[1]);
        // An eye on the side the pair faces, looking at points of the shared edge.
        let eye = centre * eye_distance + eye_offset;
        let rays: Vec<(Vec3, Vec3)> = along
            .iter()
            .map(|&k| (eye, (a + (b - a) * k - eye).normalize()))
            .collect();
        let triangles = [first, second].map(|[p, q, r]| Triangle::new(p, q, r));
        for (k, &(origin, dir)) in rays.iter().enumerate() {
            let ray = Ray::new(origin, dir);
            let hit = triangles.iter().any(|t| t.intersect(&ray, 0.0, f32::INFINITY).is_some());
            prop_assert!(hit, "ray {} at {} of the edge passed between the triangles", k, along[k]);
        }
        let bvh = Bvh::build(&mesh_from(&[first, second]));
        let mut hits = PacketHits::none();
        bvh.intersect_packet(&packet_of(&rays, 0.0), 0, &mut hits);
        for (lane, t) in hits.t.to_array().into_iter().enumerate() {
            prop_assert!(t.is_finite(), "lane {} passed between the triangles", lane);
        }
    }
}
