//! Command-line arguments and dispatch. Every user error comes back as an `anyhow` error that
//! names the file, line or field; `main` prints it and exits with code 2.

mod bench;
mod info;
mod render;

use std::path::{Path, PathBuf};

use anyhow::Context;
use clap::{Parser, Subcommand};
use rastray::Scene;
use rastray::render::Size;
use rastray::tui::ColorMode;

/// Build small 3D scenes in the terminal and render them with a Z-buffer (Gouraud or Phong) or a
/// Whitted ray tracer.
#[derive(Debug, Parser)]
#[command(name = "rastray", version, args_conflicts_with_subcommands = true)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Option<Command>,
    /// Scene file to open (the built-in default scene when absent).
    pub scene: Option<PathBuf>,
    /// Colours of the terminal preview (default: truecolor when COLORTERM says so, else 256).
    #[arg(long, value_enum)]
    pub color: Option<ColorMode>,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Render a scene to a PNG file.
    Render(render::RenderArgs),
    /// Print a scene's objects, triangle counts and bounds.
    Info {
        /// Scene file.
        scene: PathBuf,
    },
    /// Repeat the study's two experiments for the three algorithms and write a report.
    Bench(bench::BenchArgs),
}

/// Runs the parsed command.
pub fn run(cli: Cli) -> anyhow::Result<()> {
    match cli.command {
        Some(Command::Render(args)) => render::run(&args),
        Some(Command::Info { scene }) => info::run(&scene),
        Some(Command::Bench(args)) => bench::run_bench(&args),
        None => rastray::tui::run(cli.scene, cli.color.unwrap_or_else(ColorMode::detect)),
    }
}

/// Loads the scene at `path`, or the built-in default scene; returns it with the directory its
/// OBJ paths are relative to.
pub fn load_scene(path: Option<&Path>) -> anyhow::Result<(Scene, PathBuf)> {
    match path {
        Some(path) => {
            let scene = rastray::scene::load(path)?;
            let base = path.parent().map(Path::to_path_buf).unwrap_or_default();
            Ok((scene, base))
        }
        None => Ok((
            rastray::scene::default_scene(),
            std::env::current_dir().context("no working directory")?,
        )),
    }
}

/// Prints the scene's warnings on stderr, one `warning: …` line each.
pub fn print_warnings(scene: &Scene, world: &rastray::World) {
    for warning in rastray::warnings(scene, &scene.camera, world) {
        eprintln!("warning: {warning}");
    }
}

/// Parses WIDTHxHEIGHT for clap.
pub fn parse_size(s: &str) -> Result<Size, String> {
    s.parse::<Size>().map_err(|e| e.to_string())
}
