//! Each algorithm on the default scene at preview size (200×100) and at 1920×1080.

use std::hint::black_box;
use std::path::Path;
use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};
use rastray::render::{Algorithm, Progress, RenderOptions, render};
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
            group.bench_function(algorithm.name(), |b| {
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
