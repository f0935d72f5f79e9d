//! Runs a render's [`Plan`]: each input loaded once, each output written through the one
//! renderer (its thread pool and scratch memory kept from file to file), under one progress bar
//! that names the current file. With several inputs, a file that fails is reported on its own
//! line and skipped, and a summary ends the run (exit code 1 when anything failed); with one,
//! its error is the command's (exit code 2). SIGINT and SIGTERM stop the run: the file being
//! written is removed, and the exit status says which signal it was.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use rastray::World;
use rastray::export::{
    Destination, Exported, Output, Turntable, TurntableJob, TurntableWorkers,
    render_turntable_with, save_image_to,
};
use rastray::render::{Frame, Progress, RenderOptions, Renderer, Size};
use rastray::scene::{Scene, UpAxis};
use rastray::text_escape::Escaped;
use rastray::world::MeshFileCache;
use signal_hook::consts::{SIGINT, SIGTERM};

use super::batch_plan::{Job, JobKind, Plan};
use super::stdin_model::{InputFormat, StdinModel};
use super::stdout::outln;

/// A long render shows a progress bar after this long.
const PROGRESS_DELAY: Duration = Duration::from_millis(400);

/// What every job of a run shares.
#[derive(Debug)]
pub struct Settings {
    pub options: RenderOptions,
    pub size: Size,
    /// `--up`, for every input (a scene refuses it).
    pub up: Option<UpAxis>,
    /// The config file's `up`, for model files only.
    pub default_up: Option<UpAxis>,
    /// `--input-format`, for a model read from standard input.
    pub input_format: Option<InputFormat>,
    pub turntable: Option<Turntable>,
    /// Create an output's missing folders (the output is a template with fields).
    pub make_folders: bool,
    /// The display mode and overlays, whose notes are printed for each input.
    pub display: super::display_args::DisplayArgs,
    /// `--ortho`, `--view`, `--azimuth`, `--elevation`: where each job's camera stands.
    pub camera: super::camera_args::CameraArgs,
}

/// Where the worker is, for the progress bar.
#[derive(Default)]
struct Status {
    /// Jobs finished, written or failed.
    done: AtomicUsize,
    /// The current input's name.
    current: Mutex<String>,
}

/// How the run ended.
#[derive(Default)]
struct Outcome {
    written: usize,
    /// Inputs that failed, by name.
    failed: Vec<String>,
    /// The one input's error, when the run is no batch.
    error: Option<anyhow::Error>,
    /// The output being written when a signal stopped the run.
    stopped_at: Option<String>,
    /// The last output written.
    last_written: Option<String>,
}

/// Runs `plan` with `settings`; returns the exit status.
pub fn run(plan: &Plan, settings: &Settings) -> anyhow::Result<ExitCode> {
    let progress = Progress::new();
    // The handler cancels the progress itself, so a signal that arrives before a file is
    // renamed into place always wins (`Sink::commit` checks just before the rename).
    let signal = Arc::new(AtomicUsize::new(0));
    for number in [SIGINT, SIGTERM] {
        signal_hook::flag::register_usize(number, Arc::clone(&signal), number as usize)?;
        signal_hook::flag::register(number, progress.cancel_flag())?;
    }
    let status = Status::default();
    let bar = progress_bar(plan, settings);
    let started = Instant::now();
    let outcome = std::thread::scope(|s| {
        let worker = s.spawn(|| work(plan, settings, &progress, &status, &bar));
        let total = plan.jobs.len().max(1) as f64;
        let mut shown = false;
        while !worker.is_finished() {
            std::thread::sleep(Duration::from_millis(5));
            if !shown && started.elapsed() > PROGRESS_DELAY {
                bar.set_draw_target(ProgressDrawTarget::stderr());
                shown = true;
            }
            if shown {
                let done = status.done.load(Ordering::Relaxed) as f64;
                let now = (done + progress.fraction().min(1.0)) / total;
                bar.set_position((now.min(1.0) * 1000.0) as u64);
                if plan.batch {
                    let current = status.current.lock().expect("unpoisoned").clone();
                    bar.set_message(format!(
                        "{} {}: {current} ({} of {})",
                        settings.options.algorithm,
                        settings.size,
                        (done as usize + 1).min(plan.jobs.len()),
                        plan.jobs.len()
                    ));
                }
            }
        }
        bar.finish_and_clear();
        worker.join().expect("the render thread does not panic")
    });
    let number = signal.load(Ordering::Relaxed);
    if number != 0 {
        if let Some(path) = &outcome.stopped_at {
            let _ = writeln!(
                std::io::stderr(),
                "rastray: stopped by {}; {path} not written",
                signal_name(number)
            );
            return Ok(ExitCode::from(128 + number as u8));
        }
        if let Some(path) = &outcome.last_written {
            // The signal came after the file was renamed into place: the work is done and kept.
            let _ = writeln!(
                std::io::stderr(),
                "rastray: {} arrived after {path} was written; kept",
                signal_name(number)
            );
        }
    }
    if let Some(error) = outcome.error {
        return Err(error);
    }
    if !plan.batch {
        return Ok(ExitCode::SUCCESS);
    }
    let inputs = inputs_of(plan).len();
    let failed = outcome.failed.len();
    let mut summary = format!(
        "rendered {} of {inputs} inputs: {} files written",
        inputs - failed,
        outcome.written
    );
    if failed > 0 {
        summary.push_str(&format!("; failed: {}", outcome.failed.join(", ")));
    }
    let _ = writeln!(std::io::stderr(), "{summary}");
    Ok(if failed > 0 {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    })
}

/// The inputs this shard renders, in order.
fn inputs_of(plan: &Plan) -> Vec<usize> {
    let mut inputs: Vec<usize> = plan.jobs.iter().map(|j| j.input).collect();
    inputs.dedup();
    inputs
}

/// A loaded input: its scene, its world, and every file it was read from.
pub(super) struct Loaded {
    /// The input as named, for messages ("the default scene" for none).
    pub input: PathBuf,
    pub scene: Scene,
    pub world: Arc<World>,
    pub files: Vec<PathBuf>,
}

/// The worker: every job of `plan`, in order.
fn work(
    plan: &Plan,
    settings: &Settings,
    progress: &Progress,
    status: &Status,
    bar: &ProgressBar,
) -> Outcome {
    let mut outcome = Outcome::default();
    // One renderer and one frame for every still, and one set of turntable workers for every
    // turntable: thread pools, scratch memory and frame buffers are made once for the batch.
    let mut workers = Workers {
        renderer: Renderer::new(settings.options),
        frame: Frame::default(),
        turntables: TurntableWorkers::default(),
    };
    let listed: Vec<PathBuf> = plan.inputs.iter().flatten().cloned().collect();
    for input in inputs_of(plan) {
        let name = plan.input_name(input);
        *status.current.lock().expect("unpoisoned") = name.clone();
        let jobs: Vec<&Job> = plan.jobs.iter().filter(|j| j.input == input).collect();
        let report = |error: anyhow::Error, outcome: &mut Outcome| {
            if plan.batch {
                let message = Escaped(&format!("{error:#}")).to_string();
                let line = if message.starts_with(&name) {
                    format!("error: {message}")
                } else {
                    format!("error: {name}: {message}")
                };
                bar.suspend(|| {
                    let _ = writeln!(std::io::stderr(), "{line}");
                });
                outcome.failed.push(name.clone());
            } else {
                outcome.error = Some(error);
            }
        };
        let path = plan.inputs[input].as_deref();
        let loaded = match bar.suspend(|| load(path, settings, &listed)) {
            Ok(loaded) => loaded,
            Err(error) => {
                status.done.fetch_add(jobs.len(), Ordering::Relaxed);
                report(error, &mut outcome);
                if outcome.error.is_some() {
                    return outcome;
                }
                continue;
            }
        };
        for job in jobs {
            let shown = Escaped(&job.destination.path().display().to_string()).to_string();
            let written = write_job(job, &loaded, settings, &mut workers, progress);
            status.done.fetch_add(1, Ordering::Relaxed);
            match written {
                Ok(exported) => {
                    summarise(job, &exported, &settings.options, &shown, bar);
                    outcome.written += 1;
                    outcome.last_written = Some(shown);
                }
                Err(_) if progress.is_cancelled() => {
                    outcome.stopped_at = Some(shown);
                    return outcome;
                }
                Err(error) => {
                    report(error, &mut outcome);
                    // The input's other outputs would fail the same way, or have nothing to
                    // add to a failed turntable: go on with the next input.
                    if outcome.error.is_some() {
                        return outcome;
                    }
                    break;
                }
            }
        }
    }
    outcome
}

/// Loads the input at `path` (the default scene for `None`) and builds its world; warnings go
/// to stderr. `-` is a model read from standard input. `listed` are every input of the run,
/// which no output may overwrite.
pub(super) fn load(
    path: Option<&Path>,
    settings: &Settings,
    listed: &[PathBuf],
) -> anyhow::Result<Loaded> {
    if path == Some(Path::new("-")) {
        let Some(format) = settings.input_format else {
            anyhow::bail!(
                "-: a model read from standard input needs --input-format (glb, gltf, obj, stl or ply)"
            );
        };
        let model = StdinModel::read(format)?;
        return load_file(Some(model.path()), settings, listed)
            .map_err(|e| anyhow::anyhow!("{}", model.rename_in(&format!("{e:#}"))));
    }
    load_file(path, settings, listed)
}

/// Loads the scene or model at `path` (the default scene for `None`) and builds its world.
fn load_file(
    path: Option<&Path>,
    settings: &Settings,
    listed: &[PathBuf],
) -> anyhow::Result<Loaded> {
    let is_model = path.is_some_and(rastray::model_scene::is_model_file);
    let up = settings.up.or(settings.default_up.filter(|_| is_model));
    let (scene, report) = super::load_world(path, up, MeshFileCache::default())?;
    let files: Vec<PathBuf> = listed.iter().cloned().chain(report.inputs).collect();
    let world = Arc::new(report.world);
    super::print_warnings(&scene, &world);
    settings.display.print_notes(&world);
    Ok(Loaded {
        input: path.map_or_else(|| PathBuf::from("the default scene"), Path::to_path_buf),
        scene,
        world,
        files,
    })
}

/// Writes one output of a loaded input.
/// What renders the batch's jobs, kept from one job to the next.
struct Workers {
    /// Renders the stills.
    renderer: Renderer,
    /// Holds each still.
    frame: Frame,
    /// Render the turntables.
    turntables: TurntableWorkers,
}

fn write_job(
    job: &Job,
    loaded: &Loaded,
    settings: &Settings,
    workers: &mut Workers,
    progress: &Progress,
) -> anyhow::Result<Exported> {
    let destination = &job.destination;
    destination.refuse_inputs(&loaded.files)?;
    if let (true, Destination::File(path)) = (settings.make_folders, destination)
        && let Some(folder) = path.parent().filter(|f| !f.as_os_str().is_empty())
    {
        std::fs::create_dir_all(folder).map_err(|e| {
            anyhow::anyhow!(
                "{}: cannot make the folder: {e}",
                Escaped(&folder.display().to_string())
            )
        })?;
    }
    job.output
        .check_memory(&loaded.world, &settings.options, &loaded.input)?;
    let aspect = settings.size.width as f32 / settings.size.height as f32;
    let placed = settings
        .camera
        .camera_for(job.view, &loaded.scene.camera, &loaded.world, aspect);
    let camera = match (job.kind, settings.turntable) {
        (JobKind::Frame(k), Some(turntable)) => turntable.camera(&placed, k),
        _ => placed,
    };
    Ok(match job.output {
        Output::Image(format) => {
            let frame = &mut workers.frame;
            let stats = workers
                .renderer
                .render(&loaded.world, &camera, progress, frame)?;
            save_image_to(frame, format, destination, progress)?;
            Exported::Image(stats)
        }
        Output::Turntable(turntable, format) => {
            if let Destination::File(path) = destination {
                super::render::warn_unless_room(turntable, format, &settings.options, path);
            }
            let job = TurntableJob {
                world: &loaded.world,
                camera: &camera,
                options: &settings.options,
                turntable,
                format,
            };
            Exported::Turntable(render_turntable_with(
                &mut workers.turntables,
                &job,
                destination,
                progress,
            )?)
        }
    })
}

/// Prints what a job wrote: on stdout, or stderr when the image itself went to stdout.
fn summarise(
    job: &Job,
    exported: &Exported,
    options: &RenderOptions,
    shown: &str,
    bar: &ProgressBar,
) {
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
    bar.suspend(|| {
        if job.destination == Destination::Stdout {
            let _ = writeln!(std::io::stderr(), "{summary}");
        } else {
            outln!("{summary}");
        }
    });
}

/// "SIGINT" or "SIGTERM", the signals a render stops on.
pub(super) fn signal_name(number: usize) -> &'static str {
    if number == SIGINT as usize {
        "SIGINT"
    } else {
        "SIGTERM"
    }
}

/// The bar shown on stderr once a run has taken [`PROGRESS_DELAY`] (hidden until then, and
/// when stderr is not a terminal): a fraction of the outputs, and of the current one's rows or
/// frames.
fn progress_bar(plan: &Plan, settings: &Settings) -> ProgressBar {
    let bar = ProgressBar::with_draw_target(Some(1000), ProgressDrawTarget::hidden());
    bar.set_style(
        ProgressStyle::with_template("{spinner} {msg} [{bar:40}] {percent}% ({elapsed})")
            .expect("a valid template")
            .progress_chars("=> "),
    );
    let (algorithm, size) = (settings.options.algorithm, settings.size);
    bar.set_message(match plan.jobs.first().map(|j| j.output) {
        Some(Output::Turntable(t, format)) if plan.jobs.len() == 1 => {
            format!("{algorithm} {size}, {} frames of {format}", t.frames)
        }
        _ => format!("{algorithm} {size}"),
    });
    bar
}
