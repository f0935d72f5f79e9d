//! What textures cost (issue 31 asks for at most 1.3× the untextured frame time): the Khronos
//! Duck (`../shared/models/gltf/Duck.glb`) at 1920×1080, with its texture and with
//! `materials = "object"` (the same triangles, untextured), in each algorithm, into a reused
//! frame. Compare the two lines of an algorithm; `scripts/texture-cost.sh` compares binaries.

use std::hint::black_box;
use std::path::Path;
use std::sync::Arc;
use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};
use rastray::render::{Algorithm, Frame, Progress, RenderOptions, Renderer};
use rastray::{Scene, World};

/// The Duck drawn with `materials` ("file": textured, "object": untextured), with its world.
fn duck(materials: &str) -> (Scene, Arc<World>) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let model = root.join("../shared/models/gltf/Duck.glb");
    let toml = format!(
        "background = [0.1, 0.1, 0.1]\nambient = 0.2\n[[light]]\nposition = [2.0, 3.0, 4.0]\n\
         intensity = 0.8\n[camera]\nposition = [1.2, 1.0, 3.0]\ntarget = [0.0, 0.0, 0.0]\n\
         fov = 40.0\n[[object]]\ntype = \"mesh\"\npath = {:?}\nmaterials = {materials:?}\n",
        model.display().to_string()
    );
    let scene = rastray::scene::from_toml_str(&toml, Path::new("duck.toml")).expect("the scene");
    let world = World::build(&scene, root).expect("the Duck builds (../shared is needed)");
    (scene, Arc::new(world))
}

fn textures(c: &mut Criterion) {
    let looks = [("untextured", duck("object")), ("textured", duck("file"))];
    let mut group = c.benchmark_group("Duck 1920x1080");
    for algorithm in Algorithm::ALL {
        let options = RenderOptions::new(algorithm, 1920, 1080);
        for (look, (scene, world)) in &looks {
            let mut frame = Frame::default();
            group.bench_function(format!("{} {look}", algorithm.name()), |b| {
                b.iter(|| {
                    Renderer::new(options)
                        .render(world, &scene.camera, &Progress::new(), &mut frame)
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
        .sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3));
    targets = textures
}
criterion_main!(benches);
