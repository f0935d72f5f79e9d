//! `rastray render`: one scene to one image or one turntable, with the time taken and a
//! progress bar for long renders.

use std::path::PathBuf;
use std::sync::Arc;
use std::time::{Duration, Instant};

use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};
use rastray::export::{Exported, MAX_FPS, MAX_FRAMES, Output, Turntable, render_to_file};
use rastray::render::{Algorithm, Progress, RenderOptions, Size};

use super::algorithm_arg::AlgorithmArg;
use super::format_arg::FormatArg;

/// A long render shows a progress bar after this long.
const PROGRESS_DELAY: Duration = Duration::from_millis(400);

#[derive(Debug, Args)]
pub struct RenderArgs {
    /// Scene file (TOML), or a model file (.obj, .gltf, .glb) shown on its own; the built-in
    /// default scene when absent.
    pub scene: Option<PathBuf>,
    /// Algorithm.
    #[arg(short, long, value_enum, default_value_t = AlgorithmArg(Algorithm::Phong))]
    pub algorithm: AlgorithmArg,
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
    /// Output file: .png or .exr for an image, .gif or .png (animated) for a turntable.
    #[arg(short, long, default_value = "out.png")]
    pub output: PathBuf,
    /// Encoding of the output (default: the extension's; .png is png8). It must match the
    /// extension.
    #[arg(long, value_enum)]
    pub format: Option<FormatArg>,
    /// Coverage as alpha: the background is transparent, edges partly so. PNG stores straight
    /// colour, OpenEXR premultiplied; in a GIF, pixels less than half covered are transparent.
    #[arg(long)]
    pub transparent: bool,
    /// Render N frames orbiting the camera once around its target, about its up vector, into
    /// a .gif or an animated .png.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=MAX_FRAMES as i64))]
    pub turntable: Option<u32>,
    /// Turntable: frames per second.
    #[arg(long, requires = "turntable", default_value_t = rastray::export::DEFAULT_FPS,
          value_parser = clap::value_parser!(u32).range(1..=MAX_FPS as i64))]
    pub fps: u32,
}

pub fn run(args: &RenderArgs) -> anyhow::Result<()> {
    let turntable = args.turntable.map(|frames| Turntable {
        frames,
        fps: args.fps,
    });
    let output = Output::for_path(&args.output, args.format.map(|f| f.0), turntable)?;
    let (scene, base) = super::load_scene(args.scene.as_deref())?;
    let options = RenderOptions {
        samples: args.samples,
        shadows: !args.no_shadows,
        max_depth: args.max_depth,
        alpha: args.transparent,
        ..RenderOptions::new(args.algorithm.0, args.size.width, args.size.height)
    };
    options.check()?;
    let world = Arc::new(super::build_world(&scene, &base)?.world);
    super::print_warnings(&scene, &world);
    let progress = Progress::new();
    let started = Instant::now();
    let exported = std::thread::scope(|s| {
        let job = s.spawn(|| {
            render_to_file(
                &world,
                &scene.camera,
                &options,
                output,
                &args.output,
                &progress,
            )
        });
        let mut bar: Option<ProgressBar> = None;
        while !job.is_finished() {
            std::thread::sleep(Duration::from_millis(5));
            if bar.is_none() && started.elapsed() > PROGRESS_DELAY {
                bar = Some(progress_bar(&options, args.size, output));
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
    let what = format!(
        "{} {}x{} ({}x{} samples",
        options.algorithm, options.width, options.height, options.samples, options.samples
    );
    match exported? {
        Exported::Image(stats) => println!(
            "{what}, {} triangles) rendered in {:.1} ms; wrote {}",
            stats.triangles,
            stats.total().as_secs_f64() * 1000.0,
            args.output.display()
        ),
        Exported::Turntable(stats) => println!(
            "{what}, {} triangles) turntable of {} frames in {:.2} s ({:.1} ms per frame); wrote {}",
            stats.triangles,
            stats.frames,
            stats.elapsed.as_secs_f64(),
            stats.elapsed.as_secs_f64() * 1000.0 / stats.frames as f64,
            args.output.display()
        ),
    }
    Ok(())
}

/// The bar shown on stderr while a long render runs (hidden when stderr is not a terminal):
/// a fraction of the rows, or of a turntable's frames.
fn progress_bar(options: &RenderOptions, size: Size, output: Output) -> ProgressBar {
    let bar = ProgressBar::new(1000);
    bar.set_style(
        ProgressStyle::with_template("{spinner} {msg} [{bar:40}] {percent}% ({elapsed})")
            .expect("a valid template")
            .progress_chars("=> "),
    );
    bar.set_message(match output {
        Output::Image(_) => format!("{} {size}", options.algorithm),
        Output::Turntable(t, format) => {
            format!(
                "{} {size}, {} frames of {format}",
                options.algorithm, t.frames
            )
        }
    });
    bar
}
