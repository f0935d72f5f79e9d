//! A PNG export running on its own thread, with progress and cancellation.

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::thread::JoinHandle;
use std::time::Instant;

use crate::World;
use crate::export::render_to_png;
use crate::render::{Progress, RenderOptions};
use crate::scene::Scene;

/// An export in progress.
#[derive(Debug)]
pub struct ExportJob {
    /// Where the PNG goes.
    pub path: PathBuf,
    /// What is rendered.
    pub options: RenderOptions,
    /// Fraction done, and the cancel switch.
    pub progress: Arc<Progress>,
    /// When the export started.
    pub started: Instant,
    handle: JoinHandle<Result<f64, String>>,
}

impl ExportJob {
    /// Starts rendering `scene` with `options` and writing it to `path`.
    pub fn start(
        scene: Scene,
        base_dir: &Path,
        options: RenderOptions,
        path: PathBuf,
    ) -> ExportJob {
        let progress = Arc::new(Progress::new());
        let (p, out, base) = (progress.clone(), path.clone(), base_dir.to_path_buf());
        let handle = std::thread::spawn(move || {
            let started = Instant::now();
            let world = Arc::new(World::build(&scene, &base).map_err(|e| e.to_string())?);
            render_to_png(&world, &scene.camera, &options, &out, &p).map_err(|e| e.to_string())?;
            Ok(started.elapsed().as_secs_f64() * 1000.0)
        });
        ExportJob {
            path,
            options,
            progress,
            started: Instant::now(),
            handle,
        }
    }

    /// Whether the thread has finished (successfully or not).
    pub fn is_finished(&self) -> bool {
        self.handle.is_finished()
    }

    /// Waits for the thread: the time taken in ms, or why it failed.
    pub fn finish(self) -> Result<f64, String> {
        self.handle
            .join()
            .unwrap_or_else(|_| Err("the export thread panicked".into()))
    }
}
