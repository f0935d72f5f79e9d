//! The terminal editor: a live half-block preview of the scene and keyboard-driven editing.
//!
//! Keys become [`action::Action`]s ([`input`]), actions change the [`app::App`] in one place
//! ([`update`]), widgets draw it ([`view`]), and a worker thread renders the preview ([`worker`]).
//! The app owns a [`document::Document`] (what is saved) and a [`view_state::ViewState`] (where
//! the preview looks from): looking around never edits the scene.

pub mod error;
pub mod input;
pub mod persistence;
pub mod state;
pub mod terminal;
pub mod text;
pub mod update;
pub mod view;
pub mod worker;

pub use error::TuiError;
pub use terminal::signals::Exit;

use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::mpsc::{Receiver, RecvTimeoutError, channel};
use std::time::{Duration, Instant};

use ratatui::crossterm::event::Event as TermEvent;
use ratatui::layout::Rect;

use crate::scene::Scene;
use crate::world::MeshFileCache;
use input::action::Action;
use persistence::autosave::Autosave;
use persistence::recovery;
use state::app::App;
use state::{document, mode, selection};
use terminal::guard::{self, TerminalGuard};
use terminal::signals::Signals;
use terminal::{color_probe, image_layer, pacer, term_input, tmux_client, tty_input};
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
/// The preview is drawn as `probe` finds out (see [`color_probe::detect`]); it asks the
/// terminal while the scene or model is read on another thread, since a big model takes a
/// second or more to read and the terminal's answers wait on the terminal, not on the CPU.
pub fn run(
    scene_path: Option<PathBuf>,
    up: crate::scene::UpAxis,
    probe: impl FnOnce() -> color_probe::Startup,
) -> Result<Exit, TuiError> {
    let started = Instant::now();
    let mut cache = MeshFileCache::default();
    let (loaded, startup) = std::thread::scope(|scope| {
        let loading = scope.spawn(|| load(scene_path.as_deref(), up, &mut cache));
        let startup = probe();
        let loaded = loading
            .join()
            .unwrap_or_else(|panic| std::panic::resume_unwind(panic));
        (loaded, startup)
    });
    let mut editor = Editor::start(loaded?, cache, scene_path.as_deref(), startup, started)?;
    let ended = editor.event_loop();
    editor.await_last_answer();
    editor.close(ended)
}

/// The running editor: its state, the terminal it draws on, and the threads that feed it
/// events. Its fields are declared in the order they are made, so they are dropped in reverse.
struct Editor {
    app: App,
    images: image_layer::ImageLayer,
    signals: Signals,
    autosave: Autosave,
    /// Keys, terminal replies and rendered frames, from the input and render threads.
    events: Receiver<Event>,
    guard: TerminalGuard,
    state: Loop,
    pacer: pacer::Pacer,
    /// Whether something changed since the last frame drawn.
    redraw: bool,
}

impl Editor {
    /// Starts the editor on `app`, loaded from `scene_path` at `started` (with the model files
    /// it read in `cache`): the signal watch, autosave, input and render threads, and the
    /// terminal taken over.
    fn start(
        app: App,
        cache: MeshFileCache,
        scene_path: Option<&Path>,
        startup: color_probe::Startup,
        started: Instant,
    ) -> Result<Editor, TuiError> {
        let no_color = std::env::var_os("NO_COLOR").is_some_and(|v| !v.is_empty());
        let mut app = app
            .with_color(startup.color)
            .with_plain_interface(no_color)
            .with_graphics(startup.graphics.clone());
        if let Some(why) = &startup.graphics.why {
            app.info(format!("half blocks: {why}"));
        }
        if let Some(notice) = &startup.graphics.notice {
            app.info(notice.clone());
        }
        if let Some(notice) = recovery::notice(scene_path) {
            app.info(notice);
        }
        let images = image_layer::ImageLayer::new(startup.graphics);
        let signals = Signals::watch().map_err(TuiError::Signals)?;
        let autosave = Autosave::start().map_err(TuiError::Autosave)?;
        let (tx, events) = channel();
        let input_tx = tx.clone();
        tty_input::spawn(move |input| {
            let event = match input {
                term_input::TermInput::Event(e) => Event::Input(e),
                term_input::TermInput::Reply(r) => Event::Reply(r),
            };
            input_tx.send(event).is_ok()
        })
        .map_err(TuiError::Input)?;
        let worker = Worker::spawn_with(cache, move |reply| {
            let _ = tx.send(Event::Render(reply));
        });
        let mut guard = TerminalGuard::enter().map_err(TuiError::TerminalSetup)?;
        guard::clean_up_with(images.cleanup());
        let start = images.enter();
        if !start.is_empty() {
            guard.ask(&start).map_err(TuiError::TerminalSetup)?;
        }
        let state = Loop {
            worker,
            sent: None,
            latest: 0,
            scene: (u64::MAX, Arc::new(app.doc.scene().clone())),
            latency: LatencyLog::from_env(started),
            pending: None,
            motion_frames: false,
            awaiting_pixels: false,
            moving: false,
            last_picture: pacer::PictureCost::GUESS,
        };
        Ok(Editor {
            app,
            images,
            signals,
            autosave,
            events,
            guard,
            state,
            pacer: pacer::Pacer::new(),
            redraw: true,
        })
    }

    /// Requests renders, draws, and applies the events that arrive, until the user quits, a
    /// signal ends the editor, or the terminal or the event threads fail.
    fn event_loop(&mut self) -> Result<Exit, TuiError> {
        loop {
            let size = self.guard.terminal.size().map_err(TuiError::Terminal)?;
            if self.app.quit {
                return Ok(Exit::Quit);
            }
            let areas = view::layout(Rect::new(0, 0, size.width, size.height), &self.app);
            let now = Instant::now();
            // Real pixels once keys pause; frames rendered while they arrive are half blocks. The
            // picture's size follows the link, as measured when the keys pause (not after: the
            // picture's own answer must not have it sent again at another size).
            let pixels = !self.pacer.moving(now);
            if pixels && std::mem::replace(&mut self.state.moving, false) {
                let budget = self.pacer.link().pixel_budget(self.state.last_picture);
                self.app.view.set_pixel_budget(budget);
            }
            self.state.moving |= !pixels;
            self.state
                .request(&self.app, areas.map(|a| a.picture), pixels);
            // Cheap frames only over a slow link; while the picture that follows the keys is
            // rendered, the last motion frame stays: the picture covers it at once.
            let cheap = self.pacer.cheap(now, self.state.awaiting_pixels);
            let exact_due = self.pacer.exact_due(now, self.state.awaiting_pixels);
            // At most one frame in flight: the next waits for the terminal's answer to the last.
            if (self.redraw || exact_due) && self.pacer.may_draw(now) {
                self.draw(now, cheap, areas)?;
            }
            let first = self.next_event()?;
            self.redraw |= first.is_none() && self.app.is_exporting();
            // Handle everything already queued before drawing again: a held key draws once.
            let mut next = first.or_else(|| self.events.try_recv().ok());
            while let Some(event) = next {
                self.handle(event, areas);
                next = self.events.try_recv().ok();
            }
            update::apply(&mut self.app, Action::Tick);
            self.redraw |= std::mem::take(&mut self.app.ticked_change);
            if let Some(problem) = self.autosave.note(&self.app) {
                self.app.error(problem);
            }
            if let Some(signal) = self.signals.received() {
                return Ok(Exit::Signal(signal));
            }
        }
    }

    /// Draws the cells (`cheap` ones when the pacer wants them) and the pictures over them;
    /// where the pacer asks, then asks the terminal to answer once it has the frame. `now` is
    /// when this turn of the loop began.
    fn draw(
        &mut self,
        now: Instant,
        cheap: bool,
        areas: Option<view::Areas>,
    ) -> Result<(), TuiError> {
        let started = Instant::now();
        let before = self.guard.written();
        let cheap = self.app.present_previews(cheap);
        let pictures = areas.map_or_else(Vec::new, |a| view::placements(&self.app, a.picture));
        let picture_bytes = self.images.frame(&pictures);
        self.state.sent_pictures(&pictures, picture_bytes.len());
        let app = &self.app;
        self.guard
            .draw(|f| f.render_widget(app, f.area()), &picture_bytes)
            .map_err(TuiError::Terminal)?;
        if self.pacer.should_ask() {
            self.guard.ask(pacer::QUERY).map_err(TuiError::Terminal)?;
            self.pacer.carrying(picture_bytes.len());
            self.pacer.asked(now, cheap, self.guard.written() - before);
        } else {
            self.pacer.drew(cheap);
        }
        self.state.drawn(started);
        self.redraw = false;
        Ok(())
    }

    /// The next event, waited for until the pacer or a frame to be redrawn in pixels needs the
    /// loop, and at most a [`TICK`]; `None` when none came.
    fn next_event(&mut self) -> Result<Option<Event>, TuiError> {
        // Frames rendered in half blocks while keys arrived are rendered again in pixels once
        // the keys pause.
        let settle = self
            .state
            .motion_frames
            .then(|| self.pacer.settles_at())
            .flatten();
        let wake = [self.pacer.wake_at(), settle].into_iter().flatten().min();
        let wait = wake.map_or(TICK, |at| {
            at.saturating_duration_since(Instant::now()).min(TICK)
        });
        match self.events.recv_timeout(wait) {
            Ok(e) => Ok(Some(e)),
            Err(RecvTimeoutError::Timeout) => Ok(None),
            Err(RecvTimeoutError::Disconnected) => Err(TuiError::EventsStopped),
        }
    }

    /// Applies one event: the terminal's answer goes to the pacer, a key or mouse event becomes
    /// an Action through the key map, and a frame for the newest request becomes one too.
    fn handle(&mut self, event: Event, areas: Option<view::Areas>) {
        if let Event::Reply(reply) = &event {
            if let term_input::Reply::CursorPosition { .. } = reply {
                self.pacer.answered(Instant::now());
            }
            return;
        }
        self.redraw = true;
        let picture = areas.map(|a| a.preview).unwrap_or_default();
        let action = match event {
            Event::Reply(_) => None,
            Event::Input(ev) => {
                if let TermEvent::Resize(..) = ev {
                    self.images.invalidate();
                }
                if let TermEvent::FocusLost = ev {
                    let delete = self.images.hide();
                    // Best effort: without a client terminal the picture stays a while.
                    if !delete.is_empty() {
                        let _ = tmux_client::write(&delete);
                    }
                }
                if matches!(ev, TermEvent::Key(_) | TermEvent::Mouse(_)) {
                    self.pacer.input(Instant::now());
                }
                if let Some(log) = &mut self.state.latency {
                    log.key_at.get_or_insert(Instant::now());
                }
                if areas.is_some() {
                    input::map(&self.app, &ev, picture)
                } else {
                    input::map_too_small(&self.app, &ev)
                }
            }
            // A frame for a superseded request is stale: dropped. Warnings describe the
            // world built, whichever request built it: kept.
            Event::Render(reply)
                if reply.id() == self.state.latest
                    || matches!(
                        reply,
                        RenderReply::Warned { .. }
                            | RenderReply::Bounds { .. }
                            | RenderReply::ModelFiles { .. }
                    ) =>
            {
                self.state.arrived(&reply);
                Some(Action::Rendered(Box::new(reply)))
            }
            Event::Render(_) => None,
        };
        if let Some(action) = action {
            update::apply(&mut self.app, action);
        }
    }

    /// An answer to a query still on its way would reach the shell as typed text: waits a
    /// little for it while the editor still reads its input.
    fn await_last_answer(&mut self) {
        let until = Instant::now() + pacer::LAST_ANSWER;
        while self.pacer.awaiting() {
            let left = until.saturating_duration_since(Instant::now());
            match self.events.recv_timeout(left) {
                Ok(Event::Reply(term_input::Reply::CursorPosition { .. })) => {
                    self.pacer.answered(Instant::now())
                }
                Ok(_) => {}
                Err(_) => break,
            }
        }
    }

    /// The way out: edits reach the disk (the recovery file, unless the user quit) before the
    /// terminal is restored, since it may be gone; then how the editor `ended`.
    fn close(self, ended: Result<Exit, TuiError>) -> Result<Exit, TuiError> {
        // Bound in the order they were made, so that they drop in reverse as they always did:
        // the render thread before autosave, the signal watch last but the app and pictures.
        let Editor {
            app,
            images: _images,
            signals,
            autosave,
            events: _events,
            guard,
            state: _state,
            pacer: _pacer,
            redraw: _,
        } = self;
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
}

/// The editor on the scene at `path`; a path that does not exist yet starts a new scene there
/// from the built-in one (written on the first save), as text editors do with a new file name.
/// A model file (OBJ, STL, PLY, glTF; by extension or content) starts a new, unnamed scene
/// showing it, turned so that its `up` axis is +Y.
fn load(
    path: Option<&Path>,
    up: crate::scene::UpAxis,
    cache: &mut MeshFileCache,
) -> Result<App, TuiError> {
    Ok(match path {
        Some(p) if crate::model_scene::is_model_file(p) => {
            // Read once: the worker's first world takes the model from `cache`.
            let (scene, folder) = crate::pool_thread::on_pool_thread(|| {
                crate::model_scene::scene_for_model_cached(p, up, cache)
            })?;
            let mut app = App::new(scene, None, folder);
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
/// `RASTRAY_LATENCY_LOG`, for measuring the editor's responsiveness. The first line is the
/// start-up: from loading the scene or model to its first preview drawn.
struct LatencyLog {
    file: std::fs::File,
    key_at: Option<Instant>,
}

impl LatencyLog {
    /// The log, when asked for, timing the first frame from `started`.
    fn from_env(started: Instant) -> Option<LatencyLog> {
        let path = std::env::var_os("RASTRAY_LATENCY_LOG")?;
        let file = std::fs::OpenOptions::new()
            .create(true)
            .append(true)
            .open(path)
            .ok()?;
        Some(LatencyLog {
            file,
            key_at: Some(started),
        })
    }
}
