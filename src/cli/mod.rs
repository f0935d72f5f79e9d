//! Command-line arguments and dispatch. Every user error comes back as an `anyhow` error that
//! names the file, line or field; `main` prints it and exits with code 2.

mod algorithm_arg;
mod bench;
mod camera_args;
mod format_arg;
mod graphics_arg;
mod info;
mod motion;
mod render;
mod stdout;
mod up_arg;
mod view;

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::Context;
use clap::{Parser, Subcommand, ValueEnum};
use rastray::mesh::EXPECTED_MODEL;
use rastray::render::Size;
use rastray::scene::{SceneError, UpAxis};
use rastray::text_escape::Escaped;
use rastray::tui::ColorMode;
use rastray::world::{MeshFileCache, WorldReport};
use rastray::{Scene, World};

/// Build small 3D scenes in the terminal and render them with a Z-buffer (Gouraud or Phong) or a
/// Whitted ray tracer.
#[derive(Debug, Parser)]
#[command(name = "rastray", version, args_conflicts_with_subcommands = true)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Option<Command>,
    /// Scene file to open, or a model file (.obj, .stl, .ply, .gltf, .glb, or one known by its
    /// content) to look at in a new scene (the built-in default scene when absent).
    pub scene: Option<PathBuf>,
    /// For a model file opened on its own: the axis of the file that points up (x, y, z, -x,
    /// -y, -z); CAD files are usually z. Default y.
    #[arg(long, value_parser = up_arg::parse_up, allow_hyphen_values = true)]
    pub up: Option<UpAxis>,
    /// Colours of the terminal preview (default: truecolor when COLORTERM says so or the terminal
    /// answers that it has it, else 256). Wins over detection and over NO_COLOR.
    #[arg(long, value_enum)]
    pub color: Option<ColorArg>,
    /// How the editor's preview is drawn (default: asked of the terminal: kitty, iTerm2 or
    /// sixel graphics where it answers for them, else half blocks). The status line names it.
    #[arg(long, value_enum, default_value_t = graphics_arg::GraphicsArg::Auto)]
    pub graphics: graphics_arg::GraphicsArg,
}

/// The `--color` values, spelled as users type them.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum ColorArg {
    /// 24-bit RGB escape sequences.
    Truecolor,
    /// The nearest entry of the xterm 256-colour palette.
    #[value(name = "256")]
    Ansi256,
}

impl From<ColorArg> for ColorMode {
    fn from(arg: ColorArg) -> ColorMode {
        match arg {
            ColorArg::Truecolor => ColorMode::Truecolor,
            ColorArg::Ansi256 => ColorMode::Ansi256,
        }
    }
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Render a scene to an image (PNG, OpenEXR) or a turntable (GIF, animated PNG).
    Render(render::RenderArgs),
    /// Render a scene once and print it to the terminal: real pixels where it can show them.
    View(view::ViewArgs),
    /// Print a scene's objects, triangle counts and bounds.
    Info {
        /// Scene file, or a model file (.obj, .stl, .ply, .gltf, .glb) shown on its own.
        scene: PathBuf,
        /// For a model file shown on its own: the axis of the file that points up (x, y, z,
        /// -x, -y, -z). Default y.
        #[arg(long, value_parser = up_arg::parse_up, allow_hyphen_values = true)]
        up: Option<UpAxis>,
    },
    /// Repeat the study's two experiments for the three algorithms and write a report.
    Bench(bench::BenchArgs),
}

/// Runs the parsed command; returns the process exit status (the editor's is 128 + the signal's
/// number when a signal ended it).
pub fn run(cli: Cli) -> anyhow::Result<ExitCode> {
    match cli.command {
        Some(Command::Render(args)) => render::run(&args),
        Some(Command::View(args)) => view::run(&args).map(|()| ExitCode::SUCCESS),
        Some(Command::Info { scene, up }) => info::run(&scene, up).map(|()| ExitCode::SUCCESS),
        Some(Command::Bench(args)) => bench::run_bench(&args).map(|()| ExitCode::SUCCESS),
        None => {
            refuse_dumb_terminal(std::env::var("TERM").ok().as_deref())?;
            let request = cli.graphics.editor_request()?;
            let startup =
                rastray::tui::color_probe::detect(cli.color.map(ColorMode::from), request);
            refuse_up_without_model(cli.scene.as_deref(), cli.up)?;
            let exit = rastray::tui::run(cli.scene, cli.up.unwrap_or_default(), startup)?;
            Ok(ExitCode::from(exit.code()))
        }
    }
}

/// The editor moves the cursor and redraws the screen: a terminal that says it cannot
/// (`TERM=dumb`) gets a message pointing to the commands that need none of that.
fn refuse_dumb_terminal(term: Option<&str>) -> anyhow::Result<()> {
    if term == Some("dumb") {
        anyhow::bail!(
            "the editor needs a terminal that can move the cursor (TERM is \"dumb\"); \
             `rastray view SCENE` prints a picture, `rastray render SCENE -o OUT.png` writes one, \
             `rastray info SCENE` lists a scene"
        );
    }
    Ok(())
}

/// Loads the scene at `path` (or, for a model file, a scene showing it, turned so that its
/// `up` axis is +Y), or the built-in default scene; returns it with the directory its model
/// paths are relative to.
pub fn load_scene(path: Option<&Path>, up: Option<UpAxis>) -> anyhow::Result<(Scene, PathBuf)> {
    refuse_up_without_model(path, up)?;
    match path {
        Some(path) if rastray::model_scene::is_model_file(path) => {
            let scene = rastray::model_scene::scene_for_model(path, up.unwrap_or_default())?;
            let base = path.parent().map(Path::to_path_buf).unwrap_or_default();
            Ok((scene, base))
        }
        Some(path) => {
            let scene = rastray::scene::load(path).map_err(|error| match error {
                // Binary data that is no model either: say what was expected.
                SceneError::Io { error, .. }
                    if error.kind() == std::io::ErrorKind::InvalidData
                        && error.to_string().contains("UTF-8") =>
                {
                    anyhow::anyhow!(
                        "{}: neither a scene file (TOML text) nor {EXPECTED_MODEL}",
                        Escaped(&path.display().to_string())
                    )
                }
                error => error.into(),
            })?;
            let base = path.parent().map(Path::to_path_buf).unwrap_or_default();
            Ok((scene, base))
        }
        None => Ok((
            rastray::scene::default_scene(),
            std::env::current_dir().context("no working directory")?,
        )),
    }
}

/// `--up` turns a model opened on its own; a scene says it of each mesh object.
fn refuse_up_without_model(path: Option<&Path>, up: Option<UpAxis>) -> anyhow::Result<()> {
    let is_model = path.is_some_and(rastray::model_scene::is_model_file);
    if up.is_some() && !is_model {
        anyhow::bail!(
            "--up applies to a model file opened on its own; in a scene file, give the mesh \
             object `up = \"z\"`"
        );
    }
    Ok(())
}

/// Prints the scene's warnings on stderr, one `warning: …` line each, and of each kind past the
/// first few a line that counts the rest.
pub fn print_warnings(scene: &Scene, world: &rastray::World) {
    let warnings = rastray::warnings(scene, &scene.camera, world);
    for line in rastray::warnings::summarised(&warnings, rastray::warnings::WARNINGS_SHOWN_PER_KIND)
    {
        eprintln!("warning: {}", Escaped(&line));
    }
}

/// Builds the world of `scene` (model paths relative to `base`), printing on stderr what its
/// model files held that rastray skipped, one `warning:` line each.
pub fn build_world(scene: &Scene, base: &Path) -> anyhow::Result<WorldReport> {
    build_world_cached(scene, base, &mut MeshFileCache::default())
}

/// As [`build_world`], keeping the model files read in `cache`.
pub fn build_world_cached(
    scene: &Scene,
    base: &Path,
    cache: &mut MeshFileCache,
) -> anyhow::Result<WorldReport> {
    let report = World::build_report(scene, base, cache)?;
    for warning in &report.warnings {
        eprintln!("warning: {}", Escaped(&warning.to_string()));
    }
    Ok(report)
}

/// Parses WIDTHxHEIGHT for clap.
pub fn parse_size(s: &str) -> Result<Size, String> {
    s.parse::<Size>().map_err(|e| e.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn color(args: &[&str]) -> Result<Option<ColorMode>, clap::Error> {
        let cli = Cli::try_parse_from(std::iter::once("rastray").chain(args.iter().copied()))?;
        Ok(cli.color.map(ColorMode::from))
    }

    #[test]
    fn color_takes_the_documented_spellings() {
        assert_eq!(
            color(&["--color", "truecolor"]).unwrap(),
            Some(ColorMode::Truecolor)
        );
        assert_eq!(
            color(&["--color", "256"]).unwrap(),
            Some(ColorMode::Ansi256)
        );
        assert_eq!(color(&["scene.toml"]).unwrap(), None);
        let refused = color(&["--color", "ansi256"]).unwrap_err().to_string();
        assert!(refused.contains("truecolor, 256"), "{refused}");
    }
}
