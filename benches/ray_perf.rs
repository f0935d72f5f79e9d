//! The ray tracer on the two shared speed-target scenes, `../shared/perf/bunny.toml` (69,451
//! triangles) and `../shared/perf/icosphere.toml` (1,310,720 triangles), the scenes
//! `../shared/perf/vs-embree.sh` times beside Embree:
//!
//! - `build`: building the scene's acceleration structure (bounding spheres and BVHs).
//! - `trace WxH`: a render with that structure kept, shadows on, at 1920×1080 and 640×360:
//!   what `vs-embree.sh` reports as rastray's trace time.
//!
//! And many objects against one mesh (`ray many boxes`): the scene of `scripts/many-boxes.py`,
//! 313,713 unit boxes (3,764,556 triangles) each its own object, against one object holding the
//! same triangles, ray traced at 640×480 with the acceleration structure kept (`boxes trace`,
//! `one mesh trace`) and built (`boxes build`, `one mesh build`).

use std::hint::black_box;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};
use rastray::mesh::Mesh;
use rastray::render::{Algorithm, Frame, Progress, RenderOptions, Renderer};
use rastray::world::WorldObject;
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

/// Boxes in the many-objects scene, as `scripts/many-boxes.py` makes it.
const BOXES: usize = 313_713;

/// The scene of `scripts/many-boxes.py`: [`BOXES`] unit boxes on a cubic grid of spacing 2 (68
/// a side, the last layer partly filled), seen from inside down a corridor between them, one
/// light.
fn many_boxes() -> (Scene, World) {
    let side = 68;
    let far = 2 * (side - 1);
    let mid = 2 * (side / 2) + 1;
    let eye = 2 * (side / 16) + 1;
    let mut toml =
        String::from("ambient = 0.1\nbackground = [0.04, 0.05, 0.08]\nmax_depth = 2\nobject = [\n");
    for n in 0..BOXES {
        let (i, j, k) = (n % side, n / side % side, n / (side * side));
        toml += &format!(
            "{{type=\"box\",center=[{},{},{}],size=[1,1,1]}},\n",
            2 * i,
            2 * j,
            2 * k
        );
    }
    toml += &format!(
        "]\n[camera]\nposition = [{mid}, {mid}, {eye}]\ntarget = [{}, {}, {far}]\nfov = 60.0\n\
         [[light]]\nposition = [{}, {}, -10]\nintensity = 0.9\n",
        mid + 13,
        mid + 8,
        far + 10,
        far + 40
    );
    let scene = rastray::scene::from_toml_str(&toml, Path::new("boxes.toml")).expect("valid");
    let world = World::build(&scene, Path::new(".")).expect("world");
    (scene, world)
}

/// `world` with all its objects' triangles in one object (the first object's material).
fn one_mesh(world: &World) -> World {
    let mut mesh = Mesh {
        flat: true,
        ..Mesh::default()
    };
    for o in &world.objects {
        let base = mesh.positions.len() as u32;
        mesh.positions.extend_from_slice(&o.mesh.positions);
        mesh.normals.extend_from_slice(&o.mesh.normals);
        mesh.triangles
            .extend(o.mesh.triangles.iter().map(|t| t.map(|i| i + base)));
    }
    World {
        objects: vec![WorldObject::new(mesh, world.objects[0].material)],
        lights: world.lights.clone(),
        ambient: world.ambient,
        background: world.background,
        max_depth: world.max_depth,
        falloff: world.falloff,
    }
}

fn many_objects(c: &mut Criterion) {
    let (scene, boxes) = many_boxes();
    let mesh = Arc::new(one_mesh(&boxes));
    let boxes = Arc::new(boxes);
    let mut group = c.benchmark_group("ray many boxes");
    for (name, world) in [("boxes", &boxes), ("one mesh", &mesh)] {
        let options = || RenderOptions::new(Algorithm::Ray, 640, 480);
        group.bench_function(format!("{name} build"), |b| {
            b.iter(|| black_box(Renderer::new(options()).prepare(world, &Progress::new())))
        });
        let mut renderer = Renderer::new(options());
        renderer
            .prepare(world, &Progress::new())
            .expect("not cancelled");
        let mut frame = Frame::default();
        group.bench_function(format!("{name} trace 640x480"), |b| {
            b.iter(|| {
                let stats = renderer
                    .render(world, &scene.camera, &Progress::new(), &mut frame)
                    .expect("not cancelled");
                black_box((stats, &frame.pixels[0]));
            })
        });
    }
    group.finish();
}

/// Ten samples of four seconds each: the icosphere's build and 1080p trace take about 0.3 s.
fn config() -> Criterion {
    Criterion::default()
        .sample_size(10)
        .measurement_time(Duration::from_secs(4))
}

criterion_group!(name = benches; config = config(); targets = ray_tracer, many_objects);
criterion_main!(benches);
