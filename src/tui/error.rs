//! Why the editor could not start or had to stop.

use std::io;

use crate::scene::SceneError;

/// An error of [`super::run`]; each names what the editor was doing.
#[derive(Debug, thiserror::Error)]
pub enum TuiError {
    /// The scene file could not be read, or the recovery file not written.
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// The model file opened on its own could not be shown.
    #[error(transparent)]
    Model(#[from] crate::model_scene::ModelSceneError),
    /// The built-in scene needs a working directory for its OBJ paths.
    #[error("no working directory")]
    WorkingDirectory(#[source] io::Error),
    /// SIGTERM, SIGHUP or SIGINT could not be watched.
    #[error("cannot watch signals")]
    Signals(#[source] io::Error),
    /// The recovery file's writer could not be started.
    #[error("cannot start autosave")]
    Autosave(#[source] io::Error),
    /// Every source of events (input, renders) ended.
    #[error("the editor's events stopped")]
    EventsStopped,
    /// The terminal's input could not be read.
    #[error("cannot read the terminal")]
    Input(#[source] io::Error),
    /// Raw mode or the alternate screen could not be set up.
    #[error("cannot set up the terminal (the editor needs one; `rastray render` works without)")]
    TerminalSetup(#[source] io::Error),
    /// Drawing to the terminal failed while the editor ran.
    #[error("cannot draw to the terminal")]
    Terminal(#[from] io::Error),
}
