//! The `Renderer`: a reused frame is rewritten to the last bit whatever it held, the ray
//! tracer's BVH is built once per world and kept across camera moves and option changes, and the
//! stats say what each render did.

mod common;

use std::sync::Arc;
use std::time::Duration;

use glam::Vec3;
use rastray::World;
use rastray::render::{Algorithm, Frame, Progress, RenderError, RenderOptions, Renderer};
use rastray::scene::Camera;

/// The bits of every pixel: equal images, not merely close ones.
fn bits(f: &Frame) -> Vec<[u32; 3]> {
    f.pixels
        .iter()
        .map(|p| p.to_array().map(f32::to_bits))
        .collect()
}

#[test]
fn a_reused_frame_is_rewritten_to_the_last_bit() {
    let scene = common::default_scene();
    let world = common::world(&scene);
    let progress = Progress::new();
    for algorithm in Algorithm::ALL {
        for samples in [1, 2] {
            let options = RenderOptions {
                samples,
                ..RenderOptions::new(algorithm, 96, 54)
            };
            let (fresh, _) = common::render(&world, &scene.camera, options);
            let mut renderer = Renderer::new(options);
            // A frame of the same size full of NaN: any pixel left unwritten shows.
            let mut reused = Frame::filled(96, 54, Vec3::NAN);
            renderer
                .render(&world, &scene.camera, &progress, &mut reused)
                .expect("render");
            assert_eq!(
                bits(&reused),
                bits(&fresh),
                "{algorithm}, {samples}x{samples}"
            );
            // A frame of another size takes the new size.
            let mut other = Frame::filled(7, 5, Vec3::NAN);
            renderer
                .render(&world, &scene.camera, &progress, &mut other)
                .expect("render");
            assert_eq!((other.width, other.height), (96, 54));
            assert_eq!(bits(&other), bits(&fresh), "{algorithm}, resized");
        }
    }
}

/// The default scene's camera moved half a unit to the right.
fn moved(camera: &Camera) -> Camera {
    Camera {
        position: camera.position + Vec3::X * 0.5,
        ..*camera
    }
}

#[test]
fn the_bvh_is_built_once_per_world_and_kept_across_cameras_and_options() {
    let scene = common::default_scene();
    let world = common::world(&scene);
    let progress = Progress::new();
    let ray = RenderOptions::new(Algorithm::Ray, 64, 36);
    let mut renderer = Renderer::new(ray);
    let mut frame = Frame::default();
    let first = renderer
        .render(&world, &scene.camera, &progress, &mut frame)
        .expect("render");
    assert!(first.prepare > Duration::ZERO, "the first render builds");
    assert_eq!(
        first.prepare, first.bvh_build,
        "building is all it prepares"
    );

    // Another camera, then other options and another algorithm and back: nothing is rebuilt,
    // and the images are those of a renderer that starts afresh.
    let camera = moved(&scene.camera);
    let kept = renderer
        .render(&world, &camera, &progress, &mut frame)
        .expect("render");
    assert_eq!(kept.prepare, Duration::ZERO, "a camera move keeps the BVH");
    assert_eq!(kept.bvh_build, first.bvh_build, "the same BVH");
    assert_eq!(bits(&frame), bits(&common::render(&world, &camera, ray).0));
    let options = [
        RenderOptions {
            samples: 2,
            shadows: false,
            max_depth: Some(0),
            ..RenderOptions::new(Algorithm::Ray, 80, 45)
        },
        RenderOptions::new(Algorithm::Phong, 64, 36),
        ray,
    ];
    for options in options {
        renderer.set_options(options);
        let stats = renderer
            .render(&world, &camera, &progress, &mut frame)
            .expect("render");
        assert_eq!(stats.prepare, Duration::ZERO, "{options:?} rebuilt");
        let fresh = common::render(&world, &camera, options).0;
        assert_eq!(bits(&frame), bits(&fresh), "{options:?}");
    }

    // A world with the same contents but another identity is another world: built again.
    let copy = Arc::new(World::clone(&world));
    let rebuilt = renderer
        .render(&copy, &camera, &progress, &mut frame)
        .expect("render");
    assert!(
        rebuilt.prepare > Duration::ZERO,
        "another world is prepared"
    );
    assert_eq!(rebuilt.prepare, rebuilt.bvh_build);
}

#[test]
fn prepare_builds_ahead_and_the_render_then_builds_nothing() {
    let scene = common::default_scene();
    let world = common::world(&scene);
    let progress = Progress::new();
    let mut renderer = Renderer::new(RenderOptions::new(Algorithm::Ray, 32, 18));
    let prepared = renderer.prepare(&world, &progress).expect("prepare");
    assert!(prepared.prepare > Duration::ZERO);
    let mut frame = Frame::default();
    let stats = renderer
        .render(&world, &scene.camera, &progress, &mut frame)
        .expect("render");
    assert_eq!(stats.prepare, Duration::ZERO);
    assert_eq!(stats.bvh_build, prepared.bvh_build);
    // The Z-buffer prepares nothing at all.
    renderer.set_options(RenderOptions::new(Algorithm::Gouraud, 32, 18));
    let fresh = Arc::new(World::clone(&world));
    let zbuffer = renderer.prepare(&fresh, &progress).expect("prepare");
    assert_eq!(
        (zbuffer.prepare, zbuffer.bvh_build),
        (Duration::ZERO, Duration::ZERO)
    );
}

#[test]
fn stats_count_what_each_algorithm_did() {
    let scene = common::default_scene();
    let world = common::world(&scene);
    for algorithm in Algorithm::ALL {
        for samples in [1, 3] {
            let options = RenderOptions {
                samples,
                ..RenderOptions::new(algorithm, 40, 30)
            };
            let (_, stats) = common::render(&world, &scene.camera, options);
            assert_eq!(stats.triangles, world.triangle_count(), "{algorithm}");
            assert_eq!(stats.total(), stats.prepare + stats.draw + stats.filter);
            assert_eq!(
                stats.filter == Duration::ZERO,
                samples == 1,
                "{algorithm}: only supersampling filters"
            );
            if algorithm == Algorithm::Ray {
                // One primary ray per sample; the default scene has lights and mirrors.
                assert_eq!(stats.rays.primary, 40 * 30 * (samples * samples) as u64);
                assert!(
                    stats.rays.shadow > 0 && stats.rays.reflection > 0,
                    "{stats:?}"
                );
                assert!(stats.bvh_build > Duration::ZERO);
            } else {
                assert_eq!(stats.rays.total(), 0, "{algorithm} casts no rays");
                assert_eq!(stats.bvh_build, Duration::ZERO, "{algorithm} uses no BVH");
            }
        }
    }
}

#[test]
fn a_cancelled_render_stops_before_building_and_a_later_one_builds() {
    let scene = common::default_scene();
    let world = common::world(&scene);
    let mut renderer = Renderer::new(RenderOptions::new(Algorithm::Ray, 32, 18));
    let mut frame = Frame::default();
    let cancelled = Progress::new();
    cancelled.cancel();
    let error = renderer
        .render(&world, &scene.camera, &cancelled, &mut frame)
        .expect_err("cancelled");
    assert!(matches!(error, RenderError::Cancelled(_)), "{error}");
    let stats = renderer
        .render(&world, &scene.camera, &Progress::new(), &mut frame)
        .expect("render");
    assert!(
        stats.prepare > Duration::ZERO,
        "the cancelled render built nothing"
    );
}

#[test]
fn options_beyond_the_limits_are_refused_before_anything_is_drawn() {
    let scene = common::default_scene();
    let world = common::world(&scene);
    let mut renderer = Renderer::new(RenderOptions {
        samples: 9,
        ..RenderOptions::new(Algorithm::Phong, 32, 18)
    });
    let mut frame = Frame::filled(2, 2, Vec3::ONE);
    let error = renderer
        .render(&world, &scene.camera, &Progress::new(), &mut frame)
        .expect_err("9 samples");
    assert!(matches!(error, RenderError::Size(_)), "{error}");
    assert_eq!(
        (frame.width, frame.height),
        (2, 2),
        "the frame is untouched"
    );
}

/// A kept Z-buffer plans a frame's per-object work by the last frame's: whatever the last frame
/// was (another camera, another world with as many objects), every frame must come out as a new
/// renderer draws it, to the bit.
#[test]
fn a_kept_z_buffer_draws_every_frame_as_a_new_renderer_would() {
    let scene = common::default_scene();
    let world = common::world(&scene);
    // The same objects in reverse order: as many objects, each the size of another.
    let mut reversed = scene.clone();
    reversed.objects.reverse();
    let reversed_world = common::world(&reversed);
    let far = Camera {
        position: scene.camera.position * 6.0,
        ..scene.camera
    };
    let frames = [
        (&world, scene.camera),
        (&world, moved(&scene.camera)),
        (&world, far),
        (&reversed_world, scene.camera),
        (&reversed_world, far),
        (&world, scene.camera),
    ];
    let progress = Progress::new();
    for algorithm in [Algorithm::Gouraud, Algorithm::Phong] {
        for threads in [1, 2] {
            let options = RenderOptions {
                threads: std::num::NonZeroUsize::new(threads),
                ..RenderOptions::new(algorithm, 160, 96)
            };
            let mut renderer = Renderer::new(options);
            let mut frame = Frame::default();
            for (i, (world, camera)) in frames.iter().enumerate() {
                renderer
                    .render(world, camera, &progress, &mut frame)
                    .expect("render");
                let fresh = common::render(world, camera, options).0;
                assert_eq!(
                    bits(&frame),
                    bits(&fresh),
                    "{algorithm}, {threads} thread(s), frame {i}"
                );
            }
        }
    }
}
