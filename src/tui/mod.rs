//! The terminal editor: a live half-block preview of the scene and keyboard-driven editing.
//!
//! Keys become [`action::Action`]s ([`input`]), actions change the [`app::App`] in one place
//! ([`update`]), widgets draw it ([`view`]), and a worker thread renders the preview ([`worker`]).
//! The app owns a [`document::Document`] (what is saved) and a [`view_state::ViewState`] (where
//! the preview looks from): looking around never edits the scene.

pub mod action;
pub mod app;
pub mod autosave;
pub mod color_probe;
pub mod compact_backend;
pub mod disk_watch;
pub mod document;
pub mod error;
pub mod export_job;
pub mod fields;
pub mod graphics;
pub mod image_layer;
pub mod input;
pub mod keys;
pub mod mode;
pub mod motion;
pub mod orbit;
pub mod pacer;
pub mod preview;
pub mod recovery;
pub mod selection;
pub mod signals;
pub mod term_input;
pub mod terminal;
pub mod text;
pub mod theme;
pub mod tty_input;
pub mod update;
pub mod view;
pub mod view_state;
pub mod worker;

pub use error::TuiError;
pub use preview::ColorMode;
pub use signals::Exit;

use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::mpsc::{RecvTimeoutError, channel};
use std::time::{Duration, Instant};

use ratatui::crossterm::event::Event as TermEvent;
use ratatui::layout::Rect;

use crate::scene::Scene;
use action::Action;
use app::App;
use autosave::Autosave;
use signals::Signals;
use terminal::TerminalGuard;
use worker::{Job, RenderReply, Slot, Wanted, Worker};

/// How often the loop wakes without input: signal checks and the export gauge.
const TICK: Duration = Duration::from_millis(100);

/// Something the event loop reacts to.
enum Event {
    Input(TermEvent),
    Reply(term_input::Reply),
    Render(RenderReply),
}

/// Runs the editor on the scene at `scene_path` (the built-in scene when `None`) until the user
/// quits or the process receives SIGTERM, SIGHUP or SIGINT. Unsaved edits are kept in the
/// recovery file meanwhile, and written there at once when a signal or an error ends the editor.
/// The preview is drawn as `startup` says (see [`color_probe::detect`]).
pub fn run(
    scene_path: Option<PathBuf>,
    up: crate::scene::UpAxis,
    startup: color_probe::Startup,
) -> Result<Exit, TuiError> {
    let no_color = std::env::var_os("NO_COLOR").is_some_and(|v| !v.is_empty());
    let mut app = load(scene_path.as_deref(), up)?
        .with_color(startup.color)
        .with_plain_interface(no_color)
        .with_graphics(startup.graphics.clone());
    if let Some(why) = &startup.graphics.why {
        app.info(format!("half blocks: {why}"));
    }
    if let Some(notice) = recovery::notice(scene_path.as_deref()) {
        app.info(notice);
    }
    let mut images = image_layer::ImageLayer::new(startup.graphics);
    let signals = Signals::watch().map_err(TuiError::Signals)?;
    let mut autosave = Autosave::start().map_err(TuiError::Autosave)?;
    let (tx, rx) = channel();
    let input_tx = tx.clone();
    tty_input::spawn(move |input| {
        let event = match input {
            term_input::TermInput::Event(e) => Event::Input(e),
            term_input::TermInput::Reply(r) => Event::Reply(r),
        };
        input_tx.send(event).is_ok()
    })
    .map_err(TuiError::Input)?;
    let worker = Worker::spawn(move |reply| {
        let _ = tx.send(Event::Render(reply));
    });
    let mut guard = TerminalGuard::enter().map_err(TuiError::TerminalSetup)?;
    terminal::clean_up_with(images.cleanup());
    let mut state = Loop {
        worker,
        sent: None,
        latest: 0,
        scene: (u64::MAX, Arc::new(app.doc.scene().clone())),
        latency: LatencyLog::from_env(),
        pending: None,
        motion_frames: false,
        awaiting_pixels: false,
        moving: false,
        last_picture: pacer::PictureCost::GUESS,
    };
    let mut redraw = true;
    let mut pacer = pacer::Pacer::new();
    let ended = loop {
        let size = match guard.terminal.size() {
            Ok(size) => size,
            Err(e) => break Err(TuiError::Terminal(e)),
        };
        if app.quit {
            break Ok(Exit::Quit);
        }
        let areas = view::layout(Rect::new(0, 0, size.width, size.height), &app);
        let now = Instant::now();
        // Real pixels once keys pause; frames rendered while they arrive are half blocks. The
        // picture's size follows the link, as measured when the keys pause (not after: the
        // picture's own answer must not have it sent again at another size).
        let pixels = !pacer.moving(now);
        if pixels && std::mem::replace(&mut state.moving, false) {
            let budget = pacer.link().pixel_budget(state.last_picture);
            app.view.set_pixel_budget(budget);
        }
        state.moving |= !pixels;
        state.request(&app, areas.map(|a| a.picture), pixels);
        // Cheap frames only over a slow link; while the picture that follows the keys is
        // rendered, the last motion frame stays: the picture covers it at once.
        let cheap = pacer.cheap(now, state.awaiting_pixels);
        let exact_due = pacer.exact_due(now, state.awaiting_pixels);
        // At most one frame in flight: the next waits for the terminal's answer to the last.
        if (redraw || exact_due) && pacer.may_draw(now) {
            let started = Instant::now();
            let before = guard.written();
            let cheap = app.present_previews(cheap);
            let pictures = areas.map_or_else(Vec::new, |a| view::placements(&app, a.picture));
            let picture_bytes = images.frame(&pictures);
            state.sent_pictures(&pictures, picture_bytes.len());
            if let Err(e) = guard.draw(|f| f.render_widget(&app, f.area()), &picture_bytes) {
                break Err(TuiError::Terminal(e));
            }
            if pacer.should_ask() {
                if let Err(e) = guard.ask(pacer::QUERY) {
                    break Err(TuiError::Terminal(e));
                }
                pacer.carrying(picture_bytes.len());
                pacer.asked(now, cheap, guard.written() - before);
            } else {
                pacer.drew(cheap);
            }
            state.drawn(started);
            redraw = false;
        }
        // Frames rendered in half blocks while keys arrived are rendered again in pixels once
        // the keys pause.
        let settle = state.motion_frames.then(|| pacer.settles_at()).flatten();
        let wake = [pacer.wake_at(), settle].into_iter().flatten().min();
        let wait = wake.map_or(TICK, |at| {
            at.saturating_duration_since(Instant::now()).min(TICK)
        });
        let first = match rx.recv_timeout(wait) {
            Ok(e) => Some(e),
            Err(RecvTimeoutError::Timeout) => None,
            Err(RecvTimeoutError::Disconnected) => {
                break Err(TuiError::EventsStopped);
            }
        };
        redraw |= first.is_none() && app.is_exporting();
        // Handle everything already queued before drawing again: a held key draws once.
        for event in first
            .into_iter()
            .chain(std::iter::from_fn(|| rx.try_recv().ok()))
        {
            if let Event::Reply(reply) = &event {
                if let term_input::Reply::CursorPosition { .. } = reply {
                    pacer.answered(Instant::now());
                }
                continue;
            }
            redraw = true;
            let picture = areas.map(|a| a.preview).unwrap_or_default();
            let action = match event {
                Event::Reply(_) => None,
                Event::Input(ev) => {
                    if let TermEvent::Resize(..) = ev {
                        images.invalidate();
                    }
                    if matches!(ev, TermEvent::Key(_) | TermEvent::Mouse(_)) {
                        pacer.input(Instant::now());
                    }
                    if let Some(log) = &mut state.latency {
                        log.key_at.get_or_insert(Instant::now());
                    }
                    if areas.is_some() {
                        input::map(&app, &ev, picture)
                    } else {
                        input::map_too_small(&app, &ev)
                    }
                }
                // A frame for a superseded request is stale: dropped. Warnings describe the
                // world built, whichever request built it: kept.
                Event::Render(reply)
                    if reply.id() == state.latest
                        || matches!(
                            reply,
                            RenderReply::Warned { .. }
                                | RenderReply::Bounds { .. }
                                | RenderReply::ModelFiles { .. }
                        ) =>
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
        redraw |= std::mem::take(&mut app.ticked_change);
        if let Some(problem) = autosave.note(&app) {
            app.error(problem);
        }
        if let Some(signal) = signals.received() {
            break Ok(Exit::Signal(signal));
        }
    };
    // An answer to a query still on its way would reach the shell as typed text: wait a little
    // for it while the editor still reads its input.
    let until = Instant::now() + pacer::LAST_ANSWER;
    while pacer.awaiting() {
        let left = until.saturating_duration_since(Instant::now());
        match rx.recv_timeout(left) {
            Ok(Event::Reply(term_input::Reply::CursorPosition { .. })) => {
                pacer.answered(Instant::now())
            }
            Ok(_) => {}
            Err(_) => break,
        }
    }
    // Edits reach the disk before the terminal is touched: it may be gone.
    let recovered = match ended {
        Ok(Exit::Quit) => autosave.quit().map(|()| None),
        _ => autosave.flush(&app).transpose(),
    };
    drop(guard);
    recovery::report(&recovered);
    // A lost terminal fails a draw just before its SIGHUP arrives: the signal tells the story.
    signals
        .received()
        .map_or(ended, |signal| Ok(Exit::Signal(signal)))
}

/// The editor on the scene at `path`; a path that does not exist yet starts a new scene there
/// from the built-in one (written on the first save), as text editors do with a new file name.
/// A model file (OBJ, STL, PLY, glTF; by extension or content) starts a new, unnamed scene
/// showing it, turned so that its `up` axis is +Y.
fn load(path: Option<&Path>, up: crate::scene::UpAxis) -> Result<App, TuiError> {
    Ok(match path {
        Some(p) if crate::model_scene::is_model_file(p) => {
            let scene = crate::model_scene::scene_for_model(p, up)?;
            let mut app = App::new(scene, None, document::folder_of(p));
            let file = p.file_name().unwrap_or_default().to_string_lossy();
            app.doc.name_untitled(format!("new scene of {file}"));
            app.info(format!(
                "a new scene showing {}: s saves it as a scene file",
                crate::tui::text::clean(&p.display().to_string())
            ));
            app
        }
        Some(p) if !p.exists() => {
            let base = document::folder_of(p);
            let mut app = App::new(crate::scene::default_scene(), Some(p.to_path_buf()), base);
            app.info(format!("new scene {}: s saves it", p.display()));
            app
        }
        Some(p) => {
            let scene = crate::scene::load(p)?;
            App::new(scene, Some(p.to_path_buf()), document::folder_of(p))
        }
        None => App::new(
            crate::scene::default_scene(),
            None,
            std::env::current_dir().map_err(TuiError::WorkingDirectory)?,
        ),
    })
}

/// The render jobs the app needs for a picture area of `picture`: in real pixels when `pixels`
/// and the editor draws with a graphics protocol and no dialog covers the preview (within the
/// view's pixel budget), else at the size its glyph set samples (see
/// [`graphics::Graphics::cells_size`]).
pub fn wanted(app: &App, picture: Rect, pixels: bool) -> Option<Wanted> {
    let pixels = pixels && matches!(app.mode, mode::Mode::Normal | mode::Mode::Edit(_));
    let job = |slot, algorithm, area: Rect| {
        let graphics = app.view.graphics();
        let (width, height) = pixels
            .then(|| app.view.pixel_size(area.width, area.height))
            .flatten()
            .unwrap_or_else(|| graphics.cells_size(area.width, area.height));
        (area.width > 0 && area.height > 0).then_some(Job {
            slot,
            algorithm,
            width,
            height,
        })
    };
    let jobs: Vec<Job> = if app.view.compare() {
        view::compare_panes(picture)
            .into_iter()
            .enumerate()
            .filter_map(|(i, (algorithm, _, image))| job(Slot::Compare(i), algorithm, image))
            .collect()
    } else {
        job(Slot::Main, app.view.algorithm(), picture)
            .into_iter()
            .collect()
    };
    let selected_object = match app.item() {
        selection::Item::Object(i) => Some(i),
        _ => None,
    };
    (!jobs.is_empty()).then_some(Wanted {
        generation: app.doc.generation(),
        camera: app.view.camera(),
        jobs,
        display: worker::Display {
            mode: app.view.mode(),
            overlays: app.view.overlays(),
            selected_object,
        },
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
    /// Whether the last request was for half blocks where the editor draws real pixels, since
    /// keys were arriving: rendered again in pixels once they pause.
    motion_frames: bool,
    /// Whether the last request was for pictures in real pixels that have not arrived yet.
    awaiting_pixels: bool,
    /// Whether keys were arriving when the loop last looked.
    moving: bool,
    /// What the last pictures sent cost: sizes the next over a slow link.
    last_picture: pacer::PictureCost,
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
    fn request(&mut self, app: &App, picture: Option<Rect>, pixels: bool) {
        self.motion_frames = app.view.graphics().protocol.is_some() && !pixels;
        let wanted = picture.and_then(|p| wanted(app, p, pixels));
        let key_at = self.latency.as_mut().and_then(|l| l.key_at.take());
        let Some(wanted) = wanted.filter(|w| self.sent.as_ref() != Some(w)) else {
            return;
        };
        let generation = app.doc.generation();
        if self.scene.0 != generation {
            self.scene = (generation, Arc::new(app.doc.scene().clone()));
        }
        self.awaiting_pixels = app.view.graphics().protocol.is_some()
            && pixels
            && matches!(app.mode, mode::Mode::Normal | mode::Mode::Edit(_));
        self.sent = Some(wanted.clone());
        let id = self.worker.request(
            wanted,
            self.scene.1.clone(),
            app.doc.base_dir().to_path_buf(),
        );
        self.latest = id;
        self.pending = key_at.map(|key_at| Pending {
            id,
            key_at,
            render_ms: None,
        });
    }

    /// Notes what `pictures` cost when `bytes` drew them (nothing when no bytes were sent:
    /// they were on screen already).
    fn sent_pictures(&mut self, pictures: &[image_layer::Placement], bytes: usize) {
        let pixels: usize = pictures.iter().map(|p| p.image.pixels.len()).sum();
        if bytes > 0 && pixels > 0 {
            self.last_picture = pacer::PictureCost {
                pixels: pixels as u64,
                bytes: bytes as u64,
            };
        }
    }

    /// Notes the render time when the awaited request's last frame arrives.
    fn arrived(&mut self, reply: &RenderReply) {
        if reply.id() == self.latest
            && matches!(
                reply,
                RenderReply::Shot { last: true, .. } | RenderReply::Failed { .. }
            )
        {
            self.awaiting_pixels = false;
        }
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
