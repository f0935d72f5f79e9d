//! `rastray render`: one scene to one PNG, with the render time and a progress bar for long renders.

use std::path::PathBuf;
use std::time::{Duration, Instant};

use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};
use rastray::World;
use rastray::export::save_png;
use rastray::render::{Algorithm, Progress, RenderOptions, Size, render};

/// A long render shows a progress bar after this long.
const PROGRESS_DELAY: Duration = Duration::from_millis(400);

#[derive(Debug, Args)]
pub struct RenderArgs {
    /// Scene file (TOML); the built-in default scene when absent.
    pub scene: Option<PathBuf>,
    /// Algorithm.
    #[arg(short, long, value_enum, default_value_t = Algorithm::Phong)]
    pub algorithm: Algorithm,
    /// Image size, WIDTHxHEIGHT.
    #[arg(short, long, default_value = "1920x1080", value_parser = super::parse_size)]
    pub size: Size,
    /// Supersampling: N×N samples per pixel (1 to 8).
    #[arg(long, default_value_t = 1)]
    pub samples: u32,
    /// Ray tracer: reflection depth, 0 to 16 (default: the scene's max_depth).
    #[arg(long, value_parser = clap::value_parser!(u32).range(0..=rastray::scene::MAX_DEPTH as i64))]
    pub max_depth: Option<u32>,
    /// Ray tracer: cast no shadow rays.
    #[arg(long)]
    pub no_shadows: bool,
    /// Output PNG file.
    #[arg(short, long, default_value = "out.png")]
    pub output: PathBuf,
}

pub fn run(args: &RenderArgs) -> anyhow::Result<()> {
    let (scene, base) = super::load_scene(args.scene.as_deref())?;
    let options = RenderOptions {
        algorithm: args.algorithm,
        width: args.size.width,
        height: args.size.height,
        samples: args.samples,
        shadows: !args.no_shadows,
        max_depth: args.max_depth,
    };
    options.check()?;
    let world = World::build(&scene, &base)?;
    super::print_warnings(&scene, &world);
    let progress = Progress::new();
    let started = Instant::now();
    let (frame, elapsed) = std::thread::scope(|s| {
        let job = s.spawn(|| {
            let frame = render(&world, &scene.camera, &options, &progress);
            (frame, started.elapsed())
        });
        let mut bar: Option<ProgressBar> = None;
        while !job.is_finished() {
            std::thread::sleep(Duration::from_millis(5));
            if bar.is_none() && started.elapsed() > PROGRESS_DELAY {
                let b = ProgressBar::new(1000);
                b.set_style(
                    ProgressStyle::with_template(
                        "{spinner} {msg} [{bar:40}] {percent}% ({elapsed})",
                    )
                    .expect("a valid template")
                    .progress_chars("=> "),
                );
                b.set_message(format!("{} {}", options.algorithm, args.size));
                bar = Some(b);
            }
            if let Some(b) = &bar {
                b.set_position((progress.fraction() * 1000.0) as u64);
            }
        }
        if let Some(b) = bar {
            b.finish_and_clear();
        }
        job.join().expect("the render thread does not panic")
    });
    let frame = frame?;
    save_png(&frame, &args.output)?;
    println!(
        "{} {}x{} ({}x{} samples, {} triangles) rendered in {:.1} ms; wrote {}",
        options.algorithm,
        frame.width,
        frame.height,
        options.samples,
        options.samples,
        world.triangle_count(),
        elapsed.as_secs_f64() * 1000.0,
        args.output.display()
    );
    Ok(())
}
