//! Progress and cancellation shared between a render and whoever waits for it.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};

/// Counts finished image rows (of the supersampled image) and carries a cancel flag. Cheap to
/// poll. [`crate::render::Renderer::render`] sets the total; the algorithms advance it as rows finish.
#[derive(Debug, Default)]
pub struct Progress {
    done: AtomicU64,
    total: AtomicU64,
    /// Shared so that a signal handler can set it directly ([`Progress::cancel_flag`]).
    cancelled: Arc<AtomicBool>,
}

/// The render was cancelled before it finished.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[error("render cancelled")]
pub struct Cancelled;

impl Progress {
    /// A fresh tracker with nothing done.
    pub fn new() -> Progress {
        Progress::default()
    }

    /// Starts a new phase of `total` units.
    pub fn start(&self, total: u64) {
        self.done.store(0, Ordering::Relaxed);
        self.total.store(total.max(1), Ordering::Relaxed);
    }

    /// Records `units` more finished.
    pub fn advance(&self, units: u64) {
        self.done.fetch_add(units, Ordering::Relaxed);
    }

    /// Fraction finished, in [0, 1].
    pub fn fraction(&self) -> f64 {
        let total = self.total.load(Ordering::Relaxed).max(1);
        (self.done.load(Ordering::Relaxed) as f64 / total as f64).min(1.0)
    }

    /// Asks the render to stop as soon as it can.
    pub fn cancel(&self) {
        self.cancelled.store(true, Ordering::Relaxed);
    }

    /// The cancel flag itself, for a signal handler to set (`signal_hook::flag::register`):
    /// setting it is [`Progress::cancel`], with no thread in between.
    pub fn cancel_flag(&self) -> Arc<AtomicBool> {
        Arc::clone(&self.cancelled)
    }

    /// Whether [`Progress::cancel`] was called.
    pub fn is_cancelled(&self) -> bool {
        self.cancelled.load(Ordering::Relaxed)
    }

    /// `Err(Cancelled)` once cancelled.
    pub fn check(&self) -> Result<(), Cancelled> {
        if self.is_cancelled() {
            Err(Cancelled)
        } else {
            Ok(())
        }
    }
}
