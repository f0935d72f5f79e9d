//! The render thread. The newest request wins: requests queued behind it are dropped, and a
//! render still running when a newer request arrives is cancelled through [`Progress::cancel`].
//! The world is rebuilt only when the scene's generation changes (camera moves reuse it).

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::mpsc::{Receiver, Sender, channel};

use crate::World;
use crate::memory_budget::{BYTES_PER_STILL_PIXEL, Estimate};
use crate::mesh::{Measurements, measure};
use crate::pool_thread::on_pool_thread;
use crate::render::{
    Algorithm, DisplayMode, Frame, Overlays, Progress, RenderError, RenderOptions, Renderer,
    ground_grid, objects_without_uvs, overlay_bounds,
};
use crate::scene::{Camera, Scene};
use crate::terminal_image::preview::PreviewImage;
use crate::warnings::{Warning, warnings};
use crate::world::{MeshFileCache, WorldObject, WorldObjectSource};

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
    /// How every job shows the scene.
    pub display: Display,
}

/// The display mode and overlays of the previews, and what is selected.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Display {
    pub mode: DisplayMode,
    /// The overlays; their `selected` is ignored, worked out from `selected_object`.
    pub overlays: Overlays,
    /// The scene object selected in the editor (index into the scene's objects), if any.
    pub selected_object: Option<usize>,
}

/// What the overlays and the `uv` mode show that the picture cannot say: for the status bar.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Measures {
    /// The ground grid's spacing, world units, when the grid is drawn.
    pub grid_spacing: Option<f32>,
    /// Width, height and depth of the drawn bounding box, world units, when it is drawn.
    pub box_size: Option<glam::Vec3>,
    /// Objects without texture coordinates, when the `uv` mode is shown.
    pub without_uvs: usize,
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
    /// What the request's overlays and mode measured, sent before its images when it has
    /// overlays or shows `uv`.
    Measured { id: u64, measures: Measures },
    /// The warnings of a newly built world, sent before its first image; an empty list when
    /// the world before had some and this one has none.
    Warned { id: u64, warnings: Vec<Warning> },
    /// The axis-aligned bounds (min, max, world units) of a newly built world, `None` when it
    /// is empty: what preset views and "fit all" fit.
    Bounds {
        id: u64,
        bounds: Option<(glam::Vec3, glam::Vec3)>,
    },
    /// The model files a newly built world read and the files they pulled in (MTL libraries,
    /// textures, glTF buffers and images), for live reload to watch; sent when there are some,
    /// or were some for the world before.
    ModelFiles {
        id: u64,
        files: Vec<std::path::PathBuf>,
    },
    /// The size, area, closure and volume of the selected scene object `object` (all its
    /// parts, welded, world units), sent when the selection or the world changes and the
    /// object has at most [`MEASURED_TRIANGLES`] triangles.
    Shape {
        id: u64,
        object: usize,
        measurements: Measurements,
    },
}

/// Most triangles the worker measures for the properties pane: welding is about 0.1 s per
/// million triangles, and a bigger selection would hold back the next frame after every edit.
pub const MEASURED_TRIANGLES: usize = 2_000_000;

impl RenderReply {
    /// The request this reply answers.
    pub fn id(&self) -> u64 {
        match self {
            RenderReply::Shot { id, .. }
            | RenderReply::Failed { id, .. }
            | RenderReply::Measured { id, .. }
            | RenderReply::Warned { id, .. }
            | RenderReply::Bounds { id, .. }
            | RenderReply::ModelFiles { id, .. }
            | RenderReply::Shape { id, .. } => *id,
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
        Worker::spawn_with(MeshFileCache::default(), reply)
    }

    /// As [`Worker::spawn`], with the model files already read in `cache`.
    pub fn spawn_with(
        cache: MeshFileCache,
        reply: impl Fn(RenderReply) + Send + 'static,
    ) -> Worker {
        let (tx, rx) = channel();
        std::thread::Builder::new()
            .name("rastray-preview".into())
            .spawn(move || serve(rx, cache, reply))
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
fn serve(rx: Receiver<Request>, mut cache: MeshFileCache, reply: impl Fn(RenderReply)) {
    let mut world: Option<(u64, Arc<World>, Arc<[WorldObjectSource]>)> = None;
    // The current world's counts for the memory budget, beside which each preview's frames are
    // checked before they render.
    let mut budget = Estimate::default();
    // Keeps the ray tracer's BVH of the current world while only the camera moves.
    let mut renderer: Option<Renderer> = None;
    let mut frame = Frame::default();
    // The warnings of the last world built.
    let mut warned: Vec<Warning> = Vec::new();
    // Whether the last world built read any model files.
    let mut pulled_in = false;
    // The world generation and scene object last measured for the properties pane.
    let mut measured: Option<(u64, usize)> = None;
    while let Ok(mut request) = rx.recv() {
        while let Ok(newer) = rx.try_recv() {
            request = newer;
        }
        if request.progress.is_cancelled() {
            continue;
        }
        let generation = request.wanted.generation;
        let (current, sources) = match &world {
            Some((g, w, s)) if *g == generation => (w.clone(), s.clone()),
            _ => match on_pool_thread(|| {
                World::build_report(&request.scene, &request.base_dir, &mut cache)
            }) {
                Ok(report) => {
                    let w = report.world;
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
                    // While no model pulled any in, and none did before, nothing is sent.
                    if !report.inputs.is_empty() || pulled_in {
                        pulled_in = !report.inputs.is_empty();
                        reply(RenderReply::ModelFiles {
                            id: request.id,
                            files: report.inputs,
                        });
                    }
                    budget = Estimate::of_world(&w);
                    let (w, s) = (Arc::new(w), Arc::<[_]>::from(report.sources));
                    world = Some((generation, w.clone(), s.clone()));
                    (w, s)
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
        let display = request.wanted.display;
        let selected = display
            .selected_object
            .and_then(|object| world_objects_of(&sources, object));
        if let (Some(object), Some((first, end))) = (display.selected_object, selected)
            && measured != Some((generation, object))
        {
            measured = Some((generation, object));
            // An instance keeps no world-space mesh of its own: it is placed for measuring.
            let objects: Vec<std::borrow::Cow<'_, WorldObject>> = current.objects
                [first as usize..end as usize]
                .iter()
                .map(|o| match o.instance {
                    Some(_) => std::borrow::Cow::Owned(o.placed()),
                    None => std::borrow::Cow::Borrowed(o),
                })
                .collect();
            let parts: Vec<(&[glam::Vec3], &[[u32; 3]])> = objects
                .iter()
                .map(|o| (&o.mesh.positions[..], &o.mesh.triangles[..]))
                .collect();
            let triangles: usize = parts.iter().map(|(_, t)| t.len()).sum();
            if triangles <= MEASURED_TRIANGLES {
                reply(RenderReply::Shape {
                    id: request.id,
                    object,
                    measurements: on_pool_thread(|| measure(&parts)),
                });
            }
        }
        // The outline is the selection's: with no object selected there is none to draw.
        let overlays = Overlays {
            selected,
            outline: display.overlays.outline && selected.is_some(),
            ..display.overlays
        };
        if overlays.any() || display.mode == DisplayMode::Uv {
            let measures = Measures {
                grid_spacing: overlays
                    .grid
                    .then(|| ground_grid(&current).map(|g| g.spacing))
                    .flatten(),
                box_size: overlays
                    .bbox
                    .then(|| overlay_bounds(&current, overlays.selected).map(|(lo, hi)| hi - lo))
                    .flatten(),
                without_uvs: if display.mode == DisplayMode::Uv {
                    objects_without_uvs(&current)
                } else {
                    0
                },
            };
            reply(RenderReply::Measured {
                id: request.id,
                measures,
            });
        }
        let count = request.wanted.jobs.len();
        let pixels = request
            .wanted
            .jobs
            .iter()
            .map(|job| u64::from(job.width) * u64::from(job.height))
            .sum();
        // The preview's frames (two when comparing) count toward the bound like an export's.
        if let Err(over) = budget
            .with_frames(1, pixels, BYTES_PER_STILL_PIXEL)
            .check(Path::new("the preview"))
        {
            reply(RenderReply::Failed {
                id: request.id,
                message: over.to_string(),
            });
            continue;
        }
        for (n, job) in request.wanted.jobs.iter().enumerate() {
            let options = RenderOptions {
                mode: display.mode,
                overlays,
                ..RenderOptions::new(job.algorithm, job.width, job.height)
            };
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

/// The world objects (`first..end`) made from scene object `object`: one, or a glTF model's
/// parts, which are built next to each other; `None` when it made none.
fn world_objects_of(sources: &[WorldObjectSource], object: usize) -> Option<(u32, u32)> {
    let first = sources.iter().position(|s| s.object == object)?;
    let count = sources[first..]
        .iter()
        .take_while(|s| s.object == object)
        .count();
    Some((first as u32, (first + count) as u32))
}
