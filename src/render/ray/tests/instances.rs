//! Instances of one shared mesh: its BVH is built once and held by every instance, and a ray
//! moved into the mesh's space finds the hit the same mesh placed in the world gives, at the
//! same t.

use std::path::Path;
use std::sync::Arc;

use glam::{Affine3A, Quat, Vec3};

use crate::instance::{Instance, SharedMesh};
use crate::render::progress::Progress;
use crate::render::ray::accel::{FLAT_OBJECTS, SceneAccel};
use crate::render::ray::half_line::Ray;
use crate::scene::from_toml_str;
use crate::world::{World, WorldObject};

/// A world of `count` instances of a unit box, in a row along x, each turned and scaled
/// unevenly; and the same boxes placed into meshes of their own.
fn boxes(count: usize) -> (World, World) {
    let scene = from_toml_str(
        "[[object]]\ntype = \"box\"\nsize = [1.0, 1.0, 1.0]\n",
        Path::new("box.toml"),
    )
    .expect("scene");
    let mut world = World::build(&scene, Path::new(".")).expect("world");
    let unit = world.objects.remove(0);
    let shared = Arc::new(SharedMesh {
        unique: crate::mesh::UniquePositions::of(&unit.mesh),
        corner_uvs: None,
        mesh: unit.mesh.clone(),
    });
    let instances: Vec<WorldObject> = (0..count)
        .map(|i| {
            let to_world = Affine3A::from_scale_rotation_translation(
                Vec3::new(0.5, 1.0 + 0.1 * i as f32, 0.7),
                Quat::from_rotation_y(0.3 * i as f32),
                Vec3::new(2.0 * i as f32, 0.0, 0.0),
            );
            let instance = Instance::new(shared.clone(), to_world).expect("invertible");
            WorldObject::instance_of(instance, unit.material, unit.appearance.clone())
        })
        .collect();
    let placed = instances.iter().map(WorldObject::placed).collect();
    let instanced = World {
        objects: instances,
        ..world.clone()
    };
    let baked = World {
        objects: placed,
        ..world
    };
    (instanced, baked)
}

#[test]
fn the_shared_bvh_is_built_once_and_held_by_every_instance() {
    let (world, _) = boxes(3 * FLAT_OBJECTS);
    let accel = SceneAccel::build(&world, &Progress::new()).expect("not cancelled");
    let first = &accel.objects[0].bvh;
    assert!(
        accel
            .objects
            .iter()
            .all(|o| Arc::ptr_eq(&o.bvh, first) && o.to_object.is_some())
    );
    // The objects' BVHs and the one the test holds: one allocation.
    assert_eq!(Arc::strong_count(first), 3 * FLAT_OBJECTS);
}

#[test]
fn a_ray_meets_an_instance_where_it_meets_the_placed_mesh() {
    for count in [3, 3 * FLAT_OBJECTS] {
        let (instanced, baked) = boxes(count);
        let progress = Progress::new();
        let a = SceneAccel::build(&instanced, &progress).expect("built");
        let b = SceneAccel::build(&baked, &progress).expect("built");
        for i in 0..count {
            // Down onto box i from above, off its centre; and sideways along the row.
            let target = Vec3::new(2.0 * i as f32 + 0.05, 0.0, 0.1);
            for (from, to) in [
                (target + Vec3::new(0.1, 5.0, 0.2), target),
                (Vec3::new(-5.0, 0.1, 0.05), Vec3::new(60.0, 0.1, 0.05)),
            ] {
                let ray = Ray::new(from, (to - from).normalize());
                let (ha, hb) = (
                    a.intersect(&ray, 0.0, f32::INFINITY),
                    b.intersect(&ray, 0.0, f32::INFINITY),
                );
                let (ha, hb) = (ha.expect("hit"), hb.expect("hit"));
                assert_eq!(
                    (ha.object, ha.triangle),
                    (hb.object, hb.triangle),
                    "{count}: {i}"
                );
                assert!(
                    (ha.t - hb.t).abs() <= 1e-5 * hb.t,
                    "{} against {}",
                    ha.t,
                    hb.t
                );
                // The shadow test agrees up to just before the hit and just past it.
                assert!(!a.occluded(from, from + Vec3::from(ray.dir) * (hb.t * 0.999)));
                assert!(a.occluded(from, from + Vec3::from(ray.dir) * (hb.t * 1.001)));
            }
        }
    }
}
