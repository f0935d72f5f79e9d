//! `rastray view`: one render printed to stdout as a picture, in real pixels (kitty, sixel,
//! iTerm2) where the terminal can show them, else half blocks, or plain text when stdout is not
//! a terminal.

use std::io::IsTerminal;
use std::path::PathBuf;
use std::sync::Arc;

use anyhow::Context;
use clap::Args;
use rastray::World;
use rastray::render::{Algorithm, Frame, Progress, RenderOptions, Renderer};
use rastray::terminal_image::{CellArea, CellSize, Protocol};
use rastray::tui::preview::PreviewImage;

use super::algorithm_arg::AlgorithmArg;
use super::camera_args::CameraArgs;
use super::config::Defaults;
use super::graphics_arg::GraphicsArg;
use super::motion::{self, MotionArgs, Picture, Shown};

/// Width / height of the picture: the shape of `rastray render`'s default 1920×1080.
const ASPECT: f32 = 16.0 / 9.0;

/// Columns when stdout is not a terminal and `--width` is absent.
const DEFAULT_COLS: u32 = 80;

#[derive(Debug, Args)]
pub struct ViewArgs {
    /// Scene file (TOML), or a model file (.obj, .stl, .ply, .gltf, .glb, or one known by its
    /// content) shown on its own; the built-in default scene when absent.
    pub scene: Option<PathBuf>,
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

pub fn run(args: &ViewArgs, defaults: &Defaults) -> anyhow::Result<()> {
    args.camera.check(None)?;
    let up = args.up.or(defaults.up.filter(|_| {
        args.scene
            .as_deref()
            .is_some_and(rastray::model_scene::is_model_file)
    }));
    let (scene, base) = super::load_scene(args.scene.as_deref(), up)?;
    let stdout = std::io::stdout();
    let is_terminal = stdout.is_terminal();
    let protocol = args
        .graphics
        .or(defaults.graphics)
        .unwrap_or_default()
        .view_protocol()
        .unwrap_or_else(|| Protocol::detect(is_terminal, |k| std::env::var(k).ok()));
    let terminal_cols = is_terminal
        .then(|| ratatui::crossterm::terminal::size().ok())
        .flatten()
        .map(|(cols, _)| u32::from(cols));
    let cols = args.width.or(terminal_cols).unwrap_or(DEFAULT_COLS);
    let cell = CellSize::default();
    let area = CellArea::for_aspect(cols, ASPECT, cell);
    let (width, height) = protocol.picture_size(area, cell);
    let algorithm = args
        .algorithm
        .or(defaults.algorithm)
        .map_or(Algorithm::Phong, |a| a.0);
    let options = args
        .display
        .apply(RenderOptions::new(algorithm, width, height));
    options.check()?;
    let aspect = width as f32 / height as f32;
    if args.motion.active() {
        let picture = Picture {
            protocol,
            area,
            options,
        };
        return motion::play(&args.motion, &picture, || {
            let (scene, base) = super::load_scene(args.scene.as_deref(), up)?;
            let report = super::build_world(&scene, &base, args.scene.as_deref())?;
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
    let world = Arc::new(World::build(&scene, &base)?);
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
    Ok(())
}
