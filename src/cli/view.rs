//! `rastray view`: one render printed to stdout as a picture, in real pixels (kitty, sixel,
//! iTerm2) where the terminal answers for them, else text cells (see `view_terminal`), or plain
//! text when stdout is not a terminal or `TERM=dumb`.

use std::io::IsTerminal;
use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::Arc;

use anyhow::Context;
use clap::Args;
use rastray::World;
use rastray::render::{Algorithm, Frame, Progress, RenderOptions, Renderer};
use rastray::terminal_image::preview::PreviewImage;
use rastray::terminal_image::{CellArea, Protocol};
use rastray::world::MeshFileCache;

use super::algorithm_arg::AlgorithmArg;
use super::camera_args::CameraArgs;
use super::config::Defaults;
use super::graphics_arg::GraphicsArg;
use super::motion::{self, MotionArgs, Picture, Shown};
use super::view_grid;
use super::view_terminal::{self, Drawing};

/// Width / height of the picture: the shape of `rastray render`'s default 1920×1080.
const ASPECT: f32 = 16.0 / 9.0;

/// Columns when stdout is not a terminal and `--width` is absent.
const DEFAULT_COLS: u32 = 80;

#[derive(Debug, Args)]
pub struct ViewArgs {
    /// Scene file (TOML), or a model file (.obj, .stl, .ply, .gltf, .glb, or one known by its
    /// content) shown on its own; the built-in default scene when absent.
    pub scene: Option<PathBuf>,
    /// More scenes or models, shown beside the first with `--grid`.
    #[arg(requires = "grid")]
    pub more: Vec<PathBuf>,
    /// Show every input as a titled thumbnail in a grid: a contact sheet in the terminal.
    #[arg(long, conflicts_with_all = ["spin", "watch"])]
    pub grid: bool,
    /// With --grid: thumbnails per row (default: as many of about 24 columns as fit).
    #[arg(long, requires = "grid", value_parser = clap::value_parser!(u32).range(1..=100))]
    pub columns: Option<u32>,
    /// For a model file shown on its own: the axis of the file that points up (x, y, z, -x,
    /// -y, -z); CAD files are usually z. Default y.
    #[arg(long, value_parser = super::up_arg::parse_up, allow_hyphen_values = true)]
    pub up: Option<rastray::scene::UpAxis>,
    /// Algorithm (default phong, or the config file's).
    #[arg(short, long, value_enum)]
    pub algorithm: Option<AlgorithmArg>,
    /// Width in terminal columns (default: the terminal's width, or 80).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=2000))]
    pub width: Option<u32>,
    /// How to draw: guessed from the environment, or one protocol (default auto, or the config
    /// file's).
    #[arg(long, value_enum)]
    pub graphics: Option<GraphicsArg>,
    #[command(flatten)]
    pub display: super::display_args::DisplayArgs,
    #[command(flatten)]
    pub camera: CameraArgs,
    #[command(flatten)]
    pub motion: MotionArgs,
}

pub fn run(args: &ViewArgs, defaults: &Defaults) -> anyhow::Result<ExitCode> {
    args.camera.check(None)?;
    let up = args.up.or(defaults.up.filter(|_| {
        args.scene
            .as_deref()
            .is_some_and(rastray::model_scene::is_model_file)
    }));
    // With --grid each input is loaded on its own, and one that fails is skipped. A model file
    // read here waits in `cache` for the world.
    let mut cache = MeshFileCache::default();
    let loaded = if args.grid {
        None
    } else {
        Some(super::load_scene(args.scene.as_deref(), up, &mut cache)?)
    };
    let stdout = std::io::stdout();
    let is_terminal = stdout.is_terminal();
    let drawing = view_terminal::decide(
        args.graphics.or(defaults.graphics).unwrap_or_default(),
        is_terminal,
    );
    let protocol = drawing.protocol;
    let terminal_cols = is_terminal
        .then(|| ratatui::crossterm::terminal::size().ok())
        .flatten()
        .map(|(cols, _)| u32::from(cols));
    let cols = args.width.or(terminal_cols).unwrap_or(DEFAULT_COLS);
    let cell = drawing.cell;
    let area = CellArea::for_aspect(cols, ASPECT, cell);
    let (width, height) = fit_window(protocol, protocol.picture_size(area, cell), &drawing);
    let algorithm = args
        .algorithm
        .or(defaults.algorithm)
        .map_or(Algorithm::Phong, |a| a.0);
    if args.grid {
        let inputs: Vec<PathBuf> = args.scene.iter().chain(&args.more).cloned().collect();
        return view_grid::run(&view_grid::GridRequest {
            inputs: &inputs,
            protocol,
            cols,
            cell,
            columns: args.columns,
            options: RenderOptions::new(algorithm, width, height),
            display: &args.display,
            camera: &args.camera,
            up: args.up.or(defaults.up),
        });
    }
    let (scene, base) = loaded.expect("loaded without --grid");
    let mut options = args
        .display
        .apply(RenderOptions::new(algorithm, width, height));
    // Text cells are too coarse for the box's written lengths.
    options.overlays.labels &= protocol.has_pixels();
    options.check()?;
    let aspect = width as f32 / height as f32;
    if args.motion.active() {
        let picture = Picture {
            protocol,
            area,
            options,
        };
        return motion::play(&args.motion, &picture, || {
            // The first load finds the model read above; later ones read it again.
            let cache = std::mem::take(&mut cache);
            let (scene, report) = super::load_world(args.scene.as_deref(), up, cache)?;
            let world = Arc::new(report.world);
            let camera = args.camera.camera_for(
                args.camera.view.first().copied(),
                &scene.camera,
                &world,
                aspect,
            );
            let inputs = args.scene.iter().cloned().chain(report.inputs).collect();
            Ok(Shown {
                world,
                camera,
                inputs,
            })
        });
    }
    let world = Arc::new(World::build_cached(&scene, &base, &mut cache)?);
    drop(cache);
    args.display.print_notes(&world);
    let camera = args.camera.camera_for(
        args.camera.view.first().copied(),
        &scene.camera,
        &world,
        aspect,
    );
    let mut frame = Frame::default();
    Renderer::new(options).render(&world, &camera, &Progress::new(), &mut frame)?;
    let bytes = protocol
        .encode(&PreviewImage::from_frame(&frame), area)
        .context("cannot encode the picture")?;
    super::stdout::bytes(&bytes);
    if protocol.has_pixels() {
        super::stdout::bytes(b"\n");
    }
    Ok(ExitCode::SUCCESS)
}

/// `size` made to fit the terminal: a sixel picture, which the terminal draws at its own size
/// (and xterm not at all when it is too wide), is scaled down with its aspect kept to the text
/// area's width in pixels, when known.
fn fit_window(protocol: Protocol, (width, height): (u32, u32), drawing: &Drawing) -> (u32, u32) {
    match drawing.window_width {
        Some(window) if protocol == Protocol::Sixel && width > window => {
            let scaled = u64::from(height) * u64::from(window) / u64::from(width.max(1));
            (window.max(1), (scaled as u32).max(1))
        }
        _ => (width, height),
    }
}
