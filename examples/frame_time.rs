//! Times repeated renders of one scene: `cargo run --release --example frame_time -- SCENE WxH [ALGO] [REPS]`.
//! For each algorithm, prints the minimum, median, mean and maximum wall time per frame twice:
//! rendering into one reused frame (a live preview's steady state), and into a new frame each
//! time (a one-off render, which also faults in the fresh image's memory).

use std::path::Path;
use std::sync::Arc;
use std::time::Instant;

use rastray::World;
use rastray::render::{Algorithm, Frame, Progress, RenderOptions, Renderer, Size};

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let scene_path = args
        .first()
        .map(String::as_str)
        .unwrap_or("scenes/default.toml");
    let size: Size = args
        .get(1)
        .map(String::as_str)
        .unwrap_or("1920x1080")
        .parse()?;
    let algorithms: Vec<Algorithm> = match args.get(2).map(String::as_str) {
        Some("gouraud") => vec![Algorithm::Gouraud],
        Some("phong") => vec![Algorithm::Phong],
        Some("ray") => vec![Algorithm::Ray],
        _ => Algorithm::ALL.to_vec(),
    };
    let reps: usize = args.get(3).map(|s| s.parse()).transpose()?.unwrap_or(20);
    let path = Path::new(scene_path);
    let scene = rastray::scene::load(path)?;
    let world = Arc::new(World::build(
        &scene,
        path.parent().unwrap_or(Path::new(".")),
    )?);
    println!(
        "{scene_path}: {} triangles at {size}",
        world.triangle_count()
    );
    for algorithm in algorithms {
        let options = RenderOptions::new(algorithm, size.width, size.height);
        // Each render is a one-off, by a new renderer: the ray tracer builds its BVH each time.
        let render = |frame: &mut Frame| {
            Renderer::new(options)
                .render(&world, &scene.camera, &Progress::new(), frame)
                .expect("render");
        };
        let mut frame = Frame::default();
        let reused = time(reps, || render(&mut frame));
        let fresh = time(reps, || render(&mut Frame::default()));
        println!("{algorithm:>8}: reused frame {reused}");
        println!("{:>8}  new frame    {fresh}", "");
    }
    Ok(())
}

/// Runs `render` `reps` times; the minimum, median, mean and maximum, in milliseconds.
fn time(reps: usize, mut render: impl FnMut()) -> String {
    let mut times: Vec<f64> = (0..reps)
        .map(|_| {
            let start = Instant::now();
            render();
            start.elapsed().as_secs_f64() * 1000.0
        })
        .collect();
    let mean = times.iter().sum::<f64>() / times.len() as f64;
    times.sort_by(f64::total_cmp);
    format!(
        "min {:.2} ms, median {:.2} ms, mean {mean:.2} ms, max {:.2} ms",
        times[0],
        times[times.len() / 2],
        times[times.len() - 1]
    )
}
