//! `rastray render`: scenes and models to images or turntables, one or many in one process;
//! the arguments, and the plan they make (`batch_plan`), run by `batch_run`.

use std::io::Write;
use std::num::NonZeroUsize;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::Args;
use rastray::export::{AnimationFormat, MAX_FPS, MAX_FRAMES, OutputTemplate, Turntable};
use rastray::input_file::human;
use rastray::render::{Algorithm, RenderOptions, Size};
use rastray::text_escape::Escaped;

use super::algorithm_arg::AlgorithmArg;
use super::batch_plan;
use super::batch_run;
use super::camera_args::CameraArgs;
use super::config::Defaults;
use super::format_arg::FormatArg;
use super::frames_arg::FrameRange;
use super::shard_arg::Shard;
use super::sheet;
use super::stdin_model::InputFormat;

/// The image size unless asked otherwise.
pub const DEFAULT_SIZE: Size = Size {
    width: 1920,
    height: 1080,
};

#[derive(Debug, Args)]
pub struct RenderArgs {
    /// Scene files (TOML) or model files (.obj, .stl, .ply, .gltf, .glb, or ones known by their
    /// content) shown on their own, rendered in one process, in sorted order; `-` reads one
    /// model from standard input (with --input-format); the built-in default scene when absent.
    #[arg(value_name = "IN")]
    pub inputs: Vec<PathBuf>,
    /// For a model file shown on its own: the axis of the file that points up (x, y, z, -x,
    /// -y, -z); CAD files are usually z. Default y, or the config file's.
    #[arg(long, value_parser = super::up_arg::parse_up, allow_hyphen_values = true)]
    pub up: Option<rastray::scene::UpAxis>,
    /// Algorithm (default phong, or the config file's).
    #[arg(short, long, value_enum)]
    pub algorithm: Option<AlgorithmArg>,
    /// Image size, WIDTHxHEIGHT (default 1920x1080, or the config file's).
    #[arg(short, long, value_parser = super::parse_size)]
    pub size: Option<Size>,
    /// Supersampling: N×N samples per pixel, 1 to 8 (default 1, or the config file's).
    #[arg(long)]
    pub samples: Option<u32>,
    /// Render threads, 1 to 1024 (default one per core, or the config file's); the image is
    /// the same.
    #[arg(long, value_parser = super::parse_threads)]
    pub threads: Option<NonZeroUsize>,
    /// Ray tracer: reflection depth, 0 to 16 (default: the scene's max_depth).
    #[arg(long, value_parser = clap::value_parser!(u32).range(0..=rastray::scene::MAX_DEPTH as i64))]
    pub max_depth: Option<u32>,
    /// Ray tracer: cast no shadow rays.
    #[arg(long)]
    pub no_shadows: bool,
    /// Output file, or a template for many: .png or .exr for an image, .gif or .png (animated)
    /// for a turntable; `-` (standard output), a FIFO or a device is written as a stream (PNG
    /// unless --format says). Fields: {stem} (input file name without extension), {name},
    /// {index} (from 0, inputs sorted), {view}, {algo}, {frame} (turntable frame, from 0);
    /// numbers pad as {frame:04}. Several inputs need {stem}, {name} or {index}.
    #[arg(short, long, default_value = "out.png", value_name = "FILE|TEMPLATE")]
    pub output: String,
    /// Encoding of the output (default: the extension's; .png is png8). It must match the
    /// extension.
    #[arg(long, value_enum)]
    pub format: Option<FormatArg>,
    /// Coverage as alpha: the background is transparent, edges partly so. PNG stores straight
    /// colour, OpenEXR premultiplied; in a GIF, pixels less than half covered are transparent.
    #[arg(long)]
    pub transparent: bool,
    /// Render N frames orbiting the camera once around its target, about its up vector, into
    /// a .gif or an animated .png; with {frame} in the output, each frame as an image.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=MAX_FRAMES as i64))]
    pub turntable: Option<u32>,
    /// Turntable: frames per second.
    #[arg(long, requires = "turntable", default_value_t = rastray::export::DEFAULT_FPS,
          value_parser = clap::value_parser!(u32).range(1..=MAX_FPS as i64))]
    pub fps: u32,
    /// Turntable: render only frames A to B (from 0, both included), each as an image named by
    /// {frame} in the output template; `rastray join` makes them one animation.
    #[arg(long, value_name = "A..B", requires = "turntable", value_parser = super::frames_arg::parse_frames)]
    pub frames: Option<FrameRange>,
    /// Render only the I-th of N slices (1 ≤ I ≤ N) of the outputs, in order (inputs sorted,
    /// then frames): N machines or jobs each given one slice write every file once.
    #[arg(long, value_name = "I/N", value_parser = super::shard_arg::parse_shard)]
    pub shard: Option<Shard>,
    #[command(flatten)]
    pub display: super::display_args::DisplayArgs,
    /// The format of a model read from standard input (`-`); the limits of a model file apply.
    #[arg(long, value_enum)]
    pub input_format: Option<InputFormat>,
    #[command(flatten)]
    pub camera: CameraArgs,
    /// Write one contact sheet of the inputs instead: a thumbnail of each, titled with its
    /// file's stem, in a grid (PNG).
    #[arg(long, value_name = "SHEET.png", conflicts_with_all = ["turntable", "shard", "output", "format", "transparent"])]
    pub sheet: Option<PathBuf>,
    /// Contact sheet: thumbnails per row (default: about square).
    #[arg(long, requires = "sheet", value_parser = clap::value_parser!(u32).range(1..=1000))]
    pub columns: Option<u32>,
    /// Contact sheet: each thumbnail's size, WIDTHxHEIGHT (default 256x256).
    #[arg(long, requires = "sheet", value_parser = super::parse_size)]
    pub cell: Option<Size>,
}

/// Renders what `args` ask for; flags the command line leaves out take the config file's
/// `defaults`, then the built-in ones.
pub fn run(args: &RenderArgs, defaults: &Defaults) -> anyhow::Result<ExitCode> {
    args.camera.check(Some(Path::new(&args.output)))?;
    let turntable = args.turntable.map(|frames| Turntable {
        frames,
        fps: args.fps,
    });
    let algorithm = args
        .algorithm
        .or(defaults.algorithm)
        .map_or(Algorithm::Phong, |a| a.0);
    let size = args.size.or(defaults.size).unwrap_or(DEFAULT_SIZE);
    let options = args.display.apply(RenderOptions {
        samples: args.samples.or(defaults.samples).unwrap_or(1),
        shadows: !args.no_shadows,
        max_depth: args.max_depth,
        alpha: args.transparent,
        threads: args.threads.or(defaults.threads),
        ..RenderOptions::new(algorithm, size.width, size.height)
    });
    let settings = batch_run::Settings {
        options,
        size,
        up: args.up,
        default_up: defaults.up,
        input_format: args.input_format,
        turntable,
        make_folders: OutputTemplate::parse(&args.output)?.has_fields(),
        display: args.display.clone(),
        camera: args.camera.clone(),
    };
    if let Some(path) = &args.sheet {
        let cell = args.cell.unwrap_or(Size {
            width: 256,
            height: 256,
        });
        return sheet::run(
            &args.inputs,
            &settings,
            sheet::SheetRequest {
                path,
                columns: args.columns,
                cell,
            },
        );
    }
    let plan = batch_plan::plan(&batch_plan::Request {
        inputs: &args.inputs,
        template: &args.output,
        format: args.format.map(|f| f.0),
        turntable,
        frames: args.frames,
        shard: args.shard,
        algo: &AlgorithmArg(algorithm).spelling(),
        views: &args.camera.view,
    })?;
    settings.options.check()?;
    batch_run::run(&plan, &settings)
}

/// Says on stderr when the folder of `path` has less free space than the turntable may take
/// (its frames uncompressed: an upper bound, so the file may still fit).
pub fn warn_unless_room(
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
