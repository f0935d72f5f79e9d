//! The render thread. The newest request wins: requests queued behind it are dropped, and a
//! render still running when a newer request arrives is cancelled through [`Progress::cancel`].
//! The world is rebuilt only when the scene's generation changes (camera moves reuse it).

use std::path::PathBuf;
use std::sync::Arc;
use std::sync::mpsc::{Receiver, Sender, channel};

use super::preview::PreviewImage;
use crate::World;
use crate::render::{Algorithm, Frame, Progress, RenderError, RenderOptions, Renderer};
use crate::scene::{Camera, Scene};
use crate::warnings::{Warning, warnings};
use crate::world::MeshFileCache;

/// Where a rendered image goes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Slot {
    /// The single preview.
    Main,
    /// One of the three compare panes, by index into [`Algorithm::ALL`].
    Compare(usize),
}

/// One image to render.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Job {
    pub slot: Slot,
    pub algorithm: Algorithm,
    /// Pixels.
    pub width: u32,
    /// Pixels (twice the rows of cells).
    pub height: u32,
}

/// What the preview needs now; equal requests need no new render.
#[derive(Debug, Clone, PartialEq)]
pub struct Wanted {
    pub generation: u64,
    pub camera: Camera,
    pub jobs: Vec<Job>,
}

/// A request as sent to the thread.
#[derive(Debug)]
struct Request {
    id: u64,
    wanted: Wanted,
    scene: Arc<Scene>,
    base_dir: PathBuf,
    progress: Arc<Progress>,
}

/// What the thread sends back.
#[derive(Debug, Clone, PartialEq)]
pub enum RenderReply {
    /// A finished image.
    Shot {
        id: u64,
        slot: Slot,
        image: PreviewImage,
        /// Render time, milliseconds.
        millis: f64,
        triangles: usize,
        /// Whether this was the request's last job.
        last: bool,
    },
    /// The world could not be built or the image not rendered.
    Failed { id: u64, message: String },
    /// The warnings of a newly built world, sent before its first image; an empty list when
    /// the world before had some and this one has none.
    Warned { id: u64, warnings: Vec<Warning> },
    /// The axis-aligned bounds (min, max, world units) of a newly built world, `None` when it
    /// is empty: what preset views and "fit all" fit.
    Bounds {
        id: u64,
        bounds: Option<(glam::Vec3, glam::Vec3)>,
    },
}

impl RenderReply {
    /// The request this reply answers.
    pub fn id(&self) -> u64 {
        match self {
            RenderReply::Shot { id, .. }
            | RenderReply::Failed { id, .. }
            | RenderReply::Warned { id, .. }
            | RenderReply::Bounds { id, .. } => *id,
        }
    }
}

/// Handle to the render thread.
pub struct Worker {
    tx: Sender<Request>,
    running: Option<Arc<Progress>>,
    next_id: u64,
}

impl Worker {
    /// Starts the thread; `reply` is called on it for every image or failure.
    pub fn spawn(reply: impl Fn(RenderReply) + Send + 'static) -> Worker {
        let (tx, rx) = channel();
        std::thread::Builder::new()
            .name("rastray-preview".into())
            .spawn(move || serve(rx, reply))
            .expect("the preview thread can be started");
        Worker {
            tx,
            running: None,
            next_id: 1,
        }
    }

    /// Asks for `wanted`, cancelling the request before it; returns the new request's id.
    pub fn request(&mut self, wanted: Wanted, scene: Arc<Scene>, base_dir: PathBuf) -> u64 {
        if let Some(old) = self.running.take() {
            old.cancel();
        }
        let id = self.next_id;
        self.next_id += 1;
        let progress = Arc::new(Progress::new());
        self.running = Some(progress.clone());
        let _ = self.tx.send(Request {
            id,
            wanted,
            scene,
            base_dir,
            progress,
        });
        id
    }
}

/// The thread's loop: take the newest request, build the world if needed, render each job.
fn serve(rx: Receiver<Request>, reply: impl Fn(RenderReply)) {
    let mut cache = MeshFileCache::default();
    let mut world: Option<(u64, Arc<World>)> = None;
    // Keeps the ray tracer's BVH of the current world while only the camera moves.
    let mut renderer: Option<Renderer> = None;
    let mut frame = Frame::default();
    // The warnings of the last world built.
    let mut warned: Vec<Warning> = Vec::new();
    while let Ok(mut request) = rx.recv() {
        while let Ok(newer) = rx.try_recv() {
            request = newer;
        }
        if request.progress.is_cancelled() {
            continue;
        }
        let generation = request.wanted.generation;
        let current = match &world {
            Some((g, w)) if *g == generation => w.clone(),
            _ => match World::build_cached(&request.scene, &request.base_dir, &mut cache) {
                Ok(w) => {
                    let found = warnings(&request.scene, &request.wanted.camera, &w);
                    // While there are none, and were none, only images are sent.
                    if !(found.is_empty() && warned.is_empty()) {
                        reply(RenderReply::Warned {
                            id: request.id,
                            warnings: found.clone(),
                        });
                    }
                    warned = found;
                    reply(RenderReply::Bounds {
                        id: request.id,
                        bounds: w.bounds(),
                    });
                    let w = Arc::new(w);
                    world = Some((generation, w.clone()));
                    w
                }
                Err(e) => {
                    reply(RenderReply::Failed {
                        id: request.id,
                        message: e.to_string(),
                    });
                    continue;
                }
            },
        };
        let count = request.wanted.jobs.len();
        for (n, job) in request.wanted.jobs.iter().enumerate() {
            let options = RenderOptions::new(job.algorithm, job.width, job.height);
            let renderer = renderer.get_or_insert_with(|| Renderer::new(options));
            renderer.set_options(options);
            let camera = &request.wanted.camera;
            match renderer.render(&current, camera, &request.progress, &mut frame) {
                Ok(stats) => reply(RenderReply::Shot {
                    id: request.id,
                    slot: job.slot,
                    image: PreviewImage::from_frame(&frame),
                    millis: stats.total().as_secs_f64() * 1000.0,
                    triangles: stats.triangles,
                    last: n + 1 == count,
                }),
                Err(RenderError::Cancelled(_)) => break,
                Err(e) => {
                    reply(RenderReply::Failed {
                        id: request.id,
                        message: e.to_string(),
                    });
                    break;
                }
            }
        }
    }
}
