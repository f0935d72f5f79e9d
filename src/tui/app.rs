//! The editor's state: the scene being edited and where it lives, the selection, the focused
//! pane, the current mode, undo history, the latest preview frames and the export in progress.
//! Only [`super::update`] changes it.

use std::path::PathBuf;

use super::export_job::ExportJob;
use super::preview::{ColorMode, PreviewImage};
use crate::render::Algorithm;
use crate::scene::{Camera, Scene};
use crate::warnings::Warning;

/// One entry of the scene list.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Item {
    /// Camera, ambient light, background and recursion depth.
    Settings,
    /// Index into `scene.lights`.
    Light(usize),
    /// Index into `scene.objects`.
    Object(usize),
}

/// The pane that receives navigation keys.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Focus {
    #[default]
    List,
    Properties,
    Preview,
}

impl Focus {
    /// The next pane (Tab).
    pub fn next(self) -> Focus {
        match self {
            Focus::List => Focus::Properties,
            Focus::Properties => Focus::Preview,
            Focus::Preview => Focus::List,
        }
    }

    /// The previous pane (Shift-Tab).
    pub fn prev(self) -> Focus {
        self.next().next()
    }
}

/// A line of typed text with the error of the last attempt to use it.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct LineEdit {
    pub text: String,
    pub error: Option<String>,
    /// The text is the old value, untouched: the first typed character replaces it.
    pub pristine: bool,
}

impl LineEdit {
    /// A line starting with `text`; typing a character replaces it, Backspace edits it.
    pub fn new(text: impl Into<String>) -> LineEdit {
        LineEdit {
            text: text.into(),
            error: None,
            pristine: true,
        }
    }
}

/// What a typed path is for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PromptPurpose {
    /// Save the scene under a new name.
    SaveAs,
    /// Open another scene file.
    Open,
    /// Add an OBJ mesh.
    ObjPath,
}

/// The field of the export dialog being typed into.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ExportField {
    #[default]
    Path,
    Size,
    Algorithm,
    Samples,
}

impl ExportField {
    /// Every field, in dialog order.
    pub const ALL: [ExportField; 4] = [
        ExportField::Path,
        ExportField::Size,
        ExportField::Algorithm,
        ExportField::Samples,
    ];
}

/// The export dialog's values, as typed.
#[derive(Debug, Clone, PartialEq)]
pub struct ExportForm {
    pub path: String,
    pub size: String,
    pub algorithm: Algorithm,
    pub samples: String,
    pub field: ExportField,
    /// The field shows its old value: the first typed character replaces it.
    pub pristine: bool,
    pub error: Option<String>,
}

/// Kinds the add menu offers, in menu order.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AddKind {
    Icosahedron,
    Box,
    Prism,
    Light,
    Mesh,
}

impl AddKind {
    /// Every kind, in menu order.
    pub const ALL: [AddKind; 5] = [
        AddKind::Icosahedron,
        AddKind::Box,
        AddKind::Prism,
        AddKind::Light,
        AddKind::Mesh,
    ];

    /// The menu's hotkey.
    pub fn hotkey(self) -> char {
        match self {
            AddKind::Icosahedron => 'i',
            AddKind::Box => 'b',
            AddKind::Prism => 'p',
            AddKind::Light => 'l',
            AddKind::Mesh => 'm',
        }
    }

    /// The menu's text.
    pub fn label(self) -> &'static str {
        match self {
            AddKind::Icosahedron => "icosahedron",
            AddKind::Box => "box",
            AddKind::Prism => "prism",
            AddKind::Light => "point light",
            AddKind::Mesh => "OBJ mesh…",
        }
    }
}

/// What the keys currently do.
#[derive(Debug, Clone, PartialEq, Default)]
pub enum Mode {
    /// Browsing and stepping.
    #[default]
    Normal,
    /// Typing an exact value for the chosen property.
    Edit(LineEdit),
    /// Choosing what to add; the index of the highlighted entry.
    AddMenu(usize),
    /// The key overlay, scrolled down this many rows.
    Help(usize),
    /// Typing a path.
    Prompt(PromptPurpose, LineEdit),
    /// Choosing the export's file, size, algorithm and samples.
    Export(ExportForm),
    /// Asking before quitting with unsaved edits.
    ConfirmQuit,
}

/// Whether a status message reports success or a problem.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Tone {
    Info,
    Error,
}

/// A one-line message in the status bar.
#[derive(Debug, Clone, PartialEq)]
pub struct Status {
    pub text: String,
    pub tone: Tone,
}

/// A rendered preview and how long it took.
#[derive(Debug, Clone, PartialEq)]
pub struct Shot {
    pub image: PreviewImage,
    /// Render time, milliseconds.
    pub millis: f64,
}

/// Most undo steps kept.
pub const UNDO_LIMIT: usize = 200;

/// The whole editor state.
#[derive(Debug)]
pub struct App {
    /// The scene being edited.
    pub scene: Scene,
    /// The file it was loaded from or saved to; `None` for the built-in scene.
    pub path: Option<PathBuf>,
    /// Directory OBJ paths are relative to.
    pub base_dir: PathBuf,
    /// Edits since the last save or load.
    pub dirty: bool,
    /// Index into [`App::items`].
    pub selected: usize,
    /// Index into the selected item's properties.
    pub field: usize,
    pub focus: Focus,
    pub mode: Mode,
    /// Algorithm of the single preview.
    pub algorithm: Algorithm,
    /// Whether the preview shows the three algorithms side by side.
    pub compare: bool,
    /// Earlier scenes, newest last.
    pub undo: Vec<Scene>,
    /// Undone scenes, newest last.
    pub redo: Vec<Scene>,
    /// The last edit was a camera move (consecutive moves share one undo step).
    pub camera_streak: bool,
    pub status: Option<Status>,
    /// Latest single preview.
    pub shot: Option<Shot>,
    /// Latest compare previews, in [`Algorithm::ALL`] order.
    pub compare_shots: [Option<Shot>; 3],
    /// Triangles in the last world built.
    pub triangles: Option<usize>,
    /// Warnings of the last world built; the status line shows those it did not have before.
    pub warnings: Vec<Warning>,
    /// Whether render times are shown (off for reproducible screen captures).
    pub show_timings: bool,
    /// Bumped on every change other than a camera move: the world must be rebuilt.
    pub generation: u64,
    /// The camera the scene was opened with (reset view).
    pub home: Camera,
    /// The PNG export running in the background.
    pub export: Option<ExportJob>,
    /// Last mouse position of a drag in progress (column, row).
    pub drag: Option<(u16, u16)>,
    pub color: ColorMode,
    /// Set when the event loop should end.
    pub quit: bool,
}

impl App {
    /// An editor on `scene`, loaded from `path` (or built in), with OBJ paths relative to `base_dir`.
    pub fn new(scene: Scene, path: Option<PathBuf>, base_dir: PathBuf) -> App {
        App {
            home: scene.camera,
            scene,
            path,
            base_dir,
            dirty: false,
            selected: 0,
            field: 0,
            focus: Focus::List,
            mode: Mode::Normal,
            algorithm: Algorithm::Phong,
            compare: false,
            undo: Vec::new(),
            redo: Vec::new(),
            camera_streak: false,
            status: None,
            shot: None,
            compare_shots: [None, None, None],
            triangles: None,
            warnings: Vec::new(),
            show_timings: true,
            generation: 0,
            export: None,
            drag: None,
            color: ColorMode::Truecolor,
            quit: false,
        }
    }

    /// The scene list: settings, then lights, then objects.
    pub fn items(&self) -> Vec<Item> {
        std::iter::once(Item::Settings)
            .chain((0..self.scene.lights.len()).map(Item::Light))
            .chain((0..self.scene.objects.len()).map(Item::Object))
            .collect()
    }

    /// The selected entry (the settings when the index is stale).
    pub fn item(&self) -> Item {
        self.items()
            .get(self.selected)
            .copied()
            .unwrap_or(Item::Settings)
    }

    /// The scene-list index of `item`.
    pub fn index_of(&self, item: Item) -> usize {
        self.items().iter().position(|&i| i == item).unwrap_or(0)
    }

    /// The file name shown in the status bar.
    pub fn title(&self) -> String {
        match &self.path {
            Some(p) => super::text::clean(&p.display().to_string()),
            None => "(built-in scene)".into(),
        }
    }

    /// Sets an informational status message.
    pub fn info(&mut self, text: impl Into<String>) {
        self.status = Some(Status {
            text: text.into(),
            tone: Tone::Info,
        });
    }

    /// Sets an error status message.
    pub fn error(&mut self, text: impl Into<String>) {
        self.status = Some(Status {
            text: text.into(),
            tone: Tone::Error,
        });
    }
}
