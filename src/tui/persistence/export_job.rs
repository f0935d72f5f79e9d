//! An export (an image or a turntable) running on its own thread, with progress and
//! cancellation.

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::thread::JoinHandle;
use std::time::Instant;

use crate::World;
use crate::export::{ImageFormat, Output, Turntable, render_to_file};
use crate::render::{Progress, RenderOptions};
use crate::scene::Scene;

/// An export in progress.
#[derive(Debug)]
pub struct ExportJob {
    /// Where the file goes.
    pub path: PathBuf,
    /// What is written there.
    pub output: Output,
    /// What is rendered.
    pub options: RenderOptions,
    /// Fraction done, and the cancel switch.
    pub progress: Arc<Progress>,
    /// When the export started.
    pub started: Instant,
    handle: JoinHandle<Result<f64, String>>,
}

impl ExportJob {
    /// Starts rendering `scene` with `options` and writing it to `path` as `output` says.
    pub fn start(
        scene: Scene,
        base_dir: &Path,
        options: RenderOptions,
        output: Output,
        path: PathBuf,
    ) -> ExportJob {
        let progress = Arc::new(Progress::new());
        let (p, out, base) = (progress.clone(), path.clone(), base_dir.to_path_buf());
        let handle = std::thread::spawn(move || {
            let started = Instant::now();
            let world = Arc::new(World::build(&scene, &base).map_err(|e| e.to_string())?);
            output
                .check_memory(&world, &options, &out)
                .map_err(|e| e.to_string())?;
            render_to_file(&world, &scene.camera, &options, output, &out, &p)
                .map_err(|e| e.to_string())?;
            Ok(started.elapsed().as_secs_f64() * 1000.0)
        });
        ExportJob {
            path,
            output,
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

/// What the export dialog asks for: a still image when `turntable` (frames, as typed) is 0,
/// else a turntable of that many frames; in the `requested` format, or the one the extension of
/// `path` names.
pub fn export_output(
    path: &Path,
    requested: Option<ImageFormat>,
    turntable: &str,
) -> Result<Output, String> {
    let frames: u32 = turntable
        .trim()
        .parse()
        .map_err(|_| format!("`{}` is not a number of turntable frames", turntable.trim()))?;
    let turntable = (frames > 0).then(|| Turntable::new(frames));
    if let Some(t) = turntable {
        t.check().map_err(|e| e.to_string())?;
    }
    Output::for_path(path, requested, turntable).map_err(|e| e.to_string())
}
