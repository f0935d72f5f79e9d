//! The ray tracer on about a million triangles: an icosahedron with 8 subdivisions
//! (20·4⁸ = 1,310,720 faces).
//!
//! `bvh build`: building the scene's acceleration structure (bounding spheres and one BVH).
//! `primary rays 1920x1080`: tracing with that structure already built, shadows and reflections
//! off, so every ray is a camera ray: 2,073,600 rays per iteration, with the sphere covering
//! about a third of the image, and filling its height (about 70% of the pixels).

use std::hint::black_box;
use std::path::Path;
use std::time::Duration;

use std::sync::Arc;

use criterion::{Criterion, criterion_group, criterion_main};
use glam::Vec3;
use rastray::render::{Algorithm, Frame, Progress, RenderOptions, Renderer};
use rastray::scene::{Camera, Light, Object, Shape};
use rastray::{Scene, World};

fn million_triangles() -> (Scene, Arc<World>) {
    let scene = Scene {
        camera: Camera {
            position: Vec3::new(0.0, 0.5, 3.5),
            target: Vec3::ZERO,
            up: Vec3::Y,
            fov: 45.0,
            ..Camera::default()
        },
        lights: vec![Light::default()],
        objects: vec![Object::new(Shape::Icosahedron {
            center: Vec3::ZERO,
            radius: 1.0,
            subdivisions: 8,
        })],
        ..Scene::default()
    };
    let world = World::build(&scene, Path::new(".")).expect("a built-in scene builds");
    assert_eq!(world.triangle_count(), 1_310_720);
    (scene, Arc::new(world))
}

fn ray_tracer(c: &mut Criterion) {
    let (scene, world) = million_triangles();
    let mut group = c.benchmark_group("icosahedron k=8 (1.3M triangles)");
    let primary = RenderOptions {
        shadows: false,
        max_depth: Some(0),
        ..RenderOptions::new(Algorithm::Ray, 1920, 1080)
    };
    group.bench_function("bvh build", |b| {
        b.iter(|| black_box(Renderer::new(primary).prepare(&world, &Progress::new())))
    });
    // One renderer for all the renders below: its BVH is built once, here.
    let mut renderer = Renderer::new(primary);
    renderer
        .prepare(&world, &Progress::new())
        .expect("not cancelled");
    let filling = Camera {
        position: Vec3::new(0.0, 0.0, 2.2),
        ..scene.camera
    };
    let mut frame = Frame::default();
    for (name, camera) in [("a third", scene.camera), ("filling", filling)] {
        group.bench_function(format!("primary rays 1920x1080, sphere {name}"), |b| {
            b.iter(|| {
                let stats = renderer.render(&world, &camera, &Progress::new(), &mut frame);
                black_box(&frame.pixels);
                black_box(stats)
            })
        });
    }
    group.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(5));
    targets = ray_tracer
}
criterion_main!(benches);
