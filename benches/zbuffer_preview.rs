//! The Z-buffer at the editor's preview size (160×96) on the Stanford bunny (69,451 triangles,
//! ../shared/perf/bunny.toml), Gouraud and Phong, on the default thread count: as the editor
//! renders it on every key (one renderer kept, so its working memory is reused), and as a
//! one-off render by a new renderer (as `rastray bench throughput` and vs-peer.sh time it); and
//! with the renderer kept on 1 and on 2 threads, to show what the second thread adds.
//! Skipped, with a message, where the shared models are not beside the project.

use std::hint::black_box;
use std::num::NonZeroUsize;
use std::path::Path;
use std::sync::Arc;
use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};
use rastray::render::{Algorithm, Frame, Progress, RenderOptions, Renderer};
use rastray::{Scene, World};

/// The preview size: a pane of 160×48 cells.
const SIZE: (u32, u32) = (160, 96);

fn bunny() -> Option<(Scene, Arc<World>)> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/perf/bunny.toml");
    let scene = rastray::scene::load(&path).ok()?;
    let world = World::build(&scene, path.parent()?).ok()?;
    Some((scene, Arc::new(world)))
}

fn preview(c: &mut Criterion) {
    let Some((scene, world)) = bunny() else {
        eprintln!("zbuffer_preview: ../shared/perf/bunny.toml not found; skipped");
        return;
    };
    let (width, height) = SIZE;
    let mut group = c.benchmark_group(format!("bunny {width}x{height}"));
    for algorithm in [Algorithm::Gouraud, Algorithm::Phong] {
        let options = RenderOptions::new(algorithm, width, height);
        let mut frame = Frame::default();
        let mut kept = Renderer::new(options);
        group.bench_function(format!("{} kept renderer", algorithm.name()), |b| {
            b.iter(|| {
                kept.render(&world, &scene.camera, &Progress::new(), &mut frame)
                    .expect("render");
                black_box(&frame.pixels);
            })
        });
        group.bench_function(format!("{} new renderer", algorithm.name()), |b| {
            b.iter(|| {
                Renderer::new(options)
                    .render(&world, &scene.camera, &Progress::new(), &mut frame)
                    .expect("render");
                black_box(&frame.pixels);
            })
        });
        for threads in [1, 2] {
            let mut kept = Renderer::new(RenderOptions {
                threads: NonZeroUsize::new(threads),
                ..options
            });
            let name = format!("{} kept renderer, {threads} thread(s)", algorithm.name());
            group.bench_function(name, |b| {
                b.iter(|| {
                    kept.render(&world, &scene.camera, &Progress::new(), &mut frame)
                        .expect("render");
                    black_box(&frame.pixels);
                })
            });
        }
    }
    group.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .sample_size(30)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3));
    targets = preview
}
criterion_main!(benches);
