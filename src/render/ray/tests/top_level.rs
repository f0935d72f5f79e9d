//! The tree over the objects against the flat loop over all of them: random rays through a
//! scene of a few hundred boxes and balls, some overlapping and some exact copies of another (so
//! that two objects are hit at the same t), must find the same object, triangle and t, one by
//! one and in packets, and the same occlusion.

use std::fmt::Write;
use std::path::Path;

use glam::Vec3;
use proptest::prelude::*;

use super::bvh::{direction, packet_of, point};
use crate::render::Algorithm;
use crate::render::camera::View;
use crate::render::options::RenderOptions;
use crate::render::progress::Progress;
use crate::render::ray::accel::{Hit, SceneAccel};
use crate::render::ray::half_line::Ray;
use crate::render::ray::trace_into;
use crate::render::simd::{F32x8, V3, WIDTH};
use crate::scene::from_toml_str;
use crate::world::World;

/// Objects in the scene: well past [`crate::render::ray::accel::FLAT_OBJECTS`].
const OBJECTS: usize = 300;

/// A scene of [`OBJECTS`] boxes and icosahedra at pseudo-random places in a cube of side 8
/// (a fixed pseudo-random sequence, `test_draws`), every seventh an exact copy of the one before.
fn many_objects_toml() -> String {
    let mut draw = crate::test_draws::draws(0x2545_f491);
    // 24 bits: exact in `f32`, below 1.
    let mut next = move || (draw() >> 7) as f32 / (1 << 24) as f32;
    let mut toml = String::from("[camera]\nposition = [0.0, 0.0, 9.0]\ntarget = [0.0, 0.0, 0.0]\n");
    let mut last = String::new();
    for i in 0..OBJECTS {
        if i % 7 == 6 {
            toml.push_str(&last);
            continue;
        }
        let (x, y, z) = (8.0 * next() - 4.0, 8.0 * next() - 4.0, 8.0 * next() - 4.0);
        let size = 0.1 + 0.6 * next();
        last.clear();
        if i % 3 == 0 {
            writeln!(
                last,
                "[[object]]\ntype = \"icosahedron\"\ncenter = [{x}, {y}, {z}]\nradius = {size}\nsubdivisions = 1"
            )
        } else {
            writeln!(
                last,
                "[[object]]\ntype = \"box\"\ncenter = [{x}, {y}, {z}]\nsize = [{size}, {}, {}]\nrotation = [{}, {}, 0.0]",
                size * 0.5 + 0.1,
                size,
                90.0 * next(),
                90.0 * next()
            )
        }
        .expect("writing to a String");
        toml.push_str(&last);
    }
    toml
}

/// The scene's world, searched by the tree over its objects and by the flat loop.
fn tree_and_flat() -> (SceneAccel, SceneAccel) {
    let scene = from_toml_str(&many_objects_toml(), Path::new("many.toml")).expect("valid scene");
    let world = World::build(&scene, Path::new(".")).expect("world");
    assert_eq!(world.objects.len(), OBJECTS);
    let tree = SceneAccel::build_with(&world, &Progress::new(), 0).expect("not cancelled");
    let flat = SceneAccel::build_with(&world, &Progress::new(), usize::MAX).expect("not cancelled");
    (tree, flat)
}

/// A hit as bits, so that equal means the same float bits.
fn bits(hit: Option<Hit>) -> Option<(u32, u32, u32, u32, u32)> {
    hit.map(|h| {
        (
            h.t.to_bits(),
            h.u.to_bits(),
            h.v.to_bits(),
            h.object,
            h.triangle,
        )
    })
}

proptest! {
    // Random seeds. Before boxes' far ends were widened (`BOX_FAR_MARGIN`), about 1 run in 30
    // met a packet lane where two objects hit at the same t lay on a box's face, and the tree
    // and the flat loop, whose searches start with different bounds, kept different ones.
    #![proptest_config(ProptestConfig {
        cases: 64,
        failure_persistence: None,
        ..ProptestConfig::default()
    })]

    #[test]
    fn the_tree_finds_what_the_flat_loop_finds(
        rays in prop::collection::vec((point(6.0), direction()), WIDTH),
        t_min in prop_oneof![Just(0.0f32), 0.0f32..2.0],
        ends in prop::collection::vec(0.5f32..12.0, WIDTH),
    ) {
        let (tree, flat) = tree_and_flat();
        for &(origin, dir) in &rays {
            let ray = Ray::new(origin, dir);
            prop_assert_eq!(
                bits(tree.intersect(&ray, t_min, f32::INFINITY)),
                bits(flat.intersect(&ray, t_min, f32::INFINITY))
            );
        }
        let packet = packet_of(&rays, t_min);
        let (a, b) = (tree.intersect_packet(&packet), flat.intersect_packet(&packet));
        prop_assert_eq!(a.t.to_array().map(f32::to_bits), b.t.to_array().map(f32::to_bits));
        for (k, lane) in a.hit().to_array().iter().enumerate() {
            if lane.to_bits() != 0 {
                prop_assert_eq!(a.object.to_array()[k], b.object.to_array()[k], "lane {}", k);
                prop_assert_eq!(a.triangle.to_array()[k], b.triangle.to_array()[k], "lane {}", k);
                prop_assert_eq!(a.slot.to_array()[k], b.slot.to_array()[k], "lane {}", k);
                prop_assert_eq!(a.u.to_array()[k].to_bits(), b.u.to_array()[k].to_bits());
            }
        }

        // Segments to points along the rays: blocked or not, alike one by one and in packets.
        let ends: Vec<Vec3> = rays.iter().zip(&ends).map(|(&(o, d), &s)| o + d * s).collect();
        let target = ends[0];
        for &(origin, _) in &rays {
            prop_assert_eq!(tree.occluded(origin, target), flat.occluded(origin, target));
        }
        let origins = V3::<F32x8>::gather(&std::array::from_fn::<Vec3, WIDTH, _>(|k| rays[k].0));
        let wanted = F32x8::from([-1.0f32, -1.0, 0.0, -1.0, -1.0, -1.0, 0.0, -1.0].map(|m| {
            f32::from_bits(if m < 0.0 { u32::MAX } else { 0 })
        }));
        prop_assert_eq!(
            tree.occluded_packet(origins, target, wanted).to_array().map(f32::to_bits),
            flat.occluded_packet(origins, target, wanted).to_array().map(f32::to_bits)
        );
    }
}

/// The copies in the scene do make ties: rays at a copied object hit it and its copy at the same
/// t, and both searches keep the first of the two.
#[test]
fn objects_hit_at_the_same_t_resolve_to_the_first_in_the_world() {
    let (tree, flat) = tree_and_flat();
    let mut ties = 0;
    for (i, o) in tree.objects.iter().enumerate().skip(6).step_by(7) {
        // From just outside the copy's bounding sphere toward its centre, so the copy is hit
        // unless another object overlaps it there.
        let centre = o.bounds.center;
        let origin = centre + Vec3::new(0.3, 0.2, 1.0).normalize() * (1.01 * o.bounds.radius);
        let ray = Ray::new(origin, (centre - origin).normalize());
        let (a, b) = (
            tree.intersect(&ray, 0.0, f32::INFINITY),
            flat.intersect(&ray, 0.0, f32::INFINITY),
        );
        assert_eq!(bits(a), bits(b), "object {i}");
        if a.is_some_and(|h| h.object as usize == i - 1) {
            ties += 1;
        }
    }
    assert!(
        ties > 20,
        "rays at copies that hit the original first: {ties}"
    );
}

/// The whole tracer (primary packets, shadows, reflections) draws the many-object scene to the
/// same bits with the tree over its objects as with the flat loop the renderer used before.
#[test]
fn the_many_object_scene_renders_the_same_image_with_the_tree() {
    let toml = format!(
        "max_depth = 3\n{}[[light]]\nposition = [3.0, 6.0, 8.0]\n\
         [[light]]\nposition = [-5.0, 1.0, 2.0]\nintensity = 0.4\n",
        many_objects_toml()
    );
    let scene = from_toml_str(&toml, Path::new("many.toml")).expect("valid scene");
    let mut world = World::build(&scene, Path::new(".")).expect("world");
    for o in &mut world.objects {
        o.material.reflection = 0.3;
    }
    let (width, height) = (48, 40);
    let view = View::new(&scene.camera, width, height);
    let options = RenderOptions::new(Algorithm::Ray, width, height);
    let image = |flat_objects| {
        let accel =
            SceneAccel::build_with(&world, &Progress::new(), flat_objects).expect("not cancelled");
        let mut out = vec![Vec3::ZERO; (width * height) as usize];
        let counts = trace_into(&accel, &world, &view, &options, &Progress::new(), &mut out)
            .expect("not cancelled");
        (
            out.iter()
                .map(|c| c.to_array().map(f32::to_bits))
                .collect::<Vec<_>>(),
            counts,
        )
    };
    let (tree, tree_counts) = image(0);
    let (flat, flat_counts) = image(usize::MAX);
    assert_eq!(tree_counts, flat_counts);
    assert!(
        tree_counts.shadow > 0 && tree_counts.reflection > 0,
        "{tree_counts:?}"
    );
    let differ = tree.iter().zip(&flat).filter(|(a, b)| a != b).count();
    assert_eq!(differ, 0, "pixels that differ");
    let lit = tree.iter().filter(|c| c != &&flat[0]).count();
    assert!(
        lit > 100,
        "the objects cover part of the image: {lit} pixels"
    );
}
