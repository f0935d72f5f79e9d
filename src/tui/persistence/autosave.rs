//! Autosave: while the scene has unsaved edits, a background thread keeps the
//! [recovery file](super::recovery) up to date, at most [`DELAY`] after each change, so even
//! `kill -9` or the OOM killer loses no more than the last [`DELAY`] of work. The event loop
//! only hands a copy of the scene over; the disk is written on the thread.

use std::collections::VecDeque;
use std::path::PathBuf;
use std::sync::{Arc, Condvar, Mutex, MutexGuard, PoisonError};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use super::recovery::{self, RecoveryFile};
use crate::scene::{Scene, SceneError};
use crate::tui::state::app::App;

/// Longest time an unsaved change waits before it is in the recovery file. Changes within it
/// (a drag of the camera) are written together.
pub const DELAY: Duration = Duration::from_secs(2);

/// What to do to the recovery file, in order.
#[derive(Debug)]
enum Order {
    /// Write `scene` to `path` at `due`.
    Write {
        scene: Scene,
        path: PathBuf,
        due: Instant,
    },
    /// The edits were saved: remove the file.
    Remove,
    /// The edits were left behind (another scene was opened): keep the file for the user.
    Keep,
}

/// The queue the event loop fills and the thread empties.
#[derive(Debug, Default)]
struct State {
    orders: VecDeque<Order>,
    stop: bool,
    /// A failure not yet shown to the user.
    failure: Option<String>,
}

#[derive(Debug, Default)]
struct Shared {
    state: Mutex<State>,
    wake: Condvar,
}

impl Shared {
    fn lock(&self) -> MutexGuard<'_, State> {
        self.state.lock().unwrap_or_else(PoisonError::into_inner)
    }
}

/// The unsaved scene last handed to the thread, and where it goes.
#[derive(Debug)]
struct Noted {
    scene: Scene,
    path: PathBuf,
}

/// Keeps the recovery file in step with the editor's unsaved edits.
pub struct Autosave {
    shared: Arc<Shared>,
    thread: Option<JoinHandle<RecoveryFile>>,
    noted: Option<Noted>,
}

impl Autosave {
    /// Starts the background thread.
    pub fn start() -> std::io::Result<Autosave> {
        let shared = Arc::new(Shared::default());
        let thread = std::thread::Builder::new()
            .name("rastray-autosave".into())
            .spawn({
                let shared = shared.clone();
                move || keep_up(&shared)
            })?;
        Ok(Autosave {
            shared,
            thread: Some(thread),
            noted: None,
        })
    }

    /// Hands over what changed in `app` since the last call; cheap when nothing did. Returns a
    /// failure to write the recovery file, once, for the status line.
    pub fn note(&mut self, app: &App) -> Option<String> {
        let path = recovery::path_for(app.doc.path());
        let order = match (app.doc.is_dirty(), &self.noted) {
            (true, Some(n)) if n.scene == *app.doc.scene() && n.path == path => None,
            (true, _) => {
                self.noted = Some(Noted {
                    scene: app.doc.scene().clone(),
                    path: path.clone(),
                });
                Some(Order::Write {
                    scene: app.doc.scene().clone(),
                    path,
                    due: Instant::now() + DELAY,
                })
            }
            // Clean again: saved when the scene is the one noted, else replaced by another.
            (false, Some(n)) if n.scene == *app.doc.scene() => Some(Order::Remove),
            (false, Some(_)) => Some(Order::Keep),
            (false, None) => None,
        };
        if !app.doc.is_dirty() {
            self.noted = None;
        }
        let mut state = self.shared.lock();
        if let Some(order) = order {
            push(&mut state.orders, order);
            self.shared.wake.notify_one();
        }
        state.failure.take()
    }

    /// The user quit: the edits are saved or discarded, so the recovery file goes.
    pub fn quit(mut self) -> Result<(), SceneError> {
        let mut file = self.stop();
        file.remove()
    }

    /// Writes `app`'s unsaved edits now, when there are any; returns where, or why not.
    pub fn flush(mut self, app: &App) -> Option<Result<PathBuf, SceneError>> {
        let mut file = self.stop();
        app.doc.is_dirty().then(|| {
            let path = recovery::path_for(app.doc.path());
            file.write(app.doc.scene(), &path).map(|()| path)
        })
    }

    /// Stops the thread and carries out the orders it had not reached, at once.
    fn stop(&mut self) -> RecoveryFile {
        self.shared.lock().stop = true;
        self.shared.wake.notify_one();
        let mut file = self
            .thread
            .take()
            .and_then(|t| t.join().ok())
            .unwrap_or_default();
        let orders = std::mem::take(&mut self.shared.lock().orders);
        for order in orders {
            // Nobody is left to show a failure to: the caller reports the final write.
            let _ = carry_out(&mut file, order);
        }
        file
    }
}

impl Drop for Autosave {
    /// Unwinding from a panic: what was handed over still reaches the disk.
    fn drop(&mut self) {
        if self.thread.is_some() {
            self.stop();
        }
    }
}

/// Queues `order`. Writes merge into one that keeps the first due time, so a change waits at
/// most [`DELAY`] however many follow it; a removal cancels the writes before it; keeping a
/// file first writes what is pending.
fn push(orders: &mut VecDeque<Order>, order: Order) {
    match order {
        Order::Write { scene, path, due } => match orders.back_mut() {
            Some(Order::Write {
                scene: queued_scene,
                path: queued_path,
                ..
            }) => {
                *queued_scene = scene;
                *queued_path = path;
            }
            _ => orders.push_back(Order::Write { scene, path, due }),
        },
        Order::Remove => {
            orders.retain(|o| !matches!(o, Order::Write { .. }));
            orders.push_back(Order::Remove);
        }
        Order::Keep => {
            if let Some(Order::Write { due, .. }) = orders.back_mut() {
                *due = Instant::now();
            }
            orders.push_back(Order::Keep);
        }
    }
}

/// The thread: carries out each order when it is due, writing with the lock released.
fn keep_up(shared: &Shared) -> RecoveryFile {
    let mut file = RecoveryFile::default();
    let mut last_failure = None;
    loop {
        let order = {
            let mut state = shared.lock();
            loop {
                if state.stop {
                    return file;
                }
                let now = Instant::now();
                match state.orders.front() {
                    Some(Order::Write { due, .. }) if *due > now => {
                        let wait = *due - now;
                        state = shared
                            .wake
                            .wait_timeout(state, wait)
                            .unwrap_or_else(PoisonError::into_inner)
                            .0;
                    }
                    Some(_) => break state.orders.pop_front(),
                    None => {
                        state = shared
                            .wake
                            .wait(state)
                            .unwrap_or_else(PoisonError::into_inner)
                    }
                }
            }
        };
        let Some(order) = order else { continue };
        let failure = carry_out(&mut file, order)
            .err()
            .map(|e| format!("unsaved edits are not safe: {e}"));
        if failure.is_some() && failure != last_failure {
            shared.lock().failure = failure.clone();
        }
        last_failure = failure;
    }
}

fn carry_out(file: &mut RecoveryFile, order: Order) -> Result<(), SceneError> {
    match order {
        Order::Write { scene, path, .. } => file.write(&scene, &path),
        Order::Remove => file.remove(),
        Order::Keep => {
            file.keep();
            Ok(())
        }
    }
}
