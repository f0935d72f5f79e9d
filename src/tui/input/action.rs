//! Everything the user (or a finished background job) can ask of the editor. Keys become
//! Actions in [`crate::tui::input`]; [`crate::tui::update::apply`] carries them out.

use crate::render::{Algorithm, OverlayKind};
use crate::tui::state::mode::AddKind;
use crate::tui::worker::RenderReply;

/// One request to change the editor's state.
#[derive(Debug, Clone, PartialEq)]
pub enum Action {
    /// Quit, asking first when there are unsaved edits.
    Quit,
    /// Quit without saving (answer to the question).
    QuitNow,
    /// Save, then quit (answer to the question).
    SaveAndQuit,
    /// Focus the next pane.
    FocusNext,
    /// Focus the previous pane.
    FocusPrev,
    /// Move up in the focused list, menu or form.
    Up,
    /// Move down in the focused list, menu or form.
    Down,
    /// Step the chosen property by this many steps (±1, ±10).
    Step(i32),
    /// Start typing an exact value for the chosen property.
    Edit,
    /// A typed character.
    Input(char),
    /// Delete the last typed character.
    Backspace,
    /// Clear the typed line.
    ClearInput,
    /// Accept: the typed value, the highlighted menu entry, the dialog.
    Submit,
    /// Close the dialog, menu or overlay; cancel the export in progress.
    Cancel,
    /// Show the key overlay.
    Help,
    /// Open the add menu.
    AddMenu,
    /// Add an item of this kind.
    Add(AddKind),
    /// Duplicate the selected object or light.
    Duplicate,
    /// Remove the selected object or light.
    Remove,
    Undo,
    Redo,
    /// Save to the scene's file, or ask for a path.
    Save,
    /// Ask for a path and save there.
    SaveAs,
    /// Ask for a scene file to open.
    Open,
    /// Open the export dialog.
    Export,
    /// Switch the preview's algorithm.
    Algorithm(Algorithm),
    /// Toggle the side-by-side view of the three algorithms.
    ToggleCompare,
    /// Show the display mode this many places on in `DisplayMode::ALL` (negative: back).
    CycleMode(i32),
    /// Draw an overlay over the preview, or stop drawing it.
    ToggleOverlay(OverlayKind),
    /// Turn the view around its target, degrees (yaw about +Y, pitch up).
    Orbit {
        yaw: f32,
        pitch: f32,
    },
    /// Move the view and its target sideways, as fractions of the viewing distance.
    Pan {
        right: f32,
        up: f32,
    },
    /// Scale the view's distance to its target (< 1 moves closer).
    Zoom(f32),
    /// Put the view back at the scene's camera.
    ResetView,
    /// Look from the next (1) or previous (−1) preset view, fitting the scene.
    StepPresetView(i32),
    /// Fit the scene's bounds in the view, from where it looks now.
    FitAll,
    /// Switch the view between perspective and orthographic, keeping the framing.
    ToggleProjection,
    /// Start or stop turning the view slowly about its target.
    ToggleSpin,
    /// Make the view the scene's camera: an undoable edit.
    SceneCameraFromView,
    /// A mouse button went down at (column, row).
    DragStart {
        column: u16,
        row: u16,
    },
    /// The mouse moved with the button down.
    DragTo {
        column: u16,
        row: u16,
    },
    /// The mouse button came up.
    DragEnd,
    /// A preview frame (or a failure) from the render worker.
    Rendered(Box<RenderReply>),
    /// Periodic check of background jobs.
    Tick,
    /// The terminal reported the pane focused (true) or not (focus reporting).
    TerminalFocus(bool),
}
