//! Each algorithm on the default scene at preview size (200×100) and at 1920×1080, into a reused
//! frame and into a new one. Every render is a one-off, by a new renderer: the ray tracer builds
//! its BVH each time.

use std::hint::black_box;
use std::path::Path;
use std::sync::Arc;
use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};
use rastray::render::{Algorithm, Frame, Progress, RenderOptions, Renderer};
use rastray::{Scene, World};

fn default_scene() -> (Scene, Arc<World>) {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
    let scene = rastray::scene::load(&dir.join("default.toml")).expect("scenes/default.toml loads");
    let world = World::build(&scene, &dir).expect("the default scene builds");
    (scene, Arc::new(world))
}

fn algorithms(c: &mut Criterion) {
    let (scene, world) = default_scene();
    for (width, height) in [(200, 100), (1920, 1080)] {
        let mut group = c.benchmark_group(format!("default.toml {width}x{height}"));
        for algorithm in Algorithm::ALL {
            let options = RenderOptions::new(algorithm, width, height);
            // A live preview renders into the frame it keeps; a one-off render gets a new frame
            // (at 1920x1080, 25 MB of fresh memory to fault in).
            let render = |frame: &mut Frame| {
                Renderer::new(options)
                    .render(&world, &scene.camera, &Progress::new(), frame)
                    .expect("render");
                black_box(&frame.pixels);
            };
            let mut frame = Frame::default();
            group.bench_function(format!("{} reused frame", algorithm.name()), |b| {
                b.iter(|| render(&mut frame))
            });
            group.bench_function(format!("{} new frame", algorithm.name()), |b| {
                b.iter(|| render(&mut Frame::default()))
            });
        }
        group.finish();
    }
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3));
    targets = algorithms
}
criterion_main!(benches);
