//! Command-line arguments and dispatch. Every user error comes back as an `anyhow` error that
//! names the file, line or field; `main` prints it and exits with code 2.

mod algorithm_arg;
mod batch_plan;
mod batch_run;
mod bench;
mod camera_args;
mod config;
mod display_args;
mod format_arg;
mod frames_arg;
mod graphics_arg;
mod info;
mod join;
mod mistyped;
mod motion;
mod render;
mod shard_arg;
mod sheet;
mod stdin_model;
mod stdout;
mod up_arg;
mod view;
mod view_grid;
mod view_terminal;

use std::num::NonZeroUsize;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::Context;
use clap::{CommandFactory, FromArgMatches, Parser, Subcommand, ValueEnum};
use rastray::mesh::EXPECTED_MODEL;
use rastray::pool_thread::on_pool_thread;
use rastray::render::{MAX_THREADS, Size, thread_count};
use rastray::scene::{SceneError, UpAxis};
use rastray::terminal_image::ColorMode;
use rastray::text_escape::Escaped;
use rastray::world::{Detail, MeshFileCache, WorldReport};
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
    /// sixel graphics where it answers for them, else sextants where XTVERSION names kitty,
    /// WezTerm, foot or Ghostty, else half blocks; or the config file's). The status line names
    /// it.
    #[arg(long, value_enum)]
    pub graphics: Option<graphics_arg::GraphicsArg>,
    /// Read no config file: only the command line and the built-in defaults count.
    #[arg(long, global = true)]
    pub no_config: bool,
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
    /// Render scenes or models to images (PNG, OpenEXR) or turntables (GIF, animated PNG), one
    /// or many in one process.
    Render(render::RenderArgs),
    /// Join still PNG frames (a turntable rendered in parts) into one GIF or animated PNG.
    Join(join::JoinArgs),
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
    /// Print a shell completion script (bash, zsh, fish, elvish, powershell) on stdout.
    Completions {
        /// The shell.
        shell: clap_complete::Shell,
    },
    /// Print rastray's manual page (roff) on stdout: `rastray man | man -l -`.
    Man,
    /// Print the config file in use and the defaults taken from it.
    Config,
}

/// The command line's definition, its version naming the CPU features the renderer uses.
pub fn command() -> clap::Command {
    let features = rastray::render::cpu_features();
    let features = if features.is_empty() {
        "none beyond baseline x86-64 (SSE2)".to_string()
    } else {
        features.join(", ")
    };
    let version = format!(
        "{} (CPU features in use: {features})",
        env!("CARGO_PKG_VERSION")
    );
    // Made once per process: the definition keeps it for the process's life.
    Cli::command().version(version.leak() as &str)
}

/// Parses the process's arguments; a mistyped command (`rastray veiw`) is refused with the
/// command it is close to, exit code 2.
pub fn parse() -> Cli {
    let mut args: Vec<std::ffi::OsString> = std::env::args_os().collect();
    let definition = Cli::command();
    let names: Vec<&str> = definition.get_subcommands().map(|c| c.get_name()).collect();
    // `rastray --no-config render …`: clap takes an argument before a command as the editor's,
    // which conflicts with the command; the flag is the command's as well.
    if args.len() > 2
        && args[1] == "--no-config"
        && args[2].to_str().is_some_and(|c| names.contains(&c))
    {
        args.swap(1, 2);
    }
    if let Some(word) = args.get(1).and_then(|a| a.to_str())
        && let Some(near) = mistyped::suggestion(word, &names)
    {
        eprintln!(
            "error: `{}` is no command and no file; did you mean '{near}'? (a new scene needs a .toml name; see `rastray --help`)",
            Escaped(word)
        );
        std::process::exit(2);
    }
    let matches = command().get_matches_from(args);
    Cli::from_arg_matches(&matches).unwrap_or_else(|e| e.exit())
}

/// Runs the parsed command; returns the process exit status (the editor's is 128 + the signal's
/// number when a signal ended it).
pub fn run(cli: Cli) -> anyhow::Result<ExitCode> {
    let location = config::location(|k| std::env::var(k).ok());
    let defaults = || -> anyhow::Result<config::Defaults> {
        if cli.no_config {
            Ok(config::Defaults::default())
        } else {
            config::load(location.as_ref())
        }
    };
    match cli.command {
        Some(Command::Render(args)) => render::run(&args, &defaults()?),
        Some(Command::Join(args)) => join::run(&args),
        Some(Command::View(args)) => view::run(&args, &defaults()?),
        Some(Command::Completions { shell }) => {
            let mut script = Vec::new();
            clap_complete::generate(shell, &mut command(), "rastray", &mut script);
            stdout::bytes(&script);
            Ok(ExitCode::SUCCESS)
        }
        Some(Command::Man) => {
            let mut page = Vec::new();
            clap_mangen::Man::new(command()).render(&mut page)?;
            stdout::bytes(&page);
            Ok(ExitCode::SUCCESS)
        }
        Some(Command::Config) => {
            stdout::bytes(config::describe(location.as_ref(), cli.no_config)?.as_bytes());
            Ok(ExitCode::SUCCESS)
        }
        Some(Command::Info { scene, up }) => info::run(&scene, up).map(|()| ExitCode::SUCCESS),
        Some(Command::Bench(args)) => bench::run_bench(&args).map(|()| ExitCode::SUCCESS),
        None => {
            let defaults = defaults()?;
            refuse_new_scene_without_toml(cli.scene.as_deref())?;
            refuse_dumb_terminal(std::env::var("TERM").ok().as_deref())?;
            let graphics = cli.graphics.or(defaults.graphics).unwrap_or_default();
            let request = graphics.editor_request()?;
            let color = cli.color.or(defaults.color);
            let probe =
                || rastray::tui::terminal::color_probe::detect(color.map(ColorMode::from), request);
            let up = cli.up.or(defaults.up);
            refuse_up_without_model(cli.scene.as_deref(), cli.up)?;
            let exit = rastray::tui::run(cli.scene, up.unwrap_or_default(), probe)?;
            Ok(ExitCode::from(exit.code()))
        }
    }
}

/// A scene that does not exist yet is made by the editor under the name given: that name must
/// end in `.toml`, so that a mistyped word never becomes a new scene.
fn refuse_new_scene_without_toml(path: Option<&Path>) -> anyhow::Result<()> {
    let Some(path) = path else {
        return Ok(());
    };
    let toml = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("toml"));
    if !toml && std::fs::symlink_metadata(path).is_err() {
        anyhow::bail!(
            "{}: no such file; a new scene needs a .toml name (`rastray {}.toml`), and the commands are listed by `rastray --help`",
            Escaped(&path.display().to_string()),
            Escaped(&path.with_extension("").display().to_string())
        );
    }
    Ok(())
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
/// paths are relative to. A model file is read into `cache`, where building the scene's world
/// with that cache finds it: the file is read once. Drop the cache once the world is built, so
/// that the render does not hold the file's geometry beside the world's.
pub fn load_scene(
    path: Option<&Path>,
    up: Option<UpAxis>,
    cache: &mut MeshFileCache,
) -> anyhow::Result<(Scene, PathBuf)> {
    refuse_up_without_model(path, up)?;
    match path {
        Some(path) if rastray::model_scene::is_model_file(path) => Ok(
            rastray::model_scene::scene_for_model_cached(path, up.unwrap_or_default(), cache)?,
        ),
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

/// Loads the scene or model at `path` (the default scene for `None`) and builds its world for
/// rendering: [`load_scene`] then [`build_world`], each model file read once through `cache`
/// (a fresh one, or one holding a file read before).
pub fn load_world(
    path: Option<&Path>,
    up: Option<UpAxis>,
    mut cache: MeshFileCache,
) -> anyhow::Result<(Scene, WorldReport)> {
    // Reading and building run on the pool, whose threads then share their parallel steps.
    on_pool_thread(|| {
        let (scene, base) = load_scene(path, up, &mut cache)?;
        let report = build_world(&scene, &base, path, &mut cache)?;
        Ok((scene, report))
    })
}

/// Builds the world of `scene` (model paths relative to `base`), read from `input` (`None`
/// for the default scene), taking the model files already read from `cache` and keeping those
/// it reads there; prints on stderr what its model files held that rastray skipped, one
/// `warning:` line each.
pub fn build_world(
    scene: &Scene,
    base: &Path,
    input: Option<&Path>,
    cache: &mut MeshFileCache,
) -> anyhow::Result<WorldReport> {
    build_world_with(scene, base, input, cache, Detail::Render)
}

/// As [`build_world`], with the objects built in `detail`.
pub fn build_world_with(
    scene: &Scene,
    base: &Path,
    input: Option<&Path>,
    cache: &mut MeshFileCache,
    detail: Detail,
) -> anyhow::Result<WorldReport> {
    let report =
        World::build_report_with(scene, base, cache, detail).map_err(|error| match error {
            // A world over the memory bound that no model file is the cause of: name the input.
            SceneError::OverBudget(mut over) if over.file.as_os_str().is_empty() => {
                over.file = input.map_or_else(|| "the default scene".into(), Path::to_path_buf);
                SceneError::OverBudget(over)
            }
            error => error,
        })?;
    for warning in &report.warnings {
        eprintln!("warning: {}", Escaped(&warning.to_string()));
    }
    Ok(report)
}

/// Parses a count of render threads, 1 to [`MAX_THREADS`], for clap: bounded by
/// [`thread_count`], as [`RenderOptions::check`](rastray::render::RenderOptions::check) bounds
/// every render.
pub fn parse_threads(s: &str) -> Result<NonZeroUsize, String> {
    let count: usize = s
        .trim()
        .parse()
        .map_err(|_| format!("`{s}` is not a thread count: use 1 to {MAX_THREADS}"))?;
    thread_count(count).map_err(|e| e.to_string())
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
