//! The BVH against brute force: on random meshes and random rays it must report the same
//! nearest hit and the same occlusion as testing every triangle, and a packet of eight rays the
//! same hits as each ray alone; and its structure must keep every triangle in exactly one leaf,
//! inside boxes that contain their children.

use glam::{Vec3, Vec3A};
use proptest::prelude::*;

use crate::mesh::{Mesh, icosahedron};
use crate::render::progress::{Cancelled, Progress};
use crate::render::ray::bvh::{Bvh, MAX_TREE_DEPTH, Node};
use crate::render::ray::half_line::Ray;
use crate::render::ray::intersect::Triangle;
use crate::render::ray::packet::{PacketHits, RayPacket};
use crate::render::simd::{F32x8, V3, WIDTH};

pub(super) fn mesh_from(triangles: &[[Vec3; 3]]) -> Mesh {
    let positions: Vec<Vec3> = triangles.iter().flatten().copied().collect();
    Mesh {
        normals: vec![Vec3::Y; positions.len()],
        triangles: (0..triangles.len() as u32)
            .map(|t| [3 * t, 3 * t + 1, 3 * t + 2])
            .collect(),
        positions,
        colors: None,
        uvs: None,
        flat: false,
    }
}

/// Nearest (t, triangle) by testing every triangle.
fn brute_nearest(mesh: &Mesh, ray: &Ray, t_max: f32) -> Option<(f32, u32)> {
    let mut best: Option<(f32, u32)> = None;
    for t in 0..mesh.triangle_count() {
        let [a, b, c] = mesh.corners(t);
        let limit = best.map_or(t_max, |(bt, _)| bt);
        if let Some(h) = Triangle::new(a, b, c).intersect(ray, 0.0, limit) {
            best = Some((h.t, t as u32));
        }
    }
    best
}

/// A point in the cube [-range, range]³.
pub(super) fn point(range: f32) -> impl Strategy<Value = Vec3> {
    (-range..range, -range..range, -range..range).prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

/// A unit direction.
pub(super) fn direction() -> impl Strategy<Value = Vec3> {
    point(1.0).prop_filter_map("non-zero", |d| d.try_normalize())
}

/// Small triangles scattered in a cube, so rays meet a varying number of them.
fn soup() -> impl Strategy<Value = Vec<[Vec3; 3]>> {
    prop::collection::vec(
        (point(2.0), point(0.6), point(0.6)).prop_map(|(c, e1, e2)| [c, c + e1, c + e2]),
        1..300,
    )
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn nearest_hit_matches_brute_force(
        tris in soup(),
        rays in prop::collection::vec((point(4.0), direction(), 0.5f32..10.0), 20),
    ) {
        let mesh = mesh_from(&tris);
        let bvh = Bvh::build(&mesh);
        for (origin, dir, t_max) in rays {
            let ray = Ray::new(origin, dir);
            let expected = brute_nearest(&mesh, &ray, f32::INFINITY);
            let got = bvh.intersect(&ray, 0.0, f32::INFINITY);
            match (expected, got) {
                (None, None) => {}
                (Some((t, tri)), Some(h)) => {
                    // The same arithmetic on the same triangle: the distance is identical;
                    // another triangle may win only at exactly the same distance.
                    prop_assert_eq!(h.t, t);
                    if h.triangle != tri {
                        let [a, b, c] = mesh.corners(h.triangle as usize);
                        let other = Triangle::new(a, b, c).intersect(&ray, 0.0, f32::INFINITY);
                        prop_assert_eq!(other.map(|o| o.t), Some(t));
                    }
                }
                (e, g) => prop_assert!(false, "brute force {:?}, BVH {:?}", e, g),
            }
            let blocked = brute_nearest(&mesh, &ray, t_max).is_some();
            prop_assert_eq!(bvh.occluded(&ray, 0.0, t_max), blocked);
        }
    }
}

/// Eight rays as a packet: lane k is `rays[k]`, hits beyond `t_min`.
pub(super) fn packet_of(rays: &[(Vec3, Vec3)], t_min: f32) -> RayPacket {
    let origins: Vec<Vec3> = rays.iter().map(|r| r.0).collect();
    let dirs: Vec<Vec3> = rays.iter().map(|r| r.1).collect();
    RayPacket::new(V3::gather(&origins), V3::gather(&dirs), F32x8::splat(t_min))
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn a_packet_finds_what_each_of_its_rays_finds_alone(
        tris in soup(),
        eye in point(4.0),
        towards in direction(),
        spread in prop::sample::select(vec![0.0f32, 0.01, 0.2, 2.0]),
        offsets in prop::collection::vec(point(1.0), WIDTH),
        t_min in prop::sample::select(vec![0.0f32, 0.5]),
    ) {
        // From coherent primary rays (one eye, nearby directions) to no coherence at all.
        let mesh = mesh_from(&tris);
        let bvh = Bvh::build(&mesh);
        let rays: Vec<(Vec3, Vec3)> = offsets
            .iter()
            .map(|&o| (eye, (towards + o * spread).try_normalize().unwrap_or(towards)))
            .collect();
        let mut hits = PacketHits::none();
        bvh.intersect_packet(&packet_of(&rays, t_min), 7, &mut hits);
        let (t, triangle, object) = (hits.t.to_array(), hits.triangle.to_array(), hits.object.to_array());
        for (k, &(origin, dir)) in rays.iter().enumerate() {
            let ray = Ray::new(origin, dir);
            match bvh.intersect(&ray, t_min, f32::INFINITY) {
                None => prop_assert_eq!(t[k], f32::INFINITY, "lane {} hit, the ray alone did not", k),
                Some(h) => {
                    // The same test on the same triangle, up to the order of a dot product's
                    // additions; another triangle may win only at the same distance.
                    prop_assert!((t[k] - h.t).abs() <= 1e-5 * h.t, "lane {}: {} vs {}", k, t[k], h.t);
                    prop_assert_eq!(object[k], 7);
                    if triangle[k] != h.triangle {
                        let [a, b, c] = mesh.corners(triangle[k] as usize);
                        let other = Triangle::new(a, b, c).intersect(&ray, t_min, f32::INFINITY);
                        prop_assert!(other.is_some_and(|o| (o.t - h.t).abs() <= 1e-5 * h.t));
                    }
                }
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn a_shadow_packet_finds_what_each_of_its_rays_finds_alone(
        tris in soup(),
        light in point(4.0),
        origins in prop::collection::vec(point(2.5), WIDTH),
        wanted in 0u32..256,
    ) {
        // Shadow rays: eight points toward one light, each lane its own segment length.
        let mesh = mesh_from(&tris);
        let bvh = Bvh::build(&mesh);
        let rays: Vec<(Vec3, Vec3)> = origins
            .iter()
            .map(|&o| (o, (light - o).try_normalize().unwrap_or(Vec3::X)))
            .collect();
        let lengths: [f32; WIDTH] = std::array::from_fn(|k| (light - origins[k]).length());
        let mask = bytemuck::cast::<[u32; WIDTH], F32x8>(std::array::from_fn(|k| {
            if wanted & 1 << k != 0 { u32::MAX } else { 0 }
        }));
        let blocked = bvh
            .occluded_packet(&packet_of(&rays, 0.0), F32x8::from(lengths), mask)
            .move_mask() as u32;
        for (k, &(origin, dir)) in rays.iter().enumerate() {
            let alone = wanted & 1 << k != 0 && bvh.occluded(&Ray::new(origin, dir), 0.0, lengths[k]);
            prop_assert_eq!(blocked & 1 << k != 0, alone, "lane {}", k);
        }
    }
}

/// An icosphere of 20·4⁵ = 20,480 triangles: large enough for the parallel build path.
fn sphere_mesh() -> Mesh {
    let f = icosahedron(1.0, 5);
    Mesh {
        normals: f.positions.clone(),
        positions: f.positions,
        triangles: f.triangles,
        colors: None,
        uvs: None,
        flat: false,
    }
}

#[test]
fn a_cancelled_build_stops_with_cancelled() {
    let mesh = sphere_mesh();
    let progress = Progress::new();
    assert!(Bvh::build_cancellable(&mesh, &progress).is_ok());
    progress.cancel();
    assert_eq!(
        Bvh::build_cancellable(&mesh, &progress).err(),
        Some(Cancelled)
    );
}

/// Checks `node`'s subtree: children inside their parent, triangles inside their leaf; counts
/// how often each triangle slot is reached.
fn check_subtree(bvh: &Bvh, mesh: &Mesh, node: &Node, seen: &mut [u32]) {
    let (lo, hi) = (node.lo(), node.hi());
    let inside = |p: Vec3A| p.cmpge(lo).all() && p.cmple(hi).all();
    if node.is_leaf() {
        let first = node.start() as usize;
        let slots = first..first + node.count() as usize;
        for (k, id) in slots.clone().zip(&bvh.ids[slots]) {
            seen[k] += 1;
            for v in mesh.corners(*id as usize) {
                assert!(inside(v.into()), "triangle slot {k} pokes out of its leaf");
            }
        }
    } else {
        for child in &bvh.inner[node.start() as usize].children {
            assert!(
                inside(child.lo()) && inside(child.hi()),
                "child outside its parent"
            );
            check_subtree(bvh, mesh, child, seen);
        }
    }
}

#[test]
fn every_triangle_sits_in_exactly_one_leaf() {
    let mesh = sphere_mesh();
    let bvh = Bvh::build(&mesh);
    let mut seen = vec![0u32; bvh.triangles.len()];
    check_subtree(&bvh, &mesh, &bvh.root.expect("a root"), &mut seen);
    assert!(
        seen.iter().all(|&n| n == 1),
        "a slot is in zero or two leaves"
    );
    let mut ids = bvh.ids.clone();
    ids.sort_unstable();
    assert!(ids.iter().copied().eq(0..mesh.triangle_count() as u32));
    assert_eq!(bvh.depth, bvh.measure_depth());
    assert!(bvh.depth <= MAX_TREE_DEPTH);
    println!(
        "{} triangles: {} inner nodes, depth {}",
        ids.len(),
        bvh.inner.len(),
        bvh.depth
    );
}

/// `n` small triangles along a wavy line, so that the tree has many leaves.
fn strip(n: usize) -> Mesh {
    let triangles: Vec<[Vec3; 3]> = (0..n)
        .map(|k| {
            let x = k as f32 * 0.01;
            let a = Vec3::new(x, (x * 7.0).sin(), (x * 3.0).cos());
            [
                a,
                a + Vec3::new(0.02, 0.01, 0.0),
                a + Vec3::new(0.0, 0.02, 0.01),
            ]
        })
        .collect();
    mesh_from(&triangles)
}

/// The triangles are laid out over the prims they come from (`bvh_buffer`): every slot must end
/// up holding the triangle its id names, for sizes around the rounds of that layout.
#[test]
fn every_slot_holds_the_triangle_its_id_names() {
    for n in [1, 2, 3, 4095, 4096, 8191, 8192, 8193, 20_001, 40_000] {
        let mesh = strip(n);
        let bvh = Bvh::build(&mesh);
        assert_eq!(bvh.triangles.len(), n);
        for (k, (tri, &id)) in bvh.triangles.iter().zip(&bvh.ids).enumerate() {
            let [a, b, c] = mesh.corners(id as usize);
            assert_eq!(*tri, Triangle::new(a, b, c), "slot {k} of {n}");
        }
        let mut ids = bvh.ids.clone();
        ids.sort_unstable();
        assert!(ids.iter().copied().eq(0..n as u32), "{n}: every id once");
    }
}

#[test]
fn empty_mesh_has_no_hits() {
    let bvh = Bvh::build(&Mesh::default());
    let ray = Ray::new(Vec3::ZERO, Vec3::X);
    assert!(bvh.intersect(&ray, 0.0, f32::INFINITY).is_none());
    assert!(!bvh.occluded(&ray, 0.0, f32::INFINITY));
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 100, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn the_dispatched_packet_walks_give_the_portable_walks_bits(
        tris in soup(),
        eye in point(4.0),
        towards in direction(),
        spread in prop::sample::select(vec![0.0f32, 0.01, 0.2, 2.0]),
        offsets in prop::collection::vec(point(1.0), WIDTH),
        lengths in prop::collection::vec(0.1f32..8.0, WIDTH),
        wanted in 0u32..256,
    ) {
        // Where the CPU has AVX2 the public walks run on AVX registers: they must find what the
        // SSE walk finds, bit for bit (elsewhere both are the same code).
        let bvh = Bvh::build(&mesh_from(&tris));
        let rays: Vec<(Vec3, Vec3)> = offsets
            .iter()
            .map(|&o| (eye, (towards + o * spread).try_normalize().unwrap_or(towards)))
            .collect();
        let packet = packet_of(&rays, 0.0);
        let (mut fast, mut portable) = (PacketHits::none(), PacketHits::none());
        bvh.intersect_packet(&packet, 3, &mut fast);
        bvh.nearest_in::<F32x8>(&packet, 3, &mut portable);
        let bits = |h: &PacketHits| {
            let f = |x: F32x8| x.to_array().map(f32::to_bits);
            (f(h.t), f(h.u), f(h.v), h.object.to_array(), h.triangle.to_array())
        };
        prop_assert_eq!(bits(&fast), bits(&portable));
        let t_max = F32x8::from(<[f32; WIDTH]>::try_from(lengths).unwrap());
        let mask = bytemuck::cast::<[u32; WIDTH], F32x8>(std::array::from_fn(|k| {
            if wanted & 1 << k != 0 { u32::MAX } else { 0 }
        }));
        prop_assert_eq!(
            bvh.occluded_packet(&packet, t_max, mask).move_mask(),
            bvh.any_hit_in::<F32x8>(&packet, t_max, mask).move_mask()
        );
    }
}

/// `n` unit triangles a thousand units apart along x: any split of them is cheap in area.
fn scattered(n: usize) -> Mesh {
    let triangles: Vec<[Vec3; 3]> = (0..n)
        .map(|k| {
            let a = Vec3::new(k as f32 * 1000.0, 0.0, 0.0);
            [a, a + Vec3::X, a + Vec3::Y]
        })
        .collect();
    mesh_from(&triangles)
}

#[test]
fn four_triangles_stay_one_leaf_and_eight_split() {
    // A split costs at least one visit (four triangle tests), so a node of four triangles is a
    // leaf however far apart they lie: the builder skips binning it. Eight scattered triangles
    // are worth splitting.
    let progress = Progress::new();
    let four = Bvh::build_cancellable(&scattered(4), &progress).expect("not cancelled");
    assert_eq!(four.measure_depth(), 1, "four triangles make one leaf");
    let eight = Bvh::build_cancellable(&scattered(8), &progress).expect("not cancelled");
    assert!(eight.measure_depth() > 1, "eight scattered triangles split");
}
