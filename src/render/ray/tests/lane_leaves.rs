//! A packet tests a leaf in one of two ways: each triangle against all eight rays when many of
//! its lanes entered the leaf, or each entering ray against up to eight triangles at once when
//! few did. Both must give the same bits. A ray alone in its packet (the other lanes miss the
//! mesh, so every leaf takes the per-ray test) must find what it finds among seven copies of
//! itself (every leaf takes the per-triangle test): on a closed sphere, with rays aimed at its
//! vertices and edges, where hits are decided in `f64` and neighbouring triangles tie.

use glam::Vec3;
use proptest::prelude::*;

use super::bvh::{direction, packet_of};
use crate::mesh::{Mesh, icosahedron};
use crate::render::ray::bvh::Bvh;
use crate::render::ray::packet::PacketHits;
use crate::render::simd::{F32x8, WIDTH};

/// A unit sphere of 20·4⁴ = 5,120 flat triangles; with `doubled`, each twice (as meshes with
/// duplicate faces have), so that two triangles tie at every hit and the first must win.
fn sphere(doubled: bool) -> Mesh {
    let mut f = icosahedron(1.0, 4);
    if doubled {
        f.triangles.extend(f.triangles.clone());
    }
    Mesh {
        normals: f.positions.clone(),
        positions: f.positions,
        triangles: f.triangles,
        colors: None,
        uvs: None,
        flat: true,
    }
}

/// A point of triangle `tri`: its first vertex (`kind` 0), a point of its first edge (1), or
/// a point inside (2).
fn point_of(mesh: &Mesh, tri: usize, kind: u8, along: f32) -> Vec3 {
    let [a, b, c] = mesh.corners(tri % mesh.triangle_count());
    match kind {
        0 => a,
        1 => a + (b - a) * along,
        _ => a + (b - a) * along * 0.5 + (c - a) * (1.0 - along) * 0.5,
    }
}

/// `ray` in lane 0; the other lanes are copies of it, or rays that miss the mesh.
fn lanes(ray: (Vec3, Vec3), copies: bool) -> Vec<(Vec3, Vec3)> {
    let away = (Vec3::splat(100.0), Vec3::X);
    (0..WIDTH)
        .map(|k| if k == 0 || copies { ray } else { away })
        .collect()
}

/// Lane 0 of `hits`, as bits.
fn lane0(hits: &PacketHits) -> [u32; 6] {
    let f = |x: F32x8| x.to_array()[0].to_bits();
    [
        f(hits.t),
        f(hits.u),
        f(hits.v),
        hits.object.to_array()[0],
        hits.triangle.to_array()[0],
        hits.slot.to_array()[0],
    ]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 400, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn a_ray_alone_in_its_packet_finds_the_bits_it_finds_among_copies_of_itself(
        tri in 0usize..5120,
        kind in 0u8..3,
        along in 0.0f32..1.0,
        eye in direction(),
        distance in 1.5f32..5.0,
        t_min in prop::sample::select(vec![0.0f32, 1e-4]),
        doubled in any::<bool>(),
    ) {
        let mesh = sphere(doubled);
        let bvh = Bvh::build(&mesh);
        let target = point_of(&mesh, tri, kind, along);
        // Nearest hits: from outside, mostly on the target's side, at a vertex, an edge or a
        // face.
        let origin = (target + eye * 0.7).normalize() * distance;
        let ray = (origin, (target - origin).normalize());
        let nearest = |copies: bool| {
            let mut hits = PacketHits::none();
            bvh.intersect_packet(&packet_of(&lanes(ray, copies), t_min), 5, &mut hits);
            lane0(&hits)
        };
        prop_assert_eq!(nearest(false), nearest(true));
        // Any hit: from the point on the sphere to a light, inside or outside it.
        let light = eye * (distance - 2.0);
        let (to_light, length) = ((light - target).normalize(), (light - target).length());
        let blocked = |copies: bool| {
            let rays = lanes((target, to_light), copies);
            let wanted = F32x8::from(f32::from_bits(u32::MAX));
            let t_max = F32x8::splat(length);
            bvh.occluded_packet(&packet_of(&rays, t_min), t_max, wanted).move_mask() & 1
        };
        prop_assert_eq!(blocked(false), blocked(true));
    }
}
