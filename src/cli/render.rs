//! `rastray render`: one scene to one image or one turntable, with the time taken and a
//! progress bar for long renders.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::{Duration, Instant};

use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};
use rastray::export::{
    AnimationFormat, Destination, Exported, MAX_FPS, MAX_FRAMES, Output, Turntable, render_to,
};
use rastray::input_file::human;
use rastray::render::{Algorithm, Progress, RenderOptions, Size};
use rastray::text_escape::Escaped;
use signal_hook::consts::{SIGINT, SIGTERM};

use rastray::World;
use rastray::preset_view::PresetView;
use rastray::scene::Camera;

use super::algorithm_arg::AlgorithmArg;
use super::camera_args::{CameraArgs, output_for_view};
use super::format_arg::FormatArg;
use super::stdout::outln;

/// A long render shows a progress bar after this long.
const PROGRESS_DELAY: Duration = Duration::from_millis(400);

#[derive(Debug, Args)]
pub struct RenderArgs {
    /// Scene file (TOML), or a model file (.obj, .stl, .ply, .gltf, .glb, or one known by its
    /// content) shown on its own; the built-in default scene when absent.
    pub scene: Option<PathBuf>,
    /// For a model file shown on its own: the axis of the file that points up (x, y, z, -x,
    /// -y, -z); CAD files are usually z. Default y.
    #[arg(long, value_parser = super::up_arg::parse_up, allow_hyphen_values = true)]
    pub up: Option<rastray::scene::UpAxis>,
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
    /// Output file: .png or .exr for an image, .gif or .png (animated) for a turntable; `-`
    /// (standard output), a FIFO or a device is written as a stream (PNG unless --format says).
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
    #[command(flatten)]
    pub camera: CameraArgs,
}

pub fn run(args: &RenderArgs) -> anyhow::Result<ExitCode> {
    args.camera.check(Some(&args.output))?;
    let turntable = args.turntable.map(|frames| Turntable {
        frames,
        fps: args.fps,
    });
    // One output per preset view (the `{view}` field filled in), or the one output.
    let views: Vec<Option<PresetView>> = match args.camera.view.as_slice() {
        [] => vec![None],
        views => views.iter().copied().map(Some).collect(),
    };
    let mut destinations = Vec::new();
    for &view in &views {
        let path = output_for_view(&args.output, view);
        let destination = if path == Path::new("-") {
            Destination::Stdout
        } else {
            Destination::for_path(&path)?
        };
        // The scene file first, before its name's extension is judged: `-o scene.toml` is
        // told it is the scene. Its models are checked once the world has loaded them.
        destination.refuse_inputs(args.scene.as_slice())?;
        let output = Output::for_destination(&destination, args.format.map(|f| f.0), turntable)?;
        destinations.push((destination, output));
    }
    let (scene, base) = super::load_scene(args.scene.as_deref(), args.up)?;
    let options = RenderOptions {
        samples: args.samples,
        shadows: !args.no_shadows,
        max_depth: args.max_depth,
        alpha: args.transparent,
        ..RenderOptions::new(args.algorithm.0, args.size.width, args.size.height)
    };
    options.check()?;
    let report = super::build_world(&scene, &base)?;
    let inputs: Vec<PathBuf> = args.scene.iter().cloned().chain(report.inputs).collect();
    for (destination, _) in &destinations {
        destination.refuse_inputs(&inputs)?;
    }
    let world = Arc::new(report.world);
    super::print_warnings(&scene, &world);
    let aspect = args.size.width as f32 / args.size.height as f32;
    let cameras = args.camera.cameras(&scene.camera, &world, aspect);
    for ((_, camera), (destination, output)) in cameras.iter().zip(destinations) {
        let code = render_one(args, &world, camera, &options, &destination, output)?;
        if code != ExitCode::SUCCESS {
            return Ok(code);
        }
    }
    Ok(ExitCode::SUCCESS)
}

/// Renders `world` through `camera` into `destination` as `output`, with a progress bar, and
/// says what was written; a signal stops it with 128 + its number.
fn render_one(
    args: &RenderArgs,
    world: &Arc<World>,
    camera: &Camera,
    options: &RenderOptions,
    destination: &Destination,
    output: Output,
) -> anyhow::Result<ExitCode> {
    let (world, options) = (world.clone(), *options);
    if let (Output::Turntable(turntable, format), Destination::File(path)) = (output, destination) {
        warn_unless_room(turntable, format, &options, path);
    }
    let progress = Progress::new();
    // SIGINT and SIGTERM cancel the render: whatever was being written is removed (a file is
    // only renamed into place when complete), and the exit status says which signal it was.
    // The handler cancels the progress itself, so a signal that arrives before the file is
    // renamed into place always wins (`Sink::commit` checks just before the rename).
    let signal = Arc::new(AtomicUsize::new(0));
    for number in [SIGINT, SIGTERM] {
        signal_hook::flag::register_usize(number, Arc::clone(&signal), number as usize)?;
        signal_hook::flag::register(number, progress.cancel_flag())?;
    }
    let started = Instant::now();
    let exported = std::thread::scope(|s| {
        let job = s.spawn(|| render_to(&world, camera, &options, output, destination, &progress));
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
    let shown = Escaped(&destination.path().display().to_string()).to_string();
    let exported = match (exported, signal.load(Ordering::Relaxed)) {
        // A signal cancels the render, or the wait on a stream's reader: either way it stopped.
        (Err(_), number) if number != 0 => {
            let _ = writeln!(
                std::io::stderr(),
                "rastray: stopped by {}; {shown} not written",
                signal_name(number)
            );
            return Ok(ExitCode::from(128 + number as u8));
        }
        (Ok(exported), number) if number != 0 => {
            // The signal came after the file was renamed into place: the work is done and kept.
            let _ = writeln!(
                std::io::stderr(),
                "rastray: {} arrived after {shown} was written; kept",
                signal_name(number)
            );
            exported
        }
        (exported, _) => exported?,
    };
    let what = format!(
        "{} {}x{} ({}x{} samples",
        options.algorithm, options.width, options.height, options.samples, options.samples
    );
    let summary = match exported {
        Exported::Image(stats) => format!(
            "{what}, {} triangles) rendered in {:.1} ms; wrote {shown}",
            stats.triangles,
            stats.total().as_secs_f64() * 1000.0,
        ),
        Exported::Turntable(stats) => format!(
            "{what}, {} triangles) turntable of {} frames in {:.2} s ({:.1} ms per frame); wrote {shown}",
            stats.triangles,
            stats.frames,
            stats.elapsed.as_secs_f64(),
            stats.elapsed.as_secs_f64() * 1000.0 / stats.frames as f64,
        ),
    };
    // The image itself may be on standard output: the summary then goes to stderr.
    if *destination == Destination::Stdout {
        let _ = writeln!(std::io::stderr(), "{summary}");
    } else {
        outln!("{summary}");
    }
    Ok(ExitCode::SUCCESS)
}

/// Says on stderr when the folder of `path` has less free space than the turntable may take
/// (its frames uncompressed: an upper bound, so the file may still fit).
fn warn_unless_room(
    turntable: Turntable,
    format: AnimationFormat,
    options: &RenderOptions,
    path: &Path,
) {
    let folder = match path.parent() {
        Some(folder) if !folder.as_os_str().is_empty() => folder,
        _ => Path::new("."),
    };
    let Ok(stat) = rustix::fs::statvfs(folder) else {
        return;
    };
    let free = stat.f_bavail.saturating_mul(stat.f_frsize);
    let largest = turntable.largest_size(options.width, options.height, options.alpha, format);
    if largest > free {
        let _ = writeln!(
            std::io::stderr(),
            "warning: the turntable may take up to {} (its {} frames uncompressed); {} has {} free",
            human(largest),
            turntable.frames,
            Escaped(&folder.display().to_string()),
            human(free)
        );
    }
}

/// "SIGINT" or "SIGTERM", the signals a render stops on.
fn signal_name(number: usize) -> &'static str {
    if number == SIGINT as usize {
        "SIGINT"
    } else {
        "SIGTERM"
    }
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
