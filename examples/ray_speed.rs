//! Ray tracer speed figures: BVH build time, primary rays per second on a large mesh, the
//! default scene with shadows and reflections, and how time grows with the triangle count.
//!
//! Run with `cargo run --release --example ray_speed [build|primary|scaling|default]` (all four
//! when no part is named). Each figure is the best of a few runs, in wall-clock time and, where
//! the process's CPU time is readable (Linux), in CPU time: on a machine shared with other work
//! the wall clock says more about the neighbours than about the renderer, while CPU time ÷ threads
//! is what the same run takes on otherwise idle cores.

#[path = "common/cpu_time.rs"]
mod cpu_time;

use std::path::Path;
use std::sync::Arc;
use std::time::{Duration, Instant};

use cpu_time::cpu_time;

use rastray::World;
use rastray::render::{Algorithm, Frame, Progress, RenderOptions, RenderStats, Renderer};
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

/// A measured run: wall-clock and CPU time.
#[derive(Debug, Clone, Copy)]
struct Timing {
    wall: Duration,
    cpu: Duration,
}

impl Timing {
    fn ms(self) -> String {
        let threads = rayon::current_num_threads() as f64;
        format!(
            "{:.1} ms wall, {:.1} ms CPU (= {:.1} ms on {threads} idle cores)",
            self.wall.as_secs_f64() * 1e3,
            self.cpu.as_secs_f64() * 1e3,
            self.cpu.as_secs_f64() * 1e3 / threads
        )
    }

    /// Seconds on idle cores: CPU time spread over the threads, or the wall clock when CPU
    /// time is unavailable.
    fn idle_secs(self) -> f64 {
        if self.cpu.is_zero() {
            self.wall.as_secs_f64()
        } else {
            self.cpu.as_secs_f64() / rayon::current_num_threads() as f64
        }
    }
}

/// Best of [`RUNS`] runs by CPU time (wall time when CPU time is unavailable).
fn best<T>(mut run: impl FnMut() -> T) -> (Timing, T) {
    (0..RUNS)
        .map(|_| {
            let (wall0, cpu0) = (Instant::now(), cpu_time());
            let out = run();
            let timing = Timing {
                wall: wall0.elapsed(),
                cpu: cpu_time() - cpu0,
            };
            (timing, out)
        })
        .min_by_key(|(t, _)| (t.cpu, t.wall))
        .expect("at least one run")
}

/// The world of `scene`.
fn world(scene: &Scene) -> Arc<World> {
    Arc::new(World::build(scene, Path::new(".")).expect("world"))
}

/// Best render time and figures of `scene` at 1920×1080, its BVH built beforehand.
fn trace(scene: &Scene, shadows: bool, max_depth: Option<u32>) -> (Timing, RenderStats) {
    let world = world(scene);
    let options = RenderOptions {
        shadows,
        max_depth,
        ..RenderOptions::new(Algorithm::Ray, 1920, 1080)
    };
    let mut renderer = Renderer::new(options);
    renderer
        .prepare(&world, &Progress::new())
        .expect("no cancel");
    let mut frame = Frame::default();
    best(|| {
        renderer
            .render(&world, &scene.camera, &Progress::new(), &mut frame)
            .expect("no cancel")
    })
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
    let world = world(big);
    let options = RenderOptions::new(Algorithm::Ray, 1920, 1080);
    let (build, _) = best(|| Renderer::new(options).prepare(&world, &Progress::new()));
    println!(
        "BVH build, {} triangles: {}",
        world.triangle_count(),
        build.ms()
    );
}

fn primary(big: &Scene, scaling: bool) {
    let (t_big, stats) = trace(big, false, Some(0));
    println!(
        "primary rays, {} triangles, 1920x1080: {}; {:.2} M rays/s",
        stats.triangles,
        t_big.ms(),
        stats.rays.primary as f64 / t_big.idle_secs() / 1e6
    );
    if !scaling {
        return;
    }
    let small = sphere_scene(3);
    let (t_small, stats_small) = trace(&small, false, Some(0));
    println!(
        "primary rays, {} triangles, 1920x1080: {}; {:.2} M rays/s; ratio {:.2}x",
        stats_small.triangles,
        t_small.ms(),
        stats_small.rays.primary as f64 / t_small.idle_secs() / 1e6,
        t_big.idle_secs() / t_small.idle_secs()
    );
}

fn default_scene() {
    let default = rastray::scene::default_scene();
    let (t, stats) = trace(&default, true, None);
    let rays = stats.rays;
    println!(
        "default scene, 1920x1080, shadows, depth {}: {}; rays: {} primary, {} shadow, {} reflection ({:.2} M rays/s)",
        default.max_depth,
        t.ms(),
        rays.primary,
        rays.shadow,
        rays.reflection,
        rays.total() as f64 / t.idle_secs() / 1e6
    );
}
