//! Where the editor's start-up goes on a model opened on its own, stage by stage, as the editor
//! does it: the file loaded, its scene made, the world built (with the smooth normals timed on
//! their own, once more, beside it), the worker's checks of the new world (warnings, bounds,
//! memory estimate), and the first Z-buffer frame at the preview's size. Each stage is timed by
//! wall clock on the threads given (`RAYON_NUM_THREADS`, default all cores).
//!
//! Run with `cargo run --release --example first_frame MODEL [WIDTHxHEIGHT] [phong|gouraud|ray]`
//! (default 120x92, about what a 160×48-cell terminal's preview draws in half blocks, Phong).

use std::path::PathBuf;
use std::sync::Arc;
use std::time::Instant;

use rastray::memory_budget::Estimate;
use rastray::mesh::with_colors_and_normals;
use rastray::render::{Algorithm, Frame, Progress, RenderOptions, Renderer};
use rastray::scene::UpAxis;
use rastray::world::{MeshFileCache, World};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let path = PathBuf::from(
        args.first()
            .expect("usage: first_frame MODEL [WxH] [ALGORITHM]"),
    );
    let (width, height) = args
        .get(1)
        .and_then(|s| s.split_once('x'))
        .map(|(w, h)| (w.parse().expect("width"), h.parse().expect("height")))
        .unwrap_or((120, 92));
    let algorithm = match args.get(2).map(String::as_str) {
        Some("gouraud") => Algorithm::Gouraud,
        Some("ray") => Algorithm::Ray,
        _ => Algorithm::Phong,
    };
    let all = Instant::now();
    let mut stage = Instant::now();
    let mut lap = |name: &str| {
        println!("{name:<28} {:>8.1} ms", stage.elapsed().as_secs_f64() * 1e3);
        stage = Instant::now();
    };

    let mut cache = MeshFileCache::default();
    let model = cache.get(&path).expect("the model loads");
    lap("load (parse, weld)");
    let scene = rastray::model_scene::scene_for_loaded_model(&path, &model, UpAxis::default())
        .expect("a scene of the model");
    lap("scene for the model");
    let base = path.parent().map(PathBuf::from).unwrap_or_default();
    let report = World::build_report(&scene, &base, &mut cache).expect("the world builds");
    lap("world build (all)");
    let world = Arc::new(report.world);
    let found = rastray::warnings(&scene, &scene.camera, &world);
    let bounds = world.bounds();
    let budget = Estimate::of_world(&world);
    lap("warnings, bounds, estimate");
    let options = RenderOptions::new(algorithm, width, height);
    let mut renderer = Renderer::new(options);
    let mut frame = Frame::default();
    let stats = renderer
        .render(&world, &scene.camera, &Progress::new(), &mut frame)
        .expect("the first frame renders");
    lap("first frame");
    let total = all.elapsed();
    println!(
        "{:<28} {:>8.1} ms  ({} triangles, {} warnings, bounds {}, estimate {} B; frame {} ms of it)",
        "start-up to first frame",
        total.as_secs_f64() * 1e3,
        world.triangle_count(),
        found.len(),
        bounds.is_some(),
        budget.bytes(),
        stats.total().as_millis()
    );

    // Beside it, the frame again from the same renderer (what is kept between frames), and
    // a first frame of a new renderer on the same world.
    let again = renderer
        .render(&world, &scene.camera, &Progress::new(), &mut frame)
        .expect("renders");
    let fresh = Renderer::new(options)
        .render(
            &world,
            &scene.camera,
            &Progress::new(),
            &mut Frame::default(),
        )
        .expect("renders");
    println!(
        "{:<28} {:>8.1} ms  (a new renderer's first frame: {:.1} ms)",
        "  the next frame",
        again.total().as_secs_f64() * 1e3,
        fresh.total().as_secs_f64() * 1e3
    );

    // Beside it, the smooth normals alone on the file's positions, as the world build makes them.
    let geometry = &model.parts()[0].geometry;
    let started = Instant::now();
    let mesh = with_colors_and_normals(
        &geometry.positions,
        &geometry.triangles,
        geometry.colors.as_deref(),
        scene.objects[0].smooth,
    );
    println!(
        "{:<28} {:>8.1} ms  (again, on their own; {} vertices)",
        "  of which normals",
        started.elapsed().as_secs_f64() * 1e3,
        mesh.positions.len()
    );
    drop(mesh);
    let _keep = (world, model);
}
