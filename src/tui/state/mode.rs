//! What the keys currently do: browsing, typing a value or a path, a menu, the export dialog,
//! the help overlay or the quit question, with what each has typed so far.

use crate::export::ImageFormat;
use crate::render::Algorithm;

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
    /// Add a mesh from a model file (OBJ, STL, PLY, glTF, GLB).
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
    /// The encoding: by the file's extension, or a named format.
    Format,
    /// Opaque background, or coverage as alpha.
    Background,
    Turntable,
}

impl ExportField {
    /// Every field, in dialog order.
    pub const ALL: [ExportField; 7] = [
        ExportField::Path,
        ExportField::Size,
        ExportField::Algorithm,
        ExportField::Samples,
        ExportField::Format,
        ExportField::Background,
        ExportField::Turntable,
    ];
}

/// The export dialog's values, as typed.
#[derive(Debug, Clone, PartialEq)]
pub struct ExportForm {
    pub path: String,
    /// The format asked for; `None` takes the one the file's extension names.
    pub format: Option<ImageFormat>,
    pub size: String,
    pub algorithm: Algorithm,
    /// Coverage as alpha instead of the background colour.
    pub transparent: bool,
    pub samples: String,
    /// Turntable frames; 0 writes a still image.
    pub turntable: String,
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

    /// The menu's text.
    pub fn label(self) -> &'static str {
        match self {
            AddKind::Icosahedron => "icosahedron",
            AddKind::Box => "box",
            AddKind::Prism => "prism",
            AddKind::Light => "point light",
            AddKind::Mesh => "mesh: OBJ STL PLY glTF…",
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
