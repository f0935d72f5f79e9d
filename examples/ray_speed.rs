//! Ray tracer speed figures: BVH build time, primary rays per second on a large mesh, the
//! default scene with shadows and reflections, and how time grows with the triangle count.
//!
//! Run with `cargo run --release --example ray_speed [build|primary|scaling|default]` (all four
//! when no part is named). Each figure is the best of a few runs.

use std::path::Path;
use std::time::{Duration, Instant};

use rastray::World;
use rastray::render::accel::SceneAccel;
use rastray::render::raytrace::{RayStats, render_with_stats};
use rastray::render::{Algorithm, Progress, RenderOptions, View};
use rastray::scene::{Scene, from_toml_str};

const RUNS: usize = 3;

fn sphere_scene(subdivisions: u32) -> Scene {
    let text = format!(
        r#"
ambient = 0.1
max_depth = 0
[camera]
position = [0.0, 0.0, 2.2]
target = [0.0, 0.0, 0.0]
fov = 45.0
[[light]]
position = [3.0, 4.0, 5.0]
[[object]]
type = "icosahedron"
radius = 1.0
subdivisions = {subdivisions}
"#
    );
    from_toml_str(&text, Path::new("sphere.toml")).expect("a valid scene")
}

fn best<T>(mut run: impl FnMut() -> (Duration, T)) -> (Duration, T) {
    (0..RUNS)
        .map(|_| run())
        .min_by_key(|(d, _)| *d)
        .expect("at least one run")
}

/// Best render time and ray counts of `scene` at 1920×1080.
fn trace(scene: &Scene, shadows: bool, max_depth: Option<u32>) -> (Duration, RayStats, SceneAccel) {
    let world = World::build(scene, Path::new(".")).expect("world");
    let accel = SceneAccel::build(&world);
    let mut options = RenderOptions::new(Algorithm::Ray, 1920, 1080);
    options.shadows = shadows;
    options.max_depth = max_depth;
    let view = View::new(&scene.camera, 1920, 1080);
    let (time, stats) = best(|| {
        let started = Instant::now();
        let (_, stats) = render_with_stats(&accel, &world, &view, &options, &Progress::new())
            .expect("no cancel");
        (started.elapsed(), stats)
    });
    (time, stats, accel)
}

fn main() {
    let part = std::env::args().nth(1);
    let wants = |name: &str| part.as_deref().is_none_or(|p| p == name);
    println!("threads: {}", rayon::current_num_threads());
    let big = sphere_scene(8);
    if wants("build") {
        build(&big);
    }
    if wants("primary") || wants("scaling") {
        primary(&big, wants("scaling"));
    }
    if wants("default") {
        default_scene();
    }
}

fn build(big: &Scene) {
    let world = World::build(big, Path::new(".")).expect("world");
    let (build, accel) = best(|| {
        let a = SceneAccel::build(&world);
        (a.build_time, a)
    });
    let bvh = &accel.objects[0].bvh;
    println!(
        "BVH build, {} triangles: {:.1} ms ({} nodes, depth {})",
        world.triangle_count(),
        build.as_secs_f64() * 1e3,
        bvh.nodes.len(),
        bvh.depth
    );
}

fn primary(big: &Scene, scaling: bool) {
    let (t_big, stats, accel) = trace(big, false, Some(0));
    println!(
        "primary rays, {} triangles, 1920x1080: {:.1} ms, {:.2} M rays/s",
        accel.triangle_count(),
        t_big.as_secs_f64() * 1e3,
        stats.primary as f64 / t_big.as_secs_f64() / 1e6
    );
    if !scaling {
        return;
    }
    let small = sphere_scene(3);
    let (t_small, stats_small, accel_small) = trace(&small, false, Some(0));
    println!(
        "primary rays, {} triangles, 1920x1080: {:.1} ms, {:.2} M rays/s; ratio {:.2}x",
        accel_small.triangle_count(),
        t_small.as_secs_f64() * 1e3,
        stats_small.primary as f64 / t_small.as_secs_f64() / 1e6,
        t_big.as_secs_f64() / t_small.as_secs_f64()
    );
}

fn default_scene() {
    let default = rastray::scene::default_scene();
    let (t, stats, _) = trace(&default, true, None);
    println!(
        "default scene, 1920x1080, shadows, depth {}: {:.1} ms; rays: {} primary, {} shadow, {} reflection ({:.2} M rays/s)",
        default.max_depth,
        t.as_secs_f64() * 1e3,
        stats.primary,
        stats.shadow,
        stats.reflection,
        stats.total() as f64 / t.as_secs_f64() / 1e6
    );
}
