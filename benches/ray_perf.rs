//! The ray tracer on the two shared speed-target scenes, `../shared/perf/bunny.toml` (69,451
//! triangles) and `../shared/perf/icosphere.toml` (1,310,720 triangles), the scenes
//! `../shared/perf/vs-embree.sh` times beside Embree:
//!
//! - `build`: building the scene's acceleration structure (bounding spheres and BVHs).
//! - `trace WxH`: a render with that structure kept, shadows on, at 1920×1080 and 640×360:
//!   what `vs-embree.sh` reports as rastray's trace time.

use std::hint::black_box;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};
use rastray::render::{Algorithm, Frame, Progress, RenderOptions, Renderer};
use rastray::{Scene, World};

/// The folder of the shared speed-target scenes, beside the project.
fn perf_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/perf")
}

fn load(name: &str) -> (Scene, Arc<World>) {
    let path = perf_dir().join(name);
    let scene = rastray::scene::load(&path).unwrap_or_else(|e| {
        panic!(
            "{}: {e} (the shared perf scenes sit beside the project)",
            path.display()
        )
    });
    let world =
        World::build(&scene, &perf_dir()).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    (scene, Arc::new(world))
}

fn ray_tracer(c: &mut Criterion) {
    for name in ["bunny.toml", "icosphere.toml"] {
        let (scene, world) = load(name);
        let mut group = c.benchmark_group(format!("ray {name}"));
        let options = |(width, height)| RenderOptions::new(Algorithm::Ray, width, height);
        group.bench_function("build", |b| {
            b.iter(|| black_box(Renderer::new(options((64, 36))).prepare(&world, &Progress::new())))
        });
        for (width, height) in [(1920, 1080), (640, 360)] {
            // One renderer per size: its BVH is built once, here, as Embree commits a scene.
            let mut renderer = Renderer::new(options((width, height)));
            renderer
                .prepare(&world, &Progress::new())
                .expect("not cancelled");
            let mut frame = Frame::default();
            let mut trace = || {
                let stats = renderer
                    .render(&world, &scene.camera, &Progress::new(), &mut frame)
                    .expect("not cancelled");
                black_box((stats, &frame.pixels[0]));
            };
            group.bench_function(format!("trace {width}x{height}"), |b| b.iter(&mut trace));
        }
        group.finish();
    }
}

/// Ten samples of four seconds each: the icosphere's build and 1080p trace take about 0.3 s.
fn config() -> Criterion {
    Criterion::default()
        .sample_size(10)
        .measurement_time(Duration::from_secs(4))
}

criterion_group!(name = benches; config = config(); targets = ray_tracer);
criterion_main!(benches);
