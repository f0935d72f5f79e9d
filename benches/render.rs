//! Each algorithm on the default scene at preview size (200×100) and at 1920×1080, into a reused
//! frame and into a new one.

use std::hint::black_box;
use std::path::Path;
use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};
use rastray::render::{Algorithm, Frame, Progress, RenderOptions, render, render_into};
use rastray::{Scene, World};

fn default_scene() -> (Scene, World) {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
    let scene = rastray::scene::load(&dir.join("default.toml")).expect("scenes/default.toml loads");
    let world = World::build(&scene, &dir).expect("the default scene builds");
    (scene, world)
}

fn algorithms(c: &mut Criterion) {
    let (scene, world) = default_scene();
    for (width, height) in [(200, 100), (1920, 1080)] {
        let mut group = c.benchmark_group(format!("default.toml {width}x{height}"));
        for algorithm in Algorithm::ALL {
            let options = RenderOptions::new(algorithm, width, height);
            // A live preview renders into the frame it keeps; a one-off render gets a new frame
            // (at 1920x1080, 25 MB of fresh memory to fault in).
            let mut frame = Frame::default();
            group.bench_function(format!("{} reused frame", algorithm.name()), |b| {
                b.iter(|| {
                    render_into(
                        &world,
                        &scene.camera,
                        &options,
                        &Progress::new(),
                        &mut frame,
                    )
                    .expect("render");
                    black_box(&frame.pixels);
                })
            });
            group.bench_function(format!("{} new frame", algorithm.name()), |b| {
                b.iter(|| black_box(render(&world, &scene.camera, &options, &Progress::new())))
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
