//! The terminal editor: a live half-block preview of the scene and keyboard-driven editing.
//!
//! Keys become [`action::Action`]s ([`input`]), actions change the [`app::App`] in one place
//! ([`update`]), widgets draw it ([`view`]), and a worker thread renders the preview ([`worker`]).

pub mod action;
pub mod app;
pub mod export_job;
pub mod fields;
pub mod input;
pub mod keys;
pub mod orbit;
pub mod preview;
pub mod recovery;
pub mod terminal;
pub mod text;
pub mod update;
pub mod view;
pub mod worker;

pub use preview::ColorMode;

use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{RecvTimeoutError, Sender, channel};
use std::time::{Duration, Instant};

use anyhow::Context;
use ratatui::crossterm::event::{self, Event as TermEvent};
use ratatui::layout::Rect;
use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};

use crate::scene::Scene;
use action::Action;
use app::App;
use terminal::TerminalGuard;
use worker::{Job, RenderReply, Slot, Wanted, Worker};

/// How often the loop wakes without input: signal checks and the export gauge.
const TICK: Duration = Duration::from_millis(100);

/// Something the event loop reacts to.
enum Event {
    Input(TermEvent),
    Render(RenderReply),
}

/// Runs the editor on the scene at `scene_path` (the built-in scene when `None`) until the user
/// quits or the process receives SIGTERM, SIGHUP or SIGINT; unsaved edits then go to the
/// recovery file.
pub fn run(scene_path: Option<PathBuf>, color: ColorMode) -> anyhow::Result<()> {
    let mut app = load(scene_path.as_deref())?;
    app.color = color;
    if let Some(notice) = recovery::notice(scene_path.as_deref()) {
        app.info(notice);
    }
    let signalled = Arc::new(AtomicBool::new(false));
    // Raw mode turns Ctrl-C into a key, so SIGINT only comes from `kill`: treat it like SIGTERM.
    for signal in [SIGTERM, SIGHUP, SIGINT] {
        signal_hook::flag::register(signal, signalled.clone()).context("cannot watch signals")?;
    }
    let (tx, rx) = channel();
    spawn_input(tx.clone());
    let worker = Worker::spawn(move |reply| {
        let _ = tx.send(Event::Render(reply));
    });
    let mut guard = TerminalGuard::enter().context(
        "cannot set up the terminal (the editor needs one; `rastray render` works without)",
    )?;
    let mut state = Loop {
        worker,
        sent: None,
        latest: 0,
        scene: (u64::MAX, Arc::new(app.scene.clone())),
        latency: LatencyLog::from_env(),
        pending: None,
    };
    let mut redraw = true;
    loop {
        let size = guard.terminal.size()?;
        let areas = view::layout(Rect::new(0, 0, size.width, size.height), &app);
        state.request(&app, areas.map(|a| a.picture));
        if redraw {
            let started = Instant::now();
            guard.draw(|f| f.render_widget(&app, f.area()))?;
            state.drawn(started);
        }
        if app.quit {
            break;
        }
        let first = match rx.recv_timeout(TICK) {
            Ok(e) => Some(e),
            Err(RecvTimeoutError::Timeout) => None,
            Err(RecvTimeoutError::Disconnected) => break,
        };
        redraw = first.is_none() && app.export.is_some();
        // Handle everything already queued before drawing again: a held key draws once.
        for event in first
            .into_iter()
            .chain(std::iter::from_fn(|| rx.try_recv().ok()))
        {
            redraw = true;
            let picture = areas.map(|a| a.preview).unwrap_or_default();
            let action = match event {
                Event::Input(ev) => {
                    if let Some(log) = &mut state.latency {
                        log.key_at.get_or_insert(Instant::now());
                    }
                    input::map(&app, &ev, picture)
                }
                // A frame for a superseded request is stale: dropped. Warnings describe the
                // world built, whichever request built it: kept.
                Event::Render(reply)
                    if reply.id() == state.latest
                        || matches!(reply, RenderReply::Warned { .. }) =>
                {
                    state.arrived(&reply);
                    Some(Action::Rendered(Box::new(reply)))
                }
                Event::Render(_) => None,
            };
            if let Some(action) = action {
                update::apply(&mut app, action);
            }
        }
        update::apply(&mut app, Action::Tick);
        if signalled.load(Ordering::Relaxed) {
            drop(guard);
            if app.dirty {
                let path = recovery::write(&app.scene, app.path.as_deref())?;
                eprintln!("rastray: unsaved edits written to {}", path.display());
            }
            return Ok(());
        }
    }
    Ok(())
}

/// The app on the scene at `path`, or on the built-in scene.
/// The editor on the scene at `path`; a path that does not exist yet starts a new scene there
/// from the built-in one (written on the first save), as text editors do with a new file name.
fn load(path: Option<&Path>) -> anyhow::Result<App> {
    Ok(match path {
        Some(p) if !p.exists() => {
            let base = p.parent().map(Path::to_path_buf).unwrap_or_default();
            let mut app = App::new(crate::scene::default_scene(), Some(p.to_path_buf()), base);
            app.info(format!("new scene {}: s saves it", p.display()));
            app
        }
        Some(p) => {
            let scene = crate::scene::load(p)?;
            let base = p.parent().map(Path::to_path_buf).unwrap_or_default();
            App::new(scene, Some(p.to_path_buf()), base)
        }
        None => App::new(
            crate::scene::default_scene(),
            None,
            std::env::current_dir().context("no working directory")?,
        ),
    })
}

/// Reads terminal events on their own thread, so the loop also wakes for finished frames.
fn spawn_input(tx: Sender<Event>) {
    std::thread::Builder::new()
        .name("rastray-input".into())
        .spawn(move || {
            while let Ok(ev) = event::read() {
                if tx.send(Event::Input(ev)).is_err() {
                    break;
                }
            }
        })
        .expect("the input thread can be started");
}

/// The render jobs the app needs for a picture area of `picture`.
pub fn wanted(app: &App, picture: Rect) -> Option<Wanted> {
    let job = |slot, algorithm, area: Rect| {
        (area.width > 0 && area.height > 0).then_some(Job {
            slot,
            algorithm,
            width: area.width as u32,
            height: 2 * area.height as u32,
        })
    };
    let jobs: Vec<Job> = if app.compare {
        view::compare_panes(picture)
            .into_iter()
            .enumerate()
            .filter_map(|(i, (algorithm, _, image))| job(Slot::Compare(i), algorithm, image))
            .collect()
    } else {
        job(Slot::Main, app.algorithm, picture)
            .into_iter()
            .collect()
    };
    (!jobs.is_empty()).then_some(Wanted {
        generation: app.generation,
        camera: app.scene.camera,
        jobs,
    })
}

/// Event-loop bookkeeping: what was sent to the worker, and latency measurement.
struct Loop {
    worker: Worker,
    sent: Option<Wanted>,
    /// Id of the newest request sent.
    latest: u64,
    /// The scene shared with the worker, by generation.
    scene: (u64, Arc<Scene>),
    latency: Option<LatencyLog>,
    /// The request whose frame is awaited, for the latency log.
    pending: Option<Pending>,
}

/// A request caused by a key, waiting to be drawn.
struct Pending {
    id: u64,
    key_at: Instant,
    /// Render time once the last frame arrived, ms.
    render_ms: Option<f64>,
}

impl Loop {
    /// Sends a render request when the wanted preview changed.
    fn request(&mut self, app: &App, picture: Option<Rect>) {
        let wanted = picture.and_then(|p| wanted(app, p));
        let key_at = self.latency.as_mut().and_then(|l| l.key_at.take());
        let Some(wanted) = wanted.filter(|w| self.sent.as_ref() != Some(w)) else {
            return;
        };
        if self.scene.0 != app.generation {
            self.scene = (app.generation, Arc::new(app.scene.clone()));
        }
        self.sent = Some(wanted.clone());
        let id = self
            .worker
            .request(wanted, self.scene.1.clone(), app.base_dir.clone());
        self.latest = id;
        self.pending = key_at.map(|key_at| Pending {
            id,
            key_at,
            render_ms: None,
        });
    }

    /// Notes the render time when the awaited request's last frame arrives.
    fn arrived(&mut self, reply: &RenderReply) {
        if let (
            Some(p),
            RenderReply::Shot {
                id,
                millis,
                last: true,
                ..
            },
        ) = (&mut self.pending, reply)
            && p.id == *id
        {
            p.render_ms = Some(*millis);
        }
    }

    /// Logs key-to-screen latency once the awaited frame has been drawn.
    fn drawn(&mut self, started: Instant) {
        let (Some(log), Some(p)) = (&mut self.latency, &self.pending) else {
            return;
        };
        if let Some(render_ms) = p.render_ms {
            let draw_ms = started.elapsed().as_secs_f64() * 1000.0;
            let total = p.key_at.elapsed().as_secs_f64() * 1000.0;
            let _ = writeln!(log.file, "{total:.2}\t{render_ms:.2}\t{draw_ms:.2}");
            self.pending = None;
        }
    }
}

/// Latency figures (key to drawn preview, render, draw; ms) appended to the file named by
/// `RASTRAY_LATENCY_LOG`, for measuring the editor's responsiveness.
struct LatencyLog {
    file: std::fs::File,
    key_at: Option<Instant>,
}

impl LatencyLog {
    fn from_env() -> Option<LatencyLog> {
        let path = std::env::var_os("RASTRAY_LATENCY_LOG")?;
        let file = std::fs::OpenOptions::new()
            .create(true)
            .append(true)
            .open(path)
            .ok()?;
        Some(LatencyLog { file, key_at: None })
    }
}
